//! The scene of a block of animation frames (thesis 6.4): one geometry that encloses the
//! geometry of every frame of the block, for proofs that hold in all of them.
//!
//! The thesis makes time an interval `T` and evaluates the surface over it. Here the frames
//! of a block are built as they are when each is rendered alone, and the block's geometry
//! is their common expression graph with each constant replaced by the hull of its values
//! in the frames ([`Scene::block_of`]). Where a frame's constant depends on time (a
//! parameter `a = "0.075 + 0.002*t"`, a rotation by `"15*t"` degrees, `t` in a formula),
//! the block holds the smallest interval around its values; a constant that does not
//! change stays a point. The hull of the values is at least as tight as the same formula
//! evaluated over `T` in interval arithmetic, coefficient by coefficient (it is the exact
//! range over the frames), and it encloses exactly the numbers the frames use, rounding
//! included: a frame's rotation coefficients are its `f64` sines and cosines, which an
//! interval evaluation of the exact formula need not contain.
//!
//! The frames must have one graph up to their constants: the same operations on the same
//! arguments. Frames whose graphs differ (a coefficient that is exactly 0 or 1 in one frame
//! drops a term or a product in its graph, a parameter that makes a power an integer in one
//! frame) have no block: the caller renders them in smaller blocks. Then, operation by
//! operation, the interval evaluation of the block's graph over any box encloses each
//! frame's evaluation over the same box (inclusion isotonicity of interval arithmetic in
//! the constants): a piece the block proves root-free is root-free, and proven so, in every
//! frame ([`crate::free_ranges`]).

use std::collections::HashMap;
use std::fmt;

use implicit_expr::{Constant, Context, Node, NodeId};

use super::geometry::{Geometry, Leaf};
use super::model::Scene;
use crate::ibox::hull;

/// Why frames cannot share a block.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BlockMismatch {
    /// No frame was given.
    Empty,
    /// The camera (and so every beam) differs between frames.
    Camera,
    /// The render settings differ between frames.
    Settings,
    /// The CSG objects or the leaves' clipping differ between frames.
    Objects,
    /// A leaf's graph differs between frames in more than its constants.
    Form {
        /// The leaf's name.
        leaf: String,
    },
    /// The common geometry could not be compiled.
    Build(String),
}

impl fmt::Display for BlockMismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BlockMismatch::Empty => write!(f, "no frame"),
            BlockMismatch::Camera => write!(f, "the camera moves"),
            BlockMismatch::Settings => write!(f, "the render settings change"),
            BlockMismatch::Objects => write!(f, "the objects change"),
            BlockMismatch::Form { leaf } => {
                write!(f, "surface '{leaf}' changes form (not only its constants)")
            }
            BlockMismatch::Build(e) => write!(f, "the block's geometry: {e}"),
        }
    }
}

impl std::error::Error for BlockMismatch {}

/// The common graph of several contexts, built node by node from tuples of corresponding
/// nodes (one per frame).
struct Merge<'a> {
    frames: Vec<&'a Context>,
    out: Context,
    built: HashMap<Vec<NodeId>, NodeId>,
}

/// The argument tuples of a tuple of nodes of one form, or `None` when the forms differ.
fn arguments(nodes: &[Node]) -> Option<Vec<Vec<NodeId>>> {
    let first = nodes[0];
    let same = nodes[1..].iter().all(|n| match (first, *n) {
        (Node::Var(a), Node::Var(b)) => a == b,
        (Node::Const(_), Node::Const(_)) => true,
        (Node::Unary(a, _), Node::Unary(b, _)) => a == b,
        (Node::Binary(a, _, _), Node::Binary(b, _, _)) => a == b,
        (Node::Pown(_, a), Node::Pown(_, b)) => a == b,
        _ => false,
    });
    if !same {
        return None;
    }
    let arity = match first {
        Node::Var(_) | Node::Const(_) => 0,
        Node::Unary(..) | Node::Pown(..) => 1,
        Node::Binary(..) => 2,
    };
    Some(
        (0..arity)
            .map(|k| {
                nodes
                    .iter()
                    .map(|n| match (*n, k) {
                        (Node::Unary(_, a) | Node::Pown(a, _) | Node::Binary(_, a, _), 0) => a,
                        (Node::Binary(_, _, b), _) => b,
                        _ => unreachable!("the arity matches the form"),
                    })
                    .collect()
            })
            .collect(),
    )
}

/// The hull of constants, its point value the first frame's.
fn constant_hull(nodes: &[Node]) -> Option<Constant> {
    let cs: Vec<Constant> = nodes
        .iter()
        .map(|n| match n {
            Node::Const(c) => Some(*c),
            _ => None,
        })
        .collect::<Option<_>>()?;
    let lo = cs.iter().map(Constant::lo).fold(f64::INFINITY, f64::min);
    let hi = cs
        .iter()
        .map(Constant::hi)
        .fold(f64::NEG_INFINITY, f64::max);
    Constant::enclosed(cs[0].value(), lo, hi)
}

