//! A bounding-volume hierarchy over triangles: first crossings of rays and segments, and
//! the first parameter range where a beam may meet a triangle.

use glam::DVec3;
use interval_core::Interval;
use rustc_hash::FxHashMap;

use super::shaft::Shaft;
use super::triangle::{Crossing, Triangle};
use crate::ibox::{IBox, disjoint, hull};
use crate::ray::{Beam, Ray};
use crate::root::{Proof, RootResult};

/// Triangles per leaf at most.
const LEAF_SIZE: usize = 4;

/// How many times a beam's parameter range is halved at most before a piece that may meet
/// a triangle is reported ([`Bvh::beam_first`]).
const BEAM_DEPTH: u32 = 10;

/// A node: its box and either two children or a run of triangles.
#[derive(Clone, Debug)]
struct Node {
    bounds: IBox,
    /// Leaf: the first triangle and the count; inner: the second child (the first follows
    /// the node) and 0.
    start: u32,
    count: u32,
}

/// A bounding-volume hierarchy over triangles (median splits on the longest axis of the
/// centroids).
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// The triangles, in leaf order.
    triangles: Vec<Triangle>,
    /// For each triangle in leaf order, its index in the list it was built from.
    ids: Vec<u32>,
    /// For each index in the list it was built from, the triangle's place in leaf order.
    slots: Vec<u32>,
}

/// The first crossing of a ray found in a [`Bvh`].
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct FirstCrossing {
    /// The first root of the union of the triangles along the ray, as a root finder states
    /// it: [`RootResult::NoRoot`] is a proof that no triangle is crossed in the window.
    pub result: RootResult,
    /// The triangle (its index in the list the hierarchy was built from) whose crossing
    /// is the earliest candidate, where there is one.
    pub triangle: Option<u32>,
}

impl Bvh {
    /// The hierarchy of `triangles` (any number, none included).
    pub fn new(triangles: &[Triangle]) -> Self {
        let mut order: Vec<u32> = (0..triangles.len() as u32).collect();
        let mut nodes = Vec::new();
        if !triangles.is_empty() {
            build(triangles, &mut order, 0, &mut nodes);
        }
        let mut slots = vec![0; order.len()];
        for (k, &i) in order.iter().enumerate() {
            slots[i as usize] = k as u32;
        }
        Self {
            nodes,
            triangles: order.iter().map(|&i| triangles[i as usize]).collect(),
            ids: order,
            slots,
        }
    }

    /// The triangle of index `id` in the list the hierarchy was built from.
    pub fn triangle(&self, id: u32) -> &Triangle {
        &self.triangles[self.slots[id as usize] as usize]
    }

    /// The box of every triangle (`None` when there is none).
    pub fn bounds(&self) -> Option<IBox> {
        self.nodes.first().map(|n| n.bounds)
    }

    /// The number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether there are no triangles.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The first crossing of `ray` with a triangle for parameters in `window`.
    ///
    /// Every crossing that may come before the earliest proven one is a candidate; the
    /// result's enclosure runs from the earliest candidate's start to the end of the
    /// earliest proven crossing, proven to hold a crossing where one is proven (unique
    /// where a single candidate is left), else [`Proof::Possible`].
    pub fn first_crossing(&self, ray: &Ray, window: Interval<f64>) -> FirstCrossing {
        let none = FirstCrossing {
            result: RootResult::NoRoot,
            triangle: None,
        };
        if self.nodes.is_empty() || window.is_empty() {
            return none;
        }
        let beam = ray.beam();
        // The end of the earliest proven crossing: nothing after it can come first.
        let mut bound = f64::INFINITY;
        let mut candidates: Vec<(Crossing, u32)> = Vec::new();
        let mut stack = vec![0u32];
        while let Some(i) = stack.pop() {
            let node = &self.nodes[i as usize];
            let Some(t) = beam.t_range_within(&node.bounds, window) else {
                continue;
            };
            if t.inf() > bound {
                continue;
            }
            if node.count > 0 {
                let run = node.start as usize..(node.start + node.count) as usize;
                for k in run {
                    if let Some(c) = self.triangles[k].crossing(ray.origin, ray.dir, window) {
                        if c.proven {
                            bound = bound.min(c.t.sup());
                        }
                        candidates.push((c, self.ids[k]));
                    }
                }
            } else {
                // Nearer child last, so that it is searched first.
                let (a, b) = (i + 1, node.start);
                let entry = |j: u32| {
                    beam.t_range_within(&self.nodes[j as usize].bounds, window)
                        .map_or(f64::INFINITY, |t| t.inf())
                };
                if entry(a) <= entry(b) {
                    stack.extend([b, a]);
                } else {
                    stack.extend([a, b]);
                }
            }
        }
        candidates.retain(|(c, _)| c.t.inf() <= bound);
        let Some(&(first, id)) = candidates
            .iter()
            .min_by(|x, y| x.0.t.inf().total_cmp(&y.0.t.inf()))
        else {
            return none;
        };
        let lo = first.t.inf();
        let result = if bound.is_finite() {
            let proof = if candidates.len() == 1 {
                Proof::Unique
            } else {
                Proof::Exists
            };
            RootResult::Root {
                t: Interval::new_unchecked(lo, bound),
                proof,
            }
        } else {
            let hi = candidates
                .iter()
                .map(|(c, _)| c.t.sup())
                .fold(f64::NEG_INFINITY, f64::max);
            RootResult::Root {
                t: Interval::new_unchecked(lo, hi),
                proof: Proof::Possible,
            }
        };
        FirstCrossing {
            result,
            triangle: Some(id),
        }
    }

