//! A ray function restricted to a beam over a parameter range, compiled on its own
//! (`RayFunction::from_ray_tape`): equal to the whole function inside the region, with a
//! derivative equal to the whole function's there.

use implicit_expr::{Context, RayEvaluator, RayFunction};
use interval_core::Interval;
use proptest::prelude::*;

/// A union of four spheres cut by a slab: `min`/`max` that a small beam decides.
const FORMULA: &str = "max(min(min(sqrt((x-1)^2+y^2+z^2)-0.8, sqrt((x+1)^2+y^2+z^2)-0.8), \
     min(sqrt(x^2+(y-1)^2+z^2)-0.7, sqrt(x^2+(y+1)^2+z^2)-0.7)), z - 0.5)";

fn ival(lo: f64, hi: f64) -> Interval<f64> {
    Interval::new(lo, hi).unwrap()
}

fn ray_function() -> RayFunction {
    let mut ctx = Context::new();
    let f = implicit_expr::parse::parse(&mut ctx, FORMULA, &[]).unwrap();
    RayFunction::new(&ctx, f).unwrap()
}

/// A thin beam along -z through the sphere at x = 1: its origin and direction.
fn beam_through_sphere() -> ([Interval<f64>; 3], [Interval<f64>; 3]) {
    (
        [ival(0.99, 1.01), ival(-0.01, 0.01), ival(3.0, 3.0)],
        [ival(-0.001, 0.001), ival(-0.001, 0.001), ival(-1.0, -1.0)],
    )
}

#[test]
fn a_restricted_tape_compiles_shorter() {
    let f = ray_function();
    let mut ev = RayEvaluator::<Interval<f64>>::new(&f, &[]).unwrap();
    // Over the part of the ray above the sphere.
    let (origin, dir) = beam_through_sphere();
    ev.set_ray(origin, dir);
    ev.restrict(ival(2.0, 3.0));
    let scoped = RayFunction::from_ray_tape(ev.scope()).unwrap();
    // Three of the four spheres are gone, the slab stays (undecided over the range).
    assert!(
        2 * scoped.g_tape().len() < f.g_tape().len() + 4,
        "{} of {}",
        scoped.g_tape().len(),
        f.g_tape().len()
    );
    assert!(scoped.g_dg_tape().len() < f.g_dg_tape().len() / 2);
    assert_eq!(scoped.g_dg_tape().outputs().len(), 2);
}

