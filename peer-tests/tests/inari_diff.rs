//! Differential tests of `interval_core::Interval<f64>` against inari 2 (whose operations are
//! tight: hardware directed rounding for arithmetic, MPFR for elementary functions).
//!
//! * Tight operations (`+ − × ÷`, `fma`, `sqr`, `sqrt`, `recip`, `neg`, `abs`, `min`,
//!   `max`, `mul_rev_to_pair`, `intersection`, `convex_hull`) must give identical bounds
//!   (up to the sign of zero) for all inputs, and the relations identical answers; `fma` is
//!   also exercised with products and addends near overflow and in and below the subnormal
//!   range.
//! * The numeric functions `inf sup mid rad wid mag mig` and the predicates must give
//!   identical results.
//! * Elementary functions (`pown`, `pow`, `exp`, `exp2`, `exp10`, `ln`, `log2`, `log10`,
//!   `sinh`, `cosh`, `tanh`, `sin`, `cos`, `tan`, `asin`, `acos`, `atan`, `atan2`) are
//!   documented within one ulp of tight: ours must contain inari's result, each bound at most
//!   one step wider.
//!
//! inari needs AVX2/FMA: build with `RUSTFLAGS="-C target-cpu=x86-64-v3"` and
//! `--features inari` (see the README of this package).

#![cfg(feature = "inari")]

use inari::Interval as In;
use interval_core::{Float, Interval};
use proptest::prelude::*;

mod common;
use common::*;

const CASES: u32 = 30_000;
const ELEMENTARY_CASES: u32 = 15_000;

/// A value of magnitude about `2^e` with the given fraction bits: normal, on the subnormal
/// grid below the normal range (at least the smallest subnormal), `MAX` above it.
fn with_exponent(negative: bool, e: i32, frac: u64) -> f64 {
    let biased = e + 1023;
    let v = if biased > 2046 {
        f64::MAX
    } else if biased >= 1 {
        compose(false, biased as u64, frac)
    } else {
        let m = ((1u64 << 52) | (frac & ((1 << 52) - 1))) >> (1 - biased).min(63);
        if m == 0 {
            f64::MIN_POSITIVE_SUBNORMAL
        } else {
            compose(false, 0, m)
        }
    };
    if negative { -v } else { v }
}

