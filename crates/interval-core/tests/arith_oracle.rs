//! Soundness and tightness of the directed-rounding primitives and of interval arithmetic,
//! for `f64` and `f32`, against exact rational arithmetic (`rug`).
//!
//! * Primitives (`add_down`, `mul_up`, `div_down`, `sqrt_up`, `fma_down`, ...) on random bit
//!   patterns of every class: the result must be the exact value rounded in the stated
//!   direction, checked by the neighbour test `r ≤ exact < next_up(r)` in exact arithmetic
//!   (NaN where the operation is undefined, `0 · ∞ = 0`).
//! * Interval operations: each bound must be the exact extreme of the operation over the
//!   operand sets, rounded outward (tightness, for `+ - * /`, `fma`, `sqr`, `sqrt`, `recip`,
//!   `mul_rev_to_pair`; exactness for `neg`, `abs`, `min`, `max`), and the exact result at
//!   points of the operands (finite endpoints and interior points) must lie inside
//!   (soundness, which also checks the oracle's hulls).
//! * Set operations and relations against their set definitions, evaluated on a set of
//!   rational sample points rich enough to decide them exactly.

mod common;

use common::*;
use interval_core::{Float, Interval};
use proptest::prelude::*;
use rug::Rational;

/// Instantiates a property for `f64` and `f32`.
macro_rules! for_both {
    ($cases:expr, $strategy:ident, $check:ident, $n64:ident, $n32:ident) => {
        proptest! {
            #![proptest_config(config($cases))]
            #[test]
            fn $n64(args in $strategy::<f64>()) {
                $check::<f64>(args)?;
            }
            #[test]
            fn $n32(args in $strategy::<f32>()) {
                $check::<f32>(args)?;
            }
        }
    };
}

/// Cases per property: primitives (two types × six properties), interval operations, interval
/// `fma` (three operands, more points), set operations and relations.
const PRIMITIVE_CASES: u32 = 60_000;
const INTERVAL_CASES: u32 = 15_000;
const FMA_INTERVAL_CASES: u32 = 6_000;

type Seeds<T> = Vec<(T, f64)>;
type Binary<T> = (Interval<T>, Interval<T>, Seeds<T>, Seeds<T>);
type Hull = Option<(Ext, Ext)>;

// =============================================================================================
// Primitives
// =============================================================================================

/// Checks a pair of directed results against the exact value: each must be the exact value
/// rounded in its direction (`None`: the operation is undefined and both must be NaN).
fn check_directed<T: TestFloat, E: Exact>(
    op: &str,
    args: &[T],
    exact: Option<E>,
    down: T,
    up: T,
) -> Result<(), TestCaseError> {
    match exact {
        None => prop_assert!(
            down.is_nan() && up.is_nan(),
            "{op}{args:?}: expected NaN, got down {down:?}, up {up:?}"
        ),
        Some(e) => {
            prop_assert!(
                is_round_down(down, &e),
                "{op}_down{args:?} = {down:?} is not the exact {e:?} rounded down"
            );
            prop_assert!(
                is_round_up(up, &e),
                "{op}_up{args:?} = {up:?} is not the exact {e:?} rounded up"
            );
        }
    }
    Ok(())
}

fn has_nan<T: TestFloat>(args: &[T]) -> bool {
    args.iter().any(|x| x.is_nan())
}

fn exact_sum<T: TestFloat>(a: T, b: T) -> Option<Ext> {
    if has_nan(&[a, b]) {
        return None;
    }
    Ext::of(a).add(&Ext::of(b))
}

fn exact_product<T: TestFloat>(a: T, b: T) -> Option<Ext> {
    if has_nan(&[a, b]) {
        return None;
    }
    Some(Ext::of(a).mul(&Ext::of(b)))
}

/// `a / b` as IEEE 754 defines it in the directed modes: `x / ±0` is an infinity signed by
/// the signs of both operands, `0 / 0` and `∞ / ∞` are NaN.
fn exact_quotient<T: TestFloat>(a: T, b: T) -> Option<Ext> {
    if has_nan(&[a, b]) {
        return None;
    }
    if b == T::ZERO {
        if a == T::ZERO {
            return None;
        }
        return Some(if a.is_sign_negative() == b.is_sign_negative() {
            Ext::PosInf
        } else {
            Ext::NegInf
        });
    }
    Ext::of(a).div(&Ext::of(b))
}

fn exact_sqrt<T: TestFloat>(a: T) -> Option<SqrtOf> {
    if a.is_nan() || (a < T::ZERO) {
        return None;
    }
    Some(SqrtOf(Ext::of(a)))
}

fn exact_fma<T: TestFloat>(a: T, b: T, c: T) -> Option<Ext> {
    if has_nan(&[a, b, c]) {
        return None;
    }
    Ext::of(a).mul(&Ext::of(b)).add(&Ext::of(c))
}

fn prim_add_sub<T: TestFloat>((a, b): (T, T)) -> Result<(), TestCaseError> {
    for (x, y) in [(a, b), (b, a)] {
        check_directed("add", &[x, y], exact_sum(x, y), x.add_down(y), x.add_up(y))?;
        check_directed("sub", &[x, y], exact_sum(x, -y), x.sub_down(y), x.sub_up(y))?;
    }
    Ok(())
}

fn prim_mul<T: TestFloat>((a, b): (T, T)) -> Result<(), TestCaseError> {
    check_directed(
        "mul",
        &[a, b],
        exact_product(a, b),
        a.mul_down(b),
        a.mul_up(b),
    )?;
    check_directed(
        "mul",
        &[b, a],
        exact_product(b, a),
        b.mul_down(a),
        b.mul_up(a),
    )
}

fn prim_div<T: TestFloat>((a, b): (T, T)) -> Result<(), TestCaseError> {
    check_directed(
        "div",
        &[a, b],
        exact_quotient(a, b),
        a.div_down(b),
        a.div_up(b),
    )?;
    check_directed(
        "div",
        &[b, a],
        exact_quotient(b, a),
        b.div_down(a),
        b.div_up(a),
    )
}

