//! The exact method against closed forms (squares parallel to a square light and to the
//! receiver: the blocked part is the light's overlap with the occluders' central
//! projections, rectangles) and against dense stratified segment tests (triangles in any
//! position, occluders reaching behind the receiver or through the light's plane).

use glam::DVec3;

use super::*;
use crate::shadow::Patch;

/// The square light of side 1 at height 2 above the origin, the floor `y = 0`.
fn setup() -> (Patch, Plane) {
    let light = Patch::square(DVec3::new(0.0, 2.0, 0.0), 1.0, 1);
    let floor = Plane {
        point: DVec3::ZERO,
        normal: DVec3::Y,
    };
    (light, floor)
}

/// An axis-aligned horizontal rectangle `[x0, x1] × [z0, z1]` at height `h`.
pub(super) fn rect(x0: f64, x1: f64, z0: f64, z1: f64, h: f64) -> Vec<DVec3> {
    vec![
        DVec3::new(x0, h, z0),
        DVec3::new(x1, h, z0),
        DVec3::new(x1, h, z1),
        DVec3::new(x0, h, z1),
    ]
}

/// `[a0, a1] × [b0, b1]` as a closed interval pair.
type Rect = [(f64, f64); 2];

fn overlap(a: Rect, b: Rect) -> Rect {
    [
        (a[0].0.max(b[0].0), a[0].1.min(b[0].1)),
        (a[1].0.max(b[1].0), a[1].1.min(b[1].1)),
    ]
}

fn area(r: Rect) -> f64 {
    (r[0].1 - r[0].0).max(0.0) * (r[1].1 - r[1].0).max(0.0)
}

/// The central projection from `x` (on the floor) onto the light's plane `y = 2` of the
/// rectangle `[x0, x1] × [z0, z1]` at height `h`.
fn projected(x: DVec3, r: Rect, h: f64) -> Rect {
    let t = 2.0 / h;
    let p = |c: f64, o: f64| o + (c - o) * t;
    [
        (p(r[0].0, x.x), p(r[0].1, x.x)),
        (p(r[1].0, x.z), p(r[1].1, x.z)),
    ]
}

const LIGHT: Rect = [(-0.5, 0.5), (-0.5, 0.5)];

/// Points of the floor: under the occluders, in the penumbrae and outside.
fn floor_points() -> Vec<DVec3> {
    let mut v = Vec::new();
    for i in -12..=12 {
        for k in -12..=12 {
            v.push(DVec3::new(0.17 * f64::from(i), 0.0, 0.13 * f64::from(k)));
        }
    }
    v
}

#[test]
fn a_square_parallel_to_the_light_matches_the_closed_form() {
    let (light, floor) = setup();
    let r: Rect = [(-0.3, 0.4), (-0.2, 0.25)];
    let h = 1.0;
    let occ = [rect(r[0].0, r[0].1, r[1].0, r[1].1, h)];
    let mut ex = ExactShadows::new(light, floor, &occ, 7).unwrap();
    for x in floor_points() {
        let got = ex.visible_fraction(x, Some(DVec3::Y)).unwrap();
        let want = 1.0 - area(overlap(LIGHT, projected(x, r, h)));
        assert!((got - want).abs() < 1e-9, "at {x}: {got} against {want}");
    }
    let w = ex.work();
    assert_eq!(w.queries, floor_points().len() as u64);
    assert_eq!(
        w.merges, 1,
        "one occluder: one expansion, reused by every query"
    );
}

/// Lambert's formula over the visible fragments: the light's form factor less that of the
/// hidden rectangle (the occluder's projection clipped by the light), each a rectangle
/// parallel to the floor whose form factor the formula's own tests check against the
/// closed form.
#[test]
fn the_irradiance_of_the_visible_parts_is_the_light_less_the_hidden_rectangle() {
    let (light, floor) = setup();
    let r: Rect = [(-0.3, 0.4), (-0.2, 0.25)];
    let h = 1.0;
    let occ = [rect(r[0].0, r[0].1, r[1].0, r[1].1, h)];
    let mut ex = ExactShadows::new(light, floor, &occ, 7).unwrap();
    let factor = |x: DVec3, q: Rect| {
        if area(q) == 0.0 {
            return 0.0;
        }
        form_factor(x, DVec3::Y, &rect(q[0].0, q[0].1, q[1].0, q[1].1, 2.0))
    };
    let mut shaded = 0;
    for x in floor_points() {
        let got = ex.visible_irradiance(x, DVec3::Y * 3.0).unwrap();
        let whole = factor(x, LIGHT);
        let hidden = factor(x, overlap(LIGHT, projected(x, r, h)));
        assert!((got.unoccluded - whole).abs() < 1e-12, "at {x}");
        assert!(
            (got.visible - (whole - hidden)).abs() < 1e-9,
            "at {x}: {} against {}",
            got.visible,
            whole - hidden
        );
        shaded += usize::from(hidden > 0.0);
    }
    assert!(shaded > 50, "{shaded}");
    // Nothing above a receiver facing away.
    let none = ex.visible_irradiance(DVec3::ZERO, -DVec3::Y).unwrap();
    assert_eq!((none.visible, none.unoccluded), (0.0, 0.0));
}