/// Operands of `fma` far from the moderate range: exact products near overflow
/// (`2^993` to `2^1025`), beyond it (up to `2^2046`) or tiny (`2^-1137` to `2^-895`), with
/// addends comparable to the product, cancelling it, negligible, dominating, huge with the
/// opposite sign, bringing the product back to within a few half-ulps of `±MAX`,
/// subnormal, or zero; each operand is a point or a narrow interval around the value.
fn fma_extreme() -> BoxedStrategy<(Iv, Iv, Iv)> {
    let frac = || {
        prop_oneof![
            3 => any::<u64>(),
            2 => (0u64..16).prop_map(|m| m << 48),
            1 => 0u64..4,
            1 => (0u64..4).prop_map(|k| ((1 << 52) - 1) - k),
        ]
    };
    let exp = prop_oneof![3 => 993i32..=1025, 1 => 1025i32..=2046, 3 => -1137i32..=-895];
    let shape = || (0u8..3, 1u32..=3);
    (
        (exp, 0.0..=1.0f64, any::<(bool, bool)>(), (frac(), frac())),
        (0u8..9, any::<bool>(), -3i32..=3, frac(), 0u32..=1000),
        (shape(), shape(), shape()),
    )
        .prop_map(|((e, t, signs, fa), (mode, s, k, f, r), shapes)| {
            let e = if mode == 7 { 1024 + (k & 1) } else { e };
            let lo = (e - 1023).max(-1074);
            let hi = (e + 1074).min(1023);
            let ea = lo + ((f64::from(hi - lo) * t).round() as i32).clamp(0, hi - lo);
            let a = with_exponent(signs.0, ea, fa.0);
            let b = with_exponent(signs.1, e - ea, fa.1);
            let opposite = !(signs.0 ^ signs.1);
            let pick = |lo: i32, hi: i32| lo + (i64::from(hi - lo) * i64::from(r) / 1000) as i32;
            let rn = a * b;
            let c = match mode {
                0 => with_exponent(s, e + k, f),
                1 if rn.is_finite() && rn != 0.0 => -rn,
                1 => with_exponent(opposite, e + k, f),
                2 => with_exponent(s, pick(e - 146, e - 45), f),
                3 => with_exponent(s, pick(e + 45, e + 146), f),
                4 => compose(s, 0, f),
                5 => 0.0,
                6 => with_exponent(opposite, pick(917, 1023), f),
                7 => {
                    // a·b + c = ±(MAX + k·2^970), up to the rounding of c.
                    let two = |n: u32| rug::Rational::from(1) << n;
                    let ab =
                        rug::Rational::from_f64(a).unwrap() * rug::Rational::from_f64(b).unwrap();
                    let target = rug::Rational::from_f64(f64::MAX).unwrap() + two(970) * k;
                    let target = if ab < 0 { -target } else { target };
                    let c = (target - ab).to_f64();
                    if c.is_finite() { c } else { -f64::MAX }
                }
                _ => with_exponent(s, pick(-1074, 1023), f),
            };
            let around = |v: f64, (kind, n): (u8, u32)| {
                let w = match kind {
                    0 => v,
                    1 => (0..n).fold(v, |w, _| {
                        if w.next_up().is_finite() {
                            w.next_up()
                        } else {
                            w
                        }
                    }),
                    _ => (0..n).fold(v, |w, _| {
                        if w.next_down().is_finite() {
                            w.next_down()
                        } else {
                            w
                        }
                    }),
                };
                ordered(v, w)
            };
            (
                around(a, shapes.0),
                around(b, shapes.1),
                around(c, shapes.2),
            )
        })
        .boxed()
}

// ---------------------------------------------------------------------------------------------
// Tight operations: identical bounds
// ---------------------------------------------------------------------------------------------

fn arithmetic(x: Iv, y: Iv) -> Result<(), TestCaseError> {
    let (ix, iy) = (to_inari(x), to_inari(y));
    let args = [x, y];
    check_same("add", &args, x + y, ix + iy)?;
    check_same("sub", &args, x - y, ix - iy)?;
    check_same("mul", &args, x * y, ix * iy)?;
    check_same("div", &args, x / y, ix / iy)?;
    check_same("min", &args, x.min(y), ix.min(iy))?;
    check_same("max", &args, x.max(y), ix.max(iy))?;
    check_same(
        "intersection",
        &args,
        x.intersection(y),
        ix.intersection(iy),
    )?;
    check_same("convex_hull", &args, x.convex_hull(y), ix.convex_hull(iy))?;
    let (p1, p2) = y.mul_rev_to_pair(x);
    let [q1, q2] = iy.mul_rev_to_pair(ix);
    check_same("mul_rev_to_pair.0", &args, p1, q1)?;
    check_same("mul_rev_to_pair.1", &args, p2, q2)?;

    let ctx = format!("x = {x:?}, y = {y:?}");
    prop_assert_eq!(x == y, ix == iy, "equal: {}", ctx);
    prop_assert_eq!(x.subset(y), ix.subset(iy), "subset: {}", ctx);
    prop_assert_eq!(x.less(y), ix.less(iy), "less: {}", ctx);
    prop_assert_eq!(x.strict_less(y), ix.strict_less(iy), "strict_less: {}", ctx);
    prop_assert_eq!(x.precedes(y), ix.precedes(iy), "precedes: {}", ctx);
    prop_assert_eq!(
        x.strict_precedes(y),
        ix.strict_precedes(iy),
        "strict_precedes: {}",
        ctx
    );
    prop_assert_eq!(x.interior(y), ix.interior(iy), "interior: {}", ctx);
    prop_assert_eq!(x.disjoint(y), ix.disjoint(iy), "disjoint: {}", ctx);
    Ok(())
}

