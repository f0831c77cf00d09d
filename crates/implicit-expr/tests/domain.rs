//! `domain(d, f)` and the domain extension of formulas with partial operations: the absent
//! object outside the domain, the formula's own values inside, a jump (no continuity) across
//! the boundary, and enclosure of the point values on random boxes.

use implicit_expr::{Context, Evaluator, NodeId, Tape, Var, parse::parse};
use interval_core::{Decoration, Interval};
use proptest::prelude::*;

fn iv(a: f64, b: f64) -> Interval<f64> {
    Interval::new(a, b).unwrap()
}

fn formula(text: &str) -> (Context, NodeId) {
    let mut c = Context::new();
    let f = parse(&mut c, text, &[]).unwrap();
    (c, f)
}

/// The extension of `text` and its tape.
fn extended(text: &str) -> (Context, NodeId, Tape) {
    let (mut c, f) = formula(text);
    let e = c.domain_extension(f);
    let t = Tape::new(&c, &[e]).unwrap();
    (c, e, t)
}

#[test]
fn domain_over_boxes_inside_outside_and_across() {
    let (_, _, t) = extended("z - sqrt(x)");
    let mut e = Evaluator::<Interval<f64>>::new(&t);
    // Inside: the formula's own enclosure, defined, continuous and bounded.
    let (v, dec) = e
        .eval_decorated(&[iv(1.0, 4.0), iv(0.0, 0.0), iv(0.0, 1.0)])
        .unwrap();
    assert_eq!(v, iv(-2.0, 0.0));
    assert_eq!(dec, Decoration::Com);
    // Outside: absent, and that is defined and continuous (a constant), but unbounded.
    let (v, dec) = e
        .eval_decorated(&[iv(-2.0, -1.0), iv(0.0, 0.0), iv(0.0, 1.0)])
        .unwrap();
    assert_eq!(v, iv(f64::MAX, f64::INFINITY));
    assert_eq!(dec, Decoration::Dac);
    // Across the boundary: the values inside joined with +inf, defined (on each side) but
    // not continuous.
    let (v, dec) = e
        .eval_decorated(&[iv(-1.0, 4.0), iv(0.0, 0.0), iv(0.0, 1.0)])
        .unwrap();
    assert_eq!(v, iv(-2.0, f64::INFINITY));
    assert_eq!(dec, Decoration::Def);
}

#[test]
fn point_values_are_the_formula_inside_and_infinite_outside() {
    let (c, e, _) = extended("z - sqrt(x) + ln(y) + asin(x - 1)");
    let at = |p: [f64; 3]| c.eval(e, &p).unwrap();
    let x = 1.5_f64;
    let inside = 0.25 - x.sqrt() + 2.0_f64.ln() + (x - 1.0).asin();
    assert!((at([x, 2.0, 0.25]) - inside).abs() < 1e-15);
    for p in [[-1.0, 2.0, 0.0], [1.0, -1.0, 0.0], [2.5, 2.0, 0.0]] {
        assert_eq!(at(p), f64::INFINITY, "{p:?}");
    }
}

#[test]
fn a_total_formula_is_left_as_it_is() {
    let (mut c, f) = formula("sqrt(x^2 + 1) - 2 + sqrt(4)");
    // `sqrt(x² + 1)` needs a test (the constant folding cannot see it is positive), while
    // the constant `sqrt(4)` does not.
    let (_, tests) = c.domain_split(f);
    assert_eq!(tests.len(), 1);
    let (mut c, f) = formula("x^2 + y^2 + z^2 - 1");
    assert_eq!(c.domain_extension(f), f);
}

#[test]
fn union_with_an_object_undefined_everywhere_is_the_other_object() {
    // `sqrt(-1 - x²)` is nowhere defined: without the extension the union is empty.
    let (mut c, floor) = formula("z + 1");
    let ghost = parse(&mut c, "sqrt(-1 - x^2) - 1", &[]).unwrap();
    let plain = c.min(floor, ghost);
    let ext = c.domain_extension(ghost);
    let union = c.min(floor, ext);
    let b = [iv(-1.0, 1.0), iv(-1.0, 1.0), iv(-2.0, 0.5)];
    let eval = |root| {
        let t = Tape::new(&c, &[root]).unwrap();
        Evaluator::<Interval<f64>>::new(&t)
            .eval_decorated(&b)
            .unwrap()
    };
    assert!(eval(plain).0.is_empty());
    assert_eq!(eval(union), (iv(-1.0, 1.5), Decoration::Dac));
}