#[test]
fn two_overlapping_squares_match_the_closed_form() {
    let (light, floor) = setup();
    let (ra, ha): (Rect, f64) = ([(-0.6, 0.1), (-0.3, 0.3)], 1.2);
    let (rb, hb): (Rect, f64) = ([(-0.2, 0.5), (-0.1, 0.6)], 0.7);
    let occ = [
        rect(ra[0].0, ra[0].1, ra[1].0, ra[1].1, ha),
        rect(rb[0].0, rb[0].1, rb[1].0, rb[1].1, hb),
    ];
    for seed in [1, 2, 3] {
        let mut ex = ExactShadows::new(light, floor, &occ, seed).unwrap();
        for x in floor_points() {
            let got = ex.visible_fraction(x, None).unwrap();
            let (pa, pb) = (projected(x, ra, ha), projected(x, rb, hb));
            let blocked = area(overlap(LIGHT, pa)) + area(overlap(LIGHT, pb))
                - area(overlap(overlap(LIGHT, pa), pb));
            let want = 1.0 - blocked;
            assert!(
                (got - want).abs() < 1e-9,
                "seed {seed} at {x}: {got} against {want}"
            );
        }
    }
}

/// The visible fraction by `n × n` stratified segments (cell centres), each tested against
/// every occluder triangle (fan) in floating point.
fn sampled(light: &Patch, occ: &[Vec<DVec3>], x: DVec3, n: usize) -> f64 {
    let hits = |o: DVec3, d: DVec3, t: [DVec3; 3]| {
        // Möller–Trumbore on the segment o + s·d, s ∈ (0, 1).
        let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
        let p = d.cross(e2);
        let det = e1.dot(p);
        if det.abs() < 1e-300 {
            return false;
        }
        let tv = o - t[0];
        let u = tv.dot(p) / det;
        let q = tv.cross(e1);
        let v = d.dot(q) / det;
        let s = e2.dot(q) / det;
        (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && s > 0.0 && s < 1.0
    };
    let mut free = 0;
    for i in 0..n {
        for k in 0..n {
            let l = light.point((i as f64 + 0.5) / n as f64, (k as f64 + 0.5) / n as f64);
            let blocked = occ.iter().any(|poly| {
                (1..poly.len() - 1).any(|j| hits(l, x - l, [poly[0], poly[j], poly[j + 1]]))
            });
            free += usize::from(!blocked);
        }
    }
    free as f64 / (n * n) as f64
}

#[test]
fn triangles_anywhere_match_dense_segment_sampling() {
    let (light, floor) = setup();
    let occ = vec![
        // A tilted triangle.
        vec![
            DVec3::new(-0.4, 0.8, -0.3),
            DVec3::new(0.5, 1.3, 0.0),
            DVec3::new(0.0, 0.9, 0.6),
        ],
        // A triangle reaching below the floor (clipped there: it cannot shadow from behind).
        vec![
            DVec3::new(0.6, -0.5, -0.6),
            DVec3::new(0.9, 0.9, -0.2),
            DVec3::new(0.2, 0.6, -0.9),
        ],
        // A triangle through the light's plane (its part above the light casts nothing).
        vec![
            DVec3::new(-0.8, 1.5, 0.4),
            DVec3::new(-0.3, 2.6, 0.5),
            DVec3::new(-0.6, 1.6, 0.9),
        ],
        // A vertical quadrilateral.
        vec![
            DVec3::new(0.3, 0.4, 0.5),
            DVec3::new(0.7, 0.4, 0.5),
            DVec3::new(0.7, 1.4, 0.5),
            DVec3::new(0.3, 1.4, 0.5),
        ],
    ];
    let mut ex = ExactShadows::new(light, floor, &occ, 11).unwrap();
    let n = 400;
    let mut worst: f64 = 0.0;
    for x in floor_points().into_iter().step_by(7) {
        let got = ex.visible_fraction(x, Some(DVec3::Y)).unwrap();
        let want = sampled(&light, &occ, x, n);
        worst = worst.max((got - want).abs());
        // A sample cell crossed by the shadow's boundary may count wrong: at most the cells
        // along a few edges of length about 1 (in cells of side 1/n).
        assert!(
            (got - want).abs() < 8.0 / n as f64,
            "at {x}: {got} against {want}"
        );
    }
    eprintln!("largest difference from {n}² samples: {worst:.2e}");
}

/// Twelve small triangles around a ring, climbing from height 0.5 to 1.38.
fn ring() -> Vec<Vec<DVec3>> {
    (0..12)
        .map(|i| {
            let a = f64::from(i) * 0.52;
            let c = DVec3::new(0.5 * a.cos(), 0.5 + 0.08 * f64::from(i), 0.5 * a.sin());
            vec![
                c + DVec3::new(0.2, 0.0, 0.0),
                c + DVec3::new(-0.1, 0.05, 0.17),
                c + DVec3::new(-0.1, -0.05, -0.17),
            ]
        })
        .collect()
}

#[test]
fn coherence_and_seeds_change_the_cost_not_the_answer() {
    let (light, floor) = setup();
    let occ = ring();
    let points = floor_points();
    let answers = |seed: u64, reset: bool| {
        let mut ex = ExactShadows::new(light, floor, &occ, seed).unwrap();
        let v: Vec<f64> = points
            .iter()
            .map(|&x| {
                if reset {
                    ex.reset();
                }
                ex.visible_fraction(x, None).unwrap()
            })
            .collect();
        (v, ex.work())
    };
    let (a, wa) = answers(1, false);
    let (b, _) = answers(99, false);
    let (c, wc) = answers(1, true);
    for i in 0..points.len() {
        assert!(
            (a[i] - b[i]).abs() < 1e-9 && (a[i] - c[i]).abs() < 1e-9,
            "{i}"
        );
    }
    assert!(wc.merges > wa.merges, "{wc:?} against {wa:?}");
    // The same seed gives the same tree, counters included.
    assert_eq!(answers(1, false).1, wa);
}

#[test]
fn bad_groups_and_points_are_errors() {
    let (light, floor) = setup();
    let mut ex = ExactShadows::new(light, floor, &[], 1).unwrap();
    assert_eq!(
        ex.visible_fraction(DVec3::new(3.0, 0.0, 1.0), None),
        Ok(1.0)
    );
    assert_eq!(
        ex.visible_fraction(DVec3::new(0.0, 0.5, 0.0), None),
        Err(ExactError::OffReceiver(DVec3::new(0.0, 0.5, 0.0)))
    );
    let through = Plane {
        point: DVec3::new(0.0, 2.0, 0.0),
        normal: DVec3::X,
    };
    assert_eq!(
        ExactShadows::new(light, through, &[], 1).unwrap_err(),
        ExactError::LightCrossesReceiver
    );
    let segment = Patch {
        edge_v: DVec3::ZERO,
        ..light
    };
    assert_eq!(
        ExactShadows::new(segment, floor, &[], 1).unwrap_err(),
        ExactError::DegenerateLight
    );
    // Below the horizon: a receiver facing away sees nothing of the light.
    assert_eq!(ex.visible_fraction(DVec3::ZERO, Some(-DVec3::Y)), Ok(0.0));
}

#[test]
fn a_square_split_into_two_triangles_leaks_no_light_along_the_diagonal() {
    let (light, floor) = setup();
    let r: Rect = [(-0.3, 0.4), (-0.2, 0.25)];
    let h = 1.0;
    let q = rect(r[0].0, r[0].1, r[1].0, r[1].1, h);
    let occ = [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]];
    let mut ex = ExactShadows::new(light, floor, &occ, 5).unwrap();
    for x in floor_points() {
        let got = ex.visible_fraction(x, Some(DVec3::Y)).unwrap();
        let want = 1.0 - area(overlap(LIGHT, projected(x, r, h)));
        assert!((got - want).abs() < 1e-9, "at {x}: {got} against {want}");
    }
}

