//! The lazy BSP of occluder edge lines in Plücker space (Algorithm 1 of the method, with
//! the corrections the analysis lists: the leaf's list saved before it is replaced, an
//! occluder that the light straddles given two blocked cells, undecided signs counted as
//! mixed).
//!
//! Each inner node holds an oriented occluder edge `a → b`; its children hold the lines
//! (from a light point to the shaded point) on either side of it (`side > 0`: `pos`). A leaf
//! is visible or invisible; a visible leaf with occluders still to sort is the "undefined"
//! class, expanded by the first query that reaches it: one of its occluders, chosen at
//! random (seeded), becomes the chain of its edges (`bsp(o)`), and the others are inserted
//! into that chain by the orientation of their vertex-to-vertex lines with the light
//! (Theorem 1: all on one side of an edge line, so are all lines that stab the light then
//! the occluder).

use glam::DVec3;
use interval_core::Float;

use super::fragment::{Fragment, Side};
use super::orient::{box_corner, query_plane, side_sign, side_sign_box};
use crate::shadow::Patch;
use crate::shadow::exact_work::BspWork;

/// An occluder: a convex polygon inside the slab between the light and the receiver.
#[derive(Clone, Debug)]
pub(super) struct Occluder {
    /// The polygon after clipping, its edges `verts[i] → verts[i + 1]`.
    pub verts: Vec<DVec3>,
    /// The polygon before clipping (scene vertices): the insertion predicate's points.
    pub original: Vec<DVec3>,
    /// The signs of the edge sides of the lines that cross it from the light: `+1`, `-1`, or
    /// both (`0`) where the light straddles its plane.
    pub stab: i8,
}

/// Bytes of one node of a tree's arena (an inner node's edge line and children, or a
/// leaf's flag and list of occluders, whose entries come on top): what
/// [`BspWork::peak_nodes`] costs in memory.
pub const NODE_BYTES: usize = std::mem::size_of::<Node>();

/// A node of the arena.
#[derive(Clone, Debug)]
enum Node {
    Inner {
        a: DVec3,
        b: DVec3,
        pos: u32,
        neg: u32,
    },
    Leaf {
        visible: bool,
        occluders: Vec<u32>,
    },
}

/// Whether some line `p → q` (`p` of `from`, `q` of `to`) lies on the positive side of the
/// line `a → b`, and whether some lies on the negative side (exact signs). Stops once both
/// are seen. By bilinearity of the side operator these are the signs of every line from a
/// point of the convex hull of `from` to one of `to`.
fn signs(a: DVec3, b: DVec3, from: &[DVec3], to: &[DVec3]) -> (bool, bool) {
    both_ways(
        from.iter()
            .flat_map(|&p| to.iter().map(move |&q| Some(side_sign(a, b, p, q)))),
    )
}

/// Whether some of `signs` are positive and some negative, an unknown sign (`None`)
/// counting as both; stops once both are seen.
fn both_ways(signs: impl Iterator<Item = Option<i8>>) -> (bool, bool) {
    let (mut plus, mut minus) = (false, false);
    for s in signs {
        match s {
            Some(1) => plus = true,
            Some(-1) => minus = true,
            Some(_) => {}
            None => return (true, true),
        }
        if plus && minus {
            break;
        }
    }
    (plus, minus)
}

/// Boxes of doubles holding the light's exact corners `c`, `c + e_u + e_v`, `c + e_u`,
/// `c + e_v` (opposite corners first: a mixed occluder shows both signs sooner): the
/// outward-rounded interval sums, points where the sums are exact.
pub(super) fn light_boxes(light: &Patch) -> [(DVec3, DVec3); 4] {
    [(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)].map(|(u, v)| {
        let b = light.exact_box(u, u, v, v);
        (
            DVec3::from(b.map(|i| i.inf())),
            DVec3::from(b.map(|i| i.sup())),
        )
    })
}

/// Points whose convex hull holds the light: the corners of its [`light_boxes`]. Signs
/// that are exact for the lines from these points are, by bilinearity, those of the lines
/// from every point of the light, not only from the hull of its rounded corners.
pub(super) fn enclosing_corners(light: &Patch) -> Vec<DVec3> {
    let mut points = Vec::with_capacity(4);
    for (lo, hi) in light_boxes(light) {
        for k in 0..8 {
            let p = box_corner(lo, hi, k);
            if !points.contains(&p) {
                points.push(p);
            }
        }
    }
    points
}

/// [`signs`] of the lines from the light's corners, each known as a box of doubles
/// ([`light_boxes`]): both where a box's sign may vary.
fn light_signs(a: DVec3, b: DVec3, from: &[(DVec3, DVec3)], to: &[DVec3]) -> (bool, bool) {
    both_ways(
        from.iter()
            .flat_map(|&corner| to.iter().map(move |&q| side_sign_box(a, b, corner, q))),
    )
}

