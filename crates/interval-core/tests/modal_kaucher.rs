//! Kaucher arithmetic on modal intervals: the worked examples of thesis §3.5, the algebraic
//! identities of the complete arithmetic, the behaviour of division by divisors whose set
//! holds 0, and the lattice laws of meet/join and min/max.

use interval_core::modal::{Inner, Modal, Outer, Rounding};
use interval_core::{Float, Interval};
use proptest::prelude::*;
use proptest::test_runner::Config;
use rug::Rational;

fn rat<T: Float>(x: T) -> Rational {
    Rational::from_f64(x.to_f64()).expect("finite value")
}

fn m<T: Float, R: Rounding>(a: T, b: T) -> Modal<T, R> {
    Modal::new(a, b).unwrap()
}

/// Number of representable steps from `x` up to `y` (`x ≤ y`), capped at 100.
fn ulps<T: Float>(mut x: T, y: T) -> u32 {
    let mut n = 0;
    while x < y && n < 100 {
        x = x.next_up();
        n += 1;
    }
    n
}

// ---------------------------------------------------------------------------------------
// Worked examples of the thesis.

fn thesis_sum<T: Float>() {
    let one_three = m::<T, Outer>(T::ONE, T::from_f64_rn(3.0));
    let three_two = m::<T, Outer>(T::from_f64_rn(3.0), T::TWO);
    let expected = m::<T, Outer>(T::from_f64_rn(4.0), T::from_f64_rn(5.0));
    assert_eq!(one_three + three_two, expected);
    assert_eq!(
        one_three.with_rounding::<Inner>() + three_two.with_rounding::<Inner>(),
        expected.with_rounding::<Inner>()
    );
}

#[test]
fn thesis_sum_f64() {
    thesis_sum::<f64>();
}

#[test]
fn thesis_sum_f32() {
    thesis_sum::<f32>();
}

/// The three rational extensions of `f(x, y) = xy / (x + y)` at `X = [2, 3]`,
/// `Y = [4, 3]`, each as `(first, second)` exact bounds and the computed value.
fn worked_example<T: Float, R: Rounding>() -> [(Modal<T, R>, (Rational, Rational)); 3] {
    let c = |v: f64| T::from_f64_rn(v);
    let x = m::<T, R>(c(2.0), c(3.0));
    let y = m::<T, R>(c(4.0), c(3.0));
    let four = m::<T, R>(c(4.0), c(4.0));
    let q = |n: i64, d: i64| Rational::from((n, d));
    [
        // Theorem 5: Xt* = ([2,3], [4,4], [2,3], [4,4]).
        (x * four / (x + four), (q(8, 7), q(2, 1))),
        // Theorem 3: XDt* = ([2,3], [4,4], [3,2], [4,4]).
        (x * four / (x.dual() + four), (q(4, 3), q(12, 7))),
        // Theorem 6: XD = ([2,3], [4,3], [3,2], [3,4]).
        (x * y / (x.dual() + y.dual()), (q(4, 3), q(3, 2))),
    ]
}

fn thesis_worked_example<T: Float>() {
    let outer = worked_example::<T, Outer>();
    let inner = worked_example::<T, Inner>();
    for ((o, (e1, e2)), (i, _)) in outer.iter().zip(inner.iter()) {
        // Outer brackets the exact result from outside, inner from inside.
        assert!(
            rat(o.first()) <= *e1 && rat(o.second()) >= *e2,
            "{o} vs exact"
        );
        assert!(
            rat(i.first()) >= *e1 && rat(i.second()) <= *e2,
            "{i} vs exact"
        );
        assert!(o.first() <= i.first() && i.second() <= o.second());
        assert!(i.with_rounding::<Outer>().subset(*o));
        // Exact intermediate results and one rounded quotient: at most one ulp apart.
        assert!(ulps(o.first(), i.first()) <= 1);
        assert!(ulps(i.second(), o.second()) <= 1);
        assert!(o.is_proper());
    }
    // f*(X) = fR(XD) ⊆ fR(XDt*) ⊆ fR(Xt*), as the thesis concludes.
    assert!(outer[2].0.subset(outer[1].0) && outer[1].0.subset(outer[0].0));
}

