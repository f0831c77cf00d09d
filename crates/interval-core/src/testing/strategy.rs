//! Proptest strategies for interval-core types (the `proptest` cargo feature), with the edge
//! cases that interval-core's own tests use: signed zeros, subnormals, the smallest normals,
//! magnitudes near overflow, `±MAX`, infinite bounds, empty and entire intervals, singletons,
//! intervals a few ulps wide, zero-touching and sign-mixed intervals.
//!
//! ```
//! use interval_core::Float;
//! use interval_core::testing::check_encloses_bracket;
//! use interval_core::testing::strategy::interval_and_point;
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! // For every interval x and point p of it, x² holds p², whose exact value lies between
//! // p·p rounded down and up.
//! TestRunner::default()
//!     .run(&interval_and_point::<f64>(), |(x, p)| {
//!         check_encloses_bracket(x.sqr(), p.mul_down(p), p.mul_up(p))
//!             .map_err(|e| TestCaseError::fail(e.to_string()))
//!     })
//!     .unwrap();
//! ```

use crate::decorated::{DecInterval, Decoration};
use crate::float::Float;
use crate::interval::Interval;
use crate::modal::{Modal, Rounding};
use ::proptest::prelude::*;

/// `2^k` as an exact `f64`, for `−1074 ≤ k ≤ 1023`.
fn pow2(k: i32) -> f64 {
    if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (k + 1074))
    }
}

/// The binary exponents of `T`: `(emin_subnormal, emax)` (−1074 and 1023 for `f64`, −149
/// and 127 for `f32`).
fn exponent_range<T: Float>() -> (i32, i32) {
    let tiny = T::MIN_POSITIVE_SUBNORMAL.to_f64();
    let max = T::MAX.to_f64();
    let e = |x: f64| ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let emin_sub = if tiny.to_bits() >> 52 == 0 {
        -1074
    } else {
        e(tiny)
    };
    (emin_sub, e(max))
}

/// Finite values of `T` of every class: signed zeros, the extreme subnormals and normals,
/// `±MAX` and its neighbours, subnormals, magnitudes near overflow, short-mantissa values
/// (exact results and ties) and values of every exponent, each with either sign.
pub fn finite<T: Float>() -> BoxedStrategy<T> {
    let (emin_sub, emax) = exponent_range::<T>();
    let p = T::MANTISSA_DIGITS as i32;
    let tiny = T::MIN_POSITIVE_SUBNORMAL;
    let min_normal = T::from_f64_rn(pow2(emin_sub + p - 1));
    let special = vec![
        T::ZERO,
        -T::ZERO,
        T::ONE,
        -T::ONE,
        T::HALF,
        T::TWO,
        tiny,
        -tiny,
        min_normal,
        -min_normal,
        min_normal.next_down(),
        T::MAX,
        -T::MAX,
        T::MAX.next_down(),
        T::ONE.next_up(),
        T::ONE.next_down(),
        T::from_f64_rn(0.1),
    ];
    let sign = any::<bool>();
    let with_sign = |neg: bool, v: T| if neg { -v } else { v };
    prop_oneof![
        2 => proptest::sample::select(special),
        // Subnormals: multiples of the smallest one below the normal range.
        2 => (sign, 1u64..(1u64 << (p - 1))).prop_map(move |(s, k)| {
            with_sign(s, T::from_f64_rn(T::MIN_POSITIVE_SUBNORMAL.to_f64() * k as f64))
        }),
        // Near overflow: the top binades.
        2 => (sign, 0.5f64..=1.0).prop_map(move |(s, f)| {
            with_sign(s, T::from_f64_rn(T::MAX.to_f64() * f))
        }),
        // Any exponent, random significand.
        3 => (sign, (emin_sub + p)..=emax, 1.0f64..2.0).prop_map(move |(s, e, m)| {
            with_sign(s, T::from_f64_rn(m * pow2(e)))
        }),
        // Moderate values.
        3 => (-1.0e6f64..1.0e6).prop_map(T::from_f64_rn),
        // Short significands: exact products and sums, ties.
        2 => (-2048i32..=2048, -24i32..=24)
            .prop_map(|(m, k)| T::from_f64_rn(f64::from(m) * pow2(k))),
    ]
    .boxed()
}

/// `x` stepped `k` ulps up (stopping at `MAX`).
fn step_up<T: Float>(x: T, k: u32) -> T {
    let mut y = x;
    for _ in 0..k {
        let n = y.next_up();
        if n.is_finite() {
            y = n;
        }
    }
    y
}

/// `[min(a, b), max(a, b)]`.
fn ordered<T: Float>(a: T, b: T) -> Interval<T> {
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    Interval::new_unchecked(lo, hi)
}

