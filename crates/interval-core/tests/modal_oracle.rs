//! The semantic oracle for Kaucher arithmetic (thesis §3.5.1).
//!
//! For `f(x, y)` and modal `X`, `Y`, let the proper components (`a ≤ b`, points included) be
//! the `∃` variables `x_p` and the improper ones the `∀` variables `x_i`, each over its set
//! `Prop`. Then
//!
//! * `f*(X)  = [min_{x_p} max_{x_i} f, max_{x_p} min_{x_i} f]`,
//! * `f**(X) = [max_{x_i} min_{x_p} f, min_{x_i} max_{x_p} f]`.
//!
//! Both are evaluated exactly with `rug::Rational` over candidate points: the endpoints of
//! each component, and 0 where 0 lies strictly inside a component. That set is enough for
//! `+ − · /`: for fixed other variables `f` is linear or monotone in each variable, so inner
//! optima lie at endpoints, and an outer optimum of a max (min) of such functions lies at an
//! endpoint or at their crossing, which for `x·y` and `x/y` is `x = 0`.
//!
//! The tests then check, for random finite bounds in `f64` and `f32`: (1) `f* = f**`;
//! (2) the outer result includes `f*` and (3) the inner result is included in `f**`, in the
//! modal order; (4) tightness: every bound is the exact one rounded to the neighbouring
//! representable number in its direction. Since the Kaucher formulas are only as right as
//! this check, it is what verifies the multiplication and division tables.

use interval_core::Float;
use interval_core::modal::{Inner, Modal, Outer};
use proptest::prelude::*;
use proptest::test_runner::Config;
use rug::Rational;

#[derive(Clone, Copy, Debug)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
}

const OPS: [Op; 4] = [Op::Add, Op::Sub, Op::Mul, Op::Div];

fn rat<T: Float>(x: T) -> Rational {
    Rational::from_f64(x.to_f64()).expect("finite value")
}

fn apply(op: Op, x: &Rational, y: &Rational) -> Rational {
    match op {
        Op::Add => Rational::from(x + y),
        Op::Sub => Rational::from(x - y),
        Op::Mul => Rational::from(x * y),
        Op::Div => Rational::from(x / y),
    }
}

/// Endpoints of the component, and 0 when it lies strictly inside.
fn candidates(a: &Rational, b: &Rational) -> Vec<Rational> {
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    let mut c = vec![lo.clone(), hi.clone()];
    if *lo < 0 && *hi > 0 {
        c.push(Rational::new());
    }
    c
}