fn prim_sqrt<T: TestFloat>(a: T) -> Result<(), TestCaseError> {
    check_directed("sqrt", &[a], exact_sqrt(a), a.sqrt_down(), a.sqrt_up())?;
    // Squares of random values: exact square roots.
    let s = a * a;
    if s.is_finite() {
        check_directed("sqrt", &[s], exact_sqrt(s), s.sqrt_down(), s.sqrt_up())?;
    }
    Ok(())
}

fn prim_fma<T: TestFloat>((a, b, c): (T, T, T)) -> Result<(), TestCaseError> {
    for (x, y) in [(a, b), (b, a)] {
        check_directed(
            "fma",
            &[x, y, c],
            exact_fma(x, y, c),
            x.fma_down(y, c),
            x.fma_up(y, c),
        )?;
    }
    Ok(())
}

fn any_pair<T: TestFloat>() -> BoxedStrategy<(T, T)> {
    value_pair::<T>(true)
}

fn any_triple<T: TestFloat>() -> BoxedStrategy<(T, T, T)> {
    fma_triple::<T>(true)
}

fn any_one<T: TestFloat>() -> BoxedStrategy<T> {
    any_value::<T>()
}

/// Triples of moderate values with `c` close to `−a·b` (the fast path of `f64` `fma`).
fn moderate_triple<T: TestFloat>() -> BoxedStrategy<(T, T, T)> {
    (moderate::<T>(), moderate::<T>(), -8i32..=8, moderate::<T>())
        .prop_map(|(a, b, k, c)| {
            let p = a * b;
            if k == 0 {
                (a, b, c)
            } else {
                (a, b, step(-p, k))
            }
        })
        .boxed()
}

for_both!(
    PRIMITIVE_CASES,
    any_pair,
    prim_add_sub,
    add_sub_primitives_f64,
    add_sub_primitives_f32
);
for_both!(
    PRIMITIVE_CASES,
    any_pair,
    prim_mul,
    mul_primitives_f64,
    mul_primitives_f32
);
for_both!(
    PRIMITIVE_CASES,
    any_pair,
    prim_div,
    div_primitives_f64,
    div_primitives_f32
);
for_both!(
    PRIMITIVE_CASES,
    any_one,
    prim_sqrt,
    sqrt_primitives_f64,
    sqrt_primitives_f32
);
for_both!(
    PRIMITIVE_CASES,
    any_triple,
    prim_fma,
    fma_primitives_f64,
    fma_primitives_f32
);
for_both!(
    PRIMITIVE_CASES / 2,
    moderate_triple,
    prim_fma,
    fma_primitives_moderate_f64,
    fma_primitives_moderate_f32
);
for_both!(
    PRIMITIVE_CASES,
    fma_extreme_triple,
    prim_fma,
    fma_primitives_extreme_f64,
    fma_primitives_extreme_f32
);

/// Guards the oracle itself: the neighbour test accepts exactly one value in each direction
/// (the results one step away are rejected), and `round_rational` finds the same values.
fn oracle_self_check<T: TestFloat>((a, b): (T, T)) -> Result<(), TestCaseError> {
    for (e, d, u) in [
        (exact_product(a, b), a.mul_down(b), a.mul_up(b)),
        (exact_sum(a, b), a.add_down(b), a.add_up(b)),
    ] {
        let Some(e) = e else { continue };
        prop_assert!(
            is_round_down(d, &e) && is_round_up(u, &e),
            "[{d:?}, {u:?}] is not {e:?} rounded outward ({a:?}, {b:?})"
        );
        for r in [d.next_down(), d.next_up()] {
            if r.to_raw() != d.to_raw() && !(r == T::ZERO && d == T::ZERO) {
                prop_assert!(!is_round_down(r, &e), "accepted {r:?} and {d:?} for {e:?}");
            }
        }
        for r in [u.next_down(), u.next_up()] {
            if r.to_raw() != u.to_raw() && !(r == T::ZERO && u == T::ZERO) {
                prop_assert!(!is_round_up(r, &e), "accepted {r:?} and {u:?} for {e:?}");
            }
        }
        if let Some(q) = e.finite() {
            prop_assert_eq!(round_rational::<T>(q, true), d);
            prop_assert_eq!(round_rational::<T>(q, false), u);
        }
    }
    Ok(())
}

for_both!(
    PRIMITIVE_CASES / 2,
    any_pair,
    oracle_self_check,
    oracle_self_check_f64,
    oracle_self_check_f32
);

#[test]
fn primitives_at_class_boundaries() {
    // Every pair of boundary values and infinities, exhaustively.
    fn run<T: TestFloat>() {
        let mut vals = boundary_values::<T>();
        vals.extend([T::INFINITY, T::NEG_INFINITY, T::NAN]);
        for &a in &vals {
            prim_sqrt(a).unwrap();
            for &b in &vals {
                prim_add_sub((a, b)).unwrap();
                prim_mul((a, b)).unwrap();
                prim_div((a, b)).unwrap();
                for &c in &vals {
                    prim_fma((a, b, c)).unwrap();
                }
            }
        }
    }
    run::<f64>();
    run::<f32>();
}

