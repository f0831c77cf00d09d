//! Faces: the triangles of a mesh merged into convex polygons where neighbours lie in one
//! plane (the quads of a box, the fans of a polygon an exporter triangulated).
//!
//! Two triangles are merged across an edge `a → b` when the edge occurs once each way (the
//! two are consistently wound neighbours and no third triangle shares it), when the other
//! triangle's far vertex lies **exactly** in the face's plane (Shewchuk's adaptive
//! `orient3d`, the `robust` crate, on the vertices' doubles) and when the face stays
//! **strictly convex** (every corner turns the face's way, decided by the exact `orient2d`
//! of the points projected along the axis of the plane's largest normal coordinate: a
//! projection that keeps, for points of one plane, every orientation up to one common
//! sign). Triangles with a coordinate the exact predicates do not cover (below `1e-30` or
//! above `1e30` in magnitude, [`in_range`]) stay faces of their own. A face is then exactly
//! the union of its triangles: the lines it stabs are the lines they stab (up to the shared edges, a set of measure zero), and a method that sorts
//! lines by occluder edges (the exact soft shadows) needs only the face's outline, not the
//! edges between its triangles.

use glam::DVec3;

use super::closed::corners_and_edges;
use super::orient::{Projection, in_range, orient};
use super::triangle::Triangle;

/// The most vertices a face is grown to (a face of many more would only be walked more
/// often by the methods that clip it).
pub const MAX_FACE_VERTICES: usize = 32;

/// The faces of a set of triangles: each triangle's face, and each face's outline.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Faces {
    /// Per triangle (in the order given), the index of its face.
    pub of: Vec<u32>,
    /// Per face, its vertices in order (the winding of its triangles): a strictly convex
    /// polygon, or the triangle itself where it has no merged neighbour (degenerate
    /// triangles included, as given).
    pub outlines: Vec<Vec<DVec3>>,
}

impl Faces {
    /// The number of faces.
    pub fn len(&self) -> usize {
        self.outlines.len()
    }

    /// Whether there is no face (no triangle).
    pub fn is_empty(&self) -> bool {
        self.outlines.is_empty()
    }
}

/// A face being grown: its vertices (ids and points) in order.
struct Growing {
    ids: Vec<u32>,
    points: Vec<DVec3>,
    /// The plane's projection (which keeps the turns of its points up to one sign) and
    /// the sign of a turn of the face's winding there.
    projection: Projection,
    turn: i8,
    /// Three vertices spanning the plane (the first triangle's).
    plane: [DVec3; 3],
}

impl Growing {
    /// Whether inserting `d` between vertices `i` and `i + 1` keeps the face strictly
    /// convex: only the turns at `i`, `d` and `i + 1` change.
    fn convex_with(&self, i: usize, d: DVec3) -> bool {
        let n = self.points.len();
        let at = |k: usize| self.points[k % n];
        let (before, a, b, after) = (at(i + n - 1), at(i), at(i + 1), at(i + 2));
        let t = self.projection;
        t.orient(before, a, d) == self.turn
            && t.orient(a, d, b) == self.turn
            && t.orient(d, b, after) == self.turn
    }
}

/// Whether the exact predicates are exact on `tri`'s vertices ([`in_range`]), so that
/// merging it decides coplanarity and convexity exactly (below `1e-30`, `orient3d` could
/// underflow to zero on triangles that are not coplanar).
fn mergeable(tri: &Triangle) -> bool {
    tri.v.iter().all(|&p| in_range(p))
}