/// A tree told the box of its query points answers as one without it, with fewer merges
/// where the box is small, and refuses points outside the box and boxes that are none.
#[test]
fn a_region_changes_the_cost_not_the_answer() {
    let (light, floor) = setup();
    // Twelve triangles around a ring, and the two squares of the closed-form tests.
    let mut occ = ring();
    occ.push(rect(-0.3, 0.2, -0.25, 0.3, 1.0));
    occ.push(rect(0.0, 0.6, -0.1, 0.5, 1.4));
    let (mut merges, mut merges_in_regions) = (0, 0);
    // Tiles of 0.34 × 0.26 over the floor points, each its own tree.
    for (ti, tk) in (-3..3).flat_map(|i| (-3..3).map(move |k| (i, k))) {
        let (x0, z0) = (0.34 * f64::from(ti) - 0.17, 0.26 * f64::from(tk) - 0.13);
        let (lo, hi) = (
            DVec3::new(x0, 0.0, z0),
            DVec3::new(x0 + 0.34, 0.0, z0 + 0.26),
        );
        let points: Vec<DVec3> = floor_points()
            .into_iter()
            .filter(|x| lo.cmple(*x).all() && x.cmple(hi).all())
            .collect();
        let mut plain = ExactShadows::new(light, floor, &occ, 5).unwrap();
        let mut boxed = ExactShadows::new(light, floor, &occ, 5).unwrap();
        boxed.set_region(lo, hi).unwrap();
        for &x in &points {
            let (a, b) = (
                plain.visible_fraction(x, Some(DVec3::Y)).unwrap(),
                boxed.visible_fraction(x, Some(DVec3::Y)).unwrap(),
            );
            assert!((a - b).abs() < 1e-9, "at {x}: {a} against {b}");
        }
        merges += plain.work().merges;
        merges_in_regions += boxed.work().merges;
        let outside = hi + DVec3::new(0.01, 0.0, 0.0);
        assert_eq!(
            boxed.visible_fraction(outside, None),
            Err(ExactError::OutsideRegion(outside))
        );
    }
    assert!(
        merges_in_regions < merges,
        "{merges_in_regions} merges in regions against {merges}"
    );
    let mut ex = ExactShadows::new(light, floor, &occ, 5).unwrap();
    let (lo, hi) = (DVec3::ONE, DVec3::ZERO);
    assert_eq!(ex.set_region(lo, hi), Err(ExactError::BadRegion(lo, hi)));
    let nan = DVec3::new(f64::NAN, 0.0, 0.0);
    assert!(ex.set_region(nan, DVec3::ONE).is_err());
}