#[test]
fn primitives_known_values() {
    let tiny = f64::MIN_POSITIVE_SUBNORMAL;
    // Overflow: down saturates at MAX, up goes to +∞.
    assert_eq!(f64::MAX.add_down(f64::MAX), f64::MAX);
    assert_eq!(f64::MAX.add_up(f64::MAX), f64::INFINITY);
    assert_eq!((-f64::MAX).mul_down(2.0), f64::NEG_INFINITY);
    assert_eq!((-f64::MAX).mul_up(2.0), -f64::MAX);
    // Underflow onto the subnormal grid.
    assert_eq!(tiny.mul_down(0.5), 0.0);
    assert_eq!(tiny.mul_up(0.5), tiny);
    assert_eq!((-tiny).div_down(3.0), -tiny);
    assert_eq!(
        f32::MIN_POSITIVE_SUBNORMAL.mul_up(0.25),
        f32::MIN_POSITIVE_SUBNORMAL
    );
    // 0 · ∞ = 0.
    assert_eq!(0.0f64.mul_down(f64::INFINITY), 0.0);
    assert_eq!(f32::NEG_INFINITY.mul_up(-0.0), 0.0);
    // A zero factor gives exactly 0 both ways (whatever the other's sign or size); a NaN
    // factor stays NaN.
    for x in [-3.5f64, 1e-310, f64::MAX, f64::NEG_INFINITY, 0.0, -0.0] {
        for (a, b) in [(x, 0.0), (0.0, x), (x, -0.0), (-0.0, x)] {
            assert_eq!((a.mul_down(b), a.mul_up(b)), (0.0, 0.0), "{a} · {b}");
        }
    }
    assert!(0.0f64.mul_down(f64::NAN).is_nan() && f64::NAN.mul_up(-0.0).is_nan());
    // One-ulp brackets of inexact results.
    assert_eq!(1.0f64.div_up(3.0), 1.0f64.div_down(3.0).next_up());
    assert_eq!(2.0f64.sqrt_up(), 2.0f64.sqrt_down().next_up());
    assert_eq!(4.0f32.sqrt_down(), 2.0);
    assert_eq!(0.1f64.fma_down(10.0, -1.0), 0.1f64.fma_up(10.0, -1.0));
}

// =============================================================================================
// Interval arithmetic
// =============================================================================================

fn unary_args<T: TestFloat>() -> BoxedStrategy<(Interval<T>, Seeds<T>)> {
    (interval::<T>(), point_seeds::<T>(3)).boxed()
}

fn binary_args<T: TestFloat>() -> BoxedStrategy<Binary<T>> {
    (
        interval_pair::<T>(),
        point_seeds::<T>(3),
        point_seeds::<T>(3),
    )
        .prop_map(|((x, y), s, t)| (x, y, s, t))
        .boxed()
}

type Ternary<T> = (Interval<T>, Interval<T>, Interval<T>, Seeds<T>);

fn ternary_args<T: TestFloat>() -> BoxedStrategy<Ternary<T>> {
    (
        interval::<T>(),
        interval::<T>(),
        interval::<T>(),
        point_seeds::<T>(2),
    )
        .boxed()
}

fn moderate_ternary_args<T: TestFloat>() -> BoxedStrategy<Ternary<T>> {
    let m = || interval_with::<T>(moderate::<T>);
    (m(), m(), m(), point_seeds::<T>(2)).boxed()
}

/// An interval around `v`: the point, `v` and a value `k` steps away, `v` and `−v`, or `v`
/// and an infinity.
fn around<T: TestFloat>(v: T, kind: u8, k: i32) -> Interval<T> {
    let (p, q) = match kind {
        0 => (v, v),
        1 => (v, step(v, k)),
        2 => (v, -v),
        _ => (v, if k > 0 { T::INFINITY } else { T::NEG_INFINITY }),
    };
    Interval::new(p.min_nan(q), p.max_nan(q)).expect("ordered bounds")
}

/// Intervals around the operands of [`fma_extreme_triple`]: corner products near overflow
/// or tiny, addend bounds comparable, cancelling, negligible or dominating.
fn extreme_ternary_args<T: TestFloat>() -> BoxedStrategy<Ternary<T>> {
    let shape = || (0u8..8, prop_oneof![-3i32..=-1, 1i32..=3]);
    (
        fma_extreme_triple::<T>(),
        (shape(), shape(), shape()),
        point_seeds::<T>(2),
    )
        .prop_map(|((a, b, c), ((ka, sa), (kb, sb), (kc, sc)), seeds)| {
            // Mostly narrow intervals: the extreme corner products stay extreme.
            let kind = |k: u8| match k {
                0..=2 => 0,
                3..=5 => 1,
                6 => 2,
                _ => 3,
            };
            (
                around(a, kind(ka), sa),
                around(b, kind(kb), sb),
                around(c, kind(kc), sc),
                seeds,
            )
        })
        .boxed()
}

/// The exact value at points lies in the computed interval and in the oracle's exact hull.
fn check_point<T: TestFloat>(
    op: &str,
    at: &[T],
    value: &Rational,
    result: Interval<T>,
    hull: &Hull,
) -> Result<(), TestCaseError> {
    prop_assert!(
        encloses(result, value),
        "{op} at {at:?}: exact {value} not in {result:?}"
    );
    let e = Ext::Fin(value.clone());
    prop_assert!(
        hull.as_ref().is_some_and(|(lo, hi)| *lo <= e && e <= *hi),
        "oracle: {op} at {at:?} = {value} outside the exact hull {hull:?}"
    );
    Ok(())
}

fn contains_zero(x: &Hull) -> bool {
    x.as_ref()
        .is_some_and(|(lo, hi)| lo.signum() <= 0 && hi.signum() >= 0)
}

fn iv_add_sub<T: TestFloat>((x, y, sx, sy): Binary<T>) -> Result<(), TestCaseError> {
    let (bx, by) = (ext_bounds(x), ext_bounds(y));
    let sum = bx
        .as_ref()
        .zip(by.as_ref())
        .map(|((a, b), (c, d))| (a.add(c).expect("no ∞ − ∞"), b.add(d).expect("no ∞ − ∞")));
    let diff = bx.as_ref().zip(by.as_ref()).map(|((a, b), (c, d))| {
        (
            a.add(&d.neg()).expect("no ∞ − ∞"),
            b.add(&c.neg()).expect("no ∞ − ∞"),
        )
    });
    let (s, d) = (x + y, x - y);
    check_tight(s, sum.clone())?;
    check_tight(d, diff.clone())?;
    for p in points_in(x, &sx) {
        for q in points_in(y, &sy) {
            let (rp, rq) = (rat(p), rat(q));
            check_point("+", &[p, q], &Rational::from(&rp + &rq), s, &sum)?;
            check_point("-", &[p, q], &Rational::from(&rp - &rq), d, &diff)?;
        }
    }
    Ok(())
}

fn iv_mul<T: TestFloat>((x, y, sx, sy): Binary<T>) -> Result<(), TestCaseError> {
    let hull = ext_bounds(x)
        .zip(ext_bounds(y))
        .map(|(a, b)| product_hull(&a, &b));
    let r = x * y;
    check_tight(r, hull.clone())?;
    for p in points_in(x, &sx) {
        for q in points_in(y, &sy) {
            check_point("*", &[p, q], &(rat(p) * rat(q)), r, &hull)?;
        }
    }
    Ok(())
}