impl Merge<'_> {
    /// The common node of `roots` (one node per frame), or `None` where the graphs differ.
    fn node(&mut self, roots: Vec<NodeId>) -> Option<NodeId> {
        // Depth-first, arguments before the node, without recursion (graphs may be deep).
        let mut stack = vec![(roots.clone(), false)];
        while let Some((key, ready)) = stack.pop() {
            if self.built.contains_key(&key) {
                continue;
            }
            let nodes: Vec<Node> = key
                .iter()
                .zip(&self.frames)
                .map(|(&id, c)| *c.get(id))
                .collect();
            let args = arguments(&nodes)?;
            if !ready {
                stack.push((key, true));
                stack.extend(
                    args.into_iter()
                        .filter(|a| !self.built.contains_key(a))
                        .map(|a| (a, false)),
                );
                continue;
            }
            let arg = |k: usize| self.built[&args[k]];
            // The node the frames' nodes stand for, built through the context's simplifying
            // constructors; it must come out in exactly that form. A simplification (two
            // arguments that became one node, `a − a`, `a·a`, `min(a, a)`, folded constants)
            // would make it something other than the operation on the wider arguments:
            // then the frames have no block.
            let wanted = match nodes[0] {
                Node::Var(v) => Node::Var(v),
                Node::Const(_) => Node::Const(constant_hull(&nodes)?),
                Node::Unary(op, _) => Node::Unary(op, arg(0)),
                Node::Binary(op, _, _) => {
                    // In the order the context keeps a commutative operation's arguments.
                    let (a, b) = (arg(0), arg(1));
                    if op.is_commutative() && b < a {
                        Node::Binary(op, b, a)
                    } else {
                        Node::Binary(op, a, b)
                    }
                }
                Node::Pown(_, k) => Node::Pown(arg(0), k),
            };
            let n = match wanted {
                Node::Var(v) => self.out.var(v).ok()?,
                Node::Const(c) => self.out.constant_enclosed(c),
                Node::Unary(op, a) => self.out.unary(op, a),
                Node::Binary(op, a, b) => self.out.binary(op, a, b),
                Node::Pown(a, k) => self.out.pown(a, k),
            };
            if *self.out.get(n) != wanted {
                return None;
            }
            self.built.insert(key, n);
        }
        self.built.get(&roots).copied()
    }
}

/// The geometry of a block: see the [module documentation](self).
fn block_geometry(frames: &[&Geometry]) -> Result<Geometry, BlockMismatch> {
    let first = frames[0];
    let same_objects = frames[1..].iter().all(|g| {
        g.objects() == first.objects()
            && g.leaves().len() == first.leaves().len()
            && g.leaves()
                .iter()
                .zip(first.leaves())
                .all(|(a, b)| a.clipped == b.clipped)
    });
    if !same_objects {
        return Err(BlockMismatch::Objects);
    }
    let mut merge = Merge {
        frames: frames.iter().map(|g| g.context()).collect(),
        out: Context::new(),
        built: HashMap::new(),
    };
    let mut leaves = Vec::with_capacity(first.leaves().len());
    for (i, leaf) in first.leaves().iter().enumerate() {
        let roots = frames.iter().map(|g| g.leaves()[i].node).collect();
        let node = merge.node(roots).ok_or_else(|| BlockMismatch::Form {
            leaf: leaf.name.clone(),
        })?;
        let bounds = frames[1..]
            .iter()
            .fold(leaf.bounds, |b, g| hull(&b, &g.leaves()[i].bounds));
        leaves.push(Leaf {
            node,
            bounds,
            ..leaf.clone()
        });
    }
    let bounds = frames[1..]
        .iter()
        .fold(first.bounds(), |b, g| hull(&b, &g.bounds()));
    Geometry::from_parts(merge.out, leaves, first.objects().to_vec(), bounds)
        .map_err(|e| BlockMismatch::Build(e.to_string()))
}

impl Scene {
    /// The scene of a block of `frames`: the first frame with a geometry that encloses
    /// every frame's (see the [module documentation](self)), for the proofs a block
    /// shares with its frames.
    ///
    /// # Errors
    ///
    /// [`BlockMismatch`] when the frames have different cameras, settings or objects, or
    /// a surface's graph changes between frames in more than its constants.
    pub fn block_of(frames: &[Scene]) -> Result<Scene, BlockMismatch> {
        let first = frames.first().ok_or(BlockMismatch::Empty)?;
        if frames[1..].iter().any(|f| f.camera != first.camera) {
            return Err(BlockMismatch::Camera);
        }
        if frames[1..].iter().any(|f| f.settings != first.settings) {
            return Err(BlockMismatch::Settings);
        }
        let geometries: Vec<&Geometry> = frames.iter().map(|f| &f.geometry).collect();
        Ok(Scene {
            geometry: block_geometry(&geometries)?,
            proofs: None,
            ..first.clone()
        })
    }
}