/// The faces of `tris`, where `group` tells which triangles may be merged (those of equal
/// value: one mesh's, facing one way, [`super::facing`]).
pub fn faces<G: PartialEq>(tris: &[Triangle], group: &[G]) -> Faces {
    let (corners, edges) = corners_and_edges(tris);
    let mut of = vec![u32::MAX; tris.len()];
    let mut outlines = Vec::new();
    for (t, tri) in tris.iter().enumerate() {
        if of[t] != u32::MAX {
            continue;
        }
        let id = outlines.len() as u32;
        of[t] = id;
        // A triangle whose normal may vanish (degenerate), or whose coordinates could make
        // the predicates underflow or overflow, stays alone.
        let projection = match Projection::of(tri) {
            Some(p) if mergeable(tri) => p,
            _ => {
                outlines.push(tri.v.to_vec());
                continue;
            }
        };
        let turn = projection.orient(tri.v[0], tri.v[1], tri.v[2]);
        let mut face = Growing {
            ids: corners[t].to_vec(),
            points: tri.v.to_vec(),
            projection,
            turn,
            plane: tri.v,
        };
        let mut grown = turn != 0;
        while grown && face.ids.len() < MAX_FACE_VERTICES {
            grown = false;
            for i in 0..face.ids.len() {
                let (a, b) = (face.ids[i], face.ids[(i + 1) % face.ids.len()]);
                let (Some(Some(_)), Some(&Some(u))) = (edges.get(&(a, b)), edges.get(&(b, a)))
                else {
                    continue;
                };
                if of[u] != u32::MAX || group[u] != group[t] {
                    continue;
                }
                // The neighbour's vertex off the shared edge.
                let Some(k) = (0..3).find(|&k| corners[u][k] != a && corners[u][k] != b) else {
                    continue;
                };
                let (d_id, d) = (corners[u][k], tris[u].v[k]);
                if !mergeable(&tris[u]) {
                    continue;
                }
                let [p, q, r] = face.plane;
                if face.ids.contains(&d_id) || orient(p, q, r, d) != 0 || !face.convex_with(i, d) {
                    continue;
                }
                face.ids.insert(i + 1, d_id);
                face.points.insert(i + 1, d);
                of[u] = id;
                grown = true;
                break;
            }
        }
        outlines.push(face.points);
    }
    Faces { of, outlines }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::mesh::tests::cube;

    fn dv(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    /// Twice the area of a planar polygon.
    fn twice_area(poly: &[DVec3]) -> f64 {
        let n = poly.len();
        (0..n)
            .map(|i| poly[i].cross(poly[(i + 1) % n]))
            .sum::<DVec3>()
            .length()
    }

    #[test]
    fn triangles_out_of_the_predicates_range_are_not_merged() {
        // Where `orient3d` could underflow, each triangle is its own face; a box just inside
        // the range is still six quads.
        let tiny = cube(dv(1e-40, 2e-40, 3e-40), dv(2e-40, 3e-40, 5e-40));
        assert_eq!(faces(&tiny, &[0; 12]).len(), 12);
        let small = cube(dv(1e-20, 2e-20, 3e-20), dv(2e-20, 3e-20, 5e-20));
        assert_eq!(faces(&small, &[0; 12]).len(), 6);
    }

    #[test]
    fn a_box_is_six_quads() {
        let tris = cube(dv(-1.0, 0.5, 2.0), dv(3.0, 1.25, 2.5));
        let f = faces(&tris, &[0; 12]);
        assert_eq!(f.len(), 6);
        for (k, face) in f.outlines.iter().enumerate() {
            assert_eq!(face.len(), 4);
            let members: Vec<usize> = (0..12).filter(|&t| f.of[t] == k as u32).collect();
            assert_eq!(members.len(), 2);
            let sum: f64 = members.iter().map(|&t| twice_area(&tris[t].v)).sum();
            assert!((twice_area(face) - sum).abs() <= 1e-12 * sum);
        }
    }

    #[test]
    fn different_groups_bent_neighbours_and_non_convex_unions_stay_apart() {
        let tris = cube(DVec3::ZERO, DVec3::ONE);
        // Every triangle its own group: nothing merges.
        let groups: Vec<i32> = (0..12).collect();
        assert_eq!(faces(&tris, &groups).len(), 12);
        // Two triangles folded along their shared edge.
        let folded = [
            Triangle::new(dv(0.0, 0.0, 0.0), dv(1.0, 0.0, 0.0), dv(0.0, 1.0, 0.0)),
            Triangle::new(dv(1.0, 0.0, 0.0), dv(1.0, 1.0, 1e-12), dv(0.0, 1.0, 0.0)),
        ];
        assert_eq!(faces(&folded, &[0, 0]).len(), 2);
        // Two coplanar triangles whose union has a reflex corner.
        let dart = [
            Triangle::new(dv(0.0, 0.0, 0.0), dv(2.0, 0.0, 0.0), dv(1.0, 0.2, 0.0)),
            Triangle::new(dv(2.0, 0.0, 0.0), dv(1.0, 1.0, 0.0), dv(1.0, 0.2, 0.0)),
        ];
        assert_eq!(faces(&dart, &[0, 0]).len(), 2);
        // Wound against each other (the shared edge the same way in both): not neighbours.
        let crossed = [
            Triangle::new(dv(0.0, 0.0, 0.0), dv(1.0, 0.0, 0.0), dv(0.0, 1.0, 0.0)),
            Triangle::new(dv(1.0, 0.0, 0.0), dv(0.0, 1.0, 0.0), dv(1.0, 1.0, 0.0)),
        ];
        assert_eq!(faces(&crossed, &[0, 0]).len(), 2);
        // Wound alike, they make the unit square.
        let square = [
            crossed[0],
            Triangle::new(dv(0.0, 1.0, 0.0), dv(1.0, 0.0, 0.0), dv(1.0, 1.0, 0.0)),
        ];
        assert_eq!(faces(&square, &[0, 0]).len(), 1);
    }

    /// The vertices of a convex polygon of `n` corners on the plane through `o` across axis
    /// `axis` (so that every vertex lies on it exactly), and its fan from corner `start`.
    fn fan(
        n: usize,
        start: usize,
        radius: f64,
        o: DVec3,
        axis: usize,
    ) -> (Vec<DVec3>, Vec<Triangle>) {
        let poly: Vec<DVec3> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                let (x, y) = (radius * a.cos(), radius * a.sin());
                o + match axis {
                    0 => dv(0.0, x, y),
                    1 => dv(y, 0.0, x),
                    _ => dv(x, y, 0.0),
                }
            })
            .collect();
        let s = start % n;
        let tris = (1..n - 1)
            .map(|k| Triangle::new(poly[s], poly[(s + k) % n], poly[(s + k + 1) % n]))
            .collect();
        (poly, tris)
    }

    proptest! {
        /// A convex polygon on a plane across an axis, triangulated as a fan from any
        /// corner, merges back into one face with the polygon's corners and area.
        #[test]
        fn fans_of_convex_polygons_merge_back(
            n in 3usize..MAX_FACE_VERTICES,
            start in 0usize..32,
            radius in 0.1f64..10.0,
            axis in 0usize..3,
            offset in (-5.0f64..5.0, -5.0f64..5.0, -5.0f64..5.0),
        ) {
            let o = dv(offset.0, offset.1, offset.2);
            let (poly, tris) = fan(n, start, radius, o, axis);
            let f = faces(&tris, &vec![0; tris.len()]);
            prop_assert_eq!(f.len(), 1);
            let order = |p: &DVec3, q: &DVec3| p.to_array().partial_cmp(&q.to_array()).unwrap();
            let (mut got, mut want) = (f.outlines[0].clone(), poly);
            got.sort_by(order);
            want.sort_by(order);
            prop_assert_eq!(got, want);
        }

        /// Whatever merges (fans on tilted planes, where rounding leaves most vertices off
        /// the first triangle's plane, and boxes), each face is exactly the union of its
        /// triangles: it holds their corners, its area is theirs, and it turns one way.
        #[test]
        fn every_face_is_the_union_of_its_triangles(
            n in 3usize..16,
            start in 0usize..16,
            radius in 0.1f64..10.0,
            tilt in (-1.0f64..1.0, -1.0f64..1.0, 0.1f64..1.0),
            lo in (-5.0f64..5.0, -5.0f64..5.0, -5.0f64..5.0),
            size in (0.01f64..3.0, 0.01f64..3.0, 0.01f64..3.0),
        ) {
            let normal = dv(tilt.0, tilt.1, tilt.2).normalize();
            let (u, v) = (normal.any_orthonormal_vector(), normal.cross(normal.any_orthonormal_vector()));
            let o = dv(lo.0, lo.1, lo.2);
            let (_, flat) = fan(n, start, radius, DVec3::ZERO, 2);
            let mut tris: Vec<Triangle> = flat
                .iter()
                .map(|t| Triangle { v: t.v.map(|p| o + p.x * u + p.y * v) })
                .collect();
            tris.extend(cube(o, o + dv(size.0, size.1, size.2)));
            let f = faces(&tris, &vec![0; tris.len()]);
            for (k, face) in f.outlines.iter().enumerate() {
                let members: Vec<&Triangle> =
                    (0..tris.len()).filter(|&t| f.of[t] == k as u32).map(|t| &tris[t]).collect();
                prop_assert!(!members.is_empty());
                for t in &members {
                    for p in t.v {
                        prop_assert!(face.contains(&p));
                    }
                }
                let sum: f64 = members.iter().map(|t| twice_area(&t.v)).sum();
                prop_assert!((twice_area(face) - sum).abs() <= 1e-9 * sum.max(1e-300));
                if face.len() > 3 {
                    let t = Projection::of(members[0]).expect("a face of several triangles has a plane");
                    let m = face.len();
                    let turns: Vec<i8> =
                        (0..m).map(|i| t.orient(face[i], face[(i + 1) % m], face[(i + 2) % m])).collect();
                    prop_assert!(turns.iter().all(|&s| s != 0 && s == turns[0]));
                }
            }
        }
    }
}