#[test]
fn thesis_worked_example_f64() {
    thesis_worked_example::<f64>();
}

#[test]
fn thesis_worked_example_f32() {
    thesis_worked_example::<f32>();
}

#[test]
#[allow(clippy::op_ref)] // the by-reference operator impls are under test
fn small_fixed_cases() {
    let x = m::<f64, Outer>(3.0, 2.0);
    assert_eq!(-x, m(-2.0, -3.0));
    assert_eq!(x - x, m(1.0, -1.0));
    assert_eq!(x - x.dual(), Modal::ZERO);
    // Reciprocals: [1/b2, 1/b1].
    assert_eq!(m::<f64, Outer>(2.0, 4.0).recip(), m(0.25, 0.5));
    assert_eq!(m::<f64, Outer>(4.0, 2.0).recip(), m(0.5, 0.25));
    assert_eq!(m::<f64, Outer>(-4.0, -2.0).recip(), m(-0.5, -0.25));
    // By reference.
    let y = m::<f64, Outer>(1.0, 2.0);
    assert_eq!(&x + &y, x + y);
    assert_eq!(&x * y, x * y);
    assert_eq!(x / &y, x / y);
    assert_eq!(-&x, -x);
}

// ---------------------------------------------------------------------------------------
// Division by a divisor whose set holds 0.

#[test]
fn division_by_zero_containing_divisors() {
    let inf = f64::INFINITY;
    let o = |a, b| m::<f64, Outer>(a, b);
    let entire = Modal::<f64, Outer>::ENTIRE;
    // Outer, both proper: the classical hull division.
    assert_eq!(o(1.0, 2.0) / o(0.0, 4.0), o(0.25, inf));
    assert_eq!(o(1.0, 2.0) / o(-4.0, 0.0), o(-inf, -0.25));
    assert_eq!(o(-2.0, -1.0) / o(0.0, 4.0), o(-inf, -0.25));
    assert_eq!(o(-2.0, -1.0) / o(-4.0, 0.0), o(0.25, inf));
    assert_eq!(o(-1.0, 2.0) / o(0.0, 4.0), entire);
    assert_eq!(o(1.0, 2.0) / o(-1.0, 1.0), entire);
    assert_eq!(o(3.0, 3.0) / o(0.0, 4.0), o(0.75, inf));
    assert_eq!(o(1.0, 2.0).recip(), o(0.5, 1.0));
    assert_eq!(o(0.0, 1.0).recip(), o(1.0, inf));
    // Outer, divisor [0, 0]: no classical quotient exists; the result is [−∞, +∞].
    assert_eq!(o(1.0, 2.0) / o(0.0, 0.0), entire);
    assert_eq!(o(0.0, 0.0) / o(0.0, 0.0), entire);
    // Outer, an improper operand: [−∞, +∞].
    assert_eq!(o(2.0, 1.0) / o(0.0, 4.0), entire);
    assert_eq!(o(2.0, 1.0) / o(-1.0, 1.0), entire);
    assert_eq!(o(1.0, 2.0) / o(1.0, -1.0), entire);
    assert_eq!(o(1.0, 2.0) / o(4.0, 0.0), entire);
    assert_eq!(o(1.0, 2.0) / o(0.0, -4.0), entire);
    assert_eq!(o(2.0, 1.0) / o(1.0, -1.0), entire);
    // Inner: always [+∞, −∞], whatever the modalities.
    let i = |a, b| m::<f64, Inner>(a, b);
    let dual_entire = Modal::<f64, Inner>::DUAL_ENTIRE;
    for (a, b) in [
        (i(1.0, 2.0), i(0.0, 4.0)),
        (i(1.0, 2.0), i(-1.0, 1.0)),
        (i(1.0, 2.0), i(0.0, 0.0)),
        (i(2.0, 1.0), i(1.0, -1.0)),
        (i(-1.0, 2.0), i(0.0, -4.0)),
    ] {
        assert_eq!(a / b, dual_entire);
        assert_eq!(a.checked_div(b), None);
        assert!(b.prop_contains(0.0));
    }
    // checked_div: None exactly when 0 ∈ Prop(B).
    assert_eq!(o(1.0, 2.0).checked_div(o(0.0, 4.0)), None);
    assert_eq!(o(1.0, 2.0).checked_div(o(1.0, -1.0)), None);
    assert_eq!(o(1.0, 2.0).checked_div(o(-0.0, 0.0)), None);
    assert_eq!(o(1.0, 2.0).checked_div(o(2.0, 4.0)), Some(o(0.25, 1.0)));
    assert_eq!(o(1.0, 2.0).checked_div(o(4.0, 2.0)), Some(o(0.5, 0.5)));
    // The results hold no NaN and are sound for f32 as well.
    let q = m::<f32, Outer>(1.0, 2.0) / m(0.0, 3.0);
    assert_eq!(q.second(), f32::INFINITY);
    assert!(q.first() <= 1.0 / 3.0 && 3.0 * q.first() <= 1.0);
}

