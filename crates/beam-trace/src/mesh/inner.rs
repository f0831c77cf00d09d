//! Squares inside closed meshes: occluders that hide only what their mesh hides.
//!
//! A segment from a point inside a solid to a point outside it crosses the solid's boundary.
//! So a polygon inside the solid that a closed mesh bounds blocks no segment to a light
//! outside the solid that the mesh's faces do not block, whatever the segment's other end.
//! Put first into an exact-shadow tree, one such square closes a point's umbra in a few
//! cells where the faces alone cut it into about one cell per face that the point sees
//! across the light (the occluder fusion the faces lack).
//!
//! What is proven, for a component whose every undirected edge lies in exactly two of its
//! faces (a cycle modulo 2: a segment between two points not on it crosses it an even
//! number of times when both have the same parity, odd otherwise):
//!
//! * the square's centre `m` has odd parity: the segment from `m` along the square's axis
//!   to the end of the cast segment crosses an odd number of its faces, every crossing and
//!   every miss of every face proven in interval arithmetic ([`Triangle::crossing`]);
//!   where one is not, the centre is not used. (The cast segment's end is meant to lie past
//!   the component's box; where the rounding of its direction stops it short, a face
//!   crossed beyond the end has a parameter enclosure that reaches past 1, which is not a
//!   proven crossing inside the window, so the centre is refused: a proven answer means no
//!   face lies across the line beyond the end.)
//! * the square meets no face: each face lies proven on one side of the square's plane, or
//!   its section by the plane (a segment, or the face itself in the plane) is proven apart
//!   from the square, along one of the square's axes or across the segment.
//!
//! So the square (connected, off the faces) lies where `m` does: inside. A point of a light
//! outside the component's box has even parity, and every segment from the square to it
//! crosses a face. (Where the mesh intersects itself, that face may be one the exact
//! method leaves out as turned away from the light; its removal of such faces assumes an
//! embedded surface already.)

use glam::{DVec2, DVec3};
use interval_core::Interval;

use super::closed::closed_components;
use super::triangle::{Triangle, bounds_of};
use crate::ibox::{IBox, ipoint, ival};

/// A square inside a closed component of a mesh: its centre has odd crossing parity with
/// the component's faces (every crossing and miss of a segment from it to past the
/// component's box proven), and it meets no face (each proven on one side of its plane or
/// apart from it within the plane), so every segment from it to a point outside the
/// component's box crosses a face.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct InnerSquare {
    /// Its corners, in order around it.
    pub corners: [DVec3; 4],
    /// The axis its plane is perpendicular to (0, 1, 2: x, y, z).
    pub axis: usize,
    /// The box of its component's vertices: a light outside it is outside the solid.
    pub solid: IBox,
}

impl InnerSquare {
    /// The box of its corners.
    pub fn bounds(&self) -> IBox {
        let [a, _, c, _] = self.corners;
        std::array::from_fn(|k| ival(a[k].min(c[k]), a[k].max(c[k])))
    }
}

/// The two axes of the plane perpendicular to `axis`.
fn plane_axes(axis: usize) -> (usize, usize) {
    ((axis + 1) % 3, (axis + 2) % 3)
}

/// The point with coordinate `along` on `axis` and `across` on the plane's axes
/// ([`plane_axes`]).
fn point(axis: usize, along: f64, across: DVec2) -> DVec3 {
    let (u, v) = plane_axes(axis);
    let mut p = DVec3::ZERO;
    p[axis] = along;
    p[u] = across.x;
    p[v] = across.y;
    p
}

