//! The compiled geometry of a scene: leaf surfaces, CSG objects, the scene function.

use glam::DVec3;
use implicit_expr::{BinaryOp, Context, Evaluator, Grad, NodeId, RayFunction, Tape};
use interval_core::Interval;

use super::material::Material;
use crate::error::Error;
use crate::ibox::{IBox, hull};
use crate::ray::BeamEval;

/// A leaf surface `f(x, y, z) = 0` (parameters bound, transform applied), with the solid
/// `f < 0` on its inside.
#[derive(Clone, Debug)]
pub struct Leaf {
    /// Name (from the scene file).
    pub name: String,
    /// The function, in the geometry's context.
    pub node: NodeId,
    /// Material.
    pub material: Material,
    /// Bounding box (in world coordinates).
    pub bounds: IBox,
    /// Whether the function is clipped to `bounds` (positive outside it), so that its
    /// surface lies inside the box whatever the search region.
    pub clipped: bool,
}

/// A CSG tree over leaves (point-set operations, thesis 6.3).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Csg {
    /// Leaf `i` of [`Geometry::leaves`].
    Leaf(usize),
    /// Union of the children (`min`).
    Union(Vec<Csg>),
    /// Intersection of the children (`max`).
    Intersection(Vec<Csg>),
    /// The first minus the second (`max(a, −b)`).
    Difference(Box<Csg>, Box<Csg>),
}

impl Csg {
    /// The function of the tree in `ctx`, from the leaves' functions.
    pub fn build(&self, ctx: &mut Context, leaves: &[NodeId]) -> NodeId {
        match self {
            Csg::Leaf(i) => leaves[*i],
            Csg::Union(c) | Csg::Intersection(c) => {
                let union = matches!(self, Csg::Union(_));
                let mut acc = c[0].build(ctx, leaves);
                for child in &c[1..] {
                    let n = child.build(ctx, leaves);
                    acc = if union {
                        ctx.min(acc, n)
                    } else {
                        ctx.max(acc, n)
                    };
                }
                acc
            }
            Csg::Difference(a, b) => {
                let a = a.build(ctx, leaves);
                let b = b.build(ctx, leaves);
                let nb = ctx.neg(b);
                ctx.max(a, nb)
            }
        }
    }

    /// The leaves the tree uses.
    pub fn leaves(&self, out: &mut Vec<usize>) {
        match self {
            Csg::Leaf(i) => out.push(*i),
            Csg::Union(c) | Csg::Intersection(c) => c.iter().for_each(|c| c.leaves(out)),
            Csg::Difference(a, b) => {
                a.leaves(out);
                b.leaves(out);
            }
        }
    }
}

/// Margin, relative to a box's largest side, by which a clipped leaf's box is enlarged in
/// the scene bounds. A clipped surface lies inside its own box, so searching a little
/// beyond it finds nothing new; but its box faces are part of the surface, and the margin
/// puts them strictly inside the bounds, where an inclusion proof (whose end parameters
/// must be inside the bounds for every ray) can reach them from outside the solid.
const CLIP_MARGIN: f64 = 1e-3;

fn search_box(leaf: &Leaf) -> IBox {
    if !leaf.clipped {
        return leaf.bounds;
    }
    let side = leaf.bounds.iter().map(|i| i.wid()).fold(0.0, f64::max);
    let m = CLIP_MARGIN * side;
    leaf.bounds.map(|i| {
        let lo = i.inf() - m;
        let hi = i.sup() + m;
        if lo.is_finite() && hi.is_finite() {
            Interval::new_unchecked(lo, hi)
        } else {
            i
        }
    })
}

/// A leaf's function made absent (`+inf`, outside every solid) where its formula is
/// undefined ([`Context::domain_extension`]), so that the union, intersection and difference
/// of objects treat that region as outside it instead of hiding the other objects there.
///
/// A formula whose domain tests are proven to hold over the whole scene `bounds` (all the
/// search ever sees) is kept as it is: nothing changes for it, not even its tape.
fn absent_where_undefined(ctx: &mut Context, node: NodeId, bounds: &IBox) -> NodeId {
    if ctx.is_total(node) {
        return node;
    }
    let (total, tests) = ctx.domain_split(node);
    let Some(d) = tests.into_iter().reduce(|acc, t| ctx.max(acc, t)) else {
        return node;
    };
    let holds = ctx
        .eval::<Interval<f64>>(d, bounds)
        .is_ok_and(|v| !v.is_empty() && v.sup() <= 0.0);
    if holds {
        node
    } else {
        ctx.binary(BinaryOp::Domain, d, total)
    }
}