/// The closure of `{1/y : y ∈ b, y > 0}` (with `1/0⁺ = +∞`, `1/∞ = 0`), if non-empty.
fn recip_positive_part(b: &(Ext, Ext)) -> Hull {
    if b.1.signum() <= 0 {
        return None;
    }
    let recip = |v: &Ext| match v {
        Ext::PosInf => Ext::zero(),
        Ext::Fin(q) if q.cmp0().is_gt() => Ext::Fin(Rational::from(q.recip_ref())),
        _ => Ext::PosInf, // 0⁺
    };
    Some((recip(&b.1), recip(&b.0)))
}

/// The closure of `{1/y : y ∈ b, y < 0}` (with `1/0⁻ = −∞`, `1/−∞ = 0`), if non-empty.
fn recip_negative_part(b: &(Ext, Ext)) -> Hull {
    if b.0.signum() >= 0 {
        return None;
    }
    let recip = |v: &Ext| match v {
        Ext::NegInf => Ext::zero(),
        Ext::Fin(q) if q.cmp0().is_lt() => Ext::Fin(Rational::from(q.recip_ref())),
        _ => Ext::NegInf, // 0⁻
    };
    Some((recip(&b.1), recip(&b.0)))
}

/// The exact hulls of `{x/y : x ∈ a, y ∈ b, y < 0}` and of the same with `y > 0`.
fn quotient_parts(a: &Hull, b: &Hull) -> [Hull; 2] {
    let (Some(a), Some(b)) = (a, b) else {
        return [None, None];
    };
    [recip_negative_part(b), recip_positive_part(b)].map(|r| r.map(|r| product_hull(a, &r)))
}

/// The exact hull of the set-based quotient `{x/y : x ∈ a, y ∈ b, y ≠ 0}`.
fn quotient_hull(a: &Hull, b: &Hull) -> Hull {
    union_hull(quotient_parts(a, b))
}

fn iv_div<T: TestFloat>((x, y, sx, sy): Binary<T>) -> Result<(), TestCaseError> {
    let (bx, by) = (ext_bounds(x), ext_bounds(y));
    let hull = quotient_hull(&bx, &by);
    let r = x / y;
    check_tight(r, hull.clone())?;
    for p in points_in(x, &sx) {
        for q in points_in(y, &sy) {
            if q != T::ZERO {
                check_point("/", &[p, q], &(rat(p) / rat(q)), r, &hull)?;
            }
        }
    }
    Ok(())
}

fn iv_recip_sqr_sqrt<T: TestFloat>((x, sx): (Interval<T>, Seeds<T>)) -> Result<(), TestCaseError> {
    let bx = ext_bounds(x);
    let pts = points_in(x, &sx);

    // recip
    let one = Some((Ext::Fin(Rational::from(1)), Ext::Fin(Rational::from(1))));
    let hull = quotient_hull(&one, &bx);
    let r = x.recip();
    check_tight(r, hull.clone())?;
    for &p in &pts {
        if p != T::ZERO {
            check_point("recip", &[p], &Rational::from(rat(p).recip_ref()), r, &hull)?;
        }
    }

    // sqr
    let hull = bx.as_ref().map(|(a, b)| {
        let (sa, sb) = (a.mul(a), b.mul(b));
        if contains_zero(&bx) {
            (Ext::zero(), sa.max(sb))
        } else {
            (sa.clone().min(sb.clone()), sa.max(sb))
        }
    });
    let r = x.sqr();
    check_tight(r, hull.clone())?;
    for &p in &pts {
        check_point("sqr", &[p], &Rational::from(rat(p).square_ref()), r, &hull)?;
    }

    // sqrt over x ∩ [0, +∞]
    let hull = bx.as_ref().and_then(|(a, b)| {
        (b.signum() >= 0).then(|| {
            let lo = a.clone().max(Ext::zero());
            (SqrtOf(lo), SqrtOf(b.clone()))
        })
    });
    let r = x.sqrt();
    check_tight(r, hull)?;
    for &p in &pts {
        if p >= T::ZERO {
            let e = SqrtOf(Ext::of(p));
            prop_assert!(encloses(r, &e), "sqrt at {p:?} not in {r:?}");
        }
    }
    Ok(())
}

fn iv_neg_abs<T: TestFloat>((x, sx): (Interval<T>, Seeds<T>)) -> Result<(), TestCaseError> {
    let bx = ext_bounds(x);
    let hull = bx.as_ref().map(|(a, b)| (b.neg(), a.neg()));
    let r = -x;
    check_tight(r, hull.clone())?;
    prop_assert_eq!(r, x.neg());
    for p in points_in(x, &sx) {
        check_point("neg", &[p], &(-rat(p)), r, &hull)?;
    }
    let hull = bx.as_ref().map(|(a, b)| {
        let (aa, ab) = (a.clone().max(a.neg()), b.clone().max(b.neg()));
        if contains_zero(&bx) {
            (Ext::zero(), aa.max(ab))
        } else {
            (aa.clone().min(ab.clone()), aa.max(ab))
        }
    });
    let r = x.abs();
    check_tight(r, hull.clone())?;
    for p in points_in(x, &sx) {
        check_point("abs", &[p], &Rational::from(rat(p).abs_ref()), r, &hull)?;
    }
    Ok(())
}

fn iv_min_max<T: TestFloat>((x, y, sx, sy): Binary<T>) -> Result<(), TestCaseError> {
    let both = ext_bounds(x).zip(ext_bounds(y));
    let hmin = both.clone().map(|((a, b), (c, d))| (a.min(c), b.min(d)));
    let hmax = both.map(|((a, b), (c, d))| (a.max(c), b.max(d)));
    let (rmin, rmax) = (x.min(y), x.max(y));
    check_tight(rmin, hmin.clone())?;
    check_tight(rmax, hmax.clone())?;
    for p in points_in(x, &sx) {
        for q in points_in(y, &sy) {
            let (rp, rq) = (rat(p), rat(q));
            check_point("min", &[p, q], &rp.clone().min(rq.clone()), rmin, &hmin)?;
            check_point("max", &[p, q], &rp.max(rq), rmax, &hmax)?;
        }
    }
    Ok(())
}

