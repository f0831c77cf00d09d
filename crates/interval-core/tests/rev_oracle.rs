//! Reverse operations and cancellative subtraction of `Interval<f64>` and `Interval<f32>`
//! against exact arithmetic (`rug`).
//!
//! * **enclosure** (every reverse operation): for random `c`, `x` and points `z ∈ x`, if the
//!   exact `f(z)` lies in `c` (decided exactly: rationals for `sqr`, `abs`, `pown`, `·`; MPFR
//!   brackets for `cosh`, `sin`, `cos`, `tan`, `pow`, where a bracket that straddles a bound
//!   of `c` is skipped), then `z` lies in `f_rev(c, x)`; and the result lies inside `x`;
//! * **tightness**: `sqr_rev`, `abs_rev`, `pown_rev` (`1 ≤ n ≤ 64`) equal the outward
//!   roundings of the exact preimage hull, `cosh_rev` within one ulp of it; `cancel_minus`/`cancel_plus` equal the directed
//!   differences of the bounds.

mod common;

use common::{
    Ext, TestFloat, check_tight, config, interval, point_seeds, points_in, rat, round_rational,
};
use interval_core::Interval;
use proptest::prelude::*;
use rug::float::Round;
use rug::ops::PowAssignRound;
use rug::{Float as Big, Rational};

const CASES: u32 = 1500;
const PREC: u32 = 1400;

/// Whether the exact rational `v` lies in `c`.
fn in_c<T: TestFloat>(c: Interval<T>, v: &Rational) -> bool {
    match c.bounds() {
        None => false,
        Some((lo, hi)) => Ext::of(lo) <= Ext::Fin(v.clone()) && Ext::Fin(v.clone()) <= Ext::of(hi),
    }
}

/// Whether the MPFR bracket `[d, u]` of an exact value lies surely inside `c` (`Some(true)`),
/// surely outside (`Some(false)`), or straddles a bound (`None`).
fn bracket_in_c<T: TestFloat>(c: Interval<T>, d: &Big, u: &Big) -> Option<bool> {
    let (lo, hi) = c.bounds()?;
    let (lo, hi) = (lo.to_f64(), hi.to_f64());
    if *d >= lo && *u <= hi {
        Some(true)
    } else if *u < lo || *d > hi {
        Some(false)
    } else {
        None
    }
}

fn eval1(z: f64, f: fn(&mut Big, Round) -> core::cmp::Ordering) -> (Big, Big) {
    let mut d = Big::with_val(PREC, z);
    let mut u = d.clone();
    f(&mut d, Round::Down);
    f(&mut u, Round::Up);
    (d, u)
}

/// `z` (exactly) to the power `n`, for `z ≠ 0` when `n < 0`.
fn pown_exact(z: &Rational, n: i32) -> Option<Rational> {
    if n < 0 && *z == 0 {
        return None;
    }
    let mut acc = Rational::from(1);
    for _ in 0..n.unsigned_abs() {
        acc *= z;
    }
    Some(if n < 0 { Rational::from(1) / acc } else { acc })
}

/// `result ⊆ x` and every `z ∈ x` with `f(z) ∈ c` lies in `result`.
fn check_preimage<T: TestFloat>(
    name: &str,
    result: Interval<T>,
    x: Interval<T>,
    seeds: &[(T, f64)],
    maps_into_c: impl Fn(T) -> Option<bool>,
) -> Result<(), TestCaseError> {
    prop_assert!(result.subset(x), "{name}: {result:?} not inside x = {x:?}");
    for z in points_in(x, seeds) {
        if maps_into_c(z) == Some(true) {
            prop_assert!(
                result.contains(z),
                "{name}: {result:?} misses {z:?} (x = {x:?})"
            );
        }
    }
    Ok(())
}