// ---------------------------------------------------------------------------------------
// Random identities.

fn finite_f64() -> BoxedStrategy<f64> {
    prop_oneof![
        2 => Just(0.0),
        3 => (-6i32..=6).prop_map(f64::from),
        4 => (-1.0f64..1.0, -60i32..60).prop_map(|(m, e)| m * 2f64.powi(e)),
        1 => (-1.0f64..1.0).prop_map(|m| m * f64::MAX),
        2 => proptest::num::f64::POSITIVE
            | proptest::num::f64::NEGATIVE
            | proptest::num::f64::NORMAL
            | proptest::num::f64::SUBNORMAL
            | proptest::num::f64::ZERO,
    ]
    .boxed()
}

fn any_bound_f64() -> BoxedStrategy<f64> {
    prop_oneof![
        8 => finite_f64(),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
    ]
    .boxed()
}

fn finite_f32() -> BoxedStrategy<f32> {
    prop_oneof![
        2 => Just(0.0f32),
        3 => (-6i16..=6).prop_map(f32::from),
        4 => (-1.0f32..1.0, -40i32..40).prop_map(|(m, e)| m * 2f32.powi(e)),
        1 => (-1.0f32..1.0).prop_map(|m| m * f32::MAX),
        2 => proptest::num::f32::POSITIVE
            | proptest::num::f32::NEGATIVE
            | proptest::num::f32::NORMAL
            | proptest::num::f32::SUBNORMAL
            | proptest::num::f32::ZERO,
    ]
    .boxed()
}

fn any_bound_f32() -> BoxedStrategy<f32> {
    prop_oneof![
        8 => finite_f32(),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
    ]
    .boxed()
}

fn modal<T: Float>(s: BoxedStrategy<T>) -> impl Strategy<Value = Modal<T, Outer>> {
    (s.clone(), s).prop_map(|(a, b)| Modal::new(a, b).unwrap())
}

/// A proper modal interval that is also a valid classical interval.
fn proper<T: Float>(s: BoxedStrategy<T>) -> impl Strategy<Value = Modal<T, Outer>> {
    (s.clone(), s).prop_filter_map("not a real interval", |(a, b)| {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        Interval::new(lo, hi)
            .ok()
            .map(|x| Modal::try_from(x).unwrap())
    })
}

#[derive(Clone, Copy, Debug)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
}

fn op_strategy() -> impl Strategy<Value = Op> {
    prop_oneof![Just(Op::Add), Just(Op::Sub), Just(Op::Mul), Just(Op::Div)]
}

fn apply<T: Float, R: Rounding>(op: Op, x: Modal<T, R>, y: Modal<T, R>) -> Modal<T, R> {
    match op {
        Op::Add => x + y,
        Op::Sub => x - y,
        Op::Mul => x * y,
        Op::Div => x / y,
    }
}