    /// Visits, in leaf order, the triangles (their places in leaf order) of the leaves whose
    /// boxes meet the box `b`, until `visit` returns `true`; whether it did.
    fn visit_in_box(&self, b: &IBox, visit: impl FnMut(usize) -> bool) -> bool {
        self.visit_where(|node| !disjoint(node, b), visit)
    }

    /// Visits, in leaf order, the triangles (their places in leaf order) of the leaves that
    /// `keep` keeps, and of no node whose box it refuses, until `visit` returns `true`;
    /// whether it did.
    fn visit_where(
        &self,
        keep: impl Fn(&IBox) -> bool,
        mut visit: impl FnMut(usize) -> bool,
    ) -> bool {
        let mut stack = if self.nodes.is_empty() {
            vec![]
        } else {
            vec![0u32]
        };
        while let Some(i) = stack.pop() {
            let node = &self.nodes[i as usize];
            if !keep(&node.bounds) {
                continue;
            }
            if node.count > 0 {
                let run = node.start as usize..(node.start + node.count) as usize;
                if run.into_iter().any(&mut visit) {
                    return true;
                }
            } else {
                stack.extend([node.start, i + 1]);
            }
        }
        false
    }

    /// The triangles (indices in the list the hierarchy was built from) whose boxes meet
    /// the box `b`, in leaf order.
    pub fn in_box(&self, b: &IBox) -> Vec<u32> {
        let mut out = Vec::new();
        self.visit_in_box(b, |k| {
            if !disjoint(&self.triangles[k].bounds(), b) {
                out.push(self.ids[k]);
            }
            false
        });
        out
    }

    /// The triangles (indices in the list the hierarchy was built from) that some segment
    /// of `shaft` may meet ([`Shaft::may_meet`]), in leaf order. Subtrees whose box no
    /// segment reaches ([`Shaft::may_reach`]) are not visited.
    pub fn in_shaft(&self, shaft: &Shaft) -> Vec<u32> {
        let mut out = Vec::new();
        self.visit_where(
            |node| shaft.may_reach(node),
            |k| {
                if shaft.may_meet(&self.triangles[k]) {
                    out.push(self.ids[k]);
                }
                false
            },
        );
        out
    }

    /// The triangles (indices in the list the hierarchy was built from) whose boxes some
    /// segment of `shaft` may reach ([`Shaft::may_reach`]), in leaf order.
    pub fn boxes_in_shaft(&self, shaft: &Shaft) -> Vec<u32> {
        let mut out = Vec::new();
        self.visit_where(
            |node| shaft.may_reach(node),
            |k| {
                if shaft.may_reach(&self.triangles[k].bounds()) {
                    out.push(self.ids[k]);
                }
                false
            },
        );
        out
    }

    /// Whether some triangle may meet the box `b` (`false` is a proof that none does).
    pub fn may_meet(&self, b: &IBox) -> bool {
        self.may_meet_except(b, None, None)
    }

    /// [`Bvh::may_meet`] for every triangle but `except` (an index in the list the
    /// hierarchy was built from), and only for the triangles that some line of the beam
    /// of `lines` may meet where they are given.
    fn may_meet_except(
        &self,
        b: &IBox,
        mut lines: Option<&mut LineTests<'_>>,
        except: Option<u32>,
    ) -> bool {
        let skip = except.map(|e| self.slots[e as usize] as usize);
        self.visit_in_box(b, |k| {
            let t = &self.triangles[k];
            Some(k) != skip && t.may_meet(b) && lines.as_deref_mut().is_none_or(|l| !l.misses(k, t))
        })
    }

