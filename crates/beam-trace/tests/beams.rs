//! The beam tests (rejection, inclusion, EvaluateBox) against analytic answers.

use beam_trace::beam::{BeamSettings, BoxClass, Extent, evaluate_box, inclusion_test, sign_change};
use beam_trace::ray::{Beam, BeamEval, ival, point_box};
use beam_trace::root::RootCounters;
use beam_trace::scene::{Csg, Geometry, Leaf, Material};
use glam::DVec3;
use implicit_expr::Context;
use interval_core::Interval;
use proptest::prelude::*;

fn geometry(formula: &str, r: f64) -> Geometry {
    let mut ctx = Context::new();
    let f = implicit_expr::parse::parse(&mut ctx, formula, &[]).unwrap();
    let leaf = Leaf {
        name: "s".into(),
        node: f,
        material: Material::default(),
        bounds: [ival(-r, r); 3],
        clipped: false,
    };
    Geometry::new(ctx, vec![leaf], vec![Csg::Leaf(0)]).unwrap()
}

/// First root of the unit sphere along `o + t d`, if any (analytic).
fn sphere_root(o: DVec3, d: DVec3) -> Option<f64> {
    let a = d.dot(d);
    let b = 2.0 * o.dot(d);
    let c = o.dot(o) - 1.0;
    let disc = b * b - 4.0 * a * c;
    (disc >= 0.0).then(|| (-b - disc.sqrt()) / (2.0 * a))
}

fn beam(eye: DVec3, dir: DVec3, half: f64) -> Beam {
    Beam {
        origin: point_box(eye),
        dir: std::array::from_fn(|i| ival(dir[i] - half, dir[i] + half)),
    }
}

#[test]
fn sign_change_is_the_modal_meet_test() {
    assert!(sign_change(ival(-2.0, -1.0), ival(1.0, 3.0)));
    assert!(sign_change(ival(1.0, 3.0), ival(-2.0, -0.0)));
    assert!(sign_change(ival(0.0, 1.0), ival(-1.0, 0.0)));
    assert!(!sign_change(ival(-1.0, 1.0), ival(1.0, 3.0)));
    assert!(!sign_change(ival(-2.0, -1.0), ival(-1.0, 3.0)));
    assert!(!sign_change(ival(1.0, 2.0), ival(3.0, 4.0)));
    assert!(!sign_change(Interval::EMPTY, ival(3.0, 4.0)));
}

#[test]
fn central_beam_on_sphere_is_a_hit_with_t_final_around_the_roots() {
    let g = geometry("x^2+y^2+z^2-1", 1.5);
    let mut ev = BeamEval::new(g.ray_function());
    let eye = DVec3::new(0.0, 0.0, 4.0);
    let b = beam(eye, DVec3::new(0.0, 0.0, -1.0), 0.01);
    ev.set_beam(&b);
    let mut c = RootCounters::default();
    let class = evaluate_box(
        &mut ev,
        &[ival(0.0, 10.0)],
        None,
        &BeamSettings::default(),
        &mut c,
    );
    let BoxClass::Hit { t_final } = class else {
        panic!("{class:?}")
    };
    for (dx, dy) in [(-0.01, -0.01), (0.01, 0.01), (0.0, 0.0), (0.01, -0.01)] {
        let t = sphere_root(eye, DVec3::new(dx, dy, -1.0)).unwrap();
        assert!(t_final.contains(t), "{t} not in {t_final:?}");
    }
    assert!(c.g_evals > 0);
}

#[test]
fn beam_beside_the_sphere_is_a_miss_and_a_border_beam_is_undecided() {
    let g = geometry("x^2+y^2+z^2-1", 1.5);
    let mut ev = BeamEval::new(g.ray_function());
    let eye = DVec3::new(0.0, 0.0, 4.0);
    let mut c = RootCounters::default();
    let s = BeamSettings::default();
    ev.set_beam(&beam(eye, DVec3::new(0.5, 0.0, -1.0), 0.01));
    assert_eq!(
        evaluate_box(&mut ev, &[ival(0.0, 10.0)], None, &s, &mut c),
        BoxClass::Miss
    );
    // The silhouette is at direction x = 1/sqrt(15) ≈ 0.258 per unit z.
    ev.set_beam(&beam(eye, DVec3::new(0.258, 0.0, -1.0), 0.01));
    assert!(matches!(
        evaluate_box(&mut ev, &[ival(0.0, 10.0)], None, &s, &mut c),
        BoxClass::Undecided { .. }
    ));
}

