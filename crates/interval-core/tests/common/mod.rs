//! Shared helpers for the integration tests of `interval-core`.
//!
//! * Generators (proptest strategies) of `f64`/`f32` values covering every class that
//!   matters for directed rounding: signed zeros, subnormals, tiny normals, huge magnitudes
//!   near overflow, `±MAX`, infinities, NaN, short-mantissa values (exact results, ties) and
//!   plain random values; of intervals (empty, entire, half-unbounded, singletons, narrow,
//!   zero-touching, sign-mixed, ordinary); of `fma` triples with products and addends near
//!   overflow or in and below the subnormal range; and of points inside an interval (finite endpoints
//!   plus interior points).
//! * An exact oracle: [`Ext`] (extended rationals built from the exact binary values with
//!   `rug::Rational`), [`SqrtOf`] (an exact square root, compared by squaring), and the
//!   neighbour test of directed rounding: `r` is the value rounded toward −∞ of `e` iff
//!   `r ≤ e < next_up(r)` ([`is_round_down`]), and symmetrically for +∞
//!   ([`is_round_up`]). All comparisons are exact; nothing is compared in floating point.
//! * Conversions of exact values (rationals, `rug::Float`s computed by MPFR) to the nearest
//!   `f64`/`f32` below or above, on the real subnormal grid and with overflow to `±∞`
//!   ([`round_rational`], [`round_mpfr`]), for tests of functions evaluated by MPFR.
//!
//! Include it with `mod common;` from any integration test.

#![allow(dead_code)]

use core::cmp::Ordering;
use core::fmt::Debug;

use interval_core::{Float, Interval};
use proptest::prelude::*;
use proptest::test_runner::Config;
use rug::Rational;

// ---------------------------------------------------------------------------------------------
// Floating-point types under test
// ---------------------------------------------------------------------------------------------

/// What the generators need to know about `f64` and `f32` beyond [`Float`].
pub trait TestFloat: Float + Debug {
    /// Number of stored fraction bits (52 or 23).
    const FRAC_BITS: u32;
    /// Exponent bias (1023 or 127).
    const BIAS: u32;
    /// Largest biased exponent of a finite value (2046 or 254).
    const MAX_BIASED: u32;
    /// Unbiased exponent where the "huge" generator starts (2^1000 or 2^100).
    const HUGE_FROM: u32;

    /// The value with the given sign, biased exponent and fraction bits (masked).
    fn compose(negative: bool, biased_exp: u32, frac: u64) -> Self;
    /// Reinterprets the low bits of `bits` as a value of this type.
    fn from_raw(bits: u64) -> Self;
    /// The bit pattern, zero-extended.
    fn to_raw(self) -> u64;
}

impl TestFloat for f64 {
    const FRAC_BITS: u32 = 52;
    const BIAS: u32 = 1023;
    const MAX_BIASED: u32 = 2046;
    const HUGE_FROM: u32 = 1000;

    fn compose(negative: bool, biased_exp: u32, frac: u64) -> Self {
        let bits = (u64::from(negative) << 63)
            | (u64::from(biased_exp & 0x7ff) << 52)
            | (frac & ((1 << 52) - 1));
        f64::from_bits(bits)
    }
    fn from_raw(bits: u64) -> Self {
        f64::from_bits(bits)
    }
    fn to_raw(self) -> u64 {
        self.to_bits()
    }
}

impl TestFloat for f32 {
    const FRAC_BITS: u32 = 23;
    const BIAS: u32 = 127;
    const MAX_BIASED: u32 = 254;
    const HUGE_FROM: u32 = 100;

    fn compose(negative: bool, biased_exp: u32, frac: u64) -> Self {
        let bits = (u32::from(negative) << 31)
            | ((biased_exp & 0xff) << 23)
            | (frac as u32 & ((1 << 23) - 1));
        f32::from_bits(bits)
    }
    fn from_raw(bits: u64) -> Self {
        f32::from_bits(bits as u32)
    }
    fn to_raw(self) -> u64 {
        u64::from(self.to_bits())
    }
}