/// Where a face meets the plane `x[axis] = c`, in the plane's coordinates: a box of each
/// point that spans the section (a vertex in the plane, or where an edge crosses it).
/// `None`: the face is proven on one side of the plane.
fn section(t: &Triangle, axis: usize, c: f64) -> Option<Vec<[Interval<f64>; 2]>> {
    let (u, v) = plane_axes(axis);
    let h = t.v.map(|p| p[axis] - c);
    if h.iter().all(|&h| h > 0.0) || h.iter().all(|&h| h < 0.0) {
        return None;
    }
    let mut points = Vec::with_capacity(3);
    for i in 0..3 {
        let (a, b) = (t.v[i], t.v[(i + 1) % 3]);
        if a[axis] == c {
            points.push([ipoint(a[u]), ipoint(a[v])]);
        }
        if (a[axis] < c && b[axis] > c) || (a[axis] > c && b[axis] < c) {
            // a + (c − a_k) / (b_k − a_k) · (b − a), enclosed.
            let s = ipoint(c)
                .sub(ipoint(a[axis]))
                .div(ipoint(b[axis]).sub(ipoint(a[axis])));
            let at = |k: usize| ipoint(a[k]).add(s.mul(ipoint(b[k]).sub(ipoint(a[k]))));
            points.push([at(u), at(v)]);
        }
    }
    Some(points)
}

/// A point's projection `p · n`, enclosed.
fn project(p: [Interval<f64>; 2], n: DVec2) -> Interval<f64> {
    p[0].mul(ipoint(n.x)).add(p[1].mul(ipoint(n.y)))
}

/// For a section that is a segment: a normal `n` of it (from its ends' midpoints; any
/// direction gives a sound separation) and an enclosure of the segment's projection onto
/// `n` (the hull of its ends').
fn across(points: &[[Interval<f64>; 2]]) -> Option<(DVec2, Interval<f64>)> {
    let [p, q] = points else { return None };
    let mid = |p: &[Interval<f64>; 2]| DVec2::new(p[0].mid(), p[1].mid());
    let n = (mid(q) - mid(p)).perp();
    (n != DVec2::ZERO && n.is_finite()).then(|| (n, project(*p, n).convex_hull(project(*q, n))))
}

/// About the largest half-size of a square of centre `m` (plane coordinates) apart from
/// the section `points`, along one of the square's axes or across the section (negative
/// where they overlap). A guide for the size only: [`apart`] is the proof.
fn clearance(points: &[[Interval<f64>; 2]], m: DVec2) -> f64 {
    let side = |k: usize, below: bool| {
        points
            .iter()
            .map(|p| {
                if below {
                    m[k] - p[k].sup()
                } else {
                    p[k].inf() - m[k]
                }
            })
            .fold(f64::INFINITY, f64::min)
    };
    let mut best = side(0, false)
        .max(side(0, true))
        .max(side(1, false))
        .max(side(1, true));
    if let Some((n, span)) = across(points) {
        let centre = n.dot(m);
        let gap = (span.inf() - centre).max(centre - span.sup());
        best = best.max(gap / (n.x.abs() + n.y.abs()));
    }
    best
}

/// Whether the rectangle `[lo, hi]` (plane coordinates, its corners exact) is proven apart
/// from the section `points`: along an axis, or across the section's line.
fn apart(points: &[[Interval<f64>; 2]], lo: DVec2, hi: DVec2) -> bool {
    // An empty enclosure (a NaN coordinate) proves nothing.
    if points.is_empty() || points.iter().flatten().any(|c| c.is_empty()) {
        return false;
    }
    let beyond = |k: usize| {
        points.iter().all(|p| p[k].inf() > hi[k]) || points.iter().all(|p| p[k].sup() < lo[k])
    };
    if beyond(0) || beyond(1) {
        return true;
    }
    let Some((n, span)) = across(points) else {
        return false;
    };
    let rect = [(lo.x, lo.y), (hi.x, lo.y), (hi.x, hi.y), (lo.x, hi.y)]
        .map(|(x, y)| project([ipoint(x), ipoint(y)], n))
        .into_iter()
        .reduce(|a, b| a.convex_hull(b))
        .expect("four corners");
    span.disjoint(rect)
}