fn unary(x: Iv) -> Result<(), TestCaseError> {
    let ix = to_inari(x);
    check_same("neg", &[x], -x, -ix)?;
    check_same("abs", &[x], x.abs(), ix.abs())?;
    check_same("sqr", &[x], x.sqr(), ix.sqr())?;
    check_same("sqrt", &[x], x.sqrt(), ix.sqrt())?;
    check_same("recip", &[x], x.recip(), ix.recip())?;
    Ok(())
}

/// The IEEE 1788 numeric functions and predicates: identical numbers (NaN for empty on both
/// sides where the standard says so), identical answers.
fn numeric(x: Iv) -> Result<(), TestCaseError> {
    let ix = to_inari(x);
    let same_num = |a: f64, b: f64| (a.is_nan() && b.is_nan()) || a == b;
    for (name, ours, theirs) in [
        ("inf", x.inf(), ix.inf()),
        ("sup", x.sup(), ix.sup()),
        ("mid", x.mid(), ix.mid()),
        ("rad", x.rad(), ix.rad()),
        ("wid", x.wid(), ix.wid()),
        ("mag", x.mag(), ix.mag()),
        ("mig", x.mig(), ix.mig()),
    ] {
        prop_assert!(
            same_num(ours, theirs),
            "{name}({x:?}): interval-core {ours:?}, inari {theirs:?}"
        );
    }
    prop_assert_eq!(x.is_empty(), ix.is_empty());
    prop_assert_eq!(x.is_entire(), ix.is_entire());
    prop_assert_eq!(x.is_singleton(), ix.is_singleton());
    prop_assert_eq!(x.is_common_interval(), ix.is_common_interval());
    if let Some((a, b)) = x.bounds() {
        for v in [a, b, x.mid(), a.next_down(), b.next_up()] {
            if v.is_finite() {
                prop_assert_eq!(x.contains(v), ix.contains(v), "contains({:?}, {:?})", x, v);
            }
        }
    }
    Ok(())
}

fn fma(x: Iv, y: Iv, z: Iv) -> Result<(), TestCaseError> {
    let ours = x.fma(y, z);
    let theirs = to_inari(x).mul_add(to_inari(y), to_inari(z));
    check_same("fma", &[x, y, z], ours, theirs)
}

proptest! {
    #![proptest_config(config(CASES))]

    #[test]
    fn binary_operations_and_relations_match_inari(x in interval(), y in interval()) {
        arithmetic(x, y)?;
    }

    #[test]
    fn binary_operations_match_inari_on_related_operands(x in interval(), k in -2i32..=2) {
        // y close to −x: sums and differences of the bounds cancel.
        let y = match x.bounds() {
            Some((a, b)) => {
                let shift = |v: f64| if k >= 0 { (0..k).fold(v, |v, _| v.next_up()) }
                    else { (0..-k).fold(v, |v, _| v.next_down()) };
                Interval::new(shift(-b), shift(-a)).unwrap_or(x)
            }
            None => x,
        };
        arithmetic(x, y)?;
    }

    #[test]
    fn unary_operations_match_inari(x in interval()) {
        unary(x)?;
    }

    #[test]
    fn numeric_functions_match_inari(x in interval()) {
        numeric(x)?;
    }

    #[test]
    fn fma_matches_inari(x in interval(), y in interval(), z in interval()) {
        fma(x, y, z)?;
    }

    #[test]
    fn fma_matches_inari_moderate(x in elementary_interval(), y in elementary_interval(),
                                  z in elementary_interval()) {
        fma(x, y, z)?;
    }

    #[test]
    fn fma_matches_inari_far_from_moderate_range((x, y, z) in fma_extreme()) {
        fma(x, y, z)?;
    }
}

// ---------------------------------------------------------------------------------------------
// Elementary functions: contain inari's tight result, at most one ulp wider
// ---------------------------------------------------------------------------------------------

/// Our documented accuracy for the elementary functions (`pown` included): one ulp.
const ULPS: Option<u32> = Some(1);