/// A proptest configuration with `cases` cases and no regression files written to disk.
///
/// The environment variable `INTERVAL_CORE_TEST_SCALE` (a positive integer, default 1)
/// multiplies the number of cases, for longer soak runs.
pub fn config(cases: u32) -> Config {
    let scale = std::env::var("INTERVAL_CORE_TEST_SCALE")
        .ok()
        .and_then(|v| v.parse::<u32>().ok())
        .filter(|&v| v > 0)
        .unwrap_or(1);
    Config {
        cases: cases.saturating_mul(scale),
        failure_persistence: None,
        ..Config::default()
    }
}

// ---------------------------------------------------------------------------------------------
// Value generators
// ---------------------------------------------------------------------------------------------

/// Finite values that sit on class boundaries: signed zeros, the extreme subnormals and
/// normals, `±MAX`, and a few small exact numbers.
pub fn boundary_values<T: TestFloat>() -> Vec<T> {
    let tiny = T::MIN_POSITIVE_SUBNORMAL;
    let min_normal = T::compose(false, 1, 0);
    let max_sub = min_normal.next_down();
    let mut v = Vec::new();
    for x in [
        T::ZERO,
        T::ONE,
        T::TWO,
        T::HALF,
        tiny,
        tiny.next_up(),
        max_sub,
        min_normal,
        T::MAX,
        T::MAX.next_down(),
        T::ONE.next_up(),
        T::ONE.next_down(),
        T::from_f64_rn(3.0),
        T::from_f64_rn(0.1),
    ] {
        v.push(x);
        v.push(-x);
    }
    v
}

/// Finite values: boundary values, subnormals (zero exponent, random fraction), tiny normals,
/// huge magnitudes near overflow, moderate random values, short-mantissa values and random
/// finite bit patterns, each with a random sign.
pub fn finite<T: TestFloat>() -> BoxedStrategy<T> {
    let frac = any::<u64>;
    let sign = any::<bool>;
    let max_b = T::MAX_BIASED;
    let bias = T::BIAS;
    let huge_from = T::BIAS + T::HUGE_FROM;
    let moderate = if T::FRAC_BITS > 30 { 60 } else { 30 };
    prop_oneof![
        2 => proptest::sample::select(boundary_values::<T>()),
        2 => (sign(), frac()).prop_map(|(s, f)| T::compose(s, 0, f)),
        1 => (sign(), 1..=24u32, frac()).prop_map(|(s, e, f)| T::compose(s, e, f)),
        2 => (sign(), huge_from..=max_b, frac()).prop_map(|(s, e, f)| T::compose(s, e, f)),
        4 => (sign(), (bias - moderate)..=(bias + moderate), frac())
            .prop_map(|(s, e, f)| T::compose(s, e, f)),
        2 => (-2048i32..=2048, -24i32..=24)
            .prop_map(|(m, k)| T::from_f64_rn(f64::from(m) * 2f64.powi(k))),
        2 => any::<u64>()
            .prop_map(T::from_raw)
            .prop_filter("finite", |x: &T| x.is_finite()),
    ]
    .boxed()
}

/// Finite values of moderate magnitude (and zeros): products and sums of these stay far from
/// overflow and from the subnormal range.
pub fn moderate<T: TestFloat>() -> BoxedStrategy<T> {
    let bias = T::BIAS;
    prop_oneof![
        1 => Just(T::ZERO),
        1 => Just(-T::ZERO),
        4 => (any::<bool>(), (bias - 40)..=(bias + 40), any::<u64>())
            .prop_map(|(s, e, f)| T::compose(s, e, f)),
        2 => (-2048i32..=2048, -24i32..=24)
            .prop_map(|(m, k)| T::from_f64_rn(f64::from(m) * 2f64.powi(k))),
    ]
    .boxed()
}

/// Any value including `±∞` and NaN (for the rounding primitives).
pub fn any_value<T: TestFloat>() -> BoxedStrategy<T> {
    prop_oneof![
        12 => finite::<T>(),
        1 => Just(T::INFINITY),
        1 => Just(T::NEG_INFINITY),
        1 => Just(T::NAN),
    ]
    .boxed()
}

/// `x` moved by `k` representable steps (up for `k > 0`), stopping at `±MAX`.
pub fn step<T: TestFloat>(x: T, k: i32) -> T {
    let mut y = x;
    for _ in 0..k.unsigned_abs() {
        let n = if k > 0 { y.next_up() } else { y.next_down() };
        if !n.is_finite() {
            break;
        }
        y = n;
    }
    y
}

