//! A shaft: the segments from the points of one box to the points of another (a group of
//! shaded points and a light), and the proofs that a box or a triangle lies outside it.
//!
//! The segments between two boxes fill the convex hull of both (each box is convex), and
//! that hull is the box of both cut by the planes that join an edge of one box to the
//! parallel edge of the other (a supporting plane that touches each box at a single corner
//! is not a face of the hull, so every face is parallel to an axis; Haines and Wallace's
//! shaft). Each such plane is a line in the plane of the two other axes, through a corner
//! of each box's rectangle there ([`Side`]). A point's side of it is the sign of an exact
//! `orient2d` on the doubles given, so the sides' proofs are exact, and a side is kept only
//! where both rectangles are proven on its inner side. A triangle is also proven off the
//! shaft where every corner of both boxes lies strictly on one side of its plane (exact
//! `orient3d`). Where a coordinate could make the predicates overflow or underflow
//! ([`in_range`]), the tests fall back to interval arithmetic on the segments as a beam.

use glam::DVec3;
use interval_core::Interval;

use super::orient::{in_range, orient, orient2d};
use super::triangle::Triangle;
use crate::ibox::{IBox, disjoint, hull};
use crate::ray::Beam;

/// The parameters `[0, 1]` of a segment's points.
const UNIT: Interval<f64> = Interval::new_unchecked(0.0, 1.0);

/// Planes of the hull that join parallel edges of the two boxes: at most one per pair of
/// axes and corner of the rectangles there.
const MOST_SIDES: usize = 12;

/// The segments from the points of a box `from` to the points of a box `to`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Shaft {
    /// The box of both boxes, which holds every segment.
    hull: IBox,
    /// The segments as a beam: origins `from`, directions `to − from`, parameters
    /// [`UNIT`].
    beam: Beam,
    /// The hull's faces parallel to an axis that are not faces of `hull` (the first
    /// `side_count`).
    sides: [Side; MOST_SIDES],
    side_count: usize,
    /// The distinct corners of both boxes (the first `corner_count`): the hull's vertices
    /// are among them.
    corners: [DVec3; 16],
    corner_count: usize,
    /// Whether the corners' coordinates keep the exact predicates exact ([`in_range`]);
    /// where they do not, the shaft has no sides and tests as a beam.
    exact: bool,
}

/// A face of the shaft's hull parallel to the axis other than `i` and `j`: the line through
/// `a` (a corner of one box's rectangle in the plane of axes `i` and `j`) and `b` (the same
/// corner of the other's), with both rectangles on the side where `orient2d(a, b, p)` does
/// not have the sign `outside`.
#[derive(Copy, Clone, Debug, PartialEq)]
struct Side {
    i: usize,
    j: usize,
    a: [f64; 2],
    b: [f64; 2],
    /// The sign of `orient2d(a, b, p)` for the points `p` outside the hull.
    outside: i8,
    /// For each of the two axes, whether a box's innermost point on it (the least of
    /// `orient2d` times `outside`) is its upper end.
    inner_high: [bool; 2],
}

/// The upper end of `iv` where `high`, else its lower end.
fn end(iv: Interval<f64>, high: bool) -> f64 {
    if high { iv.sup() } else { iv.inf() }
}

/// Whether every bound of `b` keeps the exact predicates exact ([`in_range`]).
fn box_in_range(b: &IBox) -> bool {
    b.iter()
        .all(|iv| in_range(DVec3::new(iv.inf(), iv.sup(), 0.0)))
}

/// The four corners of a box's rectangle in the plane of axes `i` and `j`.
fn rectangle(b: &IBox, (i, j): (usize, usize)) -> [[f64; 2]; 4] {
    let (x, y) = (b[i], b[j]);
    [
        [x.inf(), y.inf()],
        [x.sup(), y.inf()],
        [x.inf(), y.sup()],
        [x.sup(), y.sup()],
    ]
}

