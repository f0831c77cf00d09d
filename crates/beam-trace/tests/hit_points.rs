//! The shading points the CPU places inside proven root enclosures: on the eye's side of a
//! floating-point sign change of `g`, inside the enclosure, and as close to the exact
//! surface as the rounding of `g` lets a sign change be found, in a lit scene; at the
//! enclosure's near end in an unlit one, which needs no more.

mod ball;

use ball::Ball;
use beam_trace::backend::{Backend, HitQuery, QueryKind, RayQuery};
use beam_trace::root::RootResult;
use beam_trace::{Cpu, Plan};
use glam::DVec3;
use interval_core::Interval;

/// The unit ball seen from a little off its axis.
const UNIT_BALL: Ball = Ball {
    centre: [0.0, 0.0, 0.0],
    r: 1.0,
    eye: [0.3, 0.4, 5.0],
    size: 24,
    fov: 30.0,
};

/// A point light above the eye.
const LIGHT: &str = "[[lights]]\ntype = \"point\"\nposition = [0.0, 100.0, 100.0]\n";

/// The roots of every pixel centre's ray in the view of a ball with the tables `tail`
/// after it, and their hit points: each ray's root enclosure (it contains the exact
/// intersection) and hit point.
fn hit_points(ball: &Ball, tail: &str) -> Vec<(beam_trace::Ray, Interval<f64>, DVec3)> {
    let scene = ball.scene(tail);
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
    hits.iter()
        .zip(&points.values)
        .map(|(&(k, t), hit)| {
            let ray = rays[k].ray;
            let exact = ball
                .exact_t(ray.origin, ray.dir)
                .expect("a hit ray meets the sphere");
            assert!(
                t.inf() <= exact && exact <= t.sup(),
                "{exact} in the enclosure {t:?}"
            );
            (ray, t, hit.point)
        })
        .collect()
}

/// The shading points of a lit ball: each lies inside its enclosure, outside the sphere
/// (the eye's side) and within a small relative distance of the exact intersection.
fn check(centre: [f64; 3], r: f64, eye: [f64; 3], tolerance: f64) {
    let ball = Ball {
        centre,
        r,
        eye,
        size: 24,
        fov: 30.0,
    };
    let c = DVec3::from(centre);
    for (ray, t, point) in hit_points(&ball, LIGHT) {
        let exact = ball.exact_t(ray.origin, ray.dir).expect("a hit");
        // The point is on the ray at a parameter inside the enclosure.
        let tp = (point - ray.origin).dot(ray.dir) / ray.dir.dot(ray.dir);
        let slack = 1e-12 * tp.abs();
        assert!(
            t.inf() - slack <= tp && tp <= t.sup() + slack,
            "{tp} in {t:?}"
        );
        let d = (point - c).length();
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

#[test]
fn unlit_hit_points_of_objects_of_different_colours_are_searched() {
    // A second object of another colour, out of view: the colour of a pixel is then its
    // first root's object's, and the point is searched as in a lit scene.
    let other = "[[surfaces]]\nformula = \"(x - 40)^2 + y^2 + z^2 - 1\"\n\
                 bounds = [[38.0, -2.0, -2.0], [42.0, 2.0, 2.0]]\n\
                 material = { color = [1.0, 0.0, 0.0] }\n";
    let ball = UNIT_BALL;
    for (ray, t, point) in hit_points(&ball, other) {
        let exact = ball.exact_t(ray.origin, ray.dir).expect("a hit");
        let tp = (point - ray.origin).dot(ray.dir) / ray.dir.dot(ray.dir);
        assert!(
            (tp - exact).abs() <= 1e-12 * exact && t.inf() <= tp && tp <= t.sup(),
            "{tp} against {exact} in {t:?}"
        );
    }
}

#[test]
fn unlit_hit_points_are_the_near_ends_of_their_enclosures() {
    let ball = UNIT_BALL;
    for (ray, t, point) in hit_points(&ball, "") {
        assert_eq!(point, ray.at(t.inf()), "enclosure {t:?}");
    }
}

/// The CPU backend's queries for `ball` with the tables `tail` after it.
fn direct_hits_of(ball: &Ball, tail: &str) -> Option<beam_trace::backend::DirectHits> {
    let scene = ball.scene(tail);
    let plan = Plan::for_scene(&scene);
    let prepared = Cpu
        .prepare(&scene, &plan, &[QueryKind::Roots, QueryKind::HitPoints])
        .unwrap_or_else(|e| panic!("{e}"));
    prepared.queries.direct_hits()
}

#[test]
fn direct_hits_are_the_answers_of_hit_points() {
    // Unlit, one surface: every record follows from the enclosure, equal bit for bit to
    // the backend's answer; an enclosure without a finite start is left to the backend.
    let ball = UNIT_BALL;
    let scene = ball.scene("");
    let plan = Plan::for_scene(&scene);
    let q = Cpu
        .prepare(&scene, &plan, &[QueryKind::Roots, QueryKind::HitPoints])
        .unwrap_or_else(|e| panic!("{e}"))
        .queries;
    let direct = q.direct_hits().expect("an unlit scene of one surface");
    let found = hit_points(&ball, "");
    let queries: Vec<HitQuery> = found
        .iter()
        .map(|&(ray, t, _)| HitQuery {
            ray,
            t,
            scope: None,
        })
        .collect();
    let answers = q.hit_points(&queries).unwrap_or_else(|e| panic!("{e}"));
    for (query, answer) in queries.iter().zip(&answers.values) {
        assert_eq!(direct.hit(&query.ray, query.t).as_ref(), Some(answer));
    }
    let open = Interval::new(f64::NEG_INFINITY, 1.0).unwrap();
    assert_eq!(direct.hit(&queries[0].ray, open), None);
    // Lit, or of two surfaces: the backend makes every record (a search, a leaf to tell).
    assert_eq!(direct_hits_of(&ball, LIGHT), None);
    let other = "[[surfaces]]\nformula = \"(x - 40)^2 + y^2 + z^2 - 1\"\n\
                 bounds = [[38.0, -2.0, -2.0], [42.0, 2.0, 2.0]]\n\
                 material = { color = [1.0, 0.0, 0.0] }\n";
    assert_eq!(direct_hits_of(&ball, other), None);
}