fn apply_classical<T: Float>(op: Op, x: Interval<T>, y: Interval<T>) -> Interval<T> {
    match op {
        Op::Add => x + y,
        Op::Sub => x - y,
        Op::Mul => x * y,
        Op::Div => x / y,
    }
}

fn no_nan<T: Float, R: Rounding>(x: Modal<T, R>) -> bool {
    !x.first().is_nan() && !x.second().is_nan()
}

/// The identities of one operation for one bound type.
fn identities<T: Float>(op: Op, a: Modal<T, Outer>, b: Modal<T, Outer>) -> Result<(), String> {
    let out = apply(op, a, b);
    let inn = apply(op, a.with_rounding::<Inner>(), b.with_rounding::<Inner>());
    if !no_nan(out) || !no_nan(inn) {
        return Err(format!("NaN in {op:?}({a:e}, {b:e}): {out:e} / {inn:e}"));
    }
    // Outer includes inner (the inner result is the outer one shrunk by rounding).
    if !inn.with_rounding::<Outer>().subset(out) {
        return Err(format!(
            "inner ⊄ outer in {op:?}({a:e}, {b:e}): {out:e} / {inn:e}"
        ));
    }
    if matches!(op, Op::Div) && b.prop_contains(T::ZERO) {
        return Ok(());
    }
    // dual(A ∘ B) = dual A ∘ dual B, with the rounding exchanged.
    let dual_inner = apply(
        op,
        a.dual().with_rounding::<Inner>(),
        b.dual().with_rounding::<Inner>(),
    );
    if out.dual() != dual_inner.with_rounding::<Outer>() {
        return Err(format!(
            "dual(outer) = {:e} but inner(dual, dual) = {dual_inner:e} for {op:?}({a:e}, {b:e})",
            out.dual()
        ));
    }
    let dual_outer = apply(op, a.dual(), b.dual());
    if inn.dual() != dual_outer.with_rounding::<Inner>() {
        return Err(format!(
            "dual(inner) = {:e} but outer(dual, dual) = {dual_outer:e} for {op:?}({a:e}, {b:e})",
            inn.dual()
        ));
    }
    Ok(())
}

/// For proper operands, `Prop(A ∘ B)` is the classical tight result.
fn classical<T: Float>(op: Op, a: Modal<T, Outer>, b: Modal<T, Outer>) -> Result<(), String> {
    if matches!(op, Op::Div) && b.first() == T::ZERO && b.second() == T::ZERO {
        return Ok(()); // documented exception: classical x / [0, 0] is empty
    }
    let modal = apply(op, a, b);
    let set = apply_classical(op, a.prop(), b.prop());
    if !modal.is_proper() || modal.prop() != set {
        return Err(format!(
            "{op:?}({a:e}, {b:e}) = {modal:e}, classical {set:e}"
        ));
    }
    Ok(())
}