/// Pairs of values: mostly independent, sometimes both in the top three binades (sums near
/// overflow), (nearly) cancelling or (nearly) equal, so sums and differences exercise
/// overflow, cancellation and exact results.
pub fn value_pair<T: TestFloat>(with_specials: bool) -> BoxedStrategy<(T, T)> {
    let base = if with_specials {
        any_value::<T>()
    } else {
        finite::<T>()
    };
    let top = (T::MAX_BIASED - 2)..=T::MAX_BIASED;
    prop_oneof![
        6 => (base.clone(), base.clone()),
        1 => (any::<bool>(), top.clone(), any::<u64>(), any::<bool>(), top, any::<u64>())
            .prop_map(|(s, e, f, t, g, h)| (T::compose(s, e, f), T::compose(t, g, h))),
        1 => (finite::<T>(), -3i32..=3).prop_map(|(a, k)| (a, -step(a, k))),
        1 => (finite::<T>(), -3i32..=3).prop_map(|(a, k)| (a, step(a, k))),
        1 => (finite::<T>(), finite::<T>()).prop_map(|(a, b)| {
            let c = T::from_f64_rn(-(a.to_f64() + b.to_f64() * 1e-9));
            (a, if c.is_finite() { c } else { -a })
        }),
    ]
    .boxed()
}

/// Triples for `fma`: mostly independent, sometimes with `c ≈ −a·b` (massive cancellation,
/// the hard case of FMA error analysis), sometimes with huge or tiny products
/// ([`fma_extreme_triple`]).
pub fn fma_triple<T: TestFloat>(with_specials: bool) -> BoxedStrategy<(T, T, T)> {
    let base = if with_specials {
        any_value::<T>()
    } else {
        finite::<T>()
    };
    prop_oneof![
        3 => (base.clone(), base.clone(), base.clone()),
        2 => (finite::<T>(), finite::<T>(), -4i32..=4).prop_map(|(a, b, k)| {
            let p = a * b;
            let c = if p.is_finite() { step(-p, k) } else { -T::MAX };
            (a, b, c)
        }),
        1 => (finite::<T>(), finite::<T>(), finite::<T>()).prop_map(|(a, b, c)| {
            // c a tiny relative perturbation of −a·b.
            let p = (a * b).to_f64();
            let c = T::from_f64_rn(-p * (1.0 + c.to_f64() * 1e-12));
            (a, b, if c.is_finite() { c } else { T::MAX })
        }),
        2 => fma_extreme_triple::<T>(),
    ]
    .boxed()
}

/// A finite value of magnitude about `2^e` (unbiased exponent `e`, fraction bits `frac`):
/// normal in the normal range, on the subnormal grid below it (at least the smallest
/// subnormal), `±MAX` above it.
pub fn with_exponent<T: TestFloat>(negative: bool, e: i32, frac: u64) -> T {
    let biased = e + T::BIAS as i32;
    let v = if biased > T::MAX_BIASED as i32 {
        T::MAX
    } else if biased >= 1 {
        T::compose(false, biased as u32, frac)
    } else {
        let mantissa = (1u64 << T::FRAC_BITS) | (frac & ((1u64 << T::FRAC_BITS) - 1));
        let m = mantissa >> (1 - biased).min(63) as u32;
        if m == 0 {
            T::MIN_POSITIVE_SUBNORMAL
        } else {
            T::compose(false, 0, m)
        }
    };
    if negative { -v } else { v }
}

/// Fraction bits: random, short (few leading bits: exact products, ties and cancellations),
/// one to three ulps above a power of two, or just below the next power of two.
pub fn fraction<T: TestFloat>() -> BoxedStrategy<u64> {
    let bits = T::FRAC_BITS;
    let mask = (1u64 << bits) - 1;
    prop_oneof![
        3 => any::<u64>(),
        2 => (0u64..16).prop_map(move |m| m << (bits - 4)),
        1 => 0u64..4,
        1 => (0u64..4).prop_map(move |k| mask - k),
    ]
    .boxed()
}

/// Largest unbiased exponent of a finite value (1023 or 127).
fn emax<T: TestFloat>() -> i32 {
    T::BIAS as i32
}

