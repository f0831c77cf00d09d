//! Closed components proven embedded: no two of their triangles meet anywhere but where
//! the mesh joins them (a shared vertex, a shared edge).
//!
//! What the exact shadows take of a closed component (its faces turned away from a light
//! block nothing its other faces do not, a square inside it blocks nothing they do not)
//! holds of the boundary of a solid. A closed, consistently oriented surface that meets
//! itself may have regions wound the other way, where neither holds. So the index judges
//! only components proven embedded: every pair of their triangles whose boxes meet is
//! tested with exact orientation predicates (Shewchuk's adaptive `orient3d` and `orient2d`,
//! the `robust` crate), and any pair that may meet elsewhere than at the vertices and edge
//! they share, or a triangle without area, leaves its component unjudged.
//!
//! The tests by the number of vertices the two triangles share (compared by their exact
//! coordinates):
//!
//! * **none**: apart when one lies strictly on one side of the other's plane; in one plane,
//!   when an edge of one has the other strictly outside; otherwise they meet exactly where
//!   an edge of one meets the other (closed) triangle;
//! * **a vertex `v`**: where one triangle's other two vertices lie on one side of the
//!   other's plane (one of them possibly on it), they meet beyond `v` only along an edge
//!   from `v` in that plane, which does so where it points into the other's angle at `v`;
//!   where each straddles the other's plane, the two sections through `v` overlap exactly
//!   where an opposite edge meets the other triangle; in one plane, the angles at `v` must
//!   be parted by one of their edges;
//! * **an edge**: apart unless the two lie in one plane on the same side of the edge (a
//!   fold);
//! * **all three**: the same triangle twice.

use glam::DVec3;

use super::bvh::Bvh;
use super::orient::{Projection, in_range, orient};
use super::triangle::Triangle;

impl Projection {
    /// Whether the edge `p → q` of a triangle whose third vertex is `r` has every point of
    /// `others` strictly on its outer side.
    fn parts(&self, (p, q, r): (DVec3, DVec3, DVec3), others: &[DVec3]) -> bool {
        let inner = self.orient(p, q, r);
        inner != 0 && others.iter().all(|&x| self.orient(p, q, x) == -inner)
    }

    /// Whether the line through the apex `v` and `a`, of a triangle whose third vertex is
    /// `r`, has every point of `others` on its outer side: strictly, or on the line
    /// beyond `v` (the ray opposite `a`, which meets the triangle only at `v`).
    fn parts_at(&self, (v, a, r): (DVec3, DVec3, DVec3), others: &[DVec3]) -> bool {
        let inner = self.orient(v, a, r);
        inner != 0
            && others.iter().all(|&x| match self.orient(v, a, x) {
                0 => beyond(v, a, x),
                o => o == -inner,
            })
    }

    /// Whether `x` lies in the closed angle of the triangle `(v, a, b)` at `v`.
    fn in_angle(&self, (v, a, b): (DVec3, DVec3, DVec3), x: DVec3) -> bool {
        let turn = self.orient(v, a, b);
        turn != 0 && self.orient(v, a, x) != -turn && self.orient(v, b, x) != turn
    }
}

/// Whether `x`, on the line through `v` and `a`, lies on the other side of `v` from `a`
/// (compared along an axis where `a` and `v` differ: exact).
fn beyond(v: DVec3, a: DVec3, x: DVec3) -> bool {
    (0..3)
        .find(|&k| a[k] != v[k])
        .is_some_and(|k| (a[k] > v[k] && x[k] < v[k]) || (a[k] < v[k] && x[k] > v[k]))
}

/// Whether the segment `p q` meets the closed triangle `t` (a triangle with area).
fn segment_meets(p: DVec3, q: DVec3, t: &Triangle, proj: Projection) -> bool {
    let [a, b, c] = t.v;
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if sp * sq > 0 {
        return false;
    }
    if sp == 0 && sq == 0 {
        // In the triangle's plane: apart where the segment's line or an edge parts them.
        let edges = [(a, b, c), (b, c, a), (c, a, b)];
        let line_parts = {
            let s: Vec<i8> = t.v.iter().map(|&x| proj.orient(p, q, x)).collect();
            s.iter().all(|&x| x > 0) || s.iter().all(|&x| x < 0)
        };
        return !(line_parts || edges.iter().any(|&e| proj.parts(e, &[p, q])));
    }
    // The segment's line crosses the plane once, inside the segment: inside the triangle
    // where it passes every edge on the same side.
    let s = [orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a)];
    !(s.contains(&1) && s.contains(&-1))
}