    /// The first range of parameters in `window` where some ray of `beam` may meet a
    /// triangle: `None` is a proof that no ray of the beam meets one there. The window is
    /// clipped to the hierarchy's box and halved, nearer half first, while the points of
    /// the beam over a piece may meet a triangle ([`Bvh::may_meet`]), at most
    /// 10 times.
    pub fn beam_first(&self, beam: &Beam, window: Interval<f64>) -> Option<Interval<f64>> {
        self.beam_first_except(beam, window, None)
    }

    /// [`Bvh::beam_first`] for every triangle but `except` (an index in the list the
    /// hierarchy was built from).
    pub fn beam_first_except(
        &self,
        beam: &Beam,
        window: Interval<f64>,
        except: Option<u32>,
    ) -> Option<Interval<f64>> {
        let t = beam.t_range_within(&self.bounds()?, window)?;
        let mut lines = LineTests {
            beam,
            known: FxHashMap::default(),
        };
        self.beam_piece(&mut lines, t, (BEAM_DEPTH, except))
    }

    /// A triangle that every ray of `beam` crosses inside `window`, and the enclosure of
    /// the crossings' parameters ([`Triangle::covers`]); tried on the triangle that the
    /// beam's central ray crosses first. `None` where none is proven.
    pub fn covering(&self, beam: &Beam, window: Interval<f64>) -> Option<(Interval<f64>, u32)> {
        let id = self.first_crossing(&beam.central_ray(), window).triangle?;
        self.triangle(id).covers(beam, window).map(|t| (t, id))
    }

    /// The first crossing of every ray of `beam` inside `window`, where one triangle is
    /// proven to hold it: every ray crosses that triangle ([`Bvh::covering`]) and no other
    /// triangle meets the beam before the end of those crossings ([`Bvh::beam_first_except`]).
    pub fn beam_hit(&self, beam: &Beam, window: Interval<f64>) -> Option<(Interval<f64>, u32)> {
        let (t, id) = self.covering(beam, window)?;
        let before = Interval::new_unchecked(window.inf(), t.sup());
        self.beam_first_except(beam, before, Some(id))
            .is_none()
            .then_some((t, id))
    }

    fn beam_piece(
        &self,
        lines: &mut LineTests<'_>,
        t: Interval<f64>,
        (depth, except): (u32, Option<u32>),
    ) -> Option<Interval<f64>> {
        if !self.may_meet_except(&lines.beam.points(t), Some(lines), except) {
            return None;
        }
        let mid = t.mid();
        if depth == 0 || !(mid > t.inf() && mid < t.sup()) || !mid.is_finite() {
            return Some(t);
        }
        let near = Interval::new_unchecked(t.inf(), mid);
        let far = Interval::new_unchecked(mid, t.sup());
        self.beam_piece(lines, near, (depth - 1, except))
            .or_else(|| self.beam_piece(lines, far, (depth - 1, except)))
    }
}

/// What is known of a beam's lines against the triangles ([`Triangle::beam_misses`]),
/// computed once per triangle (by its place in leaf order) for all the pieces of the beam's
/// search.
struct LineTests<'b> {
    beam: &'b Beam,
    known: FxHashMap<usize, bool>,
}

impl LineTests<'_> {
    /// Whether every line of the beam passes outside the triangle `t` at place `k`.
    fn misses(&mut self, k: usize, t: &Triangle) -> bool {
        *self
            .known
            .entry(k)
            .or_insert_with(|| t.beam_misses(self.beam))
    }
}

/// Builds the subtree of `order` (indices into `triangles`) at the end of `nodes`.
fn build(triangles: &[Triangle], order: &mut [u32], offset: u32, nodes: &mut Vec<Node>) {
    let me = nodes.len();
    let bounds = order
        .iter()
        .map(|&i| triangles[i as usize].bounds())
        .reduce(|a, b| hull(&a, &b))
        .expect("a node holds a triangle");
    nodes.push(Node {
        bounds,
        start: offset,
        count: order.len() as u32,
    });
    if order.len() <= LEAF_SIZE {
        return;
    }
    let centre = |i: u32| {
        let v = triangles[i as usize].v;
        (v[0] + v[1] + v[2]) / 3.0
    };
    let (lo, hi) = order.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &i| (lo.min(centre(i)), hi.max(centre(i))),
    );
    let axis = (hi - lo).max_position();
    let half = order.len() / 2;
    order.select_nth_unstable_by(half, |&a, &b| centre(a)[axis].total_cmp(&centre(b)[axis]));
    let (left, right) = order.split_at_mut(half);
    build(triangles, left, offset, nodes);
    let second = nodes.len() as u32;
    build(triangles, right, offset + half as u32, nodes);
    nodes[me].start = second;
    nodes[me].count = 0;
}