fn iv_fma<T: TestFloat>((x, y, z, seeds): Ternary<T>) -> Result<(), TestCaseError> {
    let (bx, by, bz) = (ext_bounds(x), ext_bounds(y), ext_bounds(z));
    let hull = match (&bx, &by, &bz) {
        (Some(a), Some(b), Some(c)) => {
            let (plo, phi) = product_hull(a, b);
            Some((
                plo.add(&c.0).expect("no ∞ − ∞"),
                phi.add(&c.1).expect("no ∞ − ∞"),
            ))
        }
        _ => None,
    };
    let r = x.fma(y, z);
    check_tight(r, hull.clone())?;
    let (px, py, pz) = (
        points_in(x, &seeds),
        points_in(y, &seeds),
        points_in(z, &seeds),
    );
    for &p in &px {
        for &q in &py {
            for &s in &pz {
                let v = rat(p) * rat(q) + rat(s);
                check_point("fma", &[p, q, s], &v, r, &hull)?;
            }
        }
    }
    Ok(())
}

/// The exact pieces of `mul_rev_to_pair(b, c) ⊇ {x : x·y = z, y ∈ b, z ∈ c}`, ordered.
fn mul_rev_expected(b: &Hull, c: &Hull) -> [Hull; 2] {
    if b.is_none() || c.is_none() {
        return [None, None];
    }
    if contains_zero(b) && contains_zero(c) {
        return [Some((Ext::NegInf, Ext::PosInf)), None];
    }
    let mut parts: Vec<(Ext, Ext)> = quotient_parts(c, b).into_iter().flatten().collect();
    parts.sort();
    let mut it = parts.into_iter();
    [it.next(), it.next()]
}

fn iv_mul_rev<T: TestFloat>((b, c, sb, sc): Binary<T>) -> Result<(), TestCaseError> {
    let (eb, ec) = (ext_bounds(b), ext_bounds(c));
    let [h1, h2] = mul_rev_expected(&eb, &ec);
    let (x1, x2) = b.mul_rev_to_pair(c);
    check_tight(x1, h1.clone())?;
    check_tight(x2, h2.clone())?;
    let in_pair = |v: &Rational| encloses(x1, v) || encloses(x2, v);
    let (pb, pc) = (points_in(b, &sb), points_in(c, &sc));
    for &y in &pb {
        for &z in &pc {
            if y != T::ZERO {
                let v = rat(z) / rat(y);
                prop_assert!(
                    in_pair(&v),
                    "mul_rev({b:?}, {c:?}): {z:?}/{y:?} = {v} not in ({x1:?}, {x2:?})"
                );
            } else if z == T::ZERO {
                // 0·x = 0 for every x.
                for &(s, _) in &sb {
                    prop_assert!(in_pair(&rat(s)), "mul_rev({b:?}, {c:?}) misses {s:?}");
                }
            }
        }
    }
    if !x2.is_empty() {
        prop_assert!(x1.precedes(x2), "mul_rev({b:?}, {c:?}) pieces not ordered");
    }
    Ok(())
}

for_both!(
    INTERVAL_CASES,
    binary_args,
    iv_add_sub,
    interval_add_sub_f64,
    interval_add_sub_f32
);
for_both!(
    INTERVAL_CASES,
    binary_args,
    iv_mul,
    interval_mul_f64,
    interval_mul_f32
);
for_both!(
    INTERVAL_CASES,
    binary_args,
    iv_div,
    interval_div_f64,
    interval_div_f32
);
for_both!(
    INTERVAL_CASES,
    unary_args,
    iv_recip_sqr_sqrt,
    interval_recip_sqr_sqrt_f64,
    interval_recip_sqr_sqrt_f32
);
for_both!(
    INTERVAL_CASES,
    unary_args,
    iv_neg_abs,
    interval_neg_abs_f64,
    interval_neg_abs_f32
);
for_both!(
    INTERVAL_CASES,
    binary_args,
    iv_min_max,
    interval_min_max_f64,
    interval_min_max_f32
);
for_both!(
    FMA_INTERVAL_CASES,
    ternary_args,
    iv_fma,
    interval_fma_f64,
    interval_fma_f32
);
for_both!(
    FMA_INTERVAL_CASES,
    moderate_ternary_args,
    iv_fma,
    interval_fma_moderate_f64,
    interval_fma_moderate_f32
);
for_both!(
    FMA_INTERVAL_CASES,
    extreme_ternary_args,
    iv_fma,
    interval_fma_extreme_f64,
    interval_fma_extreme_f32
);
for_both!(
    INTERVAL_CASES,
    binary_args,
    iv_mul_rev,
    interval_mul_rev_to_pair_f64,
    interval_mul_rev_to_pair_f32
);

fn iv(a: f64, b: f64) -> Interval<f64> {
    Interval::new(a, b).unwrap()
}

/// Regression test (IEEE 1788-2015 Table 4): when both operands contain 0 (and the divisor
/// is not `[0, 0]`) the quotient set `{x/y : y ≠ 0}` is `[0, 0]`, `[0, +∞]` or `[−∞, 0]`
/// unless the divisor has 0 in its interior (and the dividend is not `[0, 0]`); the result
/// must be that set, not `[−∞, +∞]`.
#[test]
fn div_with_zero_in_both_operands_is_tight() {
    let inf = f64::INFINITY;
    assert_eq!(iv(0.0, 0.0) / iv(0.0, 1.0), iv(0.0, 0.0));
    assert_eq!(iv(0.0, 0.0) / iv(-1.0, 1.0), iv(0.0, 0.0));
    assert_eq!(iv(0.0, 1.0) / iv(0.0, 1.0), iv(0.0, inf));
    assert_eq!(iv(0.0, 1.0) / iv(-1.0, 0.0), iv(-inf, 0.0));
    assert_eq!(iv(-1.0, 0.0) / iv(0.0, 1.0), iv(-inf, 0.0));
    assert_eq!(iv(-1.0, 0.0) / iv(-1.0, 0.0), iv(0.0, inf));
    assert_eq!(iv(-1.0, 1.0) / iv(0.0, 1.0), Interval::ENTIRE);
}

