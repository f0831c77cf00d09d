//! The shading points the CPU places inside proven root enclosures: on the eye's side of a
//! floating-point sign change of `g`, inside the enclosure, and as close to the exact
//! surface as the rounding of `g` lets a sign change be found.

use beam_trace::backend::{Backend, HitQuery, QueryKind, RayQuery};
use beam_trace::root::RootResult;
use beam_trace::{Cpu, Plan, Scene};
use glam::DVec3;
use interval_core::Interval;

/// A sphere of radius `r` around `centre`, seen by a 24 x 24 camera from `eye`.
fn sphere(centre: [f64; 3], r: f64, eye: [f64; 3]) -> Scene {
    let [cx, cy, cz] = centre;
    let text = format!(
        r#"
[camera]
eye = [{:?}, {:?}, {:?}]
look_at = [{cx:?}, {cy:?}, {cz:?}]
fov = 30.0
width = 24
height = 24

[[surfaces]]
formula = "(x - {cx:?})^2 + (y - {cy:?})^2 + (z - {cz:?})^2 - {:?}"
bounds = [[{:?}, {:?}, {:?}], [{:?}, {:?}, {:?}]]
"#,
        eye[0],
        eye[1],
        eye[2],
        r * r,
        cx - 2.0 * r,
        cy - 2.0 * r,
        cz - 2.0 * r,
        cx + 2.0 * r,
        cy + 2.0 * r,
        cz + 2.0 * r,
    );
    Scene::from_toml(&text, "hit_points.toml", None).unwrap_or_else(|e| panic!("{e}"))
}

/// The exact first intersection parameter of `origin + t·dir` with the sphere.
fn exact_t(origin: DVec3, dir: DVec3, centre: DVec3, r: f64) -> Option<f64> {
    let oc = origin - centre;
    let a = dir.dot(dir);
    let b = oc.dot(dir);
    let c = oc.dot(oc) - r * r;
    let disc = b * b - a * c;
    (disc >= 0.0).then(|| (-b - disc.sqrt()) / a)
}

/// Roots of every pixel centre's ray, then their shading points: each lies inside its
/// enclosure, outside the sphere (the eye's side) and within a small relative distance of
/// the exact intersection.
fn check(centre: [f64; 3], r: f64, eye: [f64; 3], tolerance: f64) {
    let scene = sphere(centre, r, eye);
    let plan = Plan::for_scene(&scene);
    let prepared = Cpu
        .prepare(&scene, &plan, &[QueryKind::Roots, QueryKind::HitPoints])
        .unwrap_or_else(|e| panic!("{e}"));
    let q = prepared.queries;
    let cam = &scene.camera;
    let rays: Vec<RayQuery> = (0..cam.height())
        .flat_map(|y| (0..cam.width()).map(move |x| (x, y)))
        .map(|(x, y)| RayQuery {
            ray: cam.ray(f64::from(x) + 0.5, f64::from(y) + 0.5),
            window: Interval::new(0.0, f64::INFINITY).unwrap(),
            scope: None,
        })
        .collect();
    let roots = q.roots(&rays).unwrap_or_else(|e| panic!("{e}"));
    let hits: Vec<(usize, Interval<f64>)> = roots
        .values
        .iter()
        .enumerate()
        .filter_map(|(k, r)| match *r {
            RootResult::Root { t, .. } => Some((k, t)),
            _ => None,
        })
        .collect();
    assert!(hits.len() > 100, "the sphere fills most of the view");
    let queries: Vec<HitQuery> = hits
        .iter()
        .map(|&(k, t)| HitQuery {
            ray: rays[k].ray,
            t,
            scope: None,
        })
        .collect();
    let points = q.hit_points(&queries).unwrap_or_else(|e| panic!("{e}"));
    let c = DVec3::from(centre);
    for (&(k, t), hit) in hits.iter().zip(&points.values) {
        let ray = rays[k].ray;
        let exact = exact_t(ray.origin, ray.dir, c, r).expect("a hit ray meets the sphere");
        assert!(
            t.inf() <= exact && exact <= t.sup(),
            "{exact} in the enclosure {t:?}"
        );
        // The point is on the ray at a parameter inside the enclosure.
        let tp = (hit.point - ray.origin).dot(ray.dir) / ray.dir.dot(ray.dir);
        let slack = 1e-12 * tp.abs();
        assert!(
            t.inf() - slack <= tp && tp <= t.sup() + slack,
            "{tp} in {t:?}"
        );
        let d = (hit.point - c).length();
        assert!(
            (d - r).abs() <= tolerance * r.max(c.length()),
            "point at distance {d} from the centre, radius {r}"
        );
        // On the eye's side: not beyond the exact intersection by more than rounding.
        assert!(tp <= exact + tolerance * exact.abs(), "{tp} before {exact}");
    }
}

#[test]
fn shading_points_lie_on_the_unit_sphere() {
    check([0.0, 0.0, 0.0], 1.0, [0.3, 0.4, 5.0], 1e-12);
}

#[test]
fn shading_points_of_a_small_far_sphere() {
    check([0.25, -0.5, 0.0], 0.01, [0.25, -0.5, 0.045], 1e-11);
}

#[test]
fn shading_points_where_g_is_noisy() {
    // Far from the origin the formula's terms are ~1e8 and cancel to a value of ~1: its
    // floating-point values change sign many times near the surface.
    check([1.0e4, 0.0, 0.0], 1.0, [1.0e4, 0.0, 6.0], 1e-11);
}