/// Whether the triangles `s` and `t` may meet elsewhere than at the vertices they share
/// and along the edge they share (see the module documentation).
fn meet_improperly(s: &Triangle, t: &Triangle) -> bool {
    let (Some(ps), Some(pt)) = (Projection::of(s), Projection::of(t)) else {
        return true;
    };
    let shared: Vec<DVec3> = s.v.iter().copied().filter(|p| t.v.contains(p)).collect();
    let rest = |tri: &Triangle| -> Vec<DVec3> {
        tri.v
            .iter()
            .copied()
            .filter(|p| !shared.contains(p))
            .collect()
    };
    let (rs, rt) = (rest(s), rest(t));
    match shared.len() {
        0 => !apart_unshared(s, t, (ps, pt)),
        1 => {
            let v = shared[0];
            let (a, b, c, d) = (rs[0], rs[1], rt[0], rt[1]);
            let (oc, od) = (orient(v, a, b, c), orient(v, a, b, d));
            let (oa, ob) = (orient(v, c, d, a), orient(v, c, d, b));
            if [oa, ob, oc, od] == [0; 4] {
                // One plane: the angles at `v` must be parted by one of their edges.
                let parted = ps.parts_at((v, a, b), &[c, d])
                    || ps.parts_at((v, b, a), &[c, d])
                    || ps.parts_at((v, c, d), &[a, b])
                    || ps.parts_at((v, d, c), &[a, b]);
                return !parted;
            }
            if oc * od >= 0 && (oc, od) != (0, 0) {
                // `t` touches `s`'s plane only along its edges from `v` to its vertices
                // in that plane.
                return [(c, oc), (d, od)]
                    .iter()
                    .any(|&(x, o)| o == 0 && ps.in_angle((v, a, b), x));
            }
            if oa * ob >= 0 && (oa, ob) != (0, 0) {
                return [(a, oa), (b, ob)]
                    .iter()
                    .any(|&(x, o)| o == 0 && pt.in_angle((v, c, d), x));
            }
            if oc * od < 0 && oa * ob < 0 {
                // Each crosses the other's plane along a segment from `v`: they overlap
                // where the nearer end lies in the other triangle.
                return segment_meets(c, d, s, ps) || segment_meets(a, b, t, pt);
            }
            // One lies in the other's plane and the other does not: a triangle without
            // area, which `Projection::of` would have refused; judged unsure.
            true
        }
        2 => {
            let (a, b, c, d) = (shared[0], shared[1], rs[0], rt[0]);
            orient(a, b, c, d) == 0 && ps.orient(a, b, c) * ps.orient(a, b, d) >= 0
        }
        _ => true,
    }
}

/// Whether two triangles with no vertex in common are proven apart.
fn apart_unshared(s: &Triangle, t: &Triangle, (ps, pt): (Projection, Projection)) -> bool {
    let sides = |p: &Triangle, q: &Triangle| q.v.map(|x| orient(p.v[0], p.v[1], p.v[2], x));
    let (of_t, of_s) = (sides(s, t), sides(t, s));
    let strict = |o: [i8; 3]| o.iter().all(|&x| x > 0) || o.iter().all(|&x| x < 0);
    if strict(of_t) || strict(of_s) {
        return true;
    }
    let edges = |p: &Triangle| {
        let [a, b, c] = p.v;
        [(a, b, c), (b, c, a), (c, a, b)]
    };
    if of_t == [0; 3] {
        return edges(s).iter().any(|&e| ps.parts(e, &t.v))
            || edges(t).iter().any(|&e| ps.parts(e, &s.v));
    }
    !(edges(s).iter().any(|&(p, q, _)| segment_meets(p, q, t, pt))
        || edges(t).iter().any(|&(p, q, _)| segment_meets(p, q, s, ps)))
}