/// The compiled geometry of a scene.
#[derive(Clone, Debug)]
pub struct Geometry {
    ctx: Context,
    leaves: Vec<Leaf>,
    objects: Vec<Csg>,
    root: NodeId,
    bounds: IBox,
    ray: RayFunction,
    f_tape: Tape,
    leaf_tape: Tape,
    object_rays: Vec<RayFunction>,
    object_tape: Tape,
}

impl Geometry {
    /// Compiles the scene function: the union of `objects` (CSG trees over `leaves`, whose
    /// nodes live in `ctx`, a context with the variables `x y z` only).
    ///
    /// Returns an error when there is no object, a tree names a missing leaf, the context
    /// has free parameters, or a tape cannot be built.
    pub fn new(mut ctx: Context, leaves: Vec<Leaf>, objects: Vec<Csg>) -> Result<Self, Error> {
        let setup = |m: String| Error::Setting {
            name: "geometry".into(),
            message: m,
        };
        if objects.is_empty() {
            return Err(setup("the scene has no surface".into()));
        }
        if ctx.var_count() > 3 {
            return Err(setup(format!(
                "unbound parameters: {}",
                ctx.var_names()[3..].join(", ")
            )));
        }
        let mut used = Vec::new();
        for o in &objects {
            o.leaves(&mut used);
        }
        if let Some(&bad) = used.iter().find(|&&i| i >= leaves.len()) {
            return Err(setup(format!(
                "CSG names leaf {bad}, there are {}",
                leaves.len()
            )));
        }
        let bounds = used[1..]
            .iter()
            .fold(search_box(&leaves[used[0]]), |b, &i| {
                hull(&b, &search_box(&leaves[i]))
            });
        let mut leaves = leaves;
        for leaf in &mut leaves {
            leaf.node = absent_where_undefined(&mut ctx, leaf.node, &bounds);
        }
        Self::from_parts(ctx, leaves, objects, bounds)
    }

    /// The geometry of leaves whose functions are final (made absent where undefined, as
    /// [`Geometry::new`] makes them) and of `objects` over them (checked), searched inside
    /// `bounds`.
    pub(crate) fn from_parts(
        mut ctx: Context,
        leaves: Vec<Leaf>,
        objects: Vec<Csg>,
        bounds: IBox,
    ) -> Result<Self, Error> {
        let nodes: Vec<NodeId> = leaves.iter().map(|l| l.node).collect();
        let object_roots: Vec<NodeId> = objects.iter().map(|o| o.build(&mut ctx, &nodes)).collect();
        let mut root = object_roots[0];
        for &n in &object_roots[1..] {
            root = ctx.min(root, n);
        }
        let ray = RayFunction::new(&ctx, root)?;
        let f_tape = Tape::new(&ctx, &[root])?;
        let leaf_tape = Tape::new(&ctx, &nodes)?;
        let object_rays = object_roots
            .iter()
            .map(|&n| RayFunction::new(&ctx, n))
            .collect::<Result<Vec<_>, _>>()?;
        let object_tape = Tape::new(&ctx, &object_roots)?;
        Ok(Self {
            ctx,
            leaves,
            objects,
            root,
            bounds,
            ray,
            f_tape,
            leaf_tape,
            object_rays,
            object_tape,
        })
    }

    /// The expression graph (leaves, objects and the scene function).
    pub fn context(&self) -> &Context {
        &self.ctx
    }

    /// The scene function `f = min(objects)`.
    pub fn root(&self) -> NodeId {
        self.root
    }

    /// The leaf surfaces.
    pub fn leaves(&self) -> &[Leaf] {
        &self.leaves
    }

    /// The top-level CSG objects.
    pub fn objects(&self) -> &[Csg] {
        &self.objects
    }