/// Unbiased exponent of the smallest subnormal (−1074 or −149).
fn emin_sub<T: TestFloat>() -> i32 {
    1 - T::BIAS as i32 - T::FRAC_BITS as i32
}

/// Two factors whose exact product is about `2^e`, the split of the exponent chosen by `t`
/// in `[0, 1]` (either factor may be subnormal or near overflow).
fn factors<T: TestFloat>(e: i32, t: f64, signs: (bool, bool), fracs: (u64, u64)) -> (T, T) {
    let lo = (e - emax::<T>()).max(emin_sub::<T>());
    let hi = (e - emin_sub::<T>()).min(emax::<T>());
    let ea = lo + ((f64::from(hi - lo) * t).round() as i32).clamp(0, hi - lo);
    (
        with_exponent(signs.0, ea, fracs.0),
        with_exponent(signs.1, e - ea, fracs.1),
    )
}

/// Finite `fma` triples far from the moderate range: exact products `a·b` near overflow
/// (`2^(emax−30)` to `2^(emax+2)`), far beyond it (up to `MAX²`) or tiny (from below the
/// smallest subnormal to `2^(emin+emax/8)`, i.e. about `2^-1137` to `2^-895` for `f64`),
/// with addends of comparable size, cancelling the product (`c` a few steps from
/// `−RN(a·b)`), negligible against it, dominating it, huge with the opposite sign, bringing
/// a product beyond `MAX` back to the edge of the finite range (`a·b + c` within a few
/// half-ulps of `±MAX`), subnormal, at the opposite extreme (tiny product with a huge addend
/// and the reverse), zero, or any finite value.
pub fn fma_extreme_triple<T: TestFloat>() -> BoxedStrategy<(T, T, T)> {
    let (emax, emin_sub) = (emax::<T>(), emin_sub::<T>());
    let emin = 1 - emax;
    let p = T::MANTISSA_DIGITS as i32;
    let huge = (emax - 30)..=(emax + 2);
    let beyond = (emax + 2)..=(2 * emax);
    let tiny = (emin_sub - p - 10)..=(emin + emax / 8);
    let product_exp = prop_oneof![3 => huge.clone(), 1 => beyond, 3 => tiny.clone()];
    let product = (
        product_exp,
        0.0..=1.0f64,
        any::<(bool, bool)>(),
        (fraction::<T>(), fraction::<T>()),
    );
    let addend = (
        0u8..11,
        any::<bool>(),
        -3i32..=3,
        fraction::<T>(),
        0u32..=1000,
    );
    (product, addend, finite::<T>())
        .prop_map(move |((e, t, signs, fracs), (mode, s, k, f, r), any_c)| {
            let e = if mode == 8 { emax + 1 + (k & 1) } else { e };
            let (a, b) = factors::<T>(e, t, signs, fracs);
            // A position in an exponent range chosen by r.
            let pick = |lo: i32, hi: i32| lo + (i64::from(hi - lo) * i64::from(r) / 1000) as i32;
            let rn = a * b;
            let c = match mode {
                // Comparable magnitude.
                0 => with_exponent(s, e + k, f),
                // Cancellation: a few steps from −RN(a·b).
                1 if rn.is_finite() && rn != T::ZERO => step(-rn, k),
                1 => with_exponent(!(signs.0 ^ signs.1), e + k, f),
                // Negligible against the product (below its ulp, down to far below).
                2 => with_exponent(s, pick(e - 2 * p - 40, e - p + 8), f),
                // Dominating the product.
                3 => with_exponent(s, pick(e + p - 8, e + 2 * p + 40), f),
                // Subnormal.
                4 => T::compose(s, 0, f),
                // At the opposite extreme of the exponent range.
                5 if e > 0 => with_exponent(s, pick(*tiny.start(), *tiny.end()), f),
                5 => with_exponent(s, pick(*huge.start(), emax), f),
                6 => T::ZERO,
                // Huge, opposite to the product.
                7 => with_exponent(!(signs.0 ^ signs.1), pick(emax - 2 * p, emax), f),
                // a·b + c = ±(MAX + k·2^(emax−p)) up to the rounding of c (far below that
                // half-ulp of MAX): at the edge of overflow.
                8 => {
                    let target = rat(T::MAX) + pow2(emax - p) * k;
                    let ab = rat(a) * rat(b);
                    let target = if ab < 0 { -target } else { target };
                    let c = round_rational::<T>(&(target - ab), true);
                    if c.is_finite() { c } else { -T::MAX }
                }
                _ => any_c,
            };
            (a, b, c)
        })
        .boxed()
}

