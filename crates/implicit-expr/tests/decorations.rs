//! Decorated evaluation of tapes: what the renderer's proofs read from it. A step function
//! is continuous on a box where it takes one value (`com`, or `dac` where an end of the box
//! is a jump) and only defined (`def`) across a jump; a partial operation outside its domain leaves nothing known (`trv`); a ray's `g`
//! is proven continuous on a parameter interval exactly where no jump lies in it.

use implicit_expr::{Context, Evaluator, RayEvaluator, RayFunction, Tape, parse::parse};
use interval_core::{DecInterval, Decoration, Interval};

fn iv(a: f64, b: f64) -> Interval<f64> {
    Interval::new(a, b).unwrap()
}

fn tape(text: &str) -> (Context, Tape) {
    let mut c = Context::new();
    let f = parse(&mut c, text, &[]).unwrap();
    let t = Tape::new(&c, &[f]).unwrap();
    (c, t)
}

/// The plain evaluator's decoration over `x × [0, 0] × [0, 0]`, checked against the
/// decorated evaluator's.
fn decoration(text: &str, x: Interval<f64>) -> Decoration {
    let (_, t) = tape(text);
    let zero = iv(0.0, 0.0);
    let (v, dec) = Evaluator::<Interval<f64>>::new(&t)
        .eval_decorated(&[x, zero, zero])
        .unwrap();
    let d = |x| DecInterval::new(x);
    let fd = Evaluator::<DecInterval<f64>>::new(&t)
        .eval(&[d(x), d(zero), d(zero)])
        .unwrap();
    assert_eq!(fd.interval(), v, "{text}");
    assert_eq!(fd.decoration(), dec, "{text}");
    dec
}

#[test]
fn step_functions_are_continuous_between_their_jumps() {
    assert_eq!(decoration("floor(x) + 1", iv(1.1, 1.9)), Decoration::Com);
    // One value on the box, but a jump at its end: its restriction is continuous (dac),
    // enough for a sign-change proof on the box.
    assert_eq!(decoration("floor(x) + 1", iv(1.0, 1.9)), Decoration::Dac);
    assert_eq!(decoration("floor(x) + 1", iv(0.5, 1.5)), Decoration::Def);
    assert_eq!(decoration("ceil(x)", iv(1.1, 1.9)), Decoration::Com);
    assert_eq!(decoration("ceil(x)", iv(1.0, 1.5)), Decoration::Def);
}

#[test]
fn partial_operations_outside_their_domain_are_trivial() {
    assert_eq!(decoration("sqrt(x) - 1", iv(0.0, 4.0)), Decoration::Com);
    assert_eq!(decoration("sqrt(x) - 1", iv(-1.0, 4.0)), Decoration::Trv);
    assert_eq!(decoration("ln(x)", iv(0.5, 2.0)), Decoration::Com);
    assert_eq!(decoration("ln(x)", iv(0.0, 2.0)), Decoration::Trv);
    assert_eq!(decoration("asin(x)", iv(-1.0, 1.0)), Decoration::Com);
    assert_eq!(decoration("asin(x)", iv(-1.0, 1.5)), Decoration::Trv);
    assert_eq!(decoration("x / (x - 1)", iv(2.0, 3.0)), Decoration::Com);
    assert_eq!(decoration("x / (x - 1)", iv(0.0, 3.0)), Decoration::Trv);
    // Defined and continuous, but beyond the format's range: dac.
    assert_eq!(decoration("exp(x)", iv(0.0, 1000.0)), Decoration::Dac);
    // A jump of a step function and an undefined operation: the least of the two.
    assert_eq!(
        decoration("floor(x) + sqrt(x)", iv(-1.0, 2.0)),
        Decoration::Trv
    );
}

/// Terraces `y = floor(x)`: a ray along `-y` at `x = 0.5` crosses the terrace at
/// `y = 0`; `g` is continuous on the whole ray, so a sign change proves the root. A ray at
/// `x = 1` (on the jump) and a beam over `x ∈ [0.9, 1.1]` are not proven continuous.
#[test]
fn rays_between_jumps_get_continuity_proofs() {
    let mut c = Context::new();
    let f = parse(&mut c, "y - floor(x)", &[]).unwrap();
    let rf = RayFunction::new(&c, f).unwrap();
    let mut ev = RayEvaluator::<Interval<f64>>::new(&rf, &[]).unwrap();
    let p = |v: f64| iv(v, v);
    let down = [p(0.0), p(-1.0), p(0.0)];
    ev.set_ray([p(0.5), p(2.0), p(0.0)], down);
    let (g, continuous) = ev.g_checked(iv(0.0, 4.0));
    assert!(g.contains(0.0));
    assert!(continuous);
    // The sign change between t = 1 and t = 3 proves a root there.
    assert!(ev.g(p(1.0)).inf() > 0.0 && ev.g(p(3.0)).sup() < 0.0);
    ev.set_ray([p(1.0), p(2.0), p(0.0)], down);
    assert!(
        ev.g_checked(iv(0.0, 4.0)).1,
        "x = 1 exactly: floor takes one value"
    );
    ev.set_ray([iv(0.9, 1.1), p(2.0), p(0.0)], down);
    assert!(
        !ev.g_checked(iv(0.0, 4.0)).1,
        "the beam holds the jump at x = 1"
    );
}