    /// The scene bounds: the hull of the leaves' boxes (a clipped leaf's box with a margin of
    /// 1e-3 of its largest side). Rays are searched only inside it.
    pub fn bounds(&self) -> IBox {
        self.bounds
    }

    /// The length of the diagonal of [`bounds`](Self::bounds): the scene's scale, which
    /// tolerances are relative to.
    pub fn diagonal(&self) -> f64 {
        crate::ibox::diagonal(&self.bounds)
    }

    /// `g` and `g'` of the scene function.
    pub fn ray_function(&self) -> &RayFunction {
        &self.ray
    }

    /// The tape of the scene function in `x y z`.
    pub fn tape(&self) -> &Tape {
        &self.f_tape
    }

    /// Per-thread evaluators of this geometry.
    pub fn evaluator(&self) -> GeometryEval {
        GeometryEval {
            beam: BeamEval::new(&self.ray),
            f_tape: self.f_tape.clone(),
            grad: Evaluator::new(&self.f_tape),
            igrad: Evaluator::new(&self.f_tape),
            interval: Evaluator::new(&self.f_tape),
            leaves: Evaluator::new(&self.leaf_tape),
            leaf_values: vec![0.0; self.leaves.len()],
            leaf_boxes: Evaluator::new(&self.leaf_tape),
            leaf_enclosures: vec![Interval::ENTIRE; self.leaves.len()],
            candidates: Evaluator::new(&self.leaf_tape),
            objects: self.object_rays.iter().map(BeamEval::new).collect(),
            object_values_eval: Evaluator::new(&self.object_tape),
            object_values: vec![0.0; self.objects.len()],
        }
    }
}

/// Evaluators of a [`Geometry`] for one thread: `g`/`g'` on rays and beams, the gradient
/// (normals), interval values on boxes, and which leaf a point lies on.
#[derive(Clone, Debug)]
pub struct GeometryEval {
    /// `g` and `g'` of the scene function on rays and beams.
    pub beam: BeamEval,
    /// The scene function's tape (the gradient evaluator may hold a pruned one).
    f_tape: Tape,
    grad: Evaluator<Grad<f64>>,
    igrad: Evaluator<Grad<Interval<f64>>>,
    interval: Evaluator<Interval<f64>>,
    leaves: Evaluator<f64>,
    leaf_values: Vec<f64>,
    /// Every leaf's function over a box ([`GeometryEval::leaves_over`]).
    leaf_boxes: Evaluator<Interval<f64>>,
    leaf_enclosures: Vec<Interval<f64>>,
    /// The leaves of a cell that may shade a point ([`GeometryEval::leaf_among`]).
    candidates: Evaluator<f64>,
    /// `g` and `g'` of each top-level object alone.
    pub objects: Vec<BeamEval>,
    object_values_eval: Evaluator<f64>,
    object_values: Vec<f64>,
}

impl GeometryEval {
    /// The gradient of the scene function at `p` (rounded to nearest).
    pub fn gradient(&mut self, p: DVec3) -> DVec3 {
        self.grad.set_tape(&self.f_tape);
        self.gradient_of(p)
    }

    /// The unit normal at `p` computed from `tape`, a version of the scene function pruned
    /// to a region holding `p` ([`Grid::scene_tape_at`](crate::grid::Grid::scene_tape_at)):
    /// the same gradient as [`normal`](Self::normal), at the cost of the pruned tape.
    pub fn normal_with(&mut self, tape: &Tape, p: DVec3) -> Option<DVec3> {
        self.grad.set_tape(tape);
        unit(self.gradient_of(p))
    }

    fn gradient_of(&mut self, p: DVec3) -> DVec3 {
        let g = self
            .grad
            .eval(&Grad::point(p.x, p.y, p.z))
            .expect("tape in x y z");
        DVec3::new(g.d[0], g.d[1], g.d[2])
    }

    /// The unit normal at `p`, or `None` where the gradient vanishes or is not finite.
    pub fn normal(&mut self, p: DVec3) -> Option<DVec3> {
        unit(self.gradient(p))
    }

