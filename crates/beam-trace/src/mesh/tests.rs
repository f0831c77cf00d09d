//! Soundness of the triangle and hierarchy tests against exact integer arithmetic.
//!
//! Coordinates are integers up to `2^20`, so that the signed volumes and the crossing
//! parameter are exact in `i128` while the interval computations in `f64` round (their
//! products reach `2^70`).

use glam::DVec3;
use interval_core::Interval;
use proptest::prelude::*;

use super::{Bvh, MeshIndex, Triangle, read_obj};
use crate::ibox::ival;
use crate::ray::{Beam, Ray};
use crate::root::{Proof, RootResult};

type I3 = [i128; 3];

fn isub(a: I3, b: I3) -> I3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn idot(a: I3, b: I3) -> i128 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn icross(a: I3, b: I3) -> I3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dv(a: I3) -> DVec3 {
    DVec3::new(a[0] as f64, a[1] as f64, a[2] as f64)
}

/// `x <= num / den` exactly (`den > 0`), or `None` where `i128` would overflow.
fn le_ratio(x: f64, num: i128, den: i128) -> Option<bool> {
    if x == 0.0 {
        return Some(0 <= num);
    }
    if x.is_infinite() {
        return Some(x < 0.0);
    }
    // x = m · 2^e exactly.
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i32;
    let frac = (bits & ((1u64 << 52) - 1)) as i128;
    let (m, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1i128 << 52), exp - 1075)
    };
    let m = if x < 0.0 { -m } else { m };
    let lhs = m.checked_mul(den)?;
    if e >= 0 {
        Some(lhs.checked_mul(1i128.checked_shl(e as u32)?)? <= num)
    } else {
        let s = u32::try_from(-e).ok().filter(|&s| s < 120)?;
        Some(lhs <= num.checked_mul(1i128.checked_shl(s)?)?)
    }
}

/// Whether `num / den` lies in `t`, exactly (`den > 0`).
fn ratio_in(t: Interval<f64>, num: i128, den: i128) -> Option<bool> {
    let lo = le_ratio(t.inf(), num, den)?;
    // num/den <= hi  <=>  !(hi < num/den)  <=>  -hi >= -num/den  <=> le_ratio(-hi, -num, den)
    let hi = le_ratio(-t.sup(), -num, den)?;
    Some(lo && hi)
}

/// The exact crossing of the line `o + t·d` with the closed triangle, as `num / den`
/// with `den > 0`, where the line meets it in one point.
fn exact_crossing(v: [I3; 3], o: I3, d: I3) -> Option<(i128, i128)> {
    let [a, b, c] = v.map(|p| isub(p, o));
    let w = [
        idot(d, icross(b, c)),
        idot(d, icross(c, a)),
        idot(d, icross(a, b)),
    ];
    let inside = w.iter().all(|&x| x >= 0) || w.iter().all(|&x| x <= 0);
    let n = icross(isub(b, a), isub(c, a));
    let (num, den) = (idot(n, a), idot(n, d));
    if !inside || den == 0 {
        return None;
    }
    Some(if den < 0 { (-num, -den) } else { (num, den) })
}

/// The triangles of integer vertex triples.
fn triangles(tris: &[[I3; 3]]) -> Vec<Triangle> {
    tris.iter()
        .map(|v| Triangle::new(dv(v[0]), dv(v[1]), dv(v[2])))
        .collect()
}

/// The beam from `o` with the directions `d ± spread`.
fn beam_around(o: I3, d: I3, spread: f64) -> Beam {
    let dir = dv(d);
    Beam {
        origin: crate::ibox::point_box(dv(o)),
        dir: std::array::from_fn(|i| ival(dir[i] - spread, dir[i] + spread)),
    }
}

/// The ray of a point-origin `beam` at the fractions `p` of its direction intervals.
fn ray_in(beam: &Beam, p: &[f64; 3]) -> Ray {
    Ray {
        origin: DVec3::from_array(std::array::from_fn(|i| beam.origin[i].inf())),
        dir: DVec3::from_array(std::array::from_fn(|i| {
            beam.dir[i].inf() + p[i] * (beam.dir[i].sup() - beam.dir[i].inf())
        })),
    }
}

const R: i64 = 1 << 20;