fn check_all<T: TestFloat>(
    c: Interval<T>,
    x: Interval<T>,
    n: i32,
    seeds: &[(T, f64)],
) -> Result<(), TestCaseError> {
    check_preimage("sqr_rev", c.sqr_rev_in(x), x, seeds, |z| {
        Some(in_c(c, &(rat(z) * rat(z))))
    })?;
    check_preimage("abs_rev", c.abs_rev_in(x), x, seeds, |z| {
        Some(in_c(c, &rat(z).abs()))
    })?;
    check_preimage("pown_rev", c.pown_rev_in(x, n), x, seeds, |z| {
        pown_exact(&rat(z), n).map(|v| in_c(c, &v))
    })?;
    check_preimage("cosh_rev", c.cosh_rev_in(x), x, seeds, |z| {
        let (d, u) = eval1(z.to_f64(), Big::cosh_round);
        bracket_in_c(c, &d, &u)
    })?;
    check_preimage("sin_rev", c.sin_rev_in(x), x, seeds, |z| {
        let (d, u) = eval1(z.to_f64(), Big::sin_round);
        bracket_in_c(c, &d, &u)
    })?;
    check_preimage("cos_rev", c.cos_rev_in(x), x, seeds, |z| {
        let (d, u) = eval1(z.to_f64(), Big::cos_round);
        bracket_in_c(c, &d, &u)
    })?;
    check_preimage("tan_rev", c.tan_rev_in(x), x, seeds, |z| {
        let (d, u) = eval1(z.to_f64(), Big::tan_round);
        bracket_in_c(c, &d, &u)
    })?;
    Ok(())
}

/// Binary reverse operations: `mul_rev` (exact) and `pow_rev1`, `pow_rev2` (MPFR).
fn check_binary<T: TestFloat>(
    b: Interval<T>,
    c: Interval<T>,
    x: Interval<T>,
    sb: &[(T, f64)],
    sx: &[(T, f64)],
) -> Result<(), TestCaseError> {
    let ys = points_in(b, sb);
    check_preimage("mul_rev", b.mul_rev_in(c, x), x, sx, |z| {
        Some(ys.iter().any(|&y| in_c(c, &(rat(z) * rat(y)))))
    })?;
    let pow_in_c = |base: T, e: T| -> Option<bool> {
        let (bf, ef) = (base.to_f64(), e.to_f64());
        if bf < 0.0 || (bf == 0.0 && ef <= 0.0) {
            return Some(false);
        }
        let mut d = Big::with_val(PREC, bf);
        let mut u = d.clone();
        let ebig = Big::with_val(PREC, ef);
        d.pow_assign_round(&ebig, Round::Down);
        u.pow_assign_round(&ebig, Round::Up);
        bracket_in_c(c, &d, &u)
    };
    check_preimage("pow_rev1", b.pow_rev1_in(c, x), x, sx, |z| {
        ys.iter().find_map(|&y| pow_in_c(z, y).filter(|&t| t))
    })?;
    // pow_rev2 with a = b: exponents z ∈ x with some base in b.
    check_preimage("pow_rev2", b.pow_rev2_in(c, x), x, sx, |z| {
        ys.iter().find_map(|&base| pow_in_c(base, z).filter(|&t| t))
    })?;
    Ok(())
}

/// Tight reverse operations: the exact preimage hull rounded outward.
fn check_tight_rev<T: TestFloat>(c: Interval<T>, n: i32) -> Result<(), TestCaseError> {
    let nonneg = c.intersection(Interval::new(T::ZERO, T::INFINITY).unwrap());
    let expected_abs = nonneg
        .bounds()
        .map(|(_, hi)| (Ext::of(hi).neg(), Ext::of(hi)));
    check_tight(c.abs_rev(), expected_abs)?;
    // sqr_rev: [−√hi, √hi] rounded outward.
    let s = c.sqr_rev();
    match nonneg.bounds() {
        None => prop_assert!(s.is_empty()),
        Some((_, hi)) => {
            let root = common::SqrtOf(Ext::of(hi));
            prop_assert!(
                common::is_round_up(s.sup(), &root),
                "sqr_rev({c:?}) = {s:?}"
            );
            prop_assert!(s.inf() == -s.sup());
        }
    }
    // cosh_rev: [−acosh(hi), acosh(hi)] of c ∩ [1, ∞], each bound within 1 ulp of tight.
    let ch = c.cosh_rev();
    match c
        .intersection(Interval::new(T::ONE, T::INFINITY).unwrap())
        .bounds()
    {
        None => prop_assert!(ch.is_empty()),
        Some((_, hi)) => {
            let mut u = Big::with_val(PREC, hi.to_f64());
            u.acosh_round(Round::Up);
            let tight: T = common::round_mpfr(&u, false);
            prop_assert!(ch.inf() == -ch.sup(), "cosh_rev({c:?}) = {ch:?}");
            prop_assert!(
                ch.sup() == tight || ch.sup() == tight.next_up(),
                "cosh_rev({c:?}) = {ch:?}, tight sup {tight:?}"
            );
        }
    }
    // pown_rev for odd n ≥ 3: rootn of the bounds, tight.
    if n >= 3 && n % 2 == 1 {
        let r = c.pown_rev(n);
        prop_assert!(r == c.rootn(n), "pown_rev({c:?}, {n}) = {r:?}");
    }
    Ok(())
}