    /// Enclosures of the scene function and its gradient over a box.
    pub fn gradient_box(&mut self, b: &IBox) -> (Interval<f64>, IBox) {
        let vars = Grad::point(b[0], b[1], b[2]);
        let g = self.igrad.eval(&vars).expect("tape in x y z");
        (g.v, g.d)
    }

    /// An enclosure of the scene function over a box.
    pub fn value_box(&mut self, b: &IBox) -> Interval<f64> {
        self.interval.eval(b).expect("tape in x y z")
    }

    /// Whether the scene has one leaf surface: every hit is that leaf's.
    pub fn single_leaf(&self) -> bool {
        self.leaves.tape().outputs().len() == 1
    }

    /// The leaf whose surface passes nearest `p` (smallest `|f_leaf(p)|`): whose material
    /// shades a hit at `p`.
    pub fn leaf_at(&mut self, p: DVec3) -> usize {
        if self.single_leaf() {
            return 0;
        }
        self.leaves
            .eval_outputs(&[p.x, p.y, p.z], &mut self.leaf_values)
            .expect("tape in x y z");
        nearest_zero(&self.leaf_values)
    }

    /// The leaves that may shade a hit inside the box `b` ([`leaf_at`](Self::leaf_at) of a
    /// point of `b`), increasing: those whose magnitude may be the smallest of every
    /// leaf's somewhere in `b` (`mig F_i(b) ≤ min_j mag F_j(b)`). Every leaf where an
    /// enclosure cannot be computed.
    pub fn leaves_over(&mut self, b: &IBox) -> Vec<usize> {
        let n = self.leaf_enclosures.len();
        if n <= 1 {
            return (0..n).collect();
        }
        if self
            .leaf_boxes
            .eval_outputs(b, &mut self.leaf_enclosures)
            .is_err()
        {
            return (0..n).collect();
        }
        let e = &self.leaf_enclosures;
        if e.iter().any(|v| v.is_empty() || v.inf().is_nan()) {
            return (0..n).collect();
        }
        let smallest = e.iter().map(|v| v.mag()).fold(f64::INFINITY, f64::min);
        (0..n).filter(|&i| e[i].mig() <= smallest).collect()
    }

    /// [`leaf_at`](Self::leaf_at) with the search narrowed to the candidates of the grid
    /// cell holding `p` ([`LeafCandidates`](crate::grid::LeafCandidates)): the same leaf,
    /// found among the candidates when one of them is nearer zero than every leaf left out
    /// can be, else by the full search.
    pub fn leaf_among(&mut self, c: &crate::grid::LeafCandidates<'_>, p: DVec3) -> usize {
        let n = c.leaves.len();
        if n == 1 && c.bound == f64::INFINITY {
            // The only leaf that may vanish in the cell, and none left out.
            return c.leaves[0] as usize;
        }
        self.candidates.set_tape(c.tape);
        self.leaf_values.resize(self.leaf_values.len().max(n), 0.0);
        let found = self
            .candidates
            .eval_outputs(&[p.x, p.y, p.z], &mut self.leaf_values[..n])
            .ok()
            .map(|()| nearest_zero(&self.leaf_values[..n]))
            .filter(|&k| self.leaf_values[k].abs() < c.bound);
        match found {
            Some(k) => c.leaves[k] as usize,
            None => self.leaf_at(p),
        }
    }

    /// The top-level object whose surface passes nearest `p` (smallest `|f_object(p)|`).
    pub fn object_at(&mut self, p: DVec3) -> usize {
        self.object_values_eval
            .eval_outputs(&[p.x, p.y, p.z], &mut self.object_values)
            .expect("tape in x y z");
        nearest_zero(&self.object_values)
    }
}

/// The unit vector along a gradient, `None` where it vanishes or is not finite.
fn unit(g: DVec3) -> Option<DVec3> {
    let n = g.normalize_or_zero();
    (n != DVec3::ZERO && n.is_finite()).then_some(n)
}

/// The index of the value of smallest magnitude (0 when all are NaN).
fn nearest_zero(values: &[f64]) -> usize {
    let mut best = (f64::INFINITY, 0);
    for (i, v) in values.iter().enumerate() {
        let a = v.abs();
        if a < best.0 {
            best = (a, i);
        }
    }
    best.1
}