// ---------------------------------------------------------------------------------------------
// Interval generators
// ---------------------------------------------------------------------------------------------

/// `[a, b]` from two finite values in either order.
fn ordered<T: TestFloat>(a: T, b: T) -> Interval<T> {
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    Interval::new(lo, hi).expect("ordered finite bounds")
}

/// Intervals of every kind: EMPTY, ENTIRE, singletons, `[−∞, b]`, `[a, +∞]`, ordinary
/// `[a, b]`, narrow ones (a few ulps), zero-touching (`[±0, b]`, `[a, ±0]`) and sign-mixed.
pub fn interval<T: TestFloat>() -> BoxedStrategy<Interval<T>> {
    interval_with(finite::<T>)
}

/// Intervals of every kind, with finite bounds drawn from `f`.
pub fn interval_with<T: TestFloat>(f: fn() -> BoxedStrategy<T>) -> BoxedStrategy<Interval<T>> {
    let signed_zero = prop_oneof![Just(T::ZERO), Just(-T::ZERO)];
    prop_oneof![
        1 => Just(Interval::<T>::EMPTY),
        1 => Just(Interval::<T>::ENTIRE),
        3 => f().prop_map(|a| Interval::point(a).unwrap()),
        2 => f().prop_map(|b| Interval::new(T::NEG_INFINITY, b).unwrap()),
        2 => f().prop_map(|a| Interval::new(a, T::INFINITY).unwrap()),
        8 => (f(), f()).prop_map(|(a, b)| ordered(a, b)),
        2 => (f(), 1i32..=4).prop_map(|(a, k)| ordered(a, step(a, k))),
        1 => (signed_zero.clone(), f()).prop_map(|(z, b)| ordered(z, b.abs())),
        1 => (signed_zero, f()).prop_map(|(z, a)| ordered(-a.abs(), z)),
        2 => (f(), f()).prop_map(|(a, b)| ordered(-a.abs(), b.abs())),
    ]
    .boxed()
}

/// Pairs of intervals: independent, or the second built from the first (negated or shifted
/// by a few ulps), so sums and differences of bounds cancel.
pub fn interval_pair<T: TestFloat>() -> BoxedStrategy<(Interval<T>, Interval<T>)> {
    prop_oneof![
        4 => (interval::<T>(), interval::<T>()),
        1 => (interval::<T>(), -2i32..=2, -2i32..=2).prop_map(|(x, k, m)| {
            let y = match x.bounds() {
                Some((lo, hi)) => {
                    let (a, b) = (step(-hi, k), step(-lo, m));
                    Interval::new(a.min_nan(b), a.max_nan(b)).unwrap_or(x)
                }
                None => x,
            };
            (x, y)
        }),
    ]
    .boxed()
}

/// Seeds for choosing points inside intervals: random values and fractions in `[0, 1]`.
pub fn point_seeds<T: TestFloat>(n: usize) -> BoxedStrategy<Vec<(T, f64)>> {
    proptest::collection::vec((finite::<T>(), 0.0..=1.0f64), n).boxed()
}

/// Points of `x`: its finite endpoints and one interior point per seed (the seed value when
/// it lies in `x`, otherwise a point at fraction `t` of the way, or at a distance `|v|` from
/// the finite end of a half-unbounded interval). Empty for the empty interval.
pub fn points_in<T: TestFloat>(x: Interval<T>, seeds: &[(T, f64)]) -> Vec<T> {
    let Some((lo, hi)) = x.bounds() else {
        return Vec::new();
    };
    let mut pts = Vec::new();
    if lo.is_finite() {
        pts.push(lo);
    }
    if hi.is_finite() {
        pts.push(hi);
    }
    for &(v, t) in seeds {
        let p = if x.contains(v) {
            v
        } else if lo.is_finite() && hi.is_finite() {
            T::from_f64_rn(lo.to_f64() * (1.0 - t) + hi.to_f64() * t)
        } else if lo.is_finite() {
            T::from_f64_rn(lo.to_f64() + v.to_f64().abs())
        } else if hi.is_finite() {
            T::from_f64_rn(hi.to_f64() - v.to_f64().abs())
        } else {
            v
        };
        let p = if !p.is_finite() {
            if lo.is_finite() { lo } else { hi }
        } else if p < lo {
            lo
        } else if p > hi {
            hi
        } else {
            p
        };
        if p.is_finite() && x.contains(p) {
            pts.push(p);
        }
    }
    pts
}