/// Regression test: sums near overflow where the round-to-nearest sum lies on the wrong side
/// of the exact sum and an error-free transformation's intermediate `RN(a + b) − a` would
/// overflow; the directed sums must still be the exact sum rounded outward.
#[test]
fn add_near_overflow_is_tight() {
    // a = −(2^1022 + 3·2^970): a + MAX is a tie between two doubles; RN picks the upper one.
    let a = -f64::from_bits(0x7fd0_0000_0000_0003);
    let exact = Ext::Fin(rat(a) + rat(f64::MAX));
    let (down, up) = (a.add_down(f64::MAX), a.add_up(f64::MAX));
    assert!(is_round_down(down, &exact), "add_down = {down:e}");
    assert!(is_round_up(up, &exact), "add_up = {up:e}");
    assert_eq!(up, down.next_up());
    let (down, up) = (f64::MAX.sub_down(-a), f64::MAX.sub_up(-a));
    assert!(is_round_down(down, &exact) && is_round_up(up, &exact));
    let x = Interval::point(a).unwrap() + Interval::point(f64::MAX).unwrap();
    check_tight(x, Some((exact.clone(), exact))).unwrap();
    // The same in f32: b = −(2^126 + 3·2^103).
    let b = -f32::from_bits(0x7e80_0003);
    let exact = Ext::Fin(rat(b) + rat(f32::MAX));
    let (down, up) = (b.add_down(f32::MAX), b.add_up(f32::MAX));
    assert!(is_round_down(down, &exact), "add_down = {down:e}");
    assert!(is_round_up(up, &exact), "add_up = {up:e}");
}

/// Regression test: a finite product that overflows the format plus an infinite addend is
/// that infinity (the product is a finite real number), for the primitives and the interval
/// `fma`.
#[test]
fn fma_with_overflowing_product_and_infinite_addend() {
    let inf = f64::INFINITY;
    // 2·MAX is a finite real number; 2·MAX + (−∞) = −∞ exactly.
    assert_eq!(2.0f64.fma_down(f64::MAX, -inf), -inf);
    assert_eq!(2.0f64.fma_up(f64::MAX, -inf), -inf);
    assert_eq!(2.0f64.fma_down(f64::MAX, inf), inf);
    assert_eq!(2.0f64.fma_up(f64::MAX, inf), inf);
    // ∞ − ∞ stays undefined.
    assert!(inf.fma_down(2.0, -inf).is_nan() && inf.fma_up(2.0, -inf).is_nan());
    // The interval result must contain 2·MAX + z for z ∈ [−∞, 0]: [−∞, +∞], not empty.
    let r = iv(2.0, 2.0).fma(iv(f64::MAX, f64::MAX), iv(-inf, 0.0));
    assert_eq!(r, Interval::ENTIRE);
}

/// Regression test: splitting at `±∞` where the interval is unbounded on that side leaves an
/// empty piece (`[+∞, sup]` and `[inf, −∞]` contain no real number).
#[test]
fn split_at_infinity_leaves_an_empty_piece() {
    let inf = f64::INFINITY;
    assert_eq!(iv(0.0, inf).split(inf), (iv(0.0, inf), Interval::EMPTY));
    assert_eq!(iv(-inf, 0.0).split(-inf), (Interval::EMPTY, iv(-inf, 0.0)));
    let (l, r) = iv(0.0, inf).split(inf);
    assert!(r.bounds().is_none(), "{l:?} {r:?}");
    let (l, r) = Interval::<f32>::ENTIRE.split(f32::NEG_INFINITY);
    assert!(l.is_empty() && r == Interval::ENTIRE, "{l:?} {r:?}");
}

/// `fma_down/up(a, b, c)` are `a·b + c` rounded down and up (checked exactly), and equal to
/// `(down, up)`.
fn assert_fma<T: TestFloat>(a: T, b: T, c: T, down: T, up: T) {
    let e = exact_fma(a, b, c).expect("defined");
    let (d, u) = (a.fma_down(b, c), a.fma_up(b, c));
    assert!(
        is_round_down(d, &e),
        "fma_down({a:e}, {b:e}, {c:e}) = {d:e}, exact {e:?}"
    );
    assert!(
        is_round_up(u, &e),
        "fma_up({a:e}, {b:e}, {c:e}) = {u:e}, exact {e:?}"
    );
    assert_eq!((d, u), (down, up), "fma({a:e}, {b:e}, {c:e})");
}

/// `fma` with a product beyond the finite range and an addend of opposite sign above
/// `2^970`: the exact result may come back into the finite range (then it is that value
/// rounded), or stay above `MAX` (then the bounds are `MAX` and `+∞`, whatever the size of
/// the addend).
#[test]
fn fma_overflowing_product_with_huge_addend() {
    let p2 = |k: i32| with_exponent::<f64>(false, k, 0);
    let inf = f64::INFINITY;
    // 2^512 · 2^512 − 2^1000 = 2^1024 − 2^1000, a double (0x7fefffffe0000000).
    let v = f64::from_bits(0x7fef_ffff_e000_0000);
    assert_eq!(Ext::of(v), Ext::Fin(pow2(1024) - pow2(1000)));
    assert_fma(p2(512), p2(512), -p2(1000), v, v);
    assert_fma(-p2(512), p2(512), p2(1000), -v, -v);
    let x = iv(p2(512), p2(512));
    assert_eq!(x.fma(x, iv(-p2(1000), -p2(1000))), iv(v, v));
    // The exact results stay above MAX.
    assert_fma(f64::MAX, f64::MAX, -f64::MAX, f64::MAX, inf);
    assert_fma(p2(600), p2(529), -p2(1010), f64::MAX, inf);
    assert_fma(-p2(600), p2(529), p2(1010), -inf, -f64::MAX);
}