/// Lattice laws for three modal intervals.
fn lattice<T: Float>(x: Modal<T>, y: Modal<T>, z: Modal<T>) -> Result<(), String> {
    let laws: [(&str, bool); 22] = [
        ("meet commutative", x.meet(y) == y.meet(x)),
        ("join commutative", x.join(y) == y.join(x)),
        ("min commutative", x.min(y) == y.min(x)),
        ("max commutative", x.max(y) == y.max(x)),
        ("meet associative", x.meet(y).meet(z) == x.meet(y.meet(z))),
        ("join associative", x.join(y).join(z) == x.join(y.join(z))),
        ("min associative", x.min(y).min(z) == x.min(y.min(z))),
        ("max associative", x.max(y).max(z) == x.max(y.max(z))),
        (
            "idempotent",
            x.meet(x) == x && x.join(x) == x && x.min(x) == x && x.max(x) == x,
        ),
        ("absorption meet/join", x.meet(x.join(y)) == x),
        ("absorption join/meet", x.join(x.meet(y)) == x),
        (
            "absorption min/max",
            x.min(x.max(y)) == x && x.max(x.min(y)) == x,
        ),
        (
            "meet distributes over join",
            x.meet(y.join(z)) == x.meet(y).join(x.meet(z)),
        ),
        (
            "join distributes over meet",
            x.join(y.meet(z)) == x.join(y).meet(x.join(z)),
        ),
        (
            "min distributes over max",
            x.min(y.max(z)) == x.min(y).max(x.min(z)),
        ),
        (
            "max distributes over min",
            x.max(y.min(z)) == x.max(y).min(x.max(z)),
        ),
        (
            "meet ⊆ operands ⊆ join",
            x.meet(y).subset(x)
                && x.meet(y).subset(y)
                && x.subset(x.join(y))
                && y.subset(x.join(y)),
        ),
        (
            "min ≤ operands ≤ max",
            x.min(y).less(x) && x.min(y).less(y) && x.less(x.max(y)) && y.less(x.max(y)),
        ),
        (
            "dual exchanges meet and join",
            x.meet(y).dual() == x.dual().join(y.dual())
                && x.join(y).dual() == x.dual().meet(y.dual()),
        ),
        (
            "meet is the greatest lower bound",
            z.subset(x.meet(y)) == (z.subset(x) && z.subset(y)),
        ),
        (
            "join is the least upper bound",
            x.join(y).subset(z) == (x.subset(z) && y.subset(z)),
        ),
        (
            "families agree with pairs",
            Modal::meet_all([x, y, z]) == Some(x.meet(y).meet(z))
                && Modal::join_all([x, y, z]) == Some(x.join(y).join(z))
                && Modal::min_all([x, y, z]) == Some(x.min(y).min(z))
                && Modal::max_all([x, y, z]) == Some(x.max(y).max(z)),
        ),
    ];
    match laws.iter().find(|(_, ok)| !ok) {
        Some((name, _)) => Err(format!("{name} fails for {x:e}, {y:e}, {z:e}")),
        None => Ok(()),
    }
}

proptest! {
    #![proptest_config(Config::with_cases(4000))]

    #[test]
    fn opposite_of_dual_cancels_f64(x in modal(finite_f64())) {
        let zero = Modal::<f64, Outer>::ZERO;
        prop_assert_eq!(x + (-x.dual()), zero);
        prop_assert_eq!(x - x.dual(), zero);
        let xi = x.with_rounding::<Inner>();
        prop_assert_eq!(xi + (-xi.dual()), zero.with_rounding::<Inner>());
        prop_assert_eq!(xi - xi.dual(), zero.with_rounding::<Inner>());
    }

    #[test]
    fn opposite_of_dual_cancels_f32(x in modal(finite_f32())) {
        let zero = Modal::<f32, Outer>::ZERO;
        prop_assert_eq!(x + (-x.dual()), zero);
        prop_assert_eq!(x - x.dual(), zero);
        let xi = x.with_rounding::<Inner>();
        prop_assert_eq!(xi - xi.dual(), zero.with_rounding::<Inner>());
    }

    #[test]
    fn dual_commutes_with_operations_f64(
        op in op_strategy(), a in modal(any_bound_f64()), b in modal(any_bound_f64())
    ) {
        let r = identities(op, a, b);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    #[test]
    fn dual_commutes_with_operations_f32(
        op in op_strategy(), a in modal(any_bound_f32()), b in modal(any_bound_f32())
    ) {
        let r = identities(op, a, b);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    #[test]
    fn proper_operands_give_classical_results_f64(
        op in op_strategy(), a in proper(any_bound_f64()), b in proper(any_bound_f64())
    ) {
        let r = classical(op, a, b);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    #[test]
    fn proper_operands_give_classical_results_f32(
        op in op_strategy(), a in proper(any_bound_f32()), b in proper(any_bound_f32())
    ) {
        let r = classical(op, a, b);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    #[test]
    fn lattice_laws_f64(
        x in modal(any_bound_f64()), y in modal(any_bound_f64()), z in modal(any_bound_f64())
    ) {
        let r = lattice(x, y, z);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }

    #[test]
    fn lattice_laws_f32(
        x in modal(any_bound_f32()), y in modal(any_bound_f32()), z in modal(any_bound_f32())
    ) {
        let r = lattice(x, y, z);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }
}