/// Intervals of every kind: empty, entire, singletons, `[−∞, b]`, `[a, +∞]`, ordinary,
/// narrow (a few ulps), zero-touching (`[±0, b]`, `[a, ±0]`) and sign-mixed, with bounds
/// from [`finite`].
pub fn interval<T: Float>() -> BoxedStrategy<Interval<T>> {
    let zero = prop_oneof![Just(T::ZERO), Just(-T::ZERO)];
    prop_oneof![
        1 => Just(Interval::<T>::EMPTY),
        1 => Just(Interval::<T>::ENTIRE),
        3 => finite::<T>().prop_map(|a| Interval::new_unchecked(a, a)),
        2 => finite::<T>().prop_map(|b| Interval::new_unchecked(T::NEG_INFINITY, b)),
        2 => finite::<T>().prop_map(|a| Interval::new_unchecked(a, T::INFINITY)),
        8 => (finite::<T>(), finite::<T>()).prop_map(|(a, b)| ordered(a, b)),
        2 => (finite::<T>(), 1u32..=4).prop_map(|(a, k)| ordered(a, step_up(a, k))),
        1 => (zero.clone(), finite::<T>()).prop_map(|(z, b)| ordered(z, b.abs())),
        1 => (zero, finite::<T>()).prop_map(|(z, a)| ordered(-a.abs(), z)),
        2 => (finite::<T>(), finite::<T>()).prop_map(|(a, b)| ordered(-a.abs(), b.abs())),
    ]
    .boxed()
}

/// Nonempty intervals with finite bounds (IEEE 1788 common intervals).
pub fn bounded_interval<T: Float>() -> BoxedStrategy<Interval<T>> {
    prop_oneof![
        3 => (finite::<T>(), finite::<T>()).prop_map(|(a, b)| ordered(a, b)),
        1 => finite::<T>().prop_map(|a| Interval::new_unchecked(a, a)),
        1 => (finite::<T>(), 1u32..=4).prop_map(|(a, k)| ordered(a, step_up(a, k))),
    ]
    .boxed()
}

/// Finite points of the nonempty interval `x`: its finite ends, interpolations between
/// them, and points at random distances from the finite end of a half-unbounded interval.
/// For the empty interval (which has no point) the strategy yields `NaN`; filter it or draw
/// from [`interval_and_point`] instead.
pub fn point_in<T: Float>(x: Interval<T>) -> BoxedStrategy<T> {
    let Some((lo, hi)) = x.bounds() else {
        return Just(T::NAN).boxed();
    };
    (0u8..4, 0.0f64..=1.0, finite::<T>())
        .prop_map(move |(k, t, v)| {
            let (a, b) = (lo.to_f64(), hi.to_f64());
            let p = match k {
                0 if lo.is_finite() => a,
                1 if hi.is_finite() => b,
                _ if a.is_finite() && b.is_finite() => a + (b - a) * t,
                _ if a.is_finite() => a + v.to_f64().abs(),
                _ if b.is_finite() => b - v.to_f64().abs(),
                _ => v.to_f64(),
            };
            let p = T::from_f64_rn(p).max_nan(lo).min_nan(hi);
            if p.is_finite() {
                p
            } else if lo.is_finite() {
                lo
            } else if hi.is_finite() {
                hi
            } else {
                T::ZERO
            }
        })
        .boxed()
}

/// A nonempty interval from [`interval`] and a finite point of it.
pub fn interval_and_point<T: Float>() -> BoxedStrategy<(Interval<T>, T)> {
    interval::<T>()
        .prop_filter("nonempty", |x| !x.is_empty())
        .prop_flat_map(|x| (Just(x), point_in(x)))
        .boxed()
}

/// Decorated intervals: [`interval`]s with any decoration they can carry (`setDec`), NaI
/// included.
pub fn dec_interval<T: Float>() -> BoxedStrategy<DecInterval<T>> {
    let dec = prop_oneof![
        4 => Just(Decoration::Com),
        1 => Just(Decoration::Dac),
        1 => Just(Decoration::Def),
        1 => Just(Decoration::Trv),
        1 => Just(Decoration::Ill),
    ];
    (interval::<T>(), dec)
        .prop_map(|(x, d)| DecInterval::set_dec(x, d))
        .boxed()
}

/// Modal intervals with rounding `R`: proper (`a ≤ b`), improper (`a > b`) and point-wise,
/// with bounds from [`finite`] and sometimes infinite.
pub fn modal<T: Float, R: Rounding>() -> BoxedStrategy<Modal<T, R>> {
    let bound = prop_oneof![
        8 => finite::<T>(),
        1 => Just(T::INFINITY),
        1 => Just(T::NEG_INFINITY),
    ];
    (bound.clone(), bound)
        .prop_map(|(a, b)| Modal::new_unchecked(a, b))
        .boxed()
}