/// The odd-parity stretches of the line through `(u, v)` along `axis` (plane coordinates
/// `m`): the gaps between its consecutive proven crossings with the faces with an odd
/// number of crossings above them, widest first; `None` where a face's crossing or miss is
/// not proven.
fn inside_stretches(
    faces: &[Triangle],
    axis: usize,
    m: DVec2,
    solid: &IBox,
) -> Option<Vec<[f64; 2]>> {
    let origin = point(axis, solid[axis].inf() - 1.0, m);
    let dir = point(axis, solid[axis].sup() + 1.0 - origin[axis], DVec2::ZERO);
    let window = ival(0.0, 1.0);
    let mut crossings = Vec::new();
    for t in faces {
        if let Some(c) = t.crossing(origin, dir, window) {
            if !c.proven {
                return None;
            }
            // The crossing's coordinate along the axis, enclosed.
            let at = ipoint(origin[axis]).add(c.t.mul(ipoint(dir[axis])));
            crossings.push([at.inf(), at.sup()]);
        }
    }
    crossings.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let n = crossings.len();
    // After the `i`-th crossing (by lower ends), the gap from the highest upper end of the
    // crossings so far to the next lower end: every crossing lies wholly on one side of it,
    // the `n − i − 1` later ones above.
    let mut reach = f64::NEG_INFINITY;
    let mut stretches = Vec::new();
    for i in 0..n.saturating_sub(1) {
        reach = reach.max(crossings[i][1]);
        let next = crossings[i + 1][0];
        if (n - i - 1) % 2 == 1 && reach < next {
            stretches.push([reach, next]);
        }
    }
    stretches.sort_by(|a, b| (b[1] - b[0]).total_cmp(&(a[1] - a[0])));
    Some(stretches)
}

/// The largest square inside the closed component `faces` (box `solid`) perpendicular to
/// `axis`, its centre tried on lines near the middle of the box and half-way to its
/// sides; `None` where no centre is proven inside or no square proven off the faces.
fn square(faces: &[Triangle], solid: &IBox, axis: usize) -> Option<InnerSquare> {
    let (u, v) = plane_axes(axis);
    let mut best: Option<(f64, InnerSquare)> = None;
    // Near the middle and half-way to the sides, off the round fractions where the
    // vertices of symmetric meshes lie (a line through a vertex proves nothing).
    for (fu, fv) in [
        (0.4987, 0.5013),
        (0.2513, 0.4989),
        (0.7489, 0.5011),
        (0.5009, 0.2491),
        (0.4991, 0.7509),
    ] {
        let at = |k: usize, f: f64| solid[k].inf() + f * (solid[k].sup() - solid[k].inf());
        let m = DVec2::new(at(u, fu), at(v, fv));
        let Some(stretches) = inside_stretches(faces, axis, m, solid) else {
            continue;
        };
        let Some(&[a, b]) = stretches.first() else {
            continue;
        };
        let c = 0.5 * (a + b);
        if !(a < c && c < b) {
            continue;
        }
        let sections: Vec<_> = faces.iter().filter_map(|t| section(t, axis, c)).collect();
        let room = sections
            .iter()
            .map(|p| clearance(p, m))
            .fold(f64::INFINITY, f64::min);
        // A margin below the room found, then a check of the square as its corners are.
        let s = 0.99 * room;
        if !(s > 0.0 && s.is_finite()) || best.as_ref().is_some_and(|(size, _)| *size >= s) {
            continue;
        }
        let (lo, hi) = (m - DVec2::splat(s), m + DVec2::splat(s));
        if !sections.iter().all(|p| apart(p, lo, hi)) {
            continue;
        }
        let corners = [(lo.x, lo.y), (hi.x, lo.y), (hi.x, hi.y), (lo.x, hi.y)]
            .map(|(x, y)| point(axis, c, DVec2::new(x, y)));
        best = Some((
            s,
            InnerSquare {
                corners,
                axis,
                solid: *solid,
            },
        ));
    }
    best.map(|(_, sq)| sq)
}

