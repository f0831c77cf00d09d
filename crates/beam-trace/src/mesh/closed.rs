//! Closed meshes: which way the triangles of a closed surface face.
//!
//! A component of a mesh (triangles connected through shared edges) is **closed** when each
//! of its directed edges `a → b` (vertices compared by their exact coordinates) occurs in
//! exactly one of its triangles and its reverse `b → a` in exactly one other: a closed,
//! consistently oriented surface. Its enclosed volume, `Σ (v0 − o) · ((v1 − o) × (v2 − o)) / 6`
//! over its triangles, is positive where the windings' normals point out of the solid and
//! negative where they point in; the sum is enclosed in outward-rounded interval
//! arithmetic, and only a proven sign counts.

use std::collections::HashMap;

use glam::DVec3;
use interval_core::Interval;

use super::triangle::Triangle;

/// A vertex's exact coordinates (`-0.0` taken as `0.0`).
fn key(p: DVec3) -> [u64; 3] {
    [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits())
}

/// The root of `i` in the union-find forest `parent`, compressing the path.
fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// The directed edges of a set of triangles: each edge `(a, b)` of vertex ids, and the
/// triangle that has it (`None` where more than one does).
pub(super) type Edges = HashMap<(u32, u32), Option<usize>>;

/// Each triangle's vertex ids (vertices compared by their exact coordinates, numbered in
/// the order they first occur), and the directed edges ([`Edges`]).
pub(super) fn corners_and_edges(tris: &[Triangle]) -> (Vec<[u32; 3]>, Edges) {
    let mut ids: HashMap<[u64; 3], u32> = HashMap::new();
    let mut vertex = |p: DVec3| {
        let n = ids.len() as u32;
        *ids.entry(key(p)).or_insert(n)
    };
    let corners: Vec<[u32; 3]> = tris.iter().map(|t| t.v.map(&mut vertex)).collect();
    let mut edges = Edges::new();
    for (t, c) in corners.iter().enumerate() {
        for k in 0..3 {
            edges
                .entry((c[k], c[(k + 1) % 3]))
                .and_modify(|e| *e = None)
                .or_insert(Some(t));
        }
    }
    (corners, edges)
}

/// Per triangle of `tris`, the component it belongs to (numbered from 0 in the order of
/// their first triangles) where that component is closed, `None` where it is not.
pub(crate) fn closed_components(tris: &[Triangle]) -> Vec<Option<u32>> {
    let (corners, edges) = corners_and_edges(tris);
    let mut parent: Vec<usize> = (0..tris.len()).collect();
    let mut open = vec![false; tris.len()];
    for (t, c) in corners.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (c[k], c[(k + 1) % 3]);
            match (edges[&(a, b)], edges.get(&(b, a))) {
                (Some(_), Some(&Some(u))) => {
                    let (ra, rb) = (root(&mut parent, t), root(&mut parent, u));
                    parent[ra] = rb;
                }
                _ => open[t] = true,
            }
        }
    }
    // Per component (by its root): its number, and whether it is closed.
    let mut components: HashMap<usize, (u32, bool)> = HashMap::new();
    for (t, open) in open.iter().enumerate() {
        let r = root(&mut parent, t);
        let next = components.len() as u32;
        components.entry(r).or_insert((next, true)).1 &= !open;
    }
    (0..tris.len())
        .map(|t| {
            let (id, closed) = components[&root(&mut parent, t)];
            closed.then_some(id)
        })
        .collect()
}

/// Per triangle of `tris`: `1` where its winding's normal is proven to point out of the
/// solid its closed component bounds, `-1` where it points in, `0` where its component is
/// not closed or the sign of the component's volume is not proven.
pub fn facing(tris: &[Triangle]) -> Vec<i8> {
    facing_of(tris, &closed_components(tris))
}