/// Squares inside a closed mesh, put first, change the size of the trees, not the
/// fractions: on a lumpy ball of 200 faces above the floor, the same fractions to 1e-9 at
/// the floor points under it, with a fraction of the nodes.
#[test]
fn squares_inside_a_closed_mesh_change_the_cost_not_the_answer() {
    let (light, floor) = setup();
    let radii: Vec<f64> = (0..97)
        .map(|i| 0.65 + 0.05 * (f64::from(i) * 1.7).sin())
        .collect();
    let ball: Vec<crate::mesh::Triangle> = crate::mesh::tests::lumpy_ball(&radii, 10, 11)
        .into_iter()
        .map(|t| {
            let [a, b, c] = t.v.map(|p| p + DVec3::new(0.1, 1.1, -0.05));
            crate::mesh::Triangle::new(a, b, c)
        })
        .collect();
    let faces: Vec<Vec<DVec3>> = ball.iter().map(|t| t.v.to_vec()).collect();
    let squares: Vec<Vec<DVec3>> = crate::mesh::inner_squares(&ball, 1)
        .into_iter()
        .filter(|s| s.axis == 1)
        .map(|s| s.corners.to_vec())
        .collect();
    assert_eq!(squares.len(), 1);
    let mut plain = ExactShadows::new(light, floor, &faces, 3).unwrap();
    let mut fused = ExactShadows::with_first(light, floor, &squares, &faces, 3).unwrap();
    let mut umbra = 0;
    for x in floor_points()
        .into_iter()
        .filter(|x| x.x.abs().max(x.z.abs()) < 1.0)
    {
        let (a, b) = (
            plain.visible_fraction(x, Some(DVec3::Y)).unwrap(),
            fused.visible_fraction(x, Some(DVec3::Y)).unwrap(),
        );
        assert!((a - b).abs() < 1e-9, "at {x}: {a} against {b}");
        umbra += usize::from(a < 1e-9);
    }
    assert!(umbra > 10, "{umbra} points in umbra");
    let (p, f) = (plain.work().inner_nodes, fused.work().inner_nodes);
    assert!(2 * f < p, "{f} nodes with the square against {p}");
}