/// Exact `(f*, f**)` as pairs of canonical bounds.
#[allow(clippy::type_complexity)]
fn semantic(
    op: Op,
    x: (Rational, Rational),
    y: (Rational, Rational),
) -> ((Rational, Rational), (Rational, Rational)) {
    let x_proper = x.0 <= x.1;
    let y_proper = y.0 <= y.1;
    let cx = candidates(&x.0, &x.1);
    let cy = candidates(&y.0, &y.1);
    let table: Vec<Vec<Rational>> = cx
        .iter()
        .map(|u| cy.iter().map(|v| apply(op, u, v)).collect())
        .collect();
    let all = || table.iter().flatten().cloned().collect::<Vec<_>>();
    let rows = || table.clone();
    let cols = || {
        (0..cy.len())
            .map(|j| table.iter().map(|r| r[j].clone()).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    };
    let singles = || all().into_iter().map(|v| vec![v]).collect::<Vec<_>>();
    // `groups`: one entry per value of the ∃ variables, listing f over the ∀ variables;
    // `tgroups`: one entry per value of the ∀ variables, listing f over the ∃ variables.
    let (groups, tgroups) = match (x_proper, y_proper) {
        (true, true) => (singles(), vec![all()]),
        (true, false) => (rows(), cols()),
        (false, true) => (cols(), rows()),
        (false, false) => (vec![all()], singles()),
    };
    let min = |v: &[Rational]| v.iter().min().unwrap().clone();
    let max = |v: &[Rational]| v.iter().max().unwrap().clone();
    let star = (
        groups.iter().map(|g| max(g)).min().unwrap(),
        groups.iter().map(|g| min(g)).max().unwrap(),
    );
    let dstar = (
        tgroups.iter().map(|g| min(g)).max().unwrap(),
        tgroups.iter().map(|g| max(g)).min().unwrap(),
    );
    (star, dstar)
}

/// `x` is `v` rounded toward −∞ in `T` (−∞ below `−MAX`).
fn is_round_down<T: Float>(x: T, v: &Rational) -> bool {
    if x == T::NEG_INFINITY {
        return *v < rat(-T::MAX);
    }
    if x == T::INFINITY || rat(x) > *v {
        return false;
    }
    let n = x.next_up();
    n == T::INFINITY || *v < rat(n)
}

/// `x` is `v` rounded toward +∞ in `T` (+∞ above `MAX`).
fn is_round_up<T: Float>(x: T, v: &Rational) -> bool {
    if x == T::INFINITY {
        return *v > rat(T::MAX);
    }
    if x == T::NEG_INFINITY || rat(x) < *v {
        return false;
    }
    let n = x.next_down();
    n == T::NEG_INFINITY || *v > rat(n)
}

/// `x ≤ v` with `x` possibly infinite.
fn le<T: Float>(x: T, v: &Rational) -> bool {
    x == T::NEG_INFINITY || (x != T::INFINITY && rat(x) <= *v)
}

/// `x ≥ v` with `x` possibly infinite.
fn ge<T: Float>(x: T, v: &Rational) -> bool {
    x == T::INFINITY || (x != T::NEG_INFINITY && rat(x) >= *v)
}

fn eval<T: Float, R: interval_core::modal::Rounding>(
    op: Op,
    x: Modal<T, R>,
    y: Modal<T, R>,
) -> Modal<T, R> {
    match op {
        Op::Add => x + y,
        Op::Sub => x - y,
        Op::Mul => x * y,
        Op::Div => x.checked_div(y).expect("divisor without 0"),
    }
}

/// Runs all four checks for one operation; `Err` names the first violation.
fn check<T: Float>(op: Op, x: (T, T), y: (T, T)) -> Result<(), String> {
    let xo = Modal::<T, Outer>::new(x.0, x.1).unwrap();
    let yo = Modal::<T, Outer>::new(y.0, y.1).unwrap();
    let out = eval(op, xo, yo);
    let inn = eval(op, xo.with_rounding::<Inner>(), yo.with_rounding::<Inner>());
    let (star, dstar) = semantic(op, (rat(x.0), rat(x.1)), (rat(y.0), rat(y.1)));
    let ctx = || {
        format!(
            "{op:?} {}: X = {xo:e}, Y = {yo:e}, outer = {out:e}, inner = {inn:e}, f* = [{}, {}]",
            T::NAME,
            star.0.to_f64(),
            star.1.to_f64()
        )
    };
    if [out.first(), out.second(), inn.first(), inn.second()]
        .iter()
        .any(|v| v.is_nan())
    {
        return Err(format!("NaN bound: {}", ctx()));
    }
    if star != dstar {
        return Err(format!(
            "f* != f**: f** = [{}, {}]: {}",
            dstar.0.to_f64(),
            dstar.1.to_f64(),
            ctx()
        ));
    }
    // (2) Out(fR) ⊇ f* and (3) Inn(fR) ⊆ f** in the modal inclusion.
    if !(le(out.first(), &star.0) && ge(out.second(), &star.1)) {
        return Err(format!("outer result does not include f*: {}", ctx()));
    }
    if !(ge(inn.first(), &dstar.0) && le(inn.second(), &dstar.1)) {
        return Err(format!("inner result is not included in f**: {}", ctx()));
    }
    // (4) Tightness.
    if !is_round_down(out.first(), &star.0) || !is_round_up(out.second(), &star.1) {
        return Err(format!("outer result not tight: {}", ctx()));
    }
    if !is_round_up(inn.first(), &star.0) || !is_round_down(inn.second(), &star.1) {
        return Err(format!("inner result not tight: {}", ctx()));
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// Exhaustive small cases: every class combination, zeros and points included.

fn exhaustive<T: Float>(values: &[T]) {
    for op in OPS {
        for &a1 in values {
            for &a2 in values {
                for &b1 in values {
                    for &b2 in values {
                        let zero_in_b = b1.min_nan(b2) <= T::ZERO && b1.max_nan(b2) >= T::ZERO;
                        if matches!(op, Op::Div) && zero_in_b {
                            continue;
                        }
                        if let Err(e) = check(op, (a1, a2), (b1, b2)) {
                            panic!("{e}");
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn exhaustive_small_bounds_f64() {
    exhaustive::<f64>(&[-3.0, -2.0, -0.5, 0.0, 1.0, 1.5, 3.0]);
}

#[test]
fn exhaustive_small_bounds_f32() {
    exhaustive::<f32>(&[-3.0, -1.0, -0.1, 0.0, 0.3, 2.0, 7.0]);
}

// ---------------------------------------------------------------------------------------
// Random bounds.

fn bound_f64() -> BoxedStrategy<f64> {
    use proptest::num::f64 as pf;
    prop_oneof![
        2 => Just(0.0),
        1 => Just(-0.0),
        3 => (-8i32..=8).prop_map(f64::from),
        4 => (-1.0f64..1.0, -40i32..40).prop_map(|(m, e)| m * 2f64.powi(e)),
        2 => pf::POSITIVE | pf::NEGATIVE | pf::NORMAL | pf::SUBNORMAL | pf::ZERO,
        1 => prop_oneof![Just(f64::MAX), Just(-f64::MAX), Just(5e-324), Just(-5e-324)],
        // The top binade, where a sum's rounding error is hardest to get right.
        1 => (0.25f64..1.0, any::<bool>()).prop_map(|(m, neg)| {
            if neg { -m * f64::MAX } else { m * f64::MAX }
        }),
    ]
    .boxed()
}

fn bound_f32() -> BoxedStrategy<f32> {
    use proptest::num::f32 as pf;
    prop_oneof![
        2 => Just(0.0f32),
        1 => Just(-0.0f32),
        3 => (-8i16..=8).prop_map(f32::from),
        4 => (-1.0f32..1.0, -30i32..30).prop_map(|(m, e)| m * 2f32.powi(e)),
        2 => pf::POSITIVE | pf::NEGATIVE | pf::NORMAL | pf::SUBNORMAL | pf::ZERO,
        1 => prop_oneof![Just(f32::MAX), Just(-f32::MAX), Just(f32::from_bits(1))],
        1 => (0.25f32..1.0, any::<bool>()).prop_map(|(m, neg)| {
            if neg { -m * f32::MAX } else { m * f32::MAX }
        }),
    ]
    .boxed()
}

/// Bounds of a divisor without 0 in its set: both of one sign (a zero draw becomes 1).
fn nonzero_divisor<T: Float>(s: BoxedStrategy<T>) -> impl Strategy<Value = (T, T)> {
    (s.clone(), s, any::<bool>()).prop_map(|(u, v, neg)| {
        let nz = |x: T| if x == T::ZERO { T::ONE } else { x.abs() };
        let (u, v) = (nz(u), nz(v));
        if neg { (-u, -v) } else { (u, v) }
    })
}

fn pair<T: Float>(s: BoxedStrategy<T>) -> impl Strategy<Value = (T, T)> {
    (s.clone(), s)
}

macro_rules! random_tests {
    ($name:ident, $t:ty, $bound:ident, $op:expr, $rhs:ident) => {
        proptest! {
            #![proptest_config(Config::with_cases(20000))]
            #[test]
            fn $name(x in pair($bound()), y in $rhs($bound())) {
                let r: Result<(), String> = check::<$t>($op, x, y);
                prop_assert!(r.is_ok(), "{}", r.unwrap_err());
            }
        }
    };
}

random_tests!(random_add_f64, f64, bound_f64, Op::Add, pair);
random_tests!(random_sub_f64, f64, bound_f64, Op::Sub, pair);
random_tests!(random_mul_f64, f64, bound_f64, Op::Mul, pair);
random_tests!(random_div_f64, f64, bound_f64, Op::Div, nonzero_divisor);
random_tests!(random_add_f32, f32, bound_f32, Op::Add, pair);
random_tests!(random_sub_f32, f32, bound_f32, Op::Sub, pair);
random_tests!(random_mul_f32, f32, bound_f32, Op::Mul, pair);
random_tests!(random_div_f32, f32, bound_f32, Op::Div, nonzero_divisor);

// ---------------------------------------------------------------------------------------
// The oracle itself, on cases worked by hand.

#[test]
fn oracle_agrees_with_hand_computed_cases() {
    let r = |n: i64| Rational::from(n);
    // The thesis's [1, 3] + [3, 2] = [4, 5].
    let (star, dstar) = semantic(Op::Add, (r(1), r(3)), (r(3), r(2)));
    assert_eq!(star, (r(4), r(5)));
    assert_eq!(dstar, star);
    // ∃x∈[1,2], ∀y∈[−1,1]: f* of x·y is [min_x max_y xy, max_x min_y xy] = [1, −1].
    let (star, _) = semantic(Op::Mul, (r(1), r(2)), (r(1), r(-1)));
    assert_eq!(star, (r(1), r(-1)));
    // Z·Z: [−1, 2]·[−4, 3] = [−8, 6]; dual Z · dual Z: [2, −1]·[3, −4] = [6, −8].
    assert_eq!(
        semantic(Op::Mul, (r(-1), r(2)), (r(-4), r(3))).0,
        (r(-8), r(6))
    );
    assert_eq!(
        semantic(Op::Mul, (r(2), r(-1)), (r(3), r(-4))).0,
        (r(6), r(-8))
    );
    // Z · dual Z = [0, 0]: the kink at 0 is needed here.
    assert_eq!(
        semantic(Op::Mul, (r(-1), r(2)), (r(3), r(-4))).0,
        (r(0), r(0))
    );
}

#[test]
fn rounding_predicates() {
    let third = Rational::from((1, 3));
    assert!(is_round_down(1.0f64.div_down(3.0), &third));
    assert!(!is_round_down(1.0f64.div_up(3.0), &third));
    assert!(is_round_up(1.0f32.div_up(3.0), &third));
    assert!(!is_round_up(1.0f32.div_down(3.0), &third));
    let huge = rat(f64::MAX) * Rational::from(2);
    assert!(is_round_up(f64::INFINITY, &huge));
    assert!(is_round_down(f64::MAX, &huge));
    assert!(is_round_down(f64::NEG_INFINITY, &Rational::from(-&huge)));
}