/// [`facing`] of `tris` whose closed components are `components`
/// ([`closed_components`]).
pub(crate) fn facing_of(tris: &[Triangle], components: &[Option<u32>]) -> Vec<i8> {
    // Per closed component: its volume about its first vertex.
    let mut volumes: HashMap<u32, (DVec3, Interval<f64>)> = HashMap::new();
    for (tri, c) in tris.iter().zip(components) {
        if let Some(c) = c {
            let entry = volumes
                .entry(*c)
                .or_insert((tri.v[0], Interval::new_unchecked(0.0, 0.0)));
            entry.1 = entry.1.add(tri.signed_volume(entry.0));
        }
    }
    components
        .iter()
        .map(|c| {
            let Some(c) = c else { return 0 };
            let volume = volumes[c].1;
            if volume.is_empty() {
                0
            } else if volume.inf() > 0.0 {
                1
            } else if volume.sup() < 0.0 {
                -1
            } else {
                0
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use proptest::prelude::*;

    use super::facing;
    use crate::ibox::ival;
    use crate::mesh::tests::lumpy_ball;
    use crate::mesh::{MeshIndex, Triangle};
    use crate::shadow::Patch;

    #[test]
    fn closed_surfaces_face_out_and_open_ones_are_not_judged() {
        let ball = lumpy_ball(&[1.0], 4, 6);
        assert!(facing(&ball).iter().all(|&f| f == 1));
        let inside_out: Vec<Triangle> = ball
            .iter()
            .map(|t| Triangle::new(t.v[0], t.v[2], t.v[1]))
            .collect();
        assert!(facing(&inside_out).iter().all(|&f| f == -1));
        // A hole, or one triangle wound the other way: not closed.
        assert!(facing(&ball[1..]).iter().all(|&f| f == 0));
        let mut flipped = ball.clone();
        flipped[3] = Triangle::new(ball[3].v[0], ball[3].v[2], ball[3].v[1]);
        assert!(facing(&flipped).iter().all(|&f| f == 0));
        // Two components, each judged on its own.
        let shifted: Vec<Triangle> = inside_out
            .iter()
            .map(|t| {
                Triangle::new(
                    t.v[0] + DVec3::X * 5.0,
                    t.v[1] + DVec3::X * 5.0,
                    t.v[2] + DVec3::X * 5.0,
                )
            })
            .collect();
        let both: Vec<Triangle> = ball.iter().chain(&shifted).copied().collect();
        let f = facing(&both);
        assert!(f[..ball.len()].iter().all(|&x| x == 1));
        assert!(f[ball.len()..].iter().all(|&x| x == -1));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// A segment to the light that crosses a face turned away from it also meets a
        /// face that is not, wherever it starts (outside the solid or inside it).
        #[test]
        fn faces_turned_away_block_nothing_the_others_do_not(
            r in proptest::collection::vec(0.5f64..1.5, 32),
            inverted in any::<bool>(),
            centre in (-3.0f64..3.0, 2.0f64..5.0, -3.0f64..3.0),
            size in 0.1f64..2.5,
            points in proptest::collection::vec(
                ((-2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0), (0.0f64..1.0, 0.0f64..1.0)), 64),
        ) {
            let mut ball = lumpy_ball(&r, 5, 7);
            if inverted {
                ball = ball.iter().map(|t| Triangle::new(t.v[0], t.v[2], t.v[1])).collect();
            }
            let index = MeshIndex::new([ball.as_slice()]);
            let light = Patch::square(DVec3::new(centre.0, centre.1, centre.2), size, 1);
            let light_box = light.bounding_box();
            let away: Vec<bool> = (0..ball.len() as u32)
                .map(|t| index.turned_away(t, &light_box, &light.corners()))
                .collect();
            prop_assume!(away.iter().any(|&a| a));
            let window = ival(0.0, 1.0);
            for ((x, y, z), (u, v)) in points {
                let from = DVec3::new(x, y, z);
                let dir = light.point(u, v) - from;
                let crosses_away = ball.iter().zip(&away).any(|(t, &a)| {
                    a && t.crossing(from, dir, window).is_some_and(|c| c.proven)
                });
                let may_cross_kept = ball
                    .iter()
                    .zip(&away)
                    .any(|(t, &a)| !a && t.crossing(from, dir, window).is_some());
                prop_assert!(!crosses_away || may_cross_kept, "{from} to {}", from + dir);
            }
        }
    }
}