/// The squares inside the closed components of `tris` that have at least `min_faces` faces
/// (what each proves: [`InnerSquare`]): per component and axis the largest found, where
/// it is at least a twentieth of the component's width across the axis.
pub fn inner_squares(tris: &[Triangle], min_faces: usize) -> Vec<InnerSquare> {
    inner_squares_of(tris, &closed_components(tris), min_faces)
}

/// [`inner_squares`] of `tris` whose closed components are `components`
/// ([`closed_components`]).
pub(crate) fn inner_squares_of(
    tris: &[Triangle],
    components: &[Option<u32>],
    min_faces: usize,
) -> Vec<InnerSquare> {
    let count = components
        .iter()
        .flatten()
        .map(|&c| c as usize + 1)
        .max()
        .unwrap_or(0);
    let mut faces: Vec<Vec<Triangle>> = vec![Vec::new(); count];
    for (t, c) in tris.iter().zip(components) {
        if let Some(c) = c {
            faces[*c as usize].push(*t);
        }
    }
    let mut out = Vec::new();
    for faces in faces.iter().filter(|f| f.len() >= min_faces.max(1)) {
        let Some(solid) = bounds_of(faces) else {
            continue;
        };
        for axis in 0..3 {
            let (u, v) = plane_axes(axis);
            let width = solid[u].wid().max(solid[v].wid());
            if let Some(sq) = square(faces, &solid, axis) {
                let side = sq.corners[2][u] - sq.corners[0][u];
                if side >= 0.05 * width {
                    out.push(sq);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use proptest::prelude::*;

    use super::inner_squares;
    use crate::ibox::ival;
    use crate::mesh::Triangle;
    use crate::mesh::tests::lumpy_ball;

    #[test]
    fn a_ball_holds_a_large_square_on_each_axis_and_an_open_mesh_none() {
        let ball = lumpy_ball(&[1.0], 12, 24);
        let squares = inner_squares(&ball, 1);
        assert_eq!(squares.len(), 3);
        for sq in &squares {
            let side = (sq.corners[2] - sq.corners[0]).length() / 2f64.sqrt();
            // The inscribed square of the unit circle has side √2; the polygon's sections
            // are a little smaller.
            assert!(side > 1.2 && side < 2f64.sqrt(), "{sq:?}");
            assert!(sq.corners.iter().all(|p| p.length() < 1.0));
        }
        assert!(inner_squares(&ball[1..], 1).is_empty());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Every segment from a point of an inner square to a point outside the mesh's box
        /// may cross one of its faces (a miss proven for every face would be a square
        /// outside the solid).
        #[test]
        fn segments_from_an_inner_square_to_outside_cross_the_mesh(
            r in proptest::collection::vec(0.4f64..1.6, 40),
            (lat, lon) in (3usize..9, 3usize..12),
            inverted in any::<bool>(),
            shift in (-3.0f64..3.0, -3.0f64..3.0, -3.0f64..3.0),
            points in proptest::collection::vec(
                ((0.0f64..1.0, 0.0f64..1.0), (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)), 48),
        ) {
            let shift = DVec3::new(shift.0, shift.1, shift.2);
            let ball: Vec<Triangle> = lumpy_ball(&r, lat, lon)
                .iter()
                .map(|t| {
                    let [a, b, c] = t.v.map(|p| p + shift);
                    if inverted { Triangle::new(a, c, b) } else { Triangle::new(a, b, c) }
                })
                .collect();
            let squares = inner_squares(&ball, 1);
            prop_assume!(!squares.is_empty());
            for sq in &squares {
                for &((s, t), (x, y, z)) in &points {
                    let [a, b, _, d] = sq.corners;
                    let from = a + (b - a) * s + (d - a) * t;
                    let dir = DVec3::new(x, y, z).normalize_or(DVec3::X);
                    // Far outside the box of the ball (radii at most 1.6).
                    let to = shift + dir * 4.0;
                    let crosses = ball
                        .iter()
                        .any(|tri| tri.crossing(from, to - from, ival(0.0, 1.0)).is_some());
                    prop_assert!(crosses, "{from} to {to} leaves {sq:?} without a crossing");
                }
            }
        }
    }
}