/// A mesh's faces (coplanar neighbours merged, [`crate::mesh::faces`]) change the cost,
/// not the fractions: boxes above the floor, one turned about two axes (its faces' vertices
/// rounded off any plane but its triangles'), the triangles against the faces, the same
/// fractions to 1e-9 at the floor points, with fewer nodes.
#[test]
fn faces_change_the_cost_not_the_answer() {
    let (light, floor) = setup();
    let (sin, cos) = 0.4f64.sin_cos();
    let turned = |p: DVec3| {
        let q = DVec3::new(cos * p.x - sin * p.y, sin * p.x + cos * p.y, p.z);
        DVec3::new(q.x, cos * q.y - sin * q.z, sin * q.y + cos * q.z)
    };
    let mut tris = Vec::new();
    for (lo, hi, turn) in [
        (
            DVec3::new(-0.6, 0.8, -0.5),
            DVec3::new(-0.1, 1.0, 0.3),
            false,
        ),
        (DVec3::new(0.2, 1.2, -0.2), DVec3::new(0.5, 1.3, 0.6), false),
        (
            DVec3::new(-0.2, -0.2, -0.2),
            DVec3::new(0.2, 0.2, 0.2),
            true,
        ),
    ] {
        let place = |p: DVec3| {
            if turn {
                turned(p) + DVec3::new(0.3, 0.6, -0.4)
            } else {
                p
            }
        };
        tris.extend(
            crate::mesh::tests::cube(lo, hi)
                .into_iter()
                .map(|t| crate::mesh::Triangle { v: t.v.map(place) }),
        );
    }
    let faces = crate::mesh::faces(&tris, &vec![0; tris.len()]);
    // The axis-aligned boxes merge into quads; the turned one's quads where rounding
    // left their corners on one plane.
    assert!(faces.len() <= 24 + 12, "{} faces", faces.len());
    let triangles: Vec<Vec<DVec3>> = tris.iter().map(|t| t.v.to_vec()).collect();
    let mut plain = ExactShadows::new(light, floor, &triangles, 5).unwrap();
    let mut fused = ExactShadows::new(light, floor, &faces.outlines, 5).unwrap();
    for x in floor_points() {
        let (a, b) = (
            plain.visible_fraction(x, Some(DVec3::Y)).unwrap(),
            fused.visible_fraction(x, Some(DVec3::Y)).unwrap(),
        );
        assert!((a - b).abs() < 1e-9, "at {x}: {a} against {b}");
    }
    let (p, f) = (plain.work().inner_nodes, fused.work().inner_nodes);
    assert!(f < p, "{f} nodes with the faces against {p}");
}

/// The closed form of [`a_square_parallel_to_the_light_matches_the_closed_form`]'s
/// visible fraction, enclosed in outward-rounded intervals.
fn enclosed_closed_form(x: DVec3, r: Rect, h: f64) -> interval_core::Interval<f64> {
    use interval_core::Interval;
    let p = |v: f64| Interval::point(v).expect("finite");
    let t = p(2.0) / p(h);
    let side = |(lo, hi): (f64, f64), o: f64, light: (f64, f64)| {
        let (a, b) = (p(o) + (p(lo) - p(o)) * t, p(o) + (p(hi) - p(o)) * t);
        let width = b.min(p(light.1)) - a.max(p(light.0));
        width.max(p(0.0))
    };
    p(1.0) - side(r[0], x.x, LIGHT[0]) * side(r[1], x.z, LIGHT[1])
}

/// Proven bounds: they hold the closed form (both enclosures of the same number must
/// meet), stay within `1e-9` of it, and the bounds of trees built in other orders (other
/// seeds, whose fragments are rounded differently) meet too; umbra and lit points are
/// proven as well as penumbra ones.
#[test]
fn proven_bounds_hold_the_closed_form() {
    let (light, floor) = setup();
    let r: Rect = [(-0.6, 0.7), (-0.65, 0.6)];
    let h = 1.0;
    let q = rect(r[0].0, r[0].1, r[1].0, r[1].1, h);
    // Two triangles: the diagonal cuts fragments at angles, whose vertices are rounded.
    let occ = [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]];
    let mut trees: Vec<ExactShadows> = (1..=3)
        .map(|seed| ExactShadows::new(light, floor, &occ, seed).unwrap())
        .collect();
    let (mut penumbra, mut umbra, mut widened) = (0, 0, 0);
    for x in floor_points() {
        let want = enclosed_closed_form(x, r, h);
        let got: Vec<FractionBounds> = trees
            .iter_mut()
            .map(|t| t.visible_bounds(x, Some(DVec3::Y)).unwrap())
            .collect();
        for b in &got {
            assert!(
                b.lower <= want.sup() && want.inf() <= b.upper,
                "at {x}: [{}, {}] against {want:?}",
                b.lower,
                b.upper
            );
            assert!(b.upper - b.lower < 1e-9, "at {x}: {b:?}");
            assert!(b.lower <= b.fraction && b.fraction <= b.upper);
            widened += usize::from(b.upper > b.lower);
        }
        for (a, b) in got.iter().zip(&got[1..]) {
            assert!(
                a.lower <= b.upper && b.lower <= a.upper,
                "at {x}: {a:?} {b:?}"
            );
        }
        penumbra += usize::from(want.inf() > 0.0 && want.sup() < 1.0);
        umbra += usize::from(got[0].upper < 1e-9);
    }
    assert!(
        penumbra > 100 && umbra > 10 && widened > 100,
        "{penumbra} {umbra} {widened}"
    );
}