impl Side {
    /// The line through corner `corner` (upper ends where `true`) of the rectangles of
    /// `from` and `to` in the plane of axes `i` and `j`, where both rectangles are proven on
    /// one side of it and it is not parallel to an axis (those are faces of the boxes' box);
    /// `None` otherwise.
    fn new(from: &IBox, to: &IBox, (i, j): (usize, usize), corner: [bool; 2]) -> Option<Side> {
        let a = [end(from[i], corner[0]), end(from[j], corner[1])];
        let b = [end(to[i], corner[0]), end(to[j], corner[1])];
        if a[0] == b[0] || a[1] == b[1] || !(a.iter().chain(&b).all(|x| x.is_finite())) {
            return None;
        }
        let signs = rectangle(from, (i, j))
            .into_iter()
            .chain(rectangle(to, (i, j)))
            .map(|p| orient2d(a, b, p));
        let (neg, pos) = signs.fold((false, false), |(neg, pos), s| (neg || s < 0, pos || s > 0));
        let outside = match (neg, pos) {
            (true, false) => 1,
            (false, true) => -1,
            _ => return None,
        };
        // `orient2d(a, b, p) = n · (p − a)` with `n = (a_j − b_j, b_i − a_i)`: a box's
        // innermost corner has the lower end on an axis where `outside · n` is positive.
        let n = [a[1] - b[1], b[0] - a[0]];
        let inner_high = n.map(|nk| f64::from(outside) * nk < 0.0);
        Some(Side {
            i,
            j,
            a,
            b,
            outside,
            inner_high,
        })
    }

    /// Whether `p` (its coordinates on the side's two axes) is proven strictly outside.
    fn outside(&self, p: [f64; 2]) -> bool {
        orient2d(self.a, self.b, p) == self.outside
    }

    /// Whether the box `b` is proven strictly outside: its innermost corner is.
    fn box_outside(&self, b: &IBox) -> bool {
        self.outside([
            end(b[self.i], self.inner_high[0]),
            end(b[self.j], self.inner_high[1]),
        ])
    }

    /// Whether every vertex of the triangle is proven strictly outside.
    fn triangle_outside(&self, t: &Triangle) -> bool {
        t.v.iter().all(|v| self.outside([v[self.i], v[self.j]]))
    }
}

impl Shaft {
    /// The segments from the points of `from` to those of `to`.
    pub fn new(from: &IBox, to: &IBox) -> Self {
        let placeholder = Side {
            i: 0,
            j: 1,
            a: [0.0; 2],
            b: [0.0; 2],
            outside: 0,
            inner_high: [false; 2],
        };
        let mut sides = [placeholder; MOST_SIDES];
        let mut side_count = 0;
        let exact = box_in_range(from) && box_in_range(to);
        for axes in [(0, 1), (0, 2), (1, 2)].into_iter().filter(|_| exact) {
            for corner in [[false, false], [true, false], [false, true], [true, true]] {
                // A degenerate box gives the same line for two corners: kept once.
                if let Some(side) = Side::new(from, to, axes, corner)
                    && !sides[..side_count].contains(&side)
                {
                    sides[side_count] = side;
                    side_count += 1;
                }
            }
        }
        let mut corners = [DVec3::ZERO; 16];
        let mut corner_count = 0;
        for b in [from, to] {
            for k in 0..8 {
                let c =
                    DVec3::from_array(std::array::from_fn(|axis| end(b[axis], k >> axis & 1 == 1)));
                if !corners[..corner_count].contains(&c) {
                    corners[corner_count] = c;
                    corner_count += 1;
                }
            }
        }
        Shaft {
            hull: hull(from, to),
            beam: Beam {
                origin: *from,
                dir: std::array::from_fn(|k| to[k] - from[k]),
            },
            sides,
            side_count,
            corners,
            corner_count,
            exact,
        }
    }

    /// Whether every corner of both boxes is proven strictly on one side of the triangle's
    /// plane (exact `orient3d`).
    fn plane_separates(&self, t: &Triangle) -> bool {
        let mut seen = 0i8;
        for c in &self.corners[..self.corner_count] {
            let s = orient(t.v[0], t.v[1], t.v[2], *c);
            if s == 0 || (seen != 0 && s != seen) {
                return false;
            }
            seen = s;
        }
        true
    }

    /// The hull's faces that join edges of the two boxes.
    fn sides(&self) -> &[Side] {
        &self.sides[..self.side_count]
    }

    /// Whether some segment may reach the box `b`: `false` is a proof that none does (`b`
    /// is disjoint from the box of both boxes, or lies outside one of the hull's other
    /// faces; where the predicates could lose exactness, the beam's parameter range inside
    /// `b` is empty).
    #[inline(always)]
    pub fn may_reach(&self, b: &IBox) -> bool {
        if disjoint(b, &self.hull) {
            return false;
        }
        if self.exact && box_in_range(b) {
            !self.sides().iter().any(|s| s.box_outside(b))
        } else {
            self.beam.t_range_within(b, UNIT).is_some()
        }
    }