fn coord() -> impl Strategy<Value = i128> {
    (-R..=R).prop_map(i128::from)
}
fn point() -> impl Strategy<Value = I3> {
    [coord(), coord(), coord()]
}
/// Small coordinates as well, so that crossings, edges and planes through the origin are
/// hit often.
fn small_point() -> impl Strategy<Value = I3> {
    [-3i128..=3, -3i128..=3, -3i128..=3]
}
fn any_point() -> impl Strategy<Value = I3> {
    prop_oneof![point(), small_point()]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4096))]

    /// A crossing in the window is never missed, and every proven one is real.
    #[test]
    fn crossings_are_sound(v in [any_point(), any_point(), any_point()], o in any_point(),
                           d in any_point(), segment in any::<bool>()) {
        prop_assume!(d != [0, 0, 0]);
        let tri = Triangle::new(dv(v[0]), dv(v[1]), dv(v[2]));
        let window = if segment { ival(0.0, 1.0) } else { ival(0.0, f64::INFINITY) };
        let got = tri.crossing(dv(o), dv(d), window);
        let exact = exact_crossing(v, o, d);
        let exact_in_window = exact.filter(|&(num, den)| {
            num >= 0 && (!segment || num <= den)
        });
        if let Some((num, den)) = exact_in_window {
            let c = got.expect("a crossing in the window was called a miss");
            let inside = ratio_in(c.t, num, den);
            prop_assume!(inside.is_some());
            prop_assert!(inside.unwrap(), "t = {num}/{den} outside {:?}", c.t);
        }
        if let Some(c) = got && c.proven {
            let (num, den) = exact.expect("a proven crossing of a line that misses");
            prop_assert!(num >= 0 && (!segment || num <= den));
            prop_assert_eq!(ratio_in(c.t, num, den), Some(true));
        }
    }

    /// The hierarchy's first crossing agrees with every triangle taken alone: no crossing
    /// before the result, a proven result holds a crossing, `NoRoot` only without one.
    #[test]
    fn first_crossings_are_sound(tris in proptest::collection::vec(
                                     [small_point(), small_point(), small_point()], 1..40),
                                 o in small_point(), d in small_point()) {
        prop_assume!(d != [0, 0, 0]);
        let bvh = Bvh::new(&triangles(&tris));
        let ray = Ray { origin: dv(o), dir: dv(d) };
        let window = ival(0.0, f64::INFINITY);
        let got = bvh.first_crossing(&ray, window).result;
        // Exact crossings in the window, as f64 enclosures of num/den (exact: small numbers).
        let exact: Vec<(i128, i128)> = tris.iter()
            .filter_map(|&v| exact_crossing(v, o, d))
            .filter(|&(num, _)| num >= 0)
            .collect();
        match got {
            RootResult::NoRoot => prop_assert!(exact.is_empty(), "missed {exact:?}"),
            RootResult::Root { t, proof } => {
                for &(num, den) in &exact {
                    prop_assert_eq!(le_ratio(t.inf(), num, den), Some(true),
                        "crossing {}/{} before {:?}", num, den, t);
                }
                if proof != Proof::Possible {
                    prop_assert!(exact.iter().any(|&(n, dd)| ratio_in(t, n, dd) == Some(true)));
                }
            }
            RootResult::Undecided { .. } => prop_assert!(false, "a mesh search is never undecided"),
        }
    }

    /// A beam called free of triangles has no ray that crosses one.
    #[test]
    fn free_beams_are_free(tris in proptest::collection::vec(
                               [small_point(), small_point(), small_point()], 1..20),
                           o in small_point(), d in small_point(),
                           spread in 0.0f64..0.5, picks in proptest::collection::vec(
                               [0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0], 8)) {
        prop_assume!(d != [0, 0, 0]);
        let bvh = Bvh::new(&triangles(&tris));
        let beam = beam_around(o, d, spread);
        let window = ival(0.0, 50.0);
        if bvh.beam_first(&beam, window).is_none() {
            for p in &picks {
                let hit = bvh.first_crossing(&ray_in(&beam, p), window).result;
                prop_assert!(!matches!(hit, RootResult::Root { proof, .. } if proof != Proof::Possible),
                    "a ray of a free beam crosses a triangle: {hit:?}");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2048))]

    /// What a beam proves of the triangles holds for rays picked inside it: a triangle
    /// missed is crossed by none, a triangle covering it is crossed by each inside the
    /// enclosure, and a proven first hit has no proven crossing of another triangle before
    /// it.
    #[test]
    fn beam_proofs_hold_for_their_rays(tris in proptest::collection::vec(
                                           [small_point(), small_point(), small_point()], 1..12),
                                       o in small_point(), d in small_point(),
                                       spread in 0.0f64..0.3, picks in proptest::collection::vec(
                                           [0.0f64..=1.0, 0.0f64..=1.0, 0.0f64..=1.0], 8)) {
        prop_assume!(d != [0, 0, 0]);
        let list = triangles(&tris);
        let bvh = Bvh::new(&list);
        let beam = beam_around(o, d, spread);
        let window = ival(0.0, 50.0);
        let rays: Vec<Ray> = picks.iter().map(|p| ray_in(&beam, p)).collect();
        let whole = ival(f64::NEG_INFINITY, f64::INFINITY);
        for tri in &list {
            if tri.beam_misses(&beam) {
                for r in &rays {
                    let c = tri.crossing(r.origin, r.dir, whole);
                    prop_assert!(c.is_none_or(|c| !c.proven), "missed, yet {c:?}");
                }
            }
            if let Some(t) = tri.covers(&beam, window) {
                prop_assert!(t.inf() >= 0.0 && t.sup() <= 50.0);
                for r in &rays {
                    let c = tri.crossing(r.origin, r.dir, window);
                    let c = c.expect("a covered ray misses");
                    prop_assert!(c.t.inf() <= t.sup() && c.t.sup() >= t.inf(), "{c:?} outside {t:?}");
                }
            }
        }
        if let Some((t, id)) = bvh.beam_hit(&beam, window) {
            for r in &rays {
                for (k, tri) in list.iter().enumerate() {
                    if k as u32 == id {
                        continue;
                    }
                    if let Some(c) = tri.crossing(r.origin, r.dir, window) && c.proven {
                        prop_assert!(c.t.sup() >= t.inf(), "triangle {k} crossed at {:?} before {t:?}", c.t);
                    }
                }
            }
        }
    }
}