/// `sin`, `cos` and `tan` may return their whole range when the rounded-up width lies in the
/// one-ulp window `[π↓, π)` (documented).
fn trig_width_window(x: Iv) -> bool {
    x.bounds().is_some_and(|(a, b)| {
        let w = b.sub_up(a);
        w.is_finite() && (std::f64::consts::PI..=std::f64::consts::PI.next_up()).contains(&w)
    })
}

/// MPFR precision for the trigonometric reference: enough to place any `f64` (up to 2^1024)
/// relative to the multiples of π/2 exactly.
const TRIG_PREC: u32 = 2400;

/// `f(x)` rounded down or up to `f64` (via MPFR at [`TRIG_PREC`] bits, same direction).
fn mpfr_trig(x: f64, f: fn(&rug::Float) -> rug::Float, down: bool) -> f64 {
    use rug::float::Round;
    let v = f(&rug::Float::with_val(TRIG_PREC, x));
    v.to_f64_round(if down { Round::Down } else { Round::Up })
}

/// The integers `k` with `a ≤ offset + k·π ≤ b`, as `(first, last)` (empty when
/// `first > last`), `offset` = 0 or π/2; computed at [`TRIG_PREC`] bits.
fn multiples_of_pi(a: f64, b: f64, half_pi_offset: bool) -> (rug::Integer, rug::Integer) {
    use rug::float::Constant;
    let pi = rug::Float::with_val(TRIG_PREC, Constant::Pi);
    let shift = |x: f64| {
        let mut v = rug::Float::with_val(TRIG_PREC, x);
        if half_pi_offset {
            v -= rug::Float::with_val(TRIG_PREC, &pi / 2u32);
        }
        v / &pi
    };
    let first = shift(a).ceil().to_integer().expect("finite");
    let last = shift(b).floor().to_integer().expect("finite");
    (first, last)
}

/// The tight enclosure of `sin` (`half_pi_offset`) or `cos` over `x`, by MPFR: the endpoint
/// values, and `±1` where an extremum `offset + kπ` lies inside (a maximum for even `k`).
fn tight_sin_cos(x: Iv, half_pi_offset: bool) -> Option<(f64, f64)> {
    let (a, b) = x.bounds()?;
    if !(a.is_finite() && b.is_finite()) {
        return Some((-1.0, 1.0));
    }
    let f: fn(&rug::Float) -> rug::Float = if half_pi_offset {
        |v| v.clone().sin()
    } else {
        |v| v.clone().cos()
    };
    let mut lo = mpfr_trig(a, f, true).min(mpfr_trig(b, f, true));
    let mut hi = mpfr_trig(a, f, false).max(mpfr_trig(b, f, false));
    let (first, last) = multiples_of_pi(a, b, half_pi_offset);
    let mut k = first;
    while k <= last {
        if k.is_even() {
            hi = 1.0;
        } else {
            lo = -1.0;
        }
        if lo == -1.0 && hi == 1.0 {
            break;
        }
        k += 1;
    }
    Some((lo, hi))
}

