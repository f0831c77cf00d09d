//! HC4-revise contractions on fixed formulas: what each reverse operation removes, that
//! an infeasible box is proven empty, and that operations without a reverse narrow nothing
//! (the random property test is `contractor_keeps_solutions` in `tests/soundness.rs`).

use implicit_expr::contractor::Contractor;
use implicit_expr::{Context, parse::parse};
use interval_core::Interval;

fn iv(a: f64, b: f64) -> Interval<f64> {
    Interval::new(a, b).unwrap()
}

/// Contracts `[x, y, 0]` to `text = target`; `None` when proven empty.
fn contract(
    text: &str,
    x: Interval<f64>,
    y: Interval<f64>,
    target: Interval<f64>,
) -> Option<[Interval<f64>; 2]> {
    let mut c = Context::new();
    let f = parse(&mut c, text, &[]).unwrap();
    let mut hc4 = Contractor::<f64>::new(&c, f);
    let mut b = [x, y, iv(0.0, 0.0)];
    hc4.contract(&mut b, target).then_some([b[0], b[1]])
}

fn close(a: Interval<f64>, lo: f64, hi: f64) -> bool {
    (a.inf() - lo).abs() < 1e-12 && (a.sup() - hi).abs() < 1e-12
}

#[test]
fn sums_products_and_squares() {
    // x + y = 1 on [0, 10]²: both at most 1.
    let [x, y] = contract("x + y - 1", iv(0.0, 10.0), iv(0.0, 10.0), Interval::ZERO).unwrap();
    assert!(close(x, 0.0, 1.0) && close(y, 0.0, 1.0), "{x:?} {y:?}");
    // x·y = 4 with y ∈ [1, 2]: x ∈ [2, 4].
    let [x, _] = contract("x*y - 4", iv(-10.0, 10.0), iv(1.0, 2.0), Interval::ZERO).unwrap();
    assert!(close(x, 2.0, 4.0), "{x:?}");
    // x² = 4 on [0, 10]: x = 2.
    let [x, _] = contract("x^2 - 4", iv(0.0, 10.0), iv(0.0, 0.0), Interval::ZERO).unwrap();
    assert!(close(x, 2.0, 2.0), "{x:?}");
    // x³ = 8 on [-10, 10]: x = 2 (pownRev).
    let [x, _] = contract("x^3 - 8", iv(-10.0, 10.0), iv(0.0, 0.0), Interval::ZERO).unwrap();
    assert!(close(x, 2.0, 2.0), "{x:?}");
}

#[test]
fn elementary_functions() {
    // √x = 3: x = 9; the negative part, where √ is undefined, goes too.
    let [x, _] = contract("sqrt(x) - 3", iv(-5.0, 20.0), iv(0.0, 0.0), Interval::ZERO).unwrap();
    assert!(close(x, 9.0, 9.0), "{x:?}");
    // eˣ = 1: x = 0; ln x = 0: x = 1.
    let [x, _] = contract("exp(x) - 1", iv(-5.0, 5.0), iv(0.0, 0.0), Interval::ZERO).unwrap();
    assert!(close(x, 0.0, 0.0), "{x:?}");
    let [x, _] = contract("ln(x)", iv(0.5, 5.0), iv(0.0, 0.0), Interval::ZERO).unwrap();
    assert!(close(x, 1.0, 1.0), "{x:?}");
    // sin x = 1 on [0, 3]: x = π/2 (sinRev).
    let [x, _] = contract("sin(x) - 1", iv(0.0, 3.0), iv(0.0, 0.0), Interval::ZERO).unwrap();
    assert!(
        x.contains(std::f64::consts::FRAC_PI_2) && x.sup() - x.inf() < 1e-6,
        "{x:?}"
    );
}

#[test]
fn min_and_max_leave_the_argument_that_decides() {
    // min(x, y + 10) = 0 with y ∈ [0, 1]: the second argument is at least 10, so x = 0.
    let [x, _] = contract(
        "min(x, y + 10)",
        iv(-5.0, 5.0),
        iv(0.0, 1.0),
        Interval::ZERO,
    )
    .unwrap();
    assert!(close(x, 0.0, 0.0), "{x:?}");
    // max(x, y) = 0: both at most 0.
    let [x, y] = contract("max(x, y)", iv(-5.0, 5.0), iv(-5.0, 5.0), Interval::ZERO).unwrap();
    assert!(close(x, -5.0, 0.0) && close(y, -5.0, 0.0), "{x:?} {y:?}");
}

#[test]
fn infeasible_boxes_are_empty_and_jumps_narrow_nothing() {
    assert!(
        contract(
            "x^2 + y^2 + 1",
            iv(-1.0, 1.0),
            iv(-1.0, 1.0),
            Interval::ZERO
        )
        .is_none()
    );
    assert!(contract("x - 10", iv(0.0, 1.0), iv(0.0, 0.0), Interval::ZERO).is_none());
    // floor(x) = 1 holds on [1, 2): no reverse, x stays.
    let [x, _] = contract("floor(x) - 1", iv(0.0, 5.0), iv(0.0, 0.0), Interval::ZERO).unwrap();
    assert_eq!(x, iv(0.0, 5.0));
}