/// True if the interval's representation is valid: empty, or `lo ≤ hi`, `lo ≠ +∞`,
/// `hi ≠ −∞` and no NaN bound.
pub fn is_valid<T: TestFloat>(x: Interval<T>) -> bool {
    match x.bounds() {
        None => true,
        Some((lo, hi)) => {
            !lo.is_nan() && !hi.is_nan() && lo <= hi && lo != T::INFINITY && hi != T::NEG_INFINITY
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Exact values
// ---------------------------------------------------------------------------------------------

/// The exact rational value of a finite float.
pub fn rat<T: TestFloat>(x: T) -> Rational {
    Rational::from_f64(x.to_f64()).expect("finite value")
}

/// `2^k` as an exact rational.
pub fn pow2(k: i32) -> Rational {
    let one = Rational::from(1);
    if k >= 0 {
        one << k.unsigned_abs()
    } else {
        one >> k.unsigned_abs()
    }
}

/// An extended real number: `−∞`, a rational, or `+∞`. The derived order is the order of
/// the extended reals.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Ext {
    /// −∞.
    NegInf,
    /// A finite value.
    Fin(Rational),
    /// +∞.
    PosInf,
}

impl Ext {
    /// The exact value of a non-NaN float (`±0` both give 0).
    pub fn of<T: TestFloat>(x: T) -> Ext {
        assert!(!x.is_nan(), "Ext::of(NaN)");
        if x == T::INFINITY {
            Ext::PosInf
        } else if x == T::NEG_INFINITY {
            Ext::NegInf
        } else {
            Ext::Fin(rat(x))
        }
    }

    /// Zero.
    pub fn zero() -> Ext {
        Ext::Fin(Rational::new())
    }

    /// The sign: −1, 0 or 1.
    pub fn signum(&self) -> i32 {
        match self {
            Ext::NegInf => -1,
            Ext::PosInf => 1,
            Ext::Fin(q) => match q.cmp0() {
                Ordering::Less => -1,
                Ordering::Equal => 0,
                Ordering::Greater => 1,
            },
        }
    }

    fn inf_with_sign(s: i32) -> Ext {
        if s < 0 { Ext::NegInf } else { Ext::PosInf }
    }

    /// `−self`.
    pub fn neg(&self) -> Ext {
        match self {
            Ext::NegInf => Ext::PosInf,
            Ext::PosInf => Ext::NegInf,
            Ext::Fin(q) => Ext::Fin(Rational::from(-q)),
        }
    }

    /// `self + other`; `None` for `∞ − ∞`.
    pub fn add(&self, other: &Ext) -> Option<Ext> {
        match (self, other) {
            (Ext::Fin(a), Ext::Fin(b)) => Some(Ext::Fin(Rational::from(a + b))),
            (Ext::PosInf, Ext::NegInf) | (Ext::NegInf, Ext::PosInf) => None,
            (Ext::Fin(_), inf) | (inf, _) => Some(inf.clone()),
        }
    }

    /// `self · other`, with `0 · ∞ = 0` (the convention of interval arithmetic).
    pub fn mul(&self, other: &Ext) -> Ext {
        match (self, other) {
            (Ext::Fin(a), Ext::Fin(b)) => Ext::Fin(Rational::from(a * b)),
            _ => {
                let s = self.signum() * other.signum();
                if s == 0 {
                    Ext::zero()
                } else {
                    Ext::inf_with_sign(s)
                }
            }
        }
    }

    /// `self / other` for `other ≠ 0`, with `finite / ∞ = 0`; `None` for `∞ / ∞`.
    pub fn div(&self, other: &Ext) -> Option<Ext> {
        assert!(other.signum() != 0, "Ext::div by zero");
        match (self, other) {
            (Ext::Fin(a), Ext::Fin(b)) => Some(Ext::Fin(Rational::from(a / b))),
            (Ext::Fin(_), _) => Some(Ext::zero()),
            (_, Ext::Fin(_)) => Some(Ext::inf_with_sign(self.signum() * other.signum())),
            _ => None,
        }
    }

    /// The finite value, if any.
    pub fn finite(&self) -> Option<&Rational> {
        match self {
            Ext::Fin(q) => Some(q),
            _ => None,
        }
    }
}

/// An exact real that a float can be compared with.
pub trait Exact: Debug {
    /// How `v` (any non-NaN float, `±∞` included) compares with the exact value.
    fn cmp_float<T: TestFloat>(&self, v: T) -> Ordering;
}

impl Exact for Ext {
    fn cmp_float<T: TestFloat>(&self, v: T) -> Ordering {
        Ext::of(v).cmp(self)
    }
}

impl Exact for Rational {
    fn cmp_float<T: TestFloat>(&self, v: T) -> Ordering {
        Ext::of(v).cmp(&Ext::Fin(self.clone()))
    }
}

/// The exact non-negative square root of an extended real `≥ 0`, compared by squaring.
#[derive(Clone, Debug)]
pub struct SqrtOf(pub Ext);

impl Exact for SqrtOf {
    fn cmp_float<T: TestFloat>(&self, v: T) -> Ordering {
        match (&self.0, Ext::of(v)) {
            (_, Ext::NegInf) => Ordering::Less,
            (Ext::PosInf, Ext::PosInf) => Ordering::Equal,
            (_, Ext::PosInf) => Ordering::Greater,
            (Ext::PosInf, _) => Ordering::Less,
            (Ext::Fin(a), Ext::Fin(q)) => {
                assert!(a.cmp0() != Ordering::Less, "SqrtOf a negative number");
                if q.cmp0() == Ordering::Less {
                    Ordering::Less
                } else {
                    Rational::from(&q * &q).cmp(a)
                }
            }
            (Ext::NegInf, _) => panic!("SqrtOf(-inf)"),
        }
    }
}

/// True if `r` is `e` rounded toward −∞ in `T`: `r ≤ e` and `next_up(r) > e` (so overflow
/// gives `MAX`, an exact `+∞` gives `+∞`, and subnormal results are on the subnormal grid).
pub fn is_round_down<T: TestFloat, E: Exact>(r: T, e: &E) -> bool {
    if r.is_nan() || e.cmp_float(r) == Ordering::Greater {
        return false;
    }
    r == T::INFINITY || e.cmp_float(r.next_up()) == Ordering::Greater
}

/// True if `r` is `e` rounded toward +∞ in `T`: `r ≥ e` and `next_down(r) < e`.
pub fn is_round_up<T: TestFloat, E: Exact>(r: T, e: &E) -> bool {
    if r.is_nan() || e.cmp_float(r) == Ordering::Less {
        return false;
    }
    r == T::NEG_INFINITY || e.cmp_float(r.next_down()) == Ordering::Less
}

/// True if `lo ≤ e ≤ hi` (exactly).
pub fn brackets<T: TestFloat, E: Exact>(lo: T, hi: T, e: &E) -> bool {
    !lo.is_nan()
        && !hi.is_nan()
        && e.cmp_float(lo) != Ordering::Greater
        && e.cmp_float(hi) != Ordering::Less
}

/// True if the interval contains the exact value `e`.
pub fn encloses<T: TestFloat, E: Exact>(x: Interval<T>, e: &E) -> bool {
    match x.bounds() {
        Some((lo, hi)) => brackets(lo, hi, e),
        None => false,
    }
}

/// Checks that `x` is the tightest interval of `T` enclosing the exact hull `expected`
/// (`None` meaning the empty set): each bound is the exact extreme rounded outward.
pub fn check_tight<T: TestFloat, E: Exact>(
    x: Interval<T>,
    expected: Option<(E, E)>,
) -> Result<(), TestCaseError> {
    prop_assert!(is_valid(x), "invalid representation {:?}", x);
    match (x.bounds(), expected) {
        (None, None) => Ok(()),
        (Some(b), None) => Err(TestCaseError::fail(format!(
            "expected the empty set, got {b:?}"
        ))),
        (None, Some(e)) => Err(TestCaseError::fail(format!(
            "got the empty set, expected the hull of {e:?}"
        ))),
        (Some((lo, hi)), Some((elo, ehi))) => {
            prop_assert!(
                is_round_down(lo, &elo),
                "lower bound {:?} is not the exact minimum {:?} rounded down (interval {:?})",
                lo,
                elo,
                x
            );
            prop_assert!(
                is_round_up(hi, &ehi),
                "upper bound {:?} is not the exact maximum {:?} rounded up (interval {:?})",
                hi,
                ehi,
                x
            );
            Ok(())
        }
    }
}

/// The exact bounds of an interval; `None` for the empty set.
pub fn ext_bounds<T: TestFloat>(x: Interval<T>) -> Option<(Ext, Ext)> {
    x.bounds().map(|(lo, hi)| (Ext::of(lo), Ext::of(hi)))
}

/// The hull `[min, max]` of a non-empty list of extended reals.
pub fn hull_of(values: impl IntoIterator<Item = Ext>) -> (Ext, Ext) {
    let mut it = values.into_iter();
    let first = it.next().expect("non-empty list");
    it.fold((first.clone(), first), |(lo, hi), v| {
        (lo.min(v.clone()), hi.max(v))
    })
}

/// The exact hull of `{x·y : x ∈ a, y ∈ b}` for closed extended intervals: the extreme of
/// the four corner products, with `0·∞ = 0`.
pub fn product_hull(a: &(Ext, Ext), b: &(Ext, Ext)) -> (Ext, Ext) {
    hull_of([a.0.mul(&b.0), a.0.mul(&b.1), a.1.mul(&b.0), a.1.mul(&b.1)])
}

/// The hull of a union of hulls (`None` entries are empty sets).
pub fn union_hull(parts: impl IntoIterator<Item = Option<(Ext, Ext)>>) -> Option<(Ext, Ext)> {
    parts
        .into_iter()
        .flatten()
        .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
}

// ---------------------------------------------------------------------------------------------
// Rounding exact values (for MPFR-based oracles)
// ---------------------------------------------------------------------------------------------

/// The nearest value of `T` below (`down`) or above the rational `q`, on the true `T` grid
/// (subnormals included; beyond `MAX` the result is `MAX` down / `+∞` up).
pub fn round_rational<T: TestFloat>(q: &Rational, down: bool) -> T {
    // Truncation toward zero in f64 gets within a couple of steps; fix by exact neighbours.
    let approx = q.to_f64();
    let mut r = if down {
        T::from_f64_down(approx)
    } else {
        T::from_f64_up(approx)
    };
    let e = Ext::Fin(q.clone());
    if down {
        while e.cmp_float(r) == Ordering::Greater {
            r = r.next_down();
        }
        while r != T::INFINITY && e.cmp_float(r.next_up()) != Ordering::Greater {
            r = r.next_up();
        }
        debug_assert!(is_round_down(r, &e));
    } else {
        while e.cmp_float(r) == Ordering::Less {
            r = r.next_up();
        }
        while r != T::NEG_INFINITY && e.cmp_float(r.next_down()) != Ordering::Less {
            r = r.next_down();
        }
        debug_assert!(is_round_up(r, &e));
    }
    r
}

/// The nearest value of `T` below (`down`) or above an MPFR number (NaN stays NaN). With
/// `v` itself rounded in the same direction at any precision ≥ `T`'s, this is the correctly
/// rounded result in that direction (directed roundings compose).
pub fn round_mpfr<T: TestFloat>(v: &rug::Float, down: bool) -> T {
    if v.is_nan() {
        T::NAN
    } else if v.is_infinite() {
        if v.is_sign_positive() {
            T::INFINITY
        } else {
            T::NEG_INFINITY
        }
    } else {
        round_rational(&v.to_rational().expect("finite"), down)
    }
}

/// A float's exact value as an MPFR number (exact at any precision ≥ 53).
pub fn mpfr<T: TestFloat>(x: T, prec: u32) -> rug::Float {
    rug::Float::with_val(prec, x.to_f64())
}