/// No proof where the tree's answer need not be the point's: an occluder reaching
/// through the receiver's plane (cut there, its cut vertices rounded), or one between the
/// plane and a point above it.
#[test]
fn no_proof_where_occluders_are_cut_or_behind_the_point() {
    let (light, floor) = setup();
    let x = DVec3::new(0.1, 0.0, 0.05);
    let square = rect(-0.3, 0.4, -0.2, 0.25, 1.0);
    let mut plain = ExactShadows::new(light, floor, std::slice::from_ref(&square), 1).unwrap();
    let b = plain.visible_bounds(x, None).unwrap();
    assert!(b.upper - b.lower < 1e-9, "{b:?}");
    // A wall from below the floor up to the light's height's half.
    let wall = vec![
        DVec3::new(0.6, -0.5, -1.0),
        DVec3::new(0.6, -0.5, 1.0),
        DVec3::new(0.6, 1.0, 1.0),
        DVec3::new(0.6, 1.0, -1.0),
    ];
    let mut cut = ExactShadows::new(light, floor, &[square.clone(), wall], 1).unwrap();
    let b = cut.visible_bounds(x, None).unwrap();
    assert_eq!((b.lower, b.upper), (0.0, 1.0));
    // A square just above the floor: in front of points on it, but a point lifted past it
    // (within the plane's tolerance) has it behind.
    let low = rect(-2.0, 2.0, -2.0, 2.0, 1e-12);
    let mut thin = ExactShadows::new(light, floor, &[square, low], 1).unwrap();
    let on = thin.visible_bounds(x, None).unwrap();
    assert_eq!((on.lower, on.upper), (0.0, 0.0));
    let above = thin.visible_bounds(x + DVec3::Y * 1e-11, None).unwrap();
    assert_eq!((above.lower, above.upper), (0.0, 1.0));
}

/// The insertions' light points hold the light's exact corners in their hull, also where
/// the sums `c + e_u` and `c + e_u + e_v` round (each coordinate of each exact corner lies
/// between the points' coordinates of its box), and are the four corners where they do not.
#[test]
fn the_insertions_light_points_enclose_the_exact_corners() {
    let exact = Patch::square(DVec3::new(0.0, 2.0, 0.0), 1.0, 1);
    assert_eq!(super::bsp::enclosing_corners(&exact).len(), 4);
    let light = Patch {
        corner: DVec3::new(0.1, 0.7, 0.3),
        edge_u: DVec3::new(0.2, 0.0, 0.0),
        edge_v: DVec3::new(0.0, 0.0, 0.7),
    };
    let points = super::bsp::enclosing_corners(&light);
    assert!(points.len() > 4, "{points:?}");
    // The exact sum of doubles as a double and its rounding error (TwoSum).
    let two_sum = |a: f64, b: f64| {
        let s = a + b;
        let bb = s - a;
        (s, (a - (s - bb)) + (b - bb))
    };
    for edges in [vec![], vec![light.edge_u], vec![light.edge_v]] {
        for k in 0..3 {
            let (mut s, mut err) = (light.corner[k], 0.0);
            for e in &edges {
                let (t, r) = two_sum(s, e[k]);
                (s, err) = (t, err + r);
            }
            // `s + err` is the exact coordinate (one rounding at most here).
            let below = points.iter().any(|p| p[k] < s || (p[k] == s && err >= 0.0));
            let above = points.iter().any(|p| p[k] > s || (p[k] == s && err <= 0.0));
            assert!(below && above, "corner {edges:?} axis {k}");
        }
    }
}