#[test]
fn difference_with_an_absent_object_removes_nothing() {
    let (mut c, a) = formula("x^2 + y^2 + z^2 - 1");
    let b = parse(&mut c, "sqrt(-1 - x^2)", &[]).unwrap();
    let b = c.domain_extension(b);
    let nb = c.neg(b);
    let diff = c.max(a, nb);
    for p in [[0.0, 0.0, 0.0], [0.5, 0.5, 0.0], [2.0, 0.0, 0.0]] {
        assert_eq!(c.eval(diff, &p).unwrap(), c.eval(a, &p).unwrap());
    }
}

#[test]
fn the_derivative_is_unbounded_across_the_boundary() {
    let (mut c, e, _) = extended("z - sqrt(x)");
    let dx = c.deriv(e, Var::X);
    let t = Tape::new(&c, &[dx]).unwrap();
    let mut ev = Evaluator::<Interval<f64>>::new(&t);
    let across = ev
        .eval(&[iv(-1.0, 1.0), iv(0.0, 0.0), iv(0.0, 1.0)])
        .unwrap();
    assert_eq!(across, Interval::ENTIRE);
    let inside = ev
        .eval(&[iv(1.0, 4.0), iv(0.0, 0.0), iv(0.0, 1.0)])
        .unwrap();
    // -1 / (2 sqrt x) over [1, 4].
    assert!(inside.contains(-0.5) && inside.contains(-0.25) && inside.sup() < 0.0);
}

#[test]
fn domain_prints_and_parses_back() {
    let (c, e, _) = extended("z - sqrt(x)");
    let text = implicit_expr::print::to_formula(&c, e);
    assert!(text.starts_with("domain("), "{text}");
    let (c2, e2) = formula(&text);
    for p in [[1.0, 0.0, 0.5], [-1.0, 0.0, 0.5], [0.0, 0.0, 0.0]] {
        assert_eq!(
            c2.eval(e2, &p).unwrap(),
            c.eval(e, &p).unwrap(),
            "{text} at {p:?}"
        );
    }
}

/// Formulas with every kind of domain, nested ones included.
const PARTIAL: [&str; 6] = [
    "z - sqrt(x)",
    "ln(x*y) - z",
    "asin(x) + acos(y/2) - z",
    "pow(x, y) - z",
    "sqrt(ln(x + 2)) - z*y",
    "min(sqrt(1 - x^2 - y^2) - z, log(z + 1) - x)",
];

/// The point value of the extension is in its enclosure over every box holding the point
/// (`+inf`, the absent object, in an enclosure whose upper bound is `+inf`).
fn holds(v: Interval<f64>, p: f64) -> bool {
    if p == f64::INFINITY {
        v.sup() == f64::INFINITY
    } else {
        p.is_nan() || v.contains(p)
    }
}

proptest! {
    #[test]
    fn the_extension_encloses_its_point_values(
        k in 0..PARTIAL.len(),
        lo in prop::array::uniform3(-3.0..3.0f64),
        w in prop::array::uniform3(0.0..2.0f64),
        s in prop::array::uniform3(0.0..=1.0f64),
    ) {
        let (c, e, t) = extended(PARTIAL[k]);
        let b: [Interval<f64>; 3] = std::array::from_fn(|i| iv(lo[i], lo[i] + w[i]));
        let p: [f64; 3] = std::array::from_fn(|i| lo[i] + s[i] * w[i]);
        let v = Evaluator::<Interval<f64>>::new(&t).eval(&b).unwrap();
        let at = c.eval(e, &p).unwrap();
        prop_assert!(holds(v, at), "{}: {at} not in {v:?} over {b:?}", PARTIAL[k]);
    }
}