/// The tight enclosure of `tan` over `x` by MPFR: ENTIRE when a pole `π/2 + kπ` lies inside,
/// otherwise the endpoint values (increasing between poles).
fn tight_tan(x: Iv) -> Option<(f64, f64)> {
    let (a, b) = x.bounds()?;
    if !(a.is_finite() && b.is_finite()) {
        return Some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let (first, last) = multiples_of_pi(a, b, true);
    if first <= last {
        return Some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let f: fn(&rug::Float) -> rug::Float = |v| v.clone().tan();
    Some((mpfr_trig(a, f, true), mpfr_trig(b, f, false)))
}

/// Checks `tight ⊆ ours`, `ours` at most `ulps` wider than `tight`, and `ours` at most one ulp
/// wider than inari's result (inari reduces huge arguments approximately and may be looser
/// than tight; it must still contain the tight result).
fn check_trig(
    op: &str,
    x: Iv,
    ours: Iv,
    theirs: In,
    tight: Option<(f64, f64)>,
    ulps: Option<u32>,
) -> Result<(), TestCaseError> {
    let reference = match tight {
        Some((lo, hi)) => In::try_from((lo, hi)).expect("valid reference"),
        None => In::EMPTY,
    };
    check_within(op, &[x], ours, reference, ulps)?;
    prop_assert!(
        reference.subset(theirs),
        "{op}({x:?}): inari {theirs:?} misses the MPFR reference {reference:?}"
    );
    if let Some((a, b)) = ours.bounds() {
        prop_assert!(
            theirs.inf().next_down() <= a && b <= theirs.sup().next_up(),
            "{op}({x:?}): interval-core {ours:?} more than 1 ulp wider than inari {theirs:?}"
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(ELEMENTARY_CASES))]

    #[test]
    fn exp_log_within_one_ulp_of_inari(x in elementary_interval()) {
        let ix = to_inari(x);
        check_within("exp", &[x], x.exp(), ix.exp(), ULPS)?;
        check_within("exp2", &[x], x.exp2(), ix.exp2(), ULPS)?;
        check_within("exp10", &[x], x.exp10(), ix.exp10(), ULPS)?;
        check_within("ln", &[x], x.ln(), ix.ln(), ULPS)?;
        check_within("log", &[x], x.log(), ix.ln(), ULPS)?;
        check_within("log2", &[x], x.log2(), ix.log2(), ULPS)?;
        check_within("log10", &[x], x.log10(), ix.log10(), ULPS)?;
    }

    #[test]
    fn hyperbolic_within_one_ulp_of_inari(x in elementary_interval()) {
        let ix = to_inari(x);
        check_within("sinh", &[x], x.sinh(), ix.sinh(), ULPS)?;
        check_within("cosh", &[x], x.cosh(), ix.cosh(), ULPS)?;
        check_within("tanh", &[x], x.tanh(), ix.tanh(), ULPS)?;
    }

    #[test]
    fn trig_within_one_ulp_of_inari(x in elementary_interval()) {
        let ix = to_inari(x);
        let ulps = if trig_width_window(x) { None } else { ULPS };
        check_trig("sin", x, x.sin(), ix.sin(), tight_sin_cos(x, true), ulps)?;
        check_trig("cos", x, x.cos(), ix.cos(), tight_sin_cos(x, false), ulps)?;
        check_trig("tan", x, x.tan(), ix.tan(), tight_tan(x), ulps)?;
        check_within("asin", &[x], x.asin(), ix.asin(), ULPS)?;
        check_within("acos", &[x], x.acos(), ix.acos(), ULPS)?;
        check_within("atan", &[x], x.atan(), ix.atan(), ULPS)?;
    }

    #[test]
    fn atan2_within_one_ulp_of_inari(y in elementary_interval(), x in elementary_interval()) {
        check_within("atan2", &[y, x], y.atan2(x), to_inari(y).atan2(to_inari(x)), ULPS)?;
    }

    #[test]
    fn pow_within_one_ulp_of_inari(x in elementary_interval(), y in elementary_interval()) {
        check_within("pow", &[x, y], x.pow(y), to_inari(x).pow(to_inari(y)), ULPS)?;
    }

    #[test]
    fn pown_within_one_ulp_of_inari(
        x in elementary_interval(),
        n in prop_oneof![4 => -12i32..=12, 1 => -80i32..=80, 1 => any::<i32>()],
    ) {
        check_within("pown", &[x], x.pown(n), to_inari(x).powi(n), ULPS)?;
    }
}

#[test]
fn known_values_agree() {
    let x = Interval::new(-2.0, 3.0).unwrap();
    assert!(same(x.pown(3), In::try_from((-8.0, 27.0)).unwrap()));
    assert!(same(x * x, to_inari(x) * to_inari(x)));
    let one = Interval::new(1.0, 1.0).unwrap();
    let third = one / Interval::new(3.0, 3.0).unwrap();
    assert!(same(
        third,
        to_inari(one) / In::try_from((3.0, 3.0)).unwrap()
    ));
}