#[test]
fn inclusion_needs_continuity() {
    // 1/x changes sign across 0 without a root: never an inclusion.
    let g = geometry("1/x", 2.0);
    let mut ev = BeamEval::new(g.ray_function());
    let b = beam(DVec3::new(-1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), 0.01);
    ev.set_beam(&b);
    let mut c = RootCounters::default();
    assert!(!inclusion_test(&mut ev, ival(0.0, 2.0), &mut c));
    let class = evaluate_box(
        &mut ev,
        &[ival(0.0, 2.0)],
        None,
        &BeamSettings::default(),
        &mut c,
    );
    assert!(!matches!(class, BoxClass::Hit { .. }), "{class:?}");
    // Nor for a step function.
    let g = geometry("floor(x)+0.5", 2.0);
    let mut ev = BeamEval::new(g.ray_function());
    ev.set_beam(&b);
    assert!(!inclusion_test(&mut ev, ival(0.0, 2.0), &mut c));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Whatever EvaluateBox proves about a random beam holds for sampled rays of it.
    #[test]
    fn proven_classes_hold_for_every_sampled_ray(
        ex in -0.5f64..0.5, ey in -0.5f64..0.5,
        dx in -0.4f64..0.4, dy in -0.4f64..0.4, half in 0.0005f64..0.1,
    ) {
        let g = geometry("x^2+y^2+z^2-1", 1.5);
        let mut ev = BeamEval::new(g.ray_function());
        let eye = DVec3::new(ex, ey, 4.0);
        let b = beam(eye, DVec3::new(dx, dy, -1.0), half);
        ev.set_beam(&b);
        let mut c = RootCounters::default();
        let class = evaluate_box(&mut ev, &[ival(0.0, 10.0)], None, &BeamSettings::default(), &mut c);
        for i in 0..=4 {
            for j in 0..=4 {
                let d = DVec3::new(
                    dx - half + half * 0.5 * f64::from(i),
                    dy - half + half * 0.5 * f64::from(j),
                    -1.0,
                );
                let root = sphere_root(eye, d);
                match class {
                    BoxClass::Miss => prop_assert!(root.is_none(), "{d:?} hits at {root:?}"),
                    BoxClass::Hit { t_final } => {
                        let t = root.expect("a hit beam's ray misses");
                        prop_assert!(t_final.contains(t), "{t} not in {t_final:?}");
                    }
                    BoxClass::Undecided { t } => {
                        if let Some(r) = root {
                            prop_assert!(r >= t.inf(), "root {r} before the undecided range {t:?}");
                        }
                    }
                }
            }
        }
    }
}

/// Why the inclusion test uses outer enclosures: with inner rounding (the thesis's
/// `Inn(fR)`) a range can lose the values that contradict its sign. For `g = 3x − y` over the
/// rays `x ∈ [0.1, 0.2]` with `y = 0.30000000000000004` (doubles), the ray `x = 0.1` has
/// `g = 3 · 0.1 − y < 0` (the product `3 · 0.1` rounds up to `y`), yet the inner-rounded range
/// is `[0, …]`: with an end value `≤ 0` elsewhere, the meet test would claim a sign change
/// for a ray that has none. The outer-rounded range keeps the negative value, and
/// [`sign_change`] refuses.
#[test]
fn inner_rounding_can_claim_a_wrong_sign_outer_cannot() {
    use interval_core::{Inner, Modal, Outer};
    let y = 0.30000000000000004f64;
    // The real value at x = 0.1: 3·0.1 = p + e exactly, with p the rounded product.
    let p = 3.0 * 0.1f64;
    let e = 3.0f64.mul_add(0.1, -p);
    assert_eq!(p, y);
    assert!(e < 0.0, "3 · 0.1 − y = {e} is negative");
    let x_inner = Modal::<f64, Inner>::proper(0.1, 0.2).unwrap();
    let inner = Modal::<f64, Inner>::point(3.0).unwrap() * x_inner - Modal::point(y).unwrap();
    assert!(
        inner.first() >= 0.0,
        "inner rounding claims g ≥ 0: {inner:?}"
    );
    let x_outer = Modal::<f64, Outer>::proper(0.1, 0.2).unwrap();
    let outer = Modal::<f64, Outer>::point(3.0).unwrap() * x_outer - Modal::point(y).unwrap();
    assert!(outer.first() <= e && outer.second() > 0.0, "{outer:?}");
    let end_b = ival(-2.0, -1.0);
    // The thesis's test on the inner value would claim a sign change ...
    let inner_meet_claims =
        inner.first().max(end_b.inf()) >= 0.0 && inner.second().min(end_b.sup()) <= 0.0;
    assert!(inner_meet_claims);
    // ... the sound test on the outer value does not.
    assert!(!sign_change(ival(outer.first(), outer.second()), end_b));
}

/// A Hit must place every ray's root inside the scene bounds: rays search only there. The
/// unit sphere seen from `z = 4` has its roots near `z = 1`; with bounds `[-0.5, 0.5]³` they
/// lie outside, and the same search that proves a hit without bounds proves none with them.
#[test]
fn inclusion_places_the_roots_inside_the_bounds() {
    let g = geometry("x^2+y^2+z^2-1", 1.5);
    let mut ev = BeamEval::new(g.ray_function());
    let b = beam(DVec3::new(0.0, 0.0, 4.0), DVec3::new(0.0, 0.0, -1.0), 0.01);
    ev.set_beam(&b);
    let s = BeamSettings::default();
    let mut c = RootCounters::default();
    let free = evaluate_box(&mut ev, &[ival(0.0, 10.0)], None, &s, &mut c);
    assert!(matches!(free, BoxClass::Hit { .. }), "{free:?}");
    let small = [ival(-0.5, 0.5); 3];
    let extent = Extent {
        beam: &b,
        bounds: &small,
    };
    let bounded = evaluate_box(&mut ev, &[ival(0.0, 10.0)], Some(&extent), &s, &mut c);
    assert!(!matches!(bounded, BoxClass::Hit { .. }), "{bounded:?}");
    // Bounds that hold the roots keep the hit.
    let large = [ival(-1.5, 1.5); 3];
    let extent = Extent {
        beam: &b,
        bounds: &large,
    };
    let kept = evaluate_box(&mut ev, &[ival(0.0, 10.0)], Some(&extent), &s, &mut c);
    assert!(matches!(kept, BoxClass::Hit { .. }), "{kept:?}");
}