/// The tree of one light and one group of receivers.
#[derive(Clone, Debug)]
pub(super) struct Bsp {
    nodes: Vec<Node>,
    occluders: Vec<Occluder>,
    light: Patch,
    /// Boxes holding the light's corners ([`light_boxes`]): the insertions' light points.
    corners: [(DVec3, DVec3); 4],
    /// How many of the occluders (the first ones) are chosen before the others, in order.
    first: u32,
    /// The corners of a box holding every query point (empty: no box given). A line that
    /// matters to an insertion reaches a query point `x` through a point `q` of the
    /// occluder between the light and `x`; its side equals that of `q → x` times a positive
    /// factor, so where the lines from the occluder's vertices to these corners all lie on
    /// one side of a node's edge, so do the lines of every query that the occluder blocks.
    region: Vec<DVec3>,
    rng: u64,
    /// The nodes an insertion has still to visit (kept to reuse its memory).
    pending: Vec<u32>,
    pub work: BspWork,
}

impl Bsp {
    /// The tree holding one undefined leaf with every occluder (a visible leaf when there is
    /// none), its random choices seeded by `seed`. A leaf expands its list's first
    /// `first` occluders in their order before it picks among the others.
    pub fn new(light: Patch, occluders: Vec<Occluder>, first: usize, seed: u64) -> Bsp {
        let mut bsp = Bsp {
            nodes: Vec::new(),
            occluders,
            light,
            corners: light_boxes(&light),
            first: first as u32,
            region: Vec::new(),
            rng: seed,
            pending: Vec::new(),
            work: BspWork::default(),
        };
        bsp.reset();
        bsp
    }

    /// Back to the root leaf with every occluder (the method without coherence).
    pub fn reset(&mut self) {
        self.nodes.clear();
        self.nodes.push(Node::Leaf {
            visible: true,
            occluders: (0..self.occluders.len() as u32).collect(),
        });
    }

    /// Restricts the insertions to the lines that reach the box `[lo, hi]`, which must hold
    /// every later query point (the caller checks it); the tree restarts from its root.
    pub fn set_region(&mut self, lo: DVec3, hi: DVec3) {
        let mut corners: Vec<DVec3> = (0..8).map(|k| box_corner(lo, hi, k)).collect();
        // A flat box (a floor tile) has each corner twice.
        corners.sort_by(|p, q| p.to_array().partial_cmp(&q.to_array()).expect("finite"));
        corners.dedup();
        self.region = corners;
        self.reset();
    }