/// `fma` with products and addends near overflow and in or below the subnormal range.
#[test]
fn fma_far_from_moderate_range_known_values() {
    let p2 = |k: i32| with_exponent::<f64>(false, k, 0);
    let ulp = p2(-52);
    let tiny = f64::MIN_POSITIVE_SUBNORMAL;
    // Huge product cancelled by a huge addend: 2^1010(1 + 2^-51 + 2^-104) − 2^1010(1 + 2^-51)
    // = 2^906 exactly.
    let (a, b, c) = (
        p2(1010) * (1.0 + ulp),
        1.0 + ulp,
        -p2(1010) * (1.0 + 2.0 * ulp),
    );
    assert_fma(a, b, c, p2(906), p2(906));
    // An overflowing product brought back by a comparable addend: 1.5·2^1024 − MAX.
    let r = p2(1023) + p2(971);
    assert_fma(1.5 * p2(600), p2(424), -f64::MAX, r, r);
    // Overflowing product, negligible addend: MAX rounded down, +∞ up.
    assert_fma(f64::MAX, 2.0, 1.0, f64::MAX, f64::INFINITY);
    assert_fma(-f64::MAX, 2.0, -tiny, f64::NEG_INFINITY, -f64::MAX);
    // Huge product, negligible addend of either sign.
    let p = p2(1020) * (1.0 + ulp);
    assert_fma(p2(1000) * (1.0 + ulp), p2(20), tiny, p, p.next_up());
    assert_fma(p2(1000) * (1.0 + ulp), p2(20), -tiny, p.next_down(), p);
    // Product 3·2^-1100 (below the subnormal range) plus a subnormal addend.
    assert_fma(p2(-550), 3.0 * p2(-550), tiny, tiny, 2.0 * tiny);
    assert_fma(
        p2(-550),
        3.0 * p2(-550),
        -5.0 * tiny,
        -5.0 * tiny,
        -4.0 * tiny,
    );
    assert_fma(p2(-550), 3.0 * p2(-550), -tiny, -tiny, 0.0);
    assert_fma(p2(-600), p2(-600), 0.0, 0.0, tiny);
    // Product about 2^-1000, addend 2^-1010:
    // 2^-1000(1 + 2^-51 + 2^-104) + 2^-1010 rounds to 2^-1000 + 2^-1010 + 2^-1051 and up.
    let v = p2(-1000) + p2(-1010) + p2(-1051);
    assert_fma(
        p2(-500) * (1.0 + ulp),
        p2(-500) * (1.0 + ulp),
        p2(-1010),
        v,
        v.next_up(),
    );
    // Tiny product, huge addend; huge product, tiny addend.
    assert_fma(tiny, p2(-10), p2(1000), p2(1000), p2(1000).next_up());
    assert_fma(tiny, -p2(-10), p2(1000), p2(1000).next_down(), p2(1000));
    assert_fma(p2(500), -p2(500), tiny, -p2(1000), (-p2(1000)).next_up());
    // The same cancellation in f32: 2^120(1 + 2^-22 + 2^-46) − 2^120(1 + 2^-22) = 2^74.
    let q2 = |k: i32| with_exponent::<f32>(false, k, 0);
    let u = q2(-23);
    let (a, b, c) = (q2(120) * (1.0 + u), 1.0 + u, -q2(120) * (1.0 + 2.0 * u));
    assert_fma(a, b, c, q2(74), q2(74));
    let t = f32::MIN_POSITIVE_SUBNORMAL;
    assert_fma(q2(-80), 3.0 * q2(-80), -t, -t, 0.0);
}

#[test]
fn div_known_values() {
    let inf = f64::INFINITY;
    assert_eq!(iv(1.0, 2.0) / iv(0.0, 4.0), iv(0.25, inf));
    assert_eq!(iv(-2.0, -1.0) / iv(0.0, 4.0), iv(-inf, -0.25));
    assert_eq!(iv(1.0, 2.0) / iv(-1.0, 1.0), Interval::ENTIRE);
    assert_eq!(iv(-1.0, 1.0) / iv(-1.0, 1.0), Interval::ENTIRE);
    assert_eq!(iv(1.0, 2.0) / iv(0.0, 0.0), Interval::EMPTY);
    assert_eq!(iv(1.0, inf) / iv(1.0, inf), iv(0.0, inf));
}

// =============================================================================================
// Set operations and relations
// =============================================================================================

/// A rational sample of the real line that decides set relations between the given
/// intervals exactly: every finite endpoint `e` and `e ± δ` (`δ = 2^-1100`, below any float
/// spacing), 0, `±2·MAX` (beyond every finite bound), and the seeds.
fn sample_points<T: TestFloat>(ivs: &[Interval<T>], seeds: &[T]) -> Vec<Rational> {
    let delta = pow2(-1100);
    let two_max = rat(T::MAX) * 2u32;
    let mut pts = vec![Rational::new(), two_max.clone(), -two_max];
    for x in ivs {
        if let Some((lo, hi)) = x.bounds() {
            for e in [lo, hi] {
                if e.is_finite() {
                    let q = rat(e);
                    pts.push(Rational::from(&q - &delta));
                    pts.push(Rational::from(&q + &delta));
                    pts.push(q);
                }
            }
        }
    }
    pts.extend(seeds.iter().filter(|s| s.is_finite()).map(|&s| rat(s)));
    pts
}

/// Witnesses for existential quantifiers: the sample plus `±3·MAX`, beyond `±2·MAX`.
fn witnesses<T: TestFloat>(pts: &[Rational]) -> Vec<Rational> {
    let three_max = rat(T::MAX) * 3u32;
    let mut w = pts.to_vec();
    w.push(three_max.clone());
    w.push(-three_max);
    w
}

fn member<T: TestFloat>(x: Interval<T>, p: &Rational) -> bool {
    encloses(x, p)
}

type SetArgs<T> = (Interval<T>, Interval<T>, Vec<T>, T);

