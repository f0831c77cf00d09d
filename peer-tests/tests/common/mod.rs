//! What the differential tests against inari share: generators of `f64` values and
//! intervals of every class, the conversion to inari's intervals and the comparisons.

#![allow(dead_code)]

use inari::Interval as In;
use interval_core::{Float, Interval};
use proptest::prelude::*;
use proptest::test_runner::Config;

/// interval-core's `f64` intervals.
pub type Iv = Interval<f64>;

/// A proptest configuration with `cases` cases and no failure file.
pub fn config(cases: u32) -> Config {
    Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    }
}

// ---------------------------------------------------------------------------------------------
// Generators
// ---------------------------------------------------------------------------------------------

pub fn compose(negative: bool, biased_exp: u64, frac: u64) -> f64 {
    f64::from_bits((u64::from(negative) << 63) | (biased_exp << 52) | (frac & ((1 << 52) - 1)))
}

/// Finite values of every class: signed zeros and other boundary values, subnormals, tiny
/// normals, huge magnitudes (2^1000 and up), moderate and short-mantissa values, raw bits.
pub fn finite() -> BoxedStrategy<f64> {
    let boundary: Vec<f64> = [
        0.0,
        1.0,
        2.0,
        0.5,
        3.0,
        0.1,
        f64::MIN_POSITIVE_SUBNORMAL,
        f64::MIN_POSITIVE,
        f64::MIN_POSITIVE.next_down(),
        f64::MAX,
        f64::MAX.next_down(),
        1.0f64.next_up(),
        1.0f64.next_down(),
    ]
    .iter()
    .flat_map(|&x| [x, -x])
    .collect();
    prop_oneof![
        2 => proptest::sample::select(boundary),
        2 => (any::<bool>(), any::<u64>()).prop_map(|(s, f)| compose(s, 0, f)),
        1 => (any::<bool>(), 1..=24u64, any::<u64>()).prop_map(|(s, e, f)| compose(s, e, f)),
        2 => (any::<bool>(), 2023..=2046u64, any::<u64>()).prop_map(|(s, e, f)| compose(s, e, f)),
        4 => (any::<bool>(), 963..=1083u64, any::<u64>()).prop_map(|(s, e, f)| compose(s, e, f)),
        2 => (-2048i32..=2048, -24i32..=24).prop_map(|(m, k)| f64::from(m) * 2f64.powi(k)),
        2 => any::<u64>().prop_map(f64::from_bits).prop_filter("finite", |x| x.is_finite()),
    ]
    .boxed()
}

/// Values where elementary functions are interesting: all classes, plus the ranges where
/// `exp` neither overflows nor underflows, `[−1, 1]`, around 1, and large trig arguments.
pub fn elementary_value() -> BoxedStrategy<f64> {
    prop_oneof![
        3 => finite(),
        2 => -760.0..760.0f64,
        2 => -8.0..8.0f64,
        2 => -1.0..=1.0f64,
        1 => 0.5..2.0f64,
        1 => 1e3..1e22f64,
        1 => -1e22..-1e3f64,
    ]
    .boxed()
}

pub fn ordered(a: f64, b: f64) -> Iv {
    Interval::new(a.min(b), a.max(b)).expect("ordered finite bounds")
}

/// Intervals of every kind with finite bounds from `f`: EMPTY, ENTIRE, singletons,
/// half-unbounded, ordinary, narrow, zero-touching and sign-mixed.
pub fn interval_with(f: fn() -> BoxedStrategy<f64>) -> BoxedStrategy<Iv> {
    let inf = f64::INFINITY;
    prop_oneof![
        1 => Just(Iv::EMPTY),
        1 => Just(Iv::ENTIRE),
        3 => f().prop_map(|a| Interval::point(a).unwrap()),
        2 => f().prop_map(move |b| Interval::new(-inf, b).unwrap()),
        2 => f().prop_map(move |a| Interval::new(a, inf).unwrap()),
        8 => (f(), f()).prop_map(|(a, b)| ordered(a, b)),
        2 => (f(), 1u32..=3).prop_map(|(a, k)| {
            let mut b = a;
            for _ in 0..k {
                if b.next_up().is_finite() {
                    b = b.next_up();
                }
            }
            ordered(a, b)
        }),
        1 => f().prop_map(|b| ordered(0.0, b.abs())),
        1 => f().prop_map(|a| ordered(-a.abs(), 0.0)),
        2 => (f(), f()).prop_map(|(a, b)| ordered(-a.abs(), b.abs())),
    ]
    .boxed()
}

pub fn interval() -> BoxedStrategy<Iv> {
    interval_with(finite)
}

pub fn elementary_interval() -> BoxedStrategy<Iv> {
    interval_with(elementary_value)
}

// ---------------------------------------------------------------------------------------------
// Comparison helpers
// ---------------------------------------------------------------------------------------------

pub fn to_inari(x: Iv) -> In {
    match x.bounds() {
        Some((a, b)) => In::try_from((a, b)).expect("valid interval"),
        None => In::EMPTY,
    }
}

/// Identical sets with identical bounds (`0 == −0`).
pub fn same(ours: Iv, theirs: In) -> bool {
    match ours.bounds() {
        None => theirs.is_empty(),
        Some((a, b)) => !theirs.is_empty() && a == theirs.inf() && b == theirs.sup(),
    }
}

pub fn check_same(op: &str, args: &[Iv], ours: Iv, theirs: In) -> Result<(), TestCaseError> {
    prop_assert!(
        same(ours, theirs),
        "{op}{args:?}: interval-core {ours:?}, inari {theirs:?}"
    );
    Ok(())
}

/// `ours ⊇ theirs`, each bound at most `ulps` steps outside inari's (`None`: containment
/// only).
pub fn check_within(
    op: &str,
    args: &[Iv],
    ours: Iv,
    theirs: In,
    ulps: Option<u32>,
) -> Result<(), TestCaseError> {
    let Some((a, b)) = ours.bounds() else {
        prop_assert!(
            theirs.is_empty(),
            "{op}{args:?}: interval-core empty, inari {theirs:?}"
        );
        return Ok(());
    };
    prop_assert!(
        !theirs.is_empty(),
        "{op}{args:?}: interval-core {ours:?}, inari empty"
    );
    let (c, d) = (theirs.inf(), theirs.sup());
    prop_assert!(
        a <= c && d <= b,
        "{op}{args:?}: interval-core {ours:?} does not contain inari {theirs:?}"
    );
    let Some(ulps) = ulps else { return Ok(()) };
    let (mut lo_limit, mut hi_limit) = (c, d);
    for _ in 0..ulps {
        lo_limit = lo_limit.next_down();
        hi_limit = hi_limit.next_up();
    }
    prop_assert!(
        lo_limit <= a && b <= hi_limit,
        "{op}{args:?}: interval-core {ours:?} is more than {ulps} ulp wider than inari {theirs:?}"
    );
    Ok(())
}