    /// Whether some segment may meet the triangle: its box is not proven off the box of
    /// both boxes, its vertices are not proven outside one face of the hull, and both boxes
    /// are not proven on one side of its plane (where the predicates could lose
    /// exactness: the lines of the beam are not proven to pass outside it,
    /// [`Triangle::beam_misses`]). `false` is a proof.
    #[inline(always)]
    pub fn may_meet(&self, t: &Triangle) -> bool {
        if disjoint(&t.bounds(), &self.hull) {
            return false;
        }
        if self.exact && t.v.iter().all(|&p| in_range(p)) {
            !self.sides().iter().any(|s| s.triangle_outside(t)) && !self.plane_separates(t)
        } else {
            !t.beam_misses(&self.beam)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ibox::{ival, point_box};
    use glam::DVec3;
    use proptest::prelude::*;

    fn cube(lo: DVec3, side: f64) -> IBox {
        std::array::from_fn(|k| ival(lo[k], lo[k] + side))
    }

    #[test]
    fn a_diagonal_shaft_has_a_side_for_each_bridge() {
        // Unit cubes at the origin and at (4, 4, 4): every pair of axes has two bridges.
        let shaft = Shaft::new(&cube(DVec3::ZERO, 1.0), &cube(DVec3::splat(4.0), 1.0));
        assert_eq!(shaft.sides().len(), 6, "{:?}", shaft.sides());
        // In the box of both, but beside the shaft.
        assert!(!shaft.may_reach(&cube(DVec3::new(4.0, 0.0, 0.0), 1.0)));
        assert!(!shaft.may_reach(&cube(DVec3::new(0.0, 4.0, 2.0), 0.5)));
        assert!(shaft.may_reach(&cube(DVec3::splat(2.0), 0.5)));
        let off = Triangle::new(
            DVec3::new(4.0, 0.0, 0.0),
            DVec3::new(5.0, 0.0, 0.0),
            DVec3::new(4.5, 1.0, 5.0),
        );
        assert!(!shaft.may_meet(&off));
    }

    #[test]
    fn a_point_sees_a_square_through_a_pyramid() {
        let from = point_box(DVec3::ZERO);
        let light: IBox = [ival(-1.0, 1.0), ival(10.0, 10.0), ival(-1.0, 1.0)];
        let shaft = Shaft::new(&from, &light);
        assert_eq!(shaft.sides().len(), 4);
        // Across the pyramid halfway up, and beside it (inside the box of both).
        let across = Triangle::new(
            DVec3::new(-2.0, 5.0, 0.0),
            DVec3::new(2.0, 5.0, 0.1),
            DVec3::new(0.0, 5.0, 2.0),
        );
        let beside = Triangle::new(
            DVec3::new(0.8, 2.0, -0.2),
            DVec3::new(0.9, 2.0, 0.2),
            DVec3::new(0.9, 3.0, 0.0),
        );
        assert!(shaft.may_meet(&across));
        assert!(!shaft.may_meet(&beside));
        assert!(!shaft.may_reach(&[ival(0.6, 1.0), ival(1.0, 3.0), ival(-0.1, 0.1)]));
    }

    #[test]
    fn far_coordinates_fall_back_to_the_beam_test() {
        let far = 1e31;
        let shaft = Shaft::new(&cube(DVec3::splat(far), far), &cube(DVec3::ZERO, 1.0));
        assert!(shaft.sides().is_empty());
        assert!(shaft.may_reach(&cube(DVec3::splat(far * 0.5), far * 0.5)));
        // Outside the box of both boxes.
        assert!(!shaft.may_reach(&cube(DVec3::splat(-3.0), 1.0)));
    }

    #[test]
    fn boxes_in_line_have_no_sides() {
        let shaft = Shaft::new(
            &cube(DVec3::ZERO, 1.0),
            &cube(DVec3::new(0.0, 0.0, 5.0), 1.0),
        );
        assert!(shaft.sides().is_empty());
    }

    #[test]
    fn contacts_on_the_hull_boundary_are_kept() {
        // The shaft from the origin to the square [1, 2]² at z = 0 is flat; (1, 0.5, 0) lies
        // on its side from the origin to (2, 1, 0).
        let shaft = Shaft::new(
            &point_box(DVec3::ZERO),
            &[ival(1.0, 2.0), ival(1.0, 2.0), ival(0.0, 0.0)],
        );
        let touching = Triangle::new(
            DVec3::new(1.0, 0.5, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 0.5, -1.0),
        );
        assert!(shaft.may_meet(&touching));
        let in_its_plane = Triangle::new(
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(3.0, 1.0, 0.0),
            DVec3::new(1.0, 3.0, 0.0),
        );
        assert!(shaft.may_meet(&in_its_plane));
        assert!(shaft.may_reach(&point_box(DVec3::new(2.0, 1.0, 0.0))));
        // Just beside the side: culled.
        let beside = Triangle::new(
            DVec3::new(1.0, 0.25, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 0.5, -1.0),
        );
        assert!(!shaft.may_meet(&beside));
    }

    /// A point of the segment between a point of each box (`s`, `u`, `w` in `[0, 1]`).
    fn segment_point(from: &IBox, to: &IBox, s: [f64; 3], u: [f64; 3], w: f64) -> DVec3 {
        let at = |b: &IBox, f: [f64; 3]| {
            DVec3::from_array(std::array::from_fn(|k| {
                b[k].inf() + f[k] * (b[k].sup() - b[k].inf())
            }))
        };
        at(from, s).lerp(at(to, u), w)
    }

    /// Inside `[0, 1]` by a margin that keeps the rounding of a segment's point inside
    /// the boxes' hull.
    fn unit() -> impl Strategy<Value = f64> {
        0.01..=0.99f64
    }

    /// Boxes on a grid of integers, flat ones (zero width) included, so that shafts meet
    /// points exactly on their faces, edges and corners.
    fn grid_box() -> impl Strategy<Value = IBox> {
        (
            prop::array::uniform3(-2i32..=2),
            prop::array::uniform3(0i32..=2),
        )
            .prop_map(|(lo, w)| {
                std::array::from_fn(|k| ival(f64::from(lo[k]), f64::from(lo[k] + w[k])))
            })
    }

    fn a_box() -> impl Strategy<Value = IBox> {
        (
            prop::array::uniform3(-4.0..4.0f64),
            prop::array::uniform3(0.05..2.0f64),
        )
            .prop_map(|(lo, w)| std::array::from_fn(|k| ival(lo[k], lo[k] + w[k])))
    }

    proptest! {
        /// No box or triangle that holds a point of a segment between the boxes is
        /// proven outside the shaft.
        #[test]
        fn what_holds_a_segment_point_is_never_culled(
            from in a_box(),
            to in a_box(),
            s in prop::array::uniform3(unit()),
            u in prop::array::uniform3(unit()),
            w in unit(),
            size in prop::array::uniform3(1e-9..0.5f64),
            e in prop::array::uniform2(prop::array::uniform3(-0.5..0.5f64)),
        ) {
            let shaft = Shaft::new(&from, &to);
            let p = segment_point(&from, &to, s, u, w);
            let around: IBox = std::array::from_fn(|k| ival(p[k] - size[k], p[k] + size[k]));
            prop_assert!(shaft.may_reach(&around));
            // A triangle with `p` as a vertex.
            let [a, b] = [e[0], e[1]].map(DVec3::from_array);
            prop_assert!(shaft.may_meet(&Triangle::new(p, p + a, p + b)));
        }

        /// Points of segments exactly on the hull's boundary (halves of grid boxes, flat
        /// boxes included: every predicate's zero case) are never culled, nor a triangle
        /// with such a point as a vertex.
        #[test]
        fn exact_contacts_are_never_culled(
            from in grid_box(),
            to in grid_box(),
            s in prop::array::uniform3(0u8..=2),
            u in prop::array::uniform3(0u8..=2),
            w in 0u8..=2,
            e in prop::array::uniform2(prop::array::uniform3(-2i32..=2)),
        ) {
            let half = |x: u8| f64::from(x) / 2.0;
            let p = segment_point(&from, &to, s.map(half), u.map(half), half(w));
            let shaft = Shaft::new(&from, &to);
            prop_assert!(shaft.may_reach(&point_box(p)), "{p:?}");
            let [a, b] = e.map(|v| DVec3::from_array(v.map(f64::from)));
            prop_assert!(shaft.may_meet(&Triangle::new(p, p + a, p + b)), "{p:?} {a:?} {b:?}");
        }

        /// A box proven outside has no point of the boxes' hull: sampled points of the
        /// segments between the two boxes all lie outside it.
        #[test]
        fn a_culled_box_holds_no_sampled_segment(
            from in a_box(),
            to in a_box(),
            probe in a_box(),
        ) {
            let shaft = Shaft::new(&from, &to);
            if !shaft.may_reach(&probe) {
                let steps = [0.0, 0.25, 0.5, 0.75, 1.0];
                for &x in &steps {
                    for &y in &steps {
                        for &z in &steps {
                            for &w in &steps {
                                let p = segment_point(&from, &to, [x, y, z], [1.0 - x, z, y], w);
                                let inside = (0..3).all(|k| probe[k].contains(p[k]));
                                prop_assert!(!inside, "{p:?} in {probe:?}");
                            }
                        }
                    }
                }
            }
        }
    }
}