/// `components` ([`super::closed::closed_components`]) with every closed component of
/// `tris` that is not proven embedded set to `None`.
pub(crate) fn embedded_components(
    tris: &[Triangle],
    components: &[Option<u32>],
) -> Vec<Option<u32>> {
    let closed: Vec<u32> = (0..tris.len() as u32)
        .filter(|&t| components[t as usize].is_some())
        .collect();
    if closed.is_empty() {
        return components.to_vec();
    }
    let members: Vec<Triangle> = closed.iter().map(|&t| tris[t as usize]).collect();
    let bvh = Bvh::new(&members);
    let mut bad = std::collections::HashSet::new();
    for (i, s) in members.iter().enumerate() {
        let cs = components[closed[i] as usize];
        if bad.contains(&cs) {
            continue;
        }
        // A triangle without area, or with coordinates where the predicates could
        // overflow or underflow, leaves its component unjudged.
        if Projection::of(s).is_none() || !s.v.iter().all(|p| in_range(*p)) {
            bad.insert(cs);
            continue;
        }
        for j in bvh.in_box(&s.bounds()) {
            let j = j as usize;
            let ct = components[closed[j] as usize];
            if j <= i || ct != cs {
                continue;
            }
            if meet_improperly(s, &members[j]) {
                bad.insert(cs);
                break;
            }
        }
    }
    components
        .iter()
        .map(|c| c.filter(|c| !bad.contains(&Some(*c))))
        .collect()
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::mesh::closed::closed_components;
    use crate::mesh::tests::{cube, lumpy_ball};

    fn tri(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Triangle {
        Triangle::new(DVec3::from(a), DVec3::from(b), DVec3::from(c))
    }

    fn judged(tris: &[Triangle]) -> usize {
        embedded_components(tris, &closed_components(tris))
            .iter()
            .filter(|c| c.is_some())
            .count()
    }

    #[test]
    fn balls_and_boxes_are_embedded() {
        let ball = lumpy_ball(&[1.0, 0.7, 1.2, 0.9], 12, 16);
        assert!(closed_components(&ball).iter().all(Option::is_some));
        assert_eq!(judged(&ball), ball.len());
        let cube = cube(DVec3::ZERO, DVec3::ONE);
        assert!(closed_components(&cube).iter().all(Option::is_some));
        assert_eq!(judged(&cube), 12);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

        /// A lumpy ball whose vertices lie at positive distances along their own
        /// directions from the centre is star-shaped, so embedded: every face is judged.
        #[test]
        fn star_shaped_balls_are_embedded(
            radii in proptest::collection::vec(0.3..1.5f64, 1..9),
            lat in 3usize..8,
            lon in 3usize..10,
        ) {
            let ball = lumpy_ball(&radii, lat, lon);
            proptest::prop_assert_eq!(judged(&ball), ball.len());
        }
    }

    #[test]
    fn a_mesh_through_itself_is_not() {
        // A ball with one vertex pushed through the far side: closed and oriented, but its
        // faces cross.
        let mut ball = lumpy_ball(&[1.0], 8, 10);
        let top = ball[0].v[0];
        let pushed = DVec3::new(top.x, -3.0 * top.y, top.z) + DVec3::splat(0.01);
        for t in &mut ball {
            for v in &mut t.v {
                if *v == top {
                    *v = pushed;
                }
            }
        }
        assert!(closed_components(&ball).iter().all(Option::is_some));
        assert_eq!(judged(&ball), 0);
    }

    #[test]
    fn pairs_by_what_they_share() {
        // No vertex shared: apart, crossing, and in one plane apart or overlapping.
        let s = tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert!(!meet_improperly(
            &s,
            &tri([0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0])
        ));
        assert!(meet_improperly(
            &s,
            &tri([0.2, 0.2, -1.0], [0.2, 0.2, 1.0], [3.0, 3.0, 0.0])
        ));
        assert!(!meet_improperly(
            &s,
            &tri([2.0, 0.0, 0.0], [3.0, 0.0, 0.0], [2.0, 1.0, 0.0])
        ));
        assert!(meet_improperly(
            &s,
            &tri([0.2, 0.2, 0.0], [3.0, 0.0, 0.0], [2.0, 1.0, 0.0])
        ));
        // A vertex shared: a fan in one plane, a fold into the other's angle, a tent.
        let v = [0.0, 0.0, 0.0];
        let fan = tri(v, [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]);
        assert!(!meet_improperly(&s, &fan));
        let over = tri(v, [1.0, 0.5, 0.0], [0.5, 1.0, 0.0]);
        assert!(meet_improperly(&s, &over));
        let edge_in = tri(v, [0.3, 0.3, 0.0], [0.0, 0.0, 1.0]);
        assert!(meet_improperly(&s, &edge_in));
        let edge_out = tri(v, [-0.3, -0.3, 0.0], [0.0, 0.0, 1.0]);
        assert!(!meet_improperly(&s, &edge_out));
        let through = tri(v, [0.4, 0.4, -1.0], [0.4, 0.4, 1.0]);
        assert!(meet_improperly(&s, &through));
        let beside = tri(v, [-0.4, -0.4, -1.0], [-0.4, -0.4, 1.0]);
        assert!(!meet_improperly(&s, &beside));
        // An edge shared: a fold in one plane, a hinge, flat neighbours.
        let (a, b) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert!(meet_improperly(&s, &tri(b, a, [0.2, 0.2, 0.0])));
        assert!(!meet_improperly(&s, &tri(b, a, [1.0, 1.0, 0.5])));
        assert!(!meet_improperly(&s, &tri(b, a, [1.0, 1.0, 0.0])));
        // The same triangle, and one without area.
        assert!(meet_improperly(&s, &s));
        assert!(meet_improperly(
            &s,
            &tri([5.0, 5.0, 5.0], [6.0, 6.0, 6.0], [7.0, 7.0, 7.0])
        ));
    }
}