/// The share of choices the last traced evaluation decided: none before any, or for
/// another range or beam; for the thin beam through the sphere at x = 1, two of the four
/// `min` and `max` (that sphere against the one at x = -1, and that pair against the pair
/// at y = ±1, which lie as far from the beam as each other; the slab's `max` is straddled),
/// and a restriction by that trace drops the three other spheres.
#[test]
fn the_decided_share_is_that_of_the_last_trace() {
    let f = ray_function();
    let mut ev = RayEvaluator::<Interval<f64>>::new(&f, &[]).unwrap();
    let (origin, dir) = beam_through_sphere();
    ev.set_ray(origin, dir);
    let t = ival(2.0, 3.0);
    assert_eq!(ev.decided_share(t), None, "nothing traced yet");
    ev.g(t);
    assert_eq!(
        ev.decided_share(t),
        None,
        "a plain evaluation records nothing"
    );
    ev.g_traced(t);
    let share = ev.decided_share(t).expect("traced over t");
    assert_eq!(share, 0.5);
    assert_eq!(ev.decided_share(ival(2.0, 2.5)), None, "another range");
    let whole = ev.scope().len();
    ev.restrict_traced(t);
    assert!(2 * ev.scope().len() < whole + 4);
    assert_eq!(ev.decided_share(t), None, "the tape has changed");
    ev.g_traced(t);
    ev.set_ray([ival(-1.01, -0.99), origin[1], origin[2]], dir);
    assert_eq!(ev.decided_share(t), None, "another beam");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// A restriction by the choices of the evaluation just made over the same range
    /// (`g_traced`, `restrict_traced`) is the restriction `restrict` makes: the same
    /// enclosure, and the same pruned tape; one over another range, or after the beam
    /// changed, is made afresh.
    #[test]
    fn a_restriction_by_the_last_trace_is_a_fresh_one(
        cx in -1.5f64..1.5, cy in -1.5f64..1.5,
        half in 1e-4f64..0.05,
        t0 in 0.0f64..4.0, w in 0.01f64..1.0, shift in 0.0f64..1.0,
    ) {
        let f = ray_function();
        let origin = [ival(cx - half, cx + half), ival(cy - half, cy + half), ival(3.0, 3.0)];
        let dir = [ival(-half, half), ival(-half, half), ival(-1.0, -1.0)];
        let t = ival(t0, t0 + w);
        let other = ival(t0 + shift, t0 + shift + w);
        let mut fresh = RayEvaluator::<Interval<f64>>::new(&f, &[]).unwrap();
        fresh.set_ray(origin, dir);
        let g = fresh.g(t);
        fresh.restrict(t);
        let mut traced = RayEvaluator::<Interval<f64>>::new(&f, &[]).unwrap();
        traced.set_ray(origin, dir);
        prop_assert_eq!(traced.g_traced(t), g);
        traced.restrict_traced(t);
        prop_assert_eq!(traced.scope().instrs(), fresh.scope().instrs());
        prop_assert_eq!(traced.g(t), fresh.g(t));
        // Traced over `t`, restricted to another range: as `restrict` there.
        let mut stale = RayEvaluator::<Interval<f64>>::new(&f, &[]).unwrap();
        stale.set_ray(origin, dir);
        stale.g_traced(t);
        stale.restrict_traced(other);
        let mut elsewhere = RayEvaluator::<Interval<f64>>::new(&f, &[]).unwrap();
        elsewhere.set_ray(origin, dir);
        elsewhere.restrict(other);
        prop_assert_eq!(stale.scope().instrs(), elsewhere.scope().instrs());
        // Traced for one beam, restricted after another was set: as `restrict` for it.
        let moved = [ival(-cx - half, -cx + half), origin[1], origin[2]];
        let mut rebeamed = RayEvaluator::<Interval<f64>>::new(&f, &[]).unwrap();
        rebeamed.set_ray(origin, dir);
        rebeamed.g_traced(t);
        rebeamed.set_ray(moved, dir);
        rebeamed.restrict_traced(t);
        let mut direct = RayEvaluator::<Interval<f64>>::new(&f, &[]).unwrap();
        direct.set_ray(moved, dir);
        direct.restrict(t);
        prop_assert_eq!(rebeamed.scope().instrs(), direct.scope().instrs());
    }

    /// Inside the region it was restricted to, the scoped function has the whole
    /// function's values and derivatives at points, and its interval enclosures over
    /// parts of the region contain the whole function's point values.
    #[test]
    fn restricted_functions_equal_the_whole_inside_their_region(
        cx in -1.5f64..1.5, cy in -1.5f64..1.5,
        dx in -0.3f64..0.3, dy in -0.3f64..0.3,
        half in 1e-4f64..0.05,
        t0 in 0.0f64..4.0, w in 0.01f64..1.0,
        u in 0.0f64..1.0, v in 0.0f64..1.0, s in 0.0f64..1.0,
    ) {
        let f = ray_function();
        let mut ev = RayEvaluator::<Interval<f64>>::new(&f, &[]).unwrap();
        let origin = [ival(cx - half, cx + half), ival(cy - half, cy + half), ival(3.0, 3.0)];
        let dir = [ival(dx - half, dx + half), ival(dy - half, dy + half), ival(-1.0, -1.0)];
        ev.set_ray(origin, dir);
        let t = ival(t0, t0 + w);
        ev.restrict(t);
        let scoped = RayFunction::from_ray_tape(ev.scope()).unwrap();
        // A ray of the beam, and a parameter of the range.
        let at = |i: Interval<f64>, k: f64| i.inf() + k * (i.sup() - i.inf());
        let o = [at(origin[0], u), at(origin[1], v), 3.0];
        let d = [at(dir[0], v), at(dir[1], u), -1.0];
        let tp = at(t, s);
        let mut whole = RayEvaluator::<f64>::new(&f, &[]).unwrap();
        let mut part = RayEvaluator::<f64>::new(&scoped, &[]).unwrap();
        whole.set_ray(o, d);
        part.set_ray(o, d);
        let (g, dg) = whole.g_dg(tp);
        let (gs, dgs) = part.g_dg(tp);
        prop_assert_eq!(g, gs);
        prop_assert!((dg - dgs).abs() <= 1e-9 * (1.0 + dg.abs()), "{} {}", dg, dgs);
        // The scoped interval evaluation over the beam encloses the point value.
        let mut scoped_ev = RayEvaluator::<Interval<f64>>::new(&scoped, &[]).unwrap();
        scoped_ev.set_ray(origin, dir);
        let (gi, dgi) = scoped_ev.g_dg(t);
        prop_assert!(gi.contains(g), "{:?} {}", gi, g);
        prop_assert!(dgi.contains(dg) || !dg.is_finite(), "{:?} {}", dgi, dg);
    }
}