#[test]
fn a_ray_through_a_shared_edge_is_a_possible_crossing_and_never_a_miss() {
    // Two triangles of the square [0, 1]² at z = 0 sharing the diagonal.
    let a = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0));
    let b = Triangle::new(DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0), DVec3::Y);
    let bvh = Bvh::new(&[a, b]);
    let ray = Ray {
        origin: DVec3::new(0.5, 0.5, 2.0),
        dir: DVec3::new(0.0, 0.0, -1.0),
    };
    let r = bvh.first_crossing(&ray, ival(0.0, f64::INFINITY)).result;
    match r {
        RootResult::Root { t, .. } => assert!(t.contains(2.0), "{t:?}"),
        other => panic!("{other:?}"),
    }
    // Off the edge: proven and unique, to a few ulps.
    let ray = Ray {
        origin: DVec3::new(0.7, 0.2, 2.0),
        dir: DVec3::new(0.0, 0.0, -1.0),
    };
    match bvh.first_crossing(&ray, ival(0.0, f64::INFINITY)).result {
        RootResult::Root {
            t,
            proof: Proof::Unique,
        } => assert!(t.contains(2.0) && t.wid() < 1e-14, "{t:?}"),
        other => panic!("{other:?}"),
    }
    // A segment that stops short of the square.
    let short = bvh.first_crossing(&ray, ival(0.0, 1.5)).result;
    assert_eq!(short, RootResult::NoRoot);
}

#[test]
fn a_ray_in_the_plane_of_a_triangle_is_never_called_a_miss() {
    // The ray runs inside the triangle for t in [10, 35]; n · d rounds to an interval
    // around 0 and n · (v0 − o) is exactly 0.
    let tri = Triangle::new(
        DVec3::ZERO,
        DVec3::new(3.0, -3.0, 0.0),
        DVec3::new(0.0, 0.0, 3.0),
    );
    let (o, d) = (DVec3::new(-1.0, 1.0, 0.5), DVec3::new(0.1, -0.1, 0.0));
    let c = tri.crossing(o, d, ival(1.0, 100.0)).expect("not a miss");
    assert!(
        !c.proven && c.t.contains(10.0) && c.t.contains(35.0),
        "{c:?}"
    );
    let c = tri
        .crossing(o, d, ival(0.0, f64::INFINITY))
        .expect("not a miss");
    assert!(c.t.contains(10.0) && c.t.contains(35.0), "{c:?}");
    let bvh = Bvh::new(&[tri]);
    let ray = Ray { origin: o, dir: d };
    assert_ne!(
        bvh.first_crossing(&ray, ival(1.0, 100.0)).result,
        RootResult::NoRoot
    );
    // Nothing is proven of a ray that is not finite.
    let c = tri.crossing(DVec3::new(f64::NAN, 0.0, 0.0), d, ival(0.0, 1.0));
    assert!(c.is_some_and(|c| !c.proven));
}

#[test]
fn only_triangles_proven_flat_are_degenerate() {
    assert!(Triangle::new(DVec3::ZERO, DVec3::ONE, DVec3::splat(2.0)).is_degenerate());
    let tiny = Triangle::new(
        DVec3::ZERO,
        DVec3::new(1e-170, 0.0, 0.0),
        DVec3::new(0.0, 1e-170, 0.0),
    );
    assert!(!tiny.is_degenerate());
}