fn check_cancel<T: TestFloat>(x: Interval<T>, y: Interval<T>) -> Result<(), TestCaseError> {
    let z = x.cancel_minus(y);
    let zp = x.cancel_plus(-y);
    prop_assert!(z == zp, "cancel_plus(x, −y) ≠ cancel_minus(x, y)");
    match (x.bounds(), y.bounds()) {
        (None, _) if y.is_empty() || y.is_common_interval() => prop_assert!(z.is_empty()),
        (Some((a, b)), Some((c, d))) if x.is_common_interval() && y.is_common_interval() => {
            let wx = rat(b) - rat(a);
            let wy = rat(d) - rat(c);
            if wx < wy {
                prop_assert!(z.is_entire());
            } else {
                let lo = rat(a) - rat(c);
                let hi = rat(b) - rat(d);
                let (el, eh) = (
                    round_rational::<T>(&lo, true),
                    round_rational::<T>(&hi, false),
                );
                prop_assert!(
                    z.inf() == el && z.sup() == eh,
                    "cancel_minus({x:?}, {y:?}) = {z:?}"
                );
                // y + z ⊇ x, and equals it up to the rounding.
                prop_assert!(x.subset(y + z));
            }
        }
        _ => prop_assert!(z.is_entire(), "cancel_minus({x:?}, {y:?}) = {z:?}"),
    }
    Ok(())
}

fn small_n() -> impl Strategy<Value = i32> {
    prop_oneof![4 => -6i32..=9, 1 => prop::sample::select(vec![0, 63, 64, -63, 100])]
}

proptest! {
    #![proptest_config(config(CASES))]

    #[test]
    fn unary_reverse_f64(c in interval::<f64>(), x in interval::<f64>(), n in small_n(), s in point_seeds::<f64>(4)) {
        check_all(c, x, n, &s)?;
        check_tight_rev(c, n)?;
    }

    #[test]
    fn unary_reverse_f32(c in interval::<f32>(), x in interval::<f32>(), n in small_n(), s in point_seeds::<f32>(4)) {
        check_all(c, x, n, &s)?;
        check_tight_rev(c, n)?;
    }

    #[test]
    fn binary_reverse_f64(b in interval::<f64>(), c in interval::<f64>(), x in interval::<f64>(), sb in point_seeds::<f64>(2), sx in point_seeds::<f64>(3)) {
        check_binary(b, c, x, &sb, &sx)?;
    }

    #[test]
    fn binary_reverse_f32(b in interval::<f32>(), c in interval::<f32>(), x in interval::<f32>(), sb in point_seeds::<f32>(2), sx in point_seeds::<f32>(3)) {
        check_binary(b, c, x, &sb, &sx)?;
    }

    #[test]
    fn cancel_f64(x in interval::<f64>(), y in interval::<f64>()) {
        check_cancel(x, y)?;
    }

    #[test]
    fn cancel_f32(x in interval::<f32>(), y in interval::<f32>()) {
        check_cancel(x, y)?;
    }

    #[test]
    fn cancel_of_a_sum_f64(x in interval::<f64>(), y in interval::<f64>()) {
        // (x + y) cancel y contains x when the sum is bounded.
        let s = x + y;
        if s.is_common_interval() && y.is_common_interval() {
            prop_assert!(x.subset(s.cancel_minus(y)));
        }
    }
}