    /// The next pseudo-random number (SplitMix64).
    fn next_random(&mut self) -> u64 {
        self.rng = self.rng.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.rng;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn push(&mut self, n: Node) -> u32 {
        if matches!(n, Node::Inner { .. }) {
            self.work.inner_nodes += 1;
        }
        self.nodes.push(n);
        self.work.peak_nodes = self.work.peak_nodes.max(self.nodes.len() as u64);
        (self.nodes.len() - 1) as u32
    }

    fn leaf(&mut self, visible: bool) -> u32 {
        self.push(Node::Leaf {
            visible,
            occluders: Vec::new(),
        })
    }

    /// The chain of `o`'s edges `from..` for the lines with edge sides of sign `sigma`: each
    /// node sends the other sign to a visible leaf and `sigma` on, the last to an invisible
    /// leaf. Returns the chain's first node.
    fn chain(&mut self, o: usize, from: usize, sigma: i8) -> u32 {
        let verts = self.occluders[o].verts.clone();
        let k = verts.len();
        let mut next = self.leaf(false);
        for i in (from..k).rev() {
            let other = self.leaf(true);
            let (pos, neg) = if sigma > 0 {
                (next, other)
            } else {
                (other, next)
            };
            next = self.push(Node::Inner {
                a: verts[i],
                b: verts[(i + 1) % k],
                pos,
                neg,
            });
        }
        next
    }

    /// `bsp(o)`: one chain, or, where the light straddles `o`'s plane, the first edge over
    /// two chains of the others, one per sign.
    fn occluder_tree(&mut self, o: usize) -> u32 {
        let stab = self.occluders[o].stab;
        if stab != 0 {
            return self.chain(o, 0, stab);
        }
        let (pos, neg) = (self.chain(o, 1, 1), self.chain(o, 1, -1));
        let v = &self.occluders[o].verts;
        let (a, b) = (v[0], v[1]);
        self.push(Node::Inner { a, b, pos, neg })
    }

    /// Sorts occluder `o` into the subtree at `root` (Algorithm 1's `insertOccluder`).
    fn insert(&mut self, root: u32, o: u32) {
        let mut stack = std::mem::take(&mut self.pending);
        stack.push(root);
        let corners = self.corners;
        while let Some(n) = stack.pop() {
            match &mut self.nodes[n as usize] {
                Node::Leaf { visible, occluders } => {
                    if *visible {
                        occluders.push(o);
                    }
                }
                &mut Node::Inner { a, b, pos, neg } => {
                    let original = &self.occluders[o as usize].original;
                    // The lines from the light's corners to the occluder's vertices; where
                    // they lie on both sides, the lines from its vertices to the corners of
                    // the receivers' region (see `Bsp::region`).
                    let (mut plus, mut minus) = light_signs(a, b, &corners, original);
                    if plus && minus && !self.region.is_empty() {
                        (plus, minus) = signs(a, b, original, &self.region);
                    }
                    match (plus, minus) {
                        (true, false) => stack.push(pos),
                        (false, true) => stack.push(neg),
                        // Every stabbing line in the hyperplane: a set of measure zero.
                        (false, false) => {}
                        (true, true) => {
                            stack.push(pos);
                            stack.push(neg);
                        }
                    }
                }
            }
        }
        self.pending = stack;
    }

    /// Expands the undefined leaf `n`: the first of the occluders put first, or else a
    /// random occluder of its list, becomes its chain; the others are inserted into that
    /// chain. (A list holds its occluders in increasing order: the tree's root holds them
    /// all in order, and an insertion appends to the lists below.)
    fn expand(&mut self, n: u32) {
        let Node::Leaf { occluders, .. } = &mut self.nodes[n as usize] else {
            unreachable!("only leaves are expanded");
        };
        let list = std::mem::take(occluders);
        let pick = if list[0] < self.first {
            list[0]
        } else {
            list[(self.next_random() % list.len() as u64) as usize]
        };
        let tree = self.occluder_tree(pick as usize);
        // The chain's root takes the leaf's place.
        let root = self.nodes[tree as usize].clone();
        self.nodes[n as usize] = root;
        self.work.merges += 1;
        for o in list.into_iter().filter(|&o| o != pick) {
            self.insert(n, o);
        }
    }

    /// The visible share of the light from `x` (its `(u, v)` area), starting from
    /// `fragment` (the light above `x`'s horizon), expanding the tree where the query
    /// reaches undefined leaves.
    pub fn query(&mut self, x: DVec3, fragment: Fragment) -> f64 {
        self.query_parts(x, fragment, None).area
    }

    /// [`Bsp::query`] with the bound on its rounding ([`Visible::slack`]), also handing
    /// each visible fragment to `parts` where given.
    pub fn query_parts(
        &mut self,
        x: DVec3,
        fragment: Fragment,
        mut parts: Option<&mut Vec<Fragment>>,
    ) -> Visible {
        self.work.queries += 1;
        let mut visible = Visible::default();
        let mut count = 0u32;
        let mut stack = vec![(0u32, fragment)];
        while let Some((n, f)) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Leaf { visible: false, .. } => {}
                Node::Leaf {
                    visible: true,
                    occluders,
                } if occluders.is_empty() => {
                    self.work.fragments += 1;
                    count += 1;
                    visible.area += f.area();
                    visible.slack = visible.slack.add_up(f.area_error());
                    if let Some(p) = parts.as_deref_mut() {
                        p.push(f);
                    }
                }
                Node::Leaf { .. } => {
                    self.expand(n);
                    stack.push((n, f));
                }
                &Node::Inner { a, b, pos, neg } => {
                    // The query plane through `x` and the edge, in the light's parameters:
                    // side(a → b, l(u, v) → x), affine in (u, v).
                    let (s, error) = query_plane(a, b, &self.light, x);
                    let (side, misplaced) = f.side_and_misplaced(&s, error);
                    visible.slack = visible.slack.add_up(misplaced);
                    match side {
                        Side::Pos => stack.push((pos, f)),
                        Side::Neg => stack.push((neg, f)),
                        Side::On => {
                            self.work.degenerate += 1;
                            stack.push((pos, f));
                        }
                        Side::Both => {
                            self.work.splits += 1;
                            let (p, m) = f.split(&s);
                            if !p.is_empty() {
                                stack.push((pos, p));
                            }
                            if !m.is_empty() {
                                stack.push((neg, m));
                            }
                        }
                    }
                }
            }
        }
        // The sum's own rounding, with a margin.
        let summing = 2.0 * f64::from(count + 1) * f64::EPSILON * visible.area;
        visible.slack = visible.slack.add_up(summing);
        visible
    }
}

/// What a query finds: the visible fragments' area, and a bound on how far it may lie from
/// the exact visible share of the light for the same tree and point.
///
/// The tree's leaves are exact (every sign that builds it is), so only the query's
/// arithmetic errs: each node a fragment reaches cuts it by a plane computed in floating
/// point ([`query_plane`], with its error bound), and the cut's vertices are rounded. A
/// point of the light ends in another leaf than its exact one only by lying, at some node
/// on its way, inside the fragment there and inside that node's band of uncertain sign;
/// `slack` sums a bound on that area over every fragment and node the query visits
/// ([`Fragment::misplaced`]), and the rounding of the areas and their sum.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub(super) struct Visible {
    /// The visible fragments' area.
    pub area: f64,
    /// The bound on `|area − exact area|`.
    pub slack: f64,
}