#[test]
fn first_of_keeps_the_earlier_root_and_the_weaker_proof_where_they_overlap() {
    let root = |lo, hi, proof| RootResult::Root {
        t: ival(lo, hi),
        proof,
    };
    assert_eq!(
        RootResult::NoRoot.first_of(root(1.0, 2.0, Proof::Unique)),
        root(1.0, 2.0, Proof::Unique)
    );
    assert_eq!(
        root(1.0, 2.0, Proof::Unique).first_of(root(3.0, 4.0, Proof::Possible)),
        root(1.0, 2.0, Proof::Unique)
    );
    assert_eq!(
        root(3.0, 4.0, Proof::Unique).first_of(root(1.0, 2.0, Proof::Possible)),
        root(1.0, 2.0, Proof::Possible)
    );
    // Overlapping: from the earlier start to the earlier end, proven by the one ending
    // first.
    assert_eq!(
        root(1.0, 3.0, Proof::Unique).first_of(root(2.0, 4.0, Proof::Possible)),
        root(1.0, 3.0, Proof::Exists)
    );
    assert_eq!(
        root(1.0, 5.0, Proof::Unique).first_of(root(2.0, 4.0, Proof::Possible)),
        root(1.0, 4.0, Proof::Possible)
    );
    let open = RootResult::Undecided { t: ival(2.0, 9.0) };
    assert_eq!(
        open.first_of(root(0.5, 1.0, Proof::Exists)),
        root(0.5, 1.0, Proof::Exists)
    );
    assert_eq!(
        open.first_of(root(1.0, 3.0, Proof::Exists)),
        RootResult::Undecided { t: ival(1.0, 9.0) }
    );
}

#[test]
fn an_obj_cube_reads_as_twelve_triangles_and_bad_files_are_named() {
    let dir = std::env::temp_dir().join(format!("beam-trace-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cube = dir.join("cube.obj");
    let mut text = String::from("o cube\n");
    for x in [0, 1] {
        for y in [0, 1] {
            for z in [0, 1] {
                text += &format!("v {x} {y} {z}\n");
            }
        }
    }
    // Vertices 1..8 as (x, y, z) bits; six quads.
    text += "f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n";
    std::fs::write(&cube, text).unwrap();
    let tris = read_obj(&cube).unwrap();
    assert_eq!(tris.len(), 12);
    let index = MeshIndex::new([tris.as_slice()]);
    assert_eq!(index.bvh().len(), 12);
    let b = index.bvh().bounds().unwrap();
    assert_eq!(b.map(|i| (i.inf(), i.sup())), [(0.0, 1.0); 3]);

    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nf 1 2 9\n").unwrap();
    assert!(read_obj(&bad).is_err());
    assert!(read_obj(&dir.join("missing.obj")).is_err());
    std::fs::write(&bad, "v 0 0 0\n").unwrap();
    assert!(read_obj(&bad).unwrap_err().contains("no triangle"));
    std::fs::remove_dir_all(&dir).ok();
}

/// The 12 triangles of the box `[lo, hi]`, wound outward.
pub(crate) fn cube(lo: DVec3, hi: DVec3) -> Vec<Triangle> {
    let c = |i: usize| {
        DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    };
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    quads
        .iter()
        .flat_map(|q| {
            [
                Triangle::new(c(q[0]), c(q[1]), c(q[2])),
                Triangle::new(c(q[0]), c(q[2]), c(q[3])),
            ]
        })
        .collect()
}

/// A closed surface around the origin: a latitude-longitude grid with single poles,
/// each vertex at its own distance `r[i]` (so not convex), windings facing out.
pub(crate) fn lumpy_ball(r: &[f64], lat: usize, lon: usize) -> Vec<Triangle> {
    let mut radius = r.iter().copied().cycle();
    let north = DVec3::Y * radius.next().unwrap();
    let south = -DVec3::Y * radius.next().unwrap();
    let mut rings = Vec::new();
    for i in 1..lat {
        let theta = std::f64::consts::PI * i as f64 / lat as f64;
        let ring: Vec<DVec3> = (0..lon)
            .map(|j| {
                let phi = std::f64::consts::TAU * j as f64 / lon as f64;
                let d = DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                );
                d * radius.next().unwrap()
            })
            .collect();
        rings.push(ring);
    }
    let mut t = Vec::new();
    for j in 0..lon {
        let k = (j + 1) % lon;
        t.push(Triangle::new(north, rings[0][k], rings[0][j]));
        let last = &rings[lat - 2];
        t.push(Triangle::new(south, last[j], last[k]));
        for i in 0..lat - 2 {
            let (a, b) = (&rings[i], &rings[i + 1]);
            t.push(Triangle::new(a[j], a[k], b[k]));
            t.push(Triangle::new(a[j], b[k], b[j]));
        }
    }
    t
}