fn set_args<T: TestFloat>() -> BoxedStrategy<SetArgs<T>> {
    let at = prop_oneof![
        6 => finite::<T>(),
        1 => Just(T::INFINITY),
        1 => Just(T::NEG_INFINITY),
        1 => Just(T::NAN),
    ];
    (
        interval_pair::<T>(),
        proptest::collection::vec(finite::<T>(), 3),
        at,
        0usize..6,
    )
        .prop_map(|((x, y), seeds, at, pick)| {
            // Split points: often an endpoint of x.
            let at = match (x.bounds(), pick) {
                (Some((lo, _)), 0) => lo,
                (Some((_, hi)), 1) => hi,
                _ => at,
            };
            (x, y, seeds, at)
        })
        .boxed()
}

/// Relations against their definitions as statements about the elements of the sets.
fn relations<T: TestFloat>((x, y, seeds, _): SetArgs<T>) -> Result<(), TestCaseError> {
    let s = sample_points(&[x, y], &seeds);
    let w = witnesses::<T>(&s);
    let mx = |p: &Rational| member(x, p);
    let my = |p: &Rational| member(y, p);
    let xs: Vec<&Rational> = s.iter().filter(|p| mx(p)).collect();
    let ys: Vec<&Rational> = s.iter().filter(|p| my(p)).collect();
    let xw: Vec<&Rational> = w.iter().filter(|p| mx(p)).collect();
    let yw: Vec<&Rational> = w.iter().filter(|p| my(p)).collect();

    let equal = s.iter().all(|p| mx(p) == my(p));
    let subset = xs.iter().all(|p| my(p));
    // ∀a∈x ∃b∈y a ≤ b, and ∀b∈y ∃a∈x a ≤ b.
    let less = xs.iter().all(|a| yw.iter().any(|b| a <= b))
        && ys.iter().all(|b| xw.iter().any(|a| a <= b));
    let strict_less =
        xs.iter().all(|a| yw.iter().any(|b| a < b)) && ys.iter().all(|b| xw.iter().any(|a| a < b));
    let precedes = xs.iter().all(|a| ys.iter().all(|b| a <= b));
    let strict_precedes = xs.iter().all(|a| ys.iter().all(|b| a < b));
    // Every element of x has a neighbourhood in y (δ is below every float spacing).
    let delta = pow2(-1100);
    let interior = xs
        .iter()
        .all(|a| my(&Rational::from(*a - &delta)) && my(&Rational::from(*a + &delta)));
    let disjoint = !s.iter().any(|p| mx(p) && my(p));

    let ctx = format!("x = {x:?}, y = {y:?}");
    prop_assert_eq!(x.equal(y), equal, "equal: {}", ctx);
    prop_assert_eq!(x == y, equal, "==: {}", ctx);
    prop_assert_eq!(x.subset(y), subset, "subset: {}", ctx);
    prop_assert_eq!(x.less(y), less, "less: {}", ctx);
    prop_assert_eq!(x.strict_less(y), strict_less, "strict_less: {}", ctx);
    prop_assert_eq!(x.precedes(y), precedes, "precedes: {}", ctx);
    prop_assert_eq!(
        x.strict_precedes(y),
        strict_precedes,
        "strict_precedes: {}",
        ctx
    );
    prop_assert_eq!(x.interior(y), interior, "interior: {}", ctx);
    prop_assert_eq!(x.disjoint(y), disjoint, "disjoint: {}", ctx);
    prop_assert_eq!(x.incident(y), !disjoint, "incident: {}", ctx);
    Ok(())
}

/// Intersection, convex hull and split against their set definitions.
fn set_operations<T: TestFloat>((x, y, seeds, at): SetArgs<T>) -> Result<(), TestCaseError> {
    let inter = x.intersection(y);
    let hull = x.convex_hull(y);
    let (left, right) = x.split(at);
    for r in [inter, hull, left, right] {
        prop_assert!(
            is_valid(r),
            "invalid result {:?} (x = {:?}, y = {:?}, at = {:?})",
            r,
            x,
            y,
            at
        );
    }
    let mut seeds = seeds;
    if at.is_finite() {
        seeds.push(at);
    }
    let s = sample_points(&[x, y, inter, hull, left, right], &seeds);
    let w = witnesses::<T>(&s);
    let union: Vec<&Rational> = w.iter().filter(|p| member(x, p) || member(y, p)).collect();
    for p in &s {
        prop_assert_eq!(
            member(inter, p),
            member(x, p) && member(y, p),
            "intersection {:?} of {:?}, {:?} at {}",
            inter,
            x,
            y,
            p
        );
        let in_hull = union.iter().any(|a| *a <= p) && union.iter().any(|b| *b >= p);
        prop_assert_eq!(
            member(hull, p),
            in_hull,
            "convex_hull {:?} of {:?}, {:?} at {}",
            hull,
            x,
            y,
            p
        );
        if at.is_nan() {
            continue;
        }
        let at_e = Ext::of(at);
        let pe = Ext::Fin(p.clone());
        prop_assert_eq!(
            member(left, p),
            member(x, p) && pe <= at_e,
            "split({:?}, {:?}).0 = {:?} at {}",
            x,
            at,
            left,
            p
        );
        prop_assert_eq!(
            member(right, p),
            member(x, p) && pe >= at_e,
            "split({:?}, {:?}).1 = {:?} at {}",
            x,
            at,
            right,
            p
        );
    }
    if at.is_nan() {
        prop_assert!(left == x && right.is_empty());
    }
    // Bisection: two non-empty halves whose union is x, the first preceding the second.
    if !x.is_empty() {
        let (l, r) = x.bisect();
        prop_assert!(is_valid(l) && is_valid(r) && !l.is_empty() && !r.is_empty());
        prop_assert!(l.precedes(r), "bisect({x:?}) = ({l:?}, {r:?})");
        for p in &s {
            prop_assert_eq!(
                member(x, p),
                member(l, p) || member(r, p),
                "bisect({:?}) at {}",
                x,
                p
            );
        }
    }
    Ok(())
}

for_both!(
    INTERVAL_CASES,
    set_args,
    relations,
    relations_match_set_definitions_f64,
    relations_match_set_definitions_f32
);
for_both!(
    INTERVAL_CASES,
    set_args,
    set_operations,
    set_operations_match_set_definitions_f64,
    set_operations_match_set_definitions_f32
);
