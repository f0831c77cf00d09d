//! Elementary functions: `pown`, `exp`, `exp2`, `exp10`, `log` (`ln`), `log2`, `log10`,
//! `pow`, `sinh`, `cosh`, `tanh`.
//!
//! # Method
//!
//! Point values come from CORE-MATH (the `core-math` crate), whose functions are *correctly
//! rounded* to nearest, with a proof. If `r = f(x)` is that result (computed in `f64` on the
//! exact `f64` value of the bound, for `f32` intervals too), the exact value `y` satisfies
//! `next_down(r) ≤ y ≤ next_up(r)`. This also holds at the edges: an overflowed `r = +∞`
//! means `y ≥ MAX` and `next_down(+∞) = MAX`; an underflowed `r = 0` means
//! `|y| ≤ MIN_POSITIVE_SUBNORMAL`. One outward step therefore encloses `y`, and since the
//! directed rounding of `y` is `r` or its neighbour, each bound is within one ulp of the
//! tight bound. The `f64` bracket is converted outward to the interval's type, which for
//! `f32` keeps the bound within one `f32` ulp of tight (nearly always exactly tight).
//!
//! Where `f(x)` is exactly representable at a special argument (listed per function), the
//! bound is `r` itself; limits at infinite arguments (`exp(−∞) = 0`, `tanh(+∞) = 1`) and the
//! mathematical range (`exp ≥ 0`, `cosh ≥ 1`, `|tanh| ≤ 1`) are enforced by clamping after the
//! outward step. Endpoints are chosen by monotonicity; `pow` uses the corners of its domain
//! box.

use super::Interval;
use crate::float::Float;
use crate::float::dyadic::Dyadic;
use core::cmp::Ordering;

/// The largest `|n|` for which `pown` computes `xⁿ` exactly (a significand of at most
/// `53·|n|` bits) and rounds it once each way; larger powers use directed chains and the
/// correctly rounded `pow`, within one ulp.
const EXACT_POWER_MAX: u32 = 64;

/// A lower bound of the exact value whose round-to-nearest `f64` value is `r`: `r` itself
/// when the value is known to be exact, otherwise the next `f64` below.
#[inline(always)]
pub(super) fn below(r: f64, exact: bool) -> f64 {
    if exact { r } else { r.next_down() }
}

/// An upper bound of the exact value whose round-to-nearest `f64` value is `r`.
#[inline(always)]
pub(super) fn above(r: f64, exact: bool) -> f64 {
    if exact { r } else { r.next_up() }
}

/// The interval `[lo, hi]` of `f64` bounds, rounded outward to `T` (exact for `f64`).
#[inline(always)]
pub(super) fn outward<T: Float>(lo: f64, hi: f64) -> Interval<T> {
    Interval::new_unchecked(T::from_f64_down(lo), T::from_f64_up(hi))
}

/// Enclosure of an increasing function `f` over `[a, b]` from its correctly rounded values,
/// clamped to `[min, max]` (the closure of the function's range).
#[inline(always)]
pub(super) fn increasing<T: Float>(
    a: T,
    b: T,
    f: fn(f64) -> f64,
    exact_at: fn(f64) -> bool,
    min: f64,
    max: f64,
) -> Interval<T> {
    let (a, b) = (a.to_f64(), b.to_f64());
    let ra = f(a);
    let rb = if a == b { ra } else { f(b) };
    let lo = below(ra, exact_at(a)).max(min);
    let hi = above(rb, exact_at(b)).min(max);
    outward(lo, hi)
}

/// Enclosure of an increasing function `f` over `[a, b]` from its correctly rounded values,
/// intersected with the exact brackets `known(a)`, `known(b)` of the function's values at the
/// endpoints (range facts such as `exp(x) ≤ 1` for `x ≤ 0` or `k ≤ log2(x) < k + 1` for
/// `2ᵏ ≤ x < 2ᵏ⁺¹`, which make a bound tight wherever the exact value is a float or the
/// rounded value crossed such a float), and clamped to `[min, max]`.
#[inline(always)]
pub(super) fn increasing_known<T: Float>(
    a: T,
    b: T,
    f: fn(f64) -> f64,
    known: fn(f64) -> (f64, f64),
    min: f64,
    max: f64,
) -> Interval<T> {
    let (a, b) = (a.to_f64(), b.to_f64());
    let ra = f(a);
    let rb = if a == b { ra } else { f(b) };
    let lo = below(ra, false).max(known(a).0).max(min);
    let hi = above(rb, false).min(known(b).1).min(max);
    outward(lo, hi)
}

/// The exponent `k` with `2ᵏ ≤ x < 2ᵏ⁺¹`, for a positive finite `x` (subnormals included).
fn ilogb(x: f64) -> i64 {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    if biased == 0 {
        -1074 + 63 - i64::from((bits & ((1 << 52) - 1)).leading_zeros())
    } else {
        biased - 1023
    }
}

/// True for a positive power of two (normal or subnormal) in `f64`.
fn is_pow2(x: f64) -> bool {
    if !(x > 0.0 && x.is_finite()) {
        return false;
    }
    let bits = x.to_bits();
    let mant = bits & ((1u64 << 52) - 1);
    if bits >> 52 == 0 {
        mant.is_power_of_two()
    } else {
        mant == 0
    }
}

/// `10^k` for `0 ≤ k ≤ 22`, all exactly representable in `f64` (`5^22 < 2^53`).
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// `2ᵏ` for `−1074 ≤ k ≤ 1023`, from its bit pattern (subnormal powers included).
fn exact_pow2(k: i32) -> f64 {
    if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (k + 1074))
    }
}

/// `2ᵏ` as a lower bound (`k` an integer): exact in range, 0 below it, `MAX` above it.
fn pow2_below(k: f64) -> f64 {
    if k < -1074.0 {
        0.0
    } else if k > 1023.0 {
        f64::MAX
    } else {
        exact_pow2(k as i32)
    }
}

/// `2ᵏ` as an upper bound (`k` an integer): exact in range, the smallest subnormal below it,
/// `+∞` above it.
fn pow2_above(k: f64) -> f64 {
    if k < -1074.0 {
        f64::MIN_POSITIVE_SUBNORMAL
    } else if k > 1023.0 {
        f64::INFINITY
    } else {
        exact_pow2(k as i32)
    }
}

/// Exact brackets of `eˣ`: `1` at 0, `≤ 1` for `x < 0`, `≥ 1` for `x > 0`.
fn exp_known(x: f64) -> (f64, f64) {
    if x == 0.0 {
        (1.0, 1.0)
    } else if x < 0.0 {
        (0.0, 1.0)
    } else {
        (1.0, f64::INFINITY)
    }
}

/// Exact brackets of `2ˣ`: `2^⌊x⌋ ≤ 2ˣ ≤ 2^⌈x⌉` (exact at the integers of the `f64` range).
fn exp2_known(x: f64) -> (f64, f64) {
    if !x.is_finite() {
        return if x > 0.0 {
            (f64::MAX, f64::INFINITY)
        } else {
            (0.0, 0.0)
        };
    }
    (pow2_below(x.floor()), pow2_above(x.ceil()))
}

/// Exact brackets of `10ˣ`: `10^⌊x⌋ ≤ 10ˣ ≤ 10^⌈x⌉` where those are `f64`s (`0..=22`),
/// `10ˣ ≤ 1` for `x ≤ 0`.
fn exp10_known(x: f64) -> (f64, f64) {
    if !x.is_finite() {
        return if x > 0.0 {
            (f64::MAX, f64::INFINITY)
        } else {
            (0.0, 0.0)
        };
    }
    let (f, c) = (x.floor(), x.ceil());
    let lo = if (0.0..=22.0).contains(&f) {
        POW10[f as usize]
    } else {
        0.0
    };
    let hi = if (0.0..=22.0).contains(&c) {
        POW10[c as usize]
    } else if c < 0.0 {
        1.0
    } else {
        f64::INFINITY
    };
    (lo, hi)
}

/// Exact brackets of `ln x` for `x ≥ 0`: `0` at 1, its sign elsewhere, `−∞` at 0.
fn log_known(x: f64) -> (f64, f64) {
    if x == 0.0 {
        (f64::NEG_INFINITY, f64::NEG_INFINITY)
    } else if x == 1.0 {
        (0.0, 0.0)
    } else if x < 1.0 {
        (f64::NEG_INFINITY, 0.0)
    } else {
        (0.0, f64::INFINITY)
    }
}

/// Exact brackets of `log2 x` for `x ≥ 0`: `k ≤ log2 x < k + 1` for `2ᵏ ≤ x < 2ᵏ⁺¹` (so
/// `k` exactly at `x = 2ᵏ`), `−∞` at 0.
fn log2_known(x: f64) -> (f64, f64) {
    if x == 0.0 {
        return (f64::NEG_INFINITY, f64::NEG_INFINITY);
    }
    if x == f64::INFINITY {
        return (f64::MAX, f64::INFINITY);
    }
    let k = ilogb(x) as f64;
    (k, if is_pow2(x) { k } else { k + 1.0 })
}

/// Exact brackets of `log10 x` for `x ≥ 0`: `k ≤ log10 x < k + 1` for `10ᵏ ≤ x < 10ᵏ⁺¹`
/// with `0 ≤ k ≤ 21` (`k` exactly at `x = 10ᵏ`, `k ≤ 22`), the sign elsewhere, `−∞` at 0.
fn log10_known(x: f64) -> (f64, f64) {
    if x == 0.0 {
        return (f64::NEG_INFINITY, f64::NEG_INFINITY);
    }
    if x < 1.0 {
        return (f64::NEG_INFINITY, 0.0);
    }
    let k = POW10.iter().rposition(|&p| p <= x).unwrap_or(0);
    if POW10[k] == x {
        (k as f64, k as f64)
    } else if k < 22 {
        (k as f64, k as f64 + 1.0)
    } else {
        (22.0, f64::INFINITY)
    }
}

/// `+0.0` for either zero, the value itself otherwise.
#[inline(always)]
pub(super) fn plus_zero(x: f64) -> f64 {
    if x == 0.0 { 0.0 } else { x }
}

/// Lower and upper bounds of `m^k` for `m ≥ 0` (possibly `+∞`) and `k ≥ 2`: binary powering
/// with multiplications rounded down (up) on nonnegative values, intersected with the
/// one-ulp bracket of the correctly rounded CORE-MATH `pow` unless the two chains already
/// end at equal or adjacent floats.
fn mag_pow<T: Float>(m: T, k: u32) -> (T, T) {
    let (mut base_lo, mut base_hi) = (m, m);
    let (mut acc_lo, mut acc_hi) = (T::ONE, T::ONE);
    let mut e = k;
    loop {
        if e & 1 == 1 {
            acc_lo = acc_lo.mul_down(base_lo);
            acc_hi = acc_hi.mul_up(base_hi);
        }
        e >>= 1;
        if e == 0 {
            break;
        }
        base_lo = base_lo.mul_down(base_lo);
        base_hi = base_hi.mul_up(base_hi);
    }
    // Equal chains are exact.
    if acc_hi == acc_lo {
        return (acc_lo, acc_hi);
    }
    // Moderate powers of finite values: the exact power, rounded once each way.
    if k <= EXACT_POWER_MAX && m.is_finite() {
        let p = Dyadic::of(m).powi(k);
        return (p.round(false), p.round(true));
    }
    let r = core_math::pow(plus_zero(m.to_f64()), f64::from(k));
    (
        acc_lo.max_nan(T::from_f64_down(below(r, false))),
        acc_hi.min_nan(T::from_f64_up(above(r, false))),
    )
}

/// Lower and upper bounds of `m^(−k)` for `m > 0` (possibly `+∞`) and `k ≥ 2`: the directed
/// reciprocals of [`mag_pow`], intersected with the bracket of CORE-MATH `pow(m, −k)`.
fn inv_mag_pow<T: Float>(m: T, k: u32) -> (T, T) {
    let (p_lo, p_hi) = mag_pow(m, k);
    let r = core_math::pow(m.to_f64(), -f64::from(k));
    let mut lo = T::ONE
        .div_down(p_hi)
        .max_nan(T::from_f64_down(below(r, false)));
    let mut hi = T::ONE.div_up(p_lo).min_nan(T::from_f64_up(above(r, false)));
    if k <= EXACT_POWER_MAX && m.is_finite() && lo != hi {
        // Move each bound inward while its neighbour still encloses 1/mᵏ, deciding
        // `c ≥ 1/mᵏ` exactly as `c·mᵏ ≥ 1`. The bracket is within an ulp or two of tight,
        // so a few steps suffice.
        let p = Dyadic::of(m).powi(k);
        let one = Dyadic::of(1.0f64);
        let vs_recip = |c: T| Dyadic::of(c).mul(&p).cmp(&one);
        for _ in 0..4 {
            let c = hi.next_down();
            if c >= lo && c.is_finite() && vs_recip(c) != Ordering::Less {
                hi = c;
            } else {
                break;
            }
        }
        for _ in 0..4 {
            let c = lo.next_up();
            if c <= hi && c.is_finite() && vs_recip(c) != Ordering::Greater {
                lo = c;
            } else {
                break;
            }
        }
    }
    (lo, hi)
}

/// Whether CORE-MATH's `pow(x, y)` (with `x ≥ 0`) is the exact value, or the exact limit,
/// of `x^y`: `y = 0`, `y = 1`, `x = 1`, `x = 0`, `x = +∞` or `y = ±∞`, with a finite result.
fn pow_exact(x: f64, y: f64, r: f64) -> bool {
    r.is_finite()
        && (y == 0.0 || y == 1.0 || x == 1.0 || x == 0.0 || x.is_infinite() || y.is_infinite())
}

/// Lower and upper `f64` bounds of `x^y` (or its limit) at one corner of the domain box,
/// `x ≥ 0`. For finite `x > 0`, `y = 1/2` uses the tight directed square roots and an
/// integer `y` the directed powering of [`mag_pow`] (both exact when the power is
/// representable); everything else the one-ulp bracket of CORE-MATH `pow`.
fn pow_corner(x: f64, y: f64) -> (f64, f64) {
    if x > 0.0 && x.is_finite() {
        if y == 0.5 {
            return (x.sqrt_down(), x.sqrt_up());
        }
        if y == y.trunc() && y.abs() <= 2_147_483_648.0 {
            let k = y.abs() as u32;
            return match k {
                0 => (1.0, 1.0),
                1 if y > 0.0 => (x, x),
                1 => (1.0.div_down(x), 1.0.div_up(x)),
                _ if y > 0.0 => mag_pow(x, k),
                _ => inv_mag_pow(x, k),
            };
        }
    }
    let r = core_math::pow(x, y);
    let exact = pow_exact(x, y, r);
    (below(r, exact), above(r, exact))
}

impl<T: Float> Interval<T> {
    /// `xⁿ` for an integer `n` (IEEE 1788 `pown`), over the set `{xⁿ : x ∈ self, x ≠ 0 if n < 0}`.
    ///
    /// **Accuracy:** tight for `|n| ≤ 64` on finite bounds: `xᵏ` is computed exactly (an
    /// exact dyadic significand of at most `53·k` bits) and rounded once each way, and a bound
    /// of `x⁻ᵏ` is moved inward while `c·xᵏ` compared exactly with 1 allows it (so
    /// `pown([0.01, 2.33], −2)` has the upper bound 10000). For `|n| > 64` each bound is
    /// within 1 ulp of the tight bound (directed chains and the correctly rounded `pow`).
    /// `n = 0, 1, 2, −1` are tight (`[1, 1]`, `self`, [`Interval::sqr`],
    /// [`Interval::recip`]).
    ///
    /// **Why:** `|x|^|n|` is computed on nonnegative magnitudes by binary powering twice, once
    /// with every multiplication rounded down and once rounded up. Multiplication is
    /// monotone on nonnegative numbers, so the two chains bracket the exact power; on their
    /// own their relative error is below `(1 + 2^(1−p))^(|n|−1) − 1 ≈ (|n| − 1)·2^(1−p)` (with
    /// `p = 53` or `24`, one more rounding for the reciprocal when `n < 0`), exact when no
    /// product is rounded. That bracket is intersected with the one-ulp bracket of the
    /// correctly rounded CORE-MATH `pow(|x|, n)` (computed in `f64`), which gives the 1-ulp
    /// bound for every `n`. Signs follow from the parity of `n`; negative `n` takes directed
    /// reciprocals. Overflow gives `+∞` upper bounds and `MAX` lower bounds.
    ///
    /// | `self`             | `n`            | result                     |
    /// |--------------------|----------------|----------------------------|
    /// | ∅                  | any            | ∅                          |
    /// | nonempty           | 0              | `[1, 1]`                   |
    /// | `[−2, 3]`          | 2, 3, 4        | `[0, 9]`, `[−8, 27]`, `[0, 81]` |
    /// | `[0, 0]`           | `n < 0`        | ∅                          |
    /// | contains 0         | even `n < 0`   | `[mag(self)ⁿ, +∞]`         |
    /// | 0 in the interior  | odd `n < 0`    | `[−∞, +∞]`                 |
    /// | `[0, b]`, `b > 0`  | odd `n < 0`    | `[b^n, +∞]`                |
    ///
    /// ```
    /// use interval_core::Interval;
    /// let x = Interval::new(-2.0, 3.0)?;
    /// assert_eq!(x.pown(3), Interval::new(-8.0, 27.0)?);
    /// assert_eq!(x.pown(4), Interval::new(0.0, 81.0)?);
    /// assert_eq!(Interval::new(-1.0, 2.0)?.pown(-2), Interval::new(0.25, f64::INFINITY)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn pown(self, n: i32) -> Self {
        if self.is_empty() {
            return self;
        }
        match n {
            0 => return Self::ONE,
            1 => return self,
            2 => return self.sqr(),
            -1 => return self.recip(),
            _ => {}
        }
        let k = n.unsigned_abs();
        let (a, b) = (self.lo, self.hi);
        let z = T::ZERO;
        let even = k.is_multiple_of(2);
        if n > 0 {
            if even {
                let (lo, _) = mag_pow(self.mig(), k);
                let (_, hi) = mag_pow(self.mag(), k);
                return Self::new_unchecked(lo, hi);
            }
            // Odd: increasing on the whole line, x^k = −(|x|^k) for x < 0.
            let lo = if a >= z {
                mag_pow(a, k).0
            } else {
                -mag_pow(-a, k).1
            };
            let hi = if b >= z {
                mag_pow(b, k).1
            } else {
                -mag_pow(-b, k).0
            };
            return Self::new_unchecked(lo, hi);
        }
        // n ≤ −2.
        if a == z && b == z {
            return Self::EMPTY;
        }
        if even {
            // 1/|x|^k: decreasing in |x|.
            let (lo, _) = inv_mag_pow(self.mag(), k);
            let hi = if a <= z && z <= b {
                T::INFINITY
            } else {
                inv_mag_pow(self.mig(), k).1
            };
            return Self::new_unchecked(lo, hi);
        }
        if a < z && z < b {
            return Self::ENTIRE;
        }
        if a >= z {
            // (0, b] or [a, b] with a > 0: decreasing.
            let lo = inv_mag_pow(b, k).0;
            let hi = if a == z {
                T::INFINITY
            } else {
                inv_mag_pow(a, k).1
            };
            Self::new_unchecked(lo, hi)
        } else {
            // [a, b) with b ≤ 0: x^(−k) = −1/|x|^k, decreasing.
            let lo = if b == z {
                T::NEG_INFINITY
            } else {
                -inv_mag_pow(-b, k).1
            };
            let hi = -inv_mag_pow(-a, k).0;
            Self::new_unchecked(lo, hi)
        }
    }

    /// `eˣ`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0`
    /// (`exp(0) = 1`), at `x = −∞` (lower bound 0) and on overflow (`[MAX, +∞]`); the upper
    /// bound of a non-positive interval is exactly 1, as is the lower bound of a
    /// non-negative one (`eˣ ≤ 1` for `x ≤ 0`, `≥ 1` for `x ≥ 0`).
    /// **Why:** CORE-MATH `exp` is correctly rounded (proved), so one outward step from its
    /// result encloses the exact value; `exp` is increasing and positive.
    ///
    /// | `self`          | result       |
    /// |-----------------|--------------|
    /// | ∅               | ∅            |
    /// | `[−∞, +∞]`      | `[0, +∞]`    |
    /// | `[0, 0]`        | `[1, 1]`     |
    /// | `[−1000, −1000]`| `[0, MIN_POSITIVE_SUBNORMAL]` |
    ///
    /// ```
    /// use interval_core::Interval;
    /// assert_eq!(Interval::new(0.0, 0.0)?.exp(), Interval::new(1.0, 1.0)?);
    /// let e = Interval::new(1.0, 1.0)?.exp();
    /// assert!(e.contains(std::f64::consts::E) && e.sup() <= e.inf().next_up().next_up());
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn exp(self) -> Self {
        if self.is_empty() {
            return self;
        }
        increasing_known(
            self.lo,
            self.hi,
            core_math::exp,
            exp_known,
            0.0,
            f64::INFINITY,
        )
    }

    /// `2ˣ`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at every integer `x`
    /// with `−1074 ≤ x ≤ 1023` (`2ˣ` exact, subnormals included), at `x = −∞` and on overflow;
    /// a bound never passes the power of two of the next integer (`2^⌊x⌋ ≤ 2ˣ ≤ 2^⌈x⌉`).
    /// **Why:** CORE-MATH `exp2` is correctly rounded, so one outward step encloses; increasing.
    ///
    /// | `self`      | result          |
    /// |-------------|-----------------|
    /// | ∅           | ∅               |
    /// | `[−∞, +∞]`  | `[0, +∞]`       |
    /// | `[−3, 10]`  | `[0.125, 1024]` |
    ///
    /// ```
    /// use interval_core::Interval;
    /// assert_eq!(Interval::new(-3.0, 10.0)?.exp2(), Interval::new(0.125, 1024.0)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn exp2(self) -> Self {
        if self.is_empty() {
            return self;
        }
        increasing_known(
            self.lo,
            self.hi,
            core_math::exp2,
            exp2_known,
            0.0,
            f64::INFINITY,
        )
    }

    /// `10ˣ`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at the integers
    /// `0 ≤ x ≤ 22` (`10ˣ` exact in `f64`), at `x = −∞` and on overflow; a bound never passes
    /// `10^⌊x⌋`, `10^⌈x⌉` where those are `f64`s, nor 1 for `x ≤ 0`.
    /// **Why:** CORE-MATH `exp10` is correctly rounded, so one outward step encloses;
    /// increasing.
    ///
    /// | `self`      | result        |
    /// |-------------|---------------|
    /// | ∅           | ∅             |
    /// | `[−∞, +∞]`  | `[0, +∞]`     |
    /// | `[0, 3]`    | `[1, 1000]`   |
    pub fn exp10(self) -> Self {
        if self.is_empty() {
            return self;
        }
        increasing_known(
            self.lo,
            self.hi,
            core_math::exp10,
            exp10_known,
            0.0,
            f64::INFINITY,
        )
    }

    /// Enclosure of an increasing logarithm over `self ∩ (0, +∞]`.
    fn log_like(self, f: fn(f64) -> f64, known: fn(f64) -> (f64, f64)) -> Self {
        if self.is_empty() || self.hi <= T::ZERO {
            return Self::EMPTY;
        }
        let lo = if self.lo > T::ZERO { self.lo } else { T::ZERO };
        increasing_known(lo, self.hi, f, known, f64::NEG_INFINITY, f64::INFINITY)
    }

    /// Natural logarithm `ln x` over `self ∩ (0, +∞]` (IEEE 1788 `log`). See also the alias
    /// [`Interval::ln`].
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 1`
    /// (`log(1) = 0`), at `x = 0` (lower bound `−∞`) and at `+∞`; bounds keep the sign of
    /// `log` (`≤ 0` below 1, `≥ 0` above).
    /// **Why:** CORE-MATH `log` is correctly rounded, so one outward step encloses; increasing.
    ///
    /// | `self`       | result        |
    /// |--------------|---------------|
    /// | ∅            | ∅             |
    /// | `[−2, −1]`   | ∅             |
    /// | `[0, 0]`     | ∅ (0 is outside the domain) |
    /// | `[−1, 1]`    | `[−∞, 0]`     |
    /// | `[−∞, +∞]`   | `[−∞, +∞]`    |
    /// | `[1, 1]`     | `[0, 0]`      |
    ///
    /// ```
    /// use interval_core::Interval;
    /// assert_eq!(Interval::new(-1.0, 1.0)?.log(), Interval::new(f64::NEG_INFINITY, 0.0)?);
    /// assert!(Interval::new(-2.0, -1.0)?.log().is_empty());
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn log(self) -> Self {
        self.log_like(core_math::log, log_known)
    }

    /// Natural logarithm: an alias of [`Interval::log`] (the IEEE 1788 name), with the same
    /// domain handling and accuracy.
    #[inline]
    pub fn ln(self) -> Self {
        self.log()
    }

    /// Base-2 logarithm over `self ∩ (0, +∞]`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at every power of two
    /// `x = 2ᵏ` (`log2 = k`, subnormal powers included), at 0 (`−∞`) and `+∞`; a bound never
    /// leaves `[k, k + 1]` for `2ᵏ ≤ x < 2ᵏ⁺¹`, so `log2([1, MAX]) = [0, 1024]`.
    /// **Why:** CORE-MATH `log2` is correctly rounded, so one outward step encloses; increasing.
    ///
    /// | `self`       | result        |
    /// |--------------|---------------|
    /// | ∅, `[−2, 0]` | ∅             |
    /// | `[0, 1]`     | `[−∞, 0]`     |
    /// | `[8, 8]`     | `[3, 3]`      |
    pub fn log2(self) -> Self {
        self.log_like(core_math::log2, log2_known)
    }

    /// Base-10 logarithm over `self ∩ (0, +∞]`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 10ᵏ` for
    /// `0 ≤ k ≤ 22` (`log10 = k`), at 0 (`−∞`) and `+∞`; a bound never leaves `[k, k + 1]`
    /// for `10ᵏ ≤ x < 10ᵏ⁺¹` (`k ≤ 21`), nor passes 0 for `x ≤ 1`.
    /// **Why:** CORE-MATH `log10` is correctly rounded, so one outward step encloses;
    /// increasing.
    ///
    /// | `self`        | result        |
    /// |---------------|---------------|
    /// | ∅, `[−2, 0]`  | ∅             |
    /// | `[0, 1]`      | `[−∞, 0]`     |
    /// | `[1, 1000]`   | `[0, 3]`      |
    pub fn log10(self) -> Self {
        self.log_like(core_math::log10, log10_known)
    }

    /// Real power `xʸ = e^(y·ln x)` over the IEEE 1788 domain
    /// `{x > 0} ∪ {x = 0, y > 0}`, with `self = x`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound. Tight where the extreme
    /// corner is a special value (`y = 0`, `y = 1`, `x = 1`, `x = 0`, `x = +∞`, `y = ±∞`:
    /// `0`, `1`, `x` or `+∞`), and where `y = 1/2` or `y` is an integer and `xʸ` is
    /// representable (`4^0.5 = 2`, `3^4 = 81`, `2^−3 = 0.125`).
    /// **Why:** `y·ln x` is bilinear in `(ln x, y)`, so over the box
    /// `(x ∩ [0, +∞]) × y` its extremes — and those of `xʸ`, `exp` being increasing — are
    /// at the four corners, with the limits `ln 0 = −∞`, `ln ∞ = +∞` and `0·∞ = 0` (which are
    /// exactly the IEEE special values of `pow`, e.g. `pow(0, −1) = +∞`, `pow(1, ∞) = 1`).
    /// Each corner is evaluated with the correctly rounded CORE-MATH `pow` and widened by
    /// one step; corners with `y = 1/2` use the tight directed square root, corners with an
    /// integer `y` the directed powering of [`Interval::pown`]. Points `x = 0, y ≤ 0` are outside the domain and dropped; their neighbours
    /// with `x > 0` still give the limits (unbounded above when `y < 0`).
    ///
    /// | `self` (`x`)  | `y`          | result        |
    /// |---------------|--------------|---------------|
    /// | ∅ or `x < 0`  | any          | ∅             |
    /// | any           | ∅            | ∅             |
    /// | `[0, 0]`      | `y ≤ 0`      | ∅             |
    /// | `[0, 0]`      | `y.sup > 0`  | `[0, 0]`      |
    /// | `[0, 1]`      | `[−1, −1]`   | `[1, +∞]`     |
    /// | `[−1, 4]`     | `[0.5, 0.5]` | `[0, 2]`      |
    ///
    /// ```
    /// use interval_core::Interval;
    /// let x = Interval::new(-1.0, 4.0)?;
    /// assert_eq!(x.pow(Interval::new(0.5, 0.5)?), Interval::new(0.0, 2.0)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn pow(self, y: Self) -> Self {
        if self.is_empty() || y.is_empty() || self.hi < T::ZERO {
            return Self::EMPTY;
        }
        let a = if self.lo > T::ZERO {
            self.lo.to_f64()
        } else {
            0.0
        };
        let b = plus_zero(self.hi.to_f64());
        let (c, d) = (y.lo.to_f64(), y.hi.to_f64());
        if b == 0.0 {
            // x = {0}: only the points with y > 0, where 0^y = 0.
            return if d > 0.0 { Self::ZERO } else { Self::EMPTY };
        }
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        let xs: &[f64] = if a == b { &[a] } else { &[a, b] };
        let ys: &[f64] = if c == d { &[c] } else { &[c, d] };
        for &xc in xs {
            for &yc in ys {
                let (l, h) = pow_corner(xc, yc);
                lo = lo.min(l);
                hi = hi.max(h);
            }
        }
        outward(lo.max(0.0), hi)
    }

    /// Hyperbolic sine.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0` and on
    /// overflow (`[MAX, +∞]`, `[−∞, −MAX]`).
    /// **Why:** CORE-MATH `sinh` is correctly rounded, so one outward step encloses;
    /// increasing.
    ///
    /// | `self`      | result        |
    /// |-------------|---------------|
    /// | ∅           | ∅             |
    /// | `[−∞, +∞]`  | `[−∞, +∞]`    |
    /// | `[0, 0]`    | `[0, 0]`      |
    pub fn sinh(self) -> Self {
        if self.is_empty() {
            return self;
        }
        increasing(
            self.lo,
            self.hi,
            core_math::sinh,
            |x| x == 0.0,
            f64::NEG_INFINITY,
            f64::INFINITY,
        )
    }

    /// Hyperbolic cosine.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0`
    /// (`cosh(0) = 1`, which is also the lower bound whenever `0 ∈ self`) and on overflow.
    /// **Why:** CORE-MATH `cosh` is correctly rounded, so one outward step encloses; `cosh`
    /// is even and increasing in `|x|`, so the bounds are taken at the mignitude and the
    /// magnitude, and the lower bound is clamped to 1.
    ///
    /// | `self`      | result        |
    /// |-------------|---------------|
    /// | ∅           | ∅             |
    /// | `[−∞, +∞]`  | `[1, +∞]`     |
    /// | `[−1, 2]`   | `[1, cosh 2]` |
    pub fn cosh(self) -> Self {
        if self.is_empty() {
            return self;
        }
        let (m, big) = (self.mig().to_f64(), self.mag().to_f64());
        let rm = core_math::cosh(m);
        let rb = if m == big { rm } else { core_math::cosh(big) };
        outward(below(rm, m == 0.0).max(1.0), above(rb, big == 0.0))
    }

    /// Hyperbolic tangent.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0` and at
    /// `±∞` (`±1`); bounds never leave `[−1, 1]`.
    /// **Why:** CORE-MATH `tanh` is correctly rounded, so one outward step encloses;
    /// increasing, and the outward step is clamped to `[−1, 1]`.
    ///
    /// | `self`      | result        |
    /// |-------------|---------------|
    /// | ∅           | ∅             |
    /// | `[−∞, +∞]`  | `[−1, 1]`     |
    /// | `[0, 0]`    | `[0, 0]`      |
    pub fn tanh(self) -> Self {
        if self.is_empty() {
            return self;
        }
        increasing(self.lo, self.hi, core_math::tanh, |x| x == 0.0, -1.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powers_of_two_are_detected() {
        assert!(is_pow2(1.0) && is_pow2(0.5) && is_pow2(f64::MIN_POSITIVE));
        assert!(is_pow2(f64::from_bits(1)) && is_pow2(f64::from_bits(1 << 20)));
        assert!(!is_pow2(3.0) && !is_pow2(0.0) && !is_pow2(-2.0) && !is_pow2(f64::INFINITY));
        assert!(!is_pow2(f64::from_bits(3)));
    }

    #[test]
    fn range_facts_bracket_the_exact_values() {
        assert_eq!(exact_pow2(-1074), f64::MIN_POSITIVE_SUBNORMAL);
        assert_eq!(exact_pow2(1023), 2f64.powi(1023));
        assert_eq!(ilogb(f64::MAX), 1023);
        assert_eq!(ilogb(f64::MIN_POSITIVE_SUBNORMAL), -1074);
        assert_eq!(ilogb(f64::from_bits(3)), -1073);
        assert_eq!(log2_known(f64::MAX), (1023.0, 1024.0));
        assert_eq!(log2_known(0.25), (-2.0, -2.0));
        assert_eq!(log10_known(1e22), (22.0, 22.0));
        assert_eq!(log10_known(999.0), (2.0, 3.0));
        assert_eq!(exp2_known(-1074.5), (0.0, f64::MIN_POSITIVE_SUBNORMAL));
        assert_eq!(exp2_known(2.5), (4.0, 8.0));
        assert_eq!(exp10_known(-0.5), (0.0, 1.0));
        assert_eq!(exp10_known(3.0), (1000.0, 1000.0));
    }

    #[test]
    fn powers_of_ten_are_exact() {
        for (k, &p) in POW10.iter().enumerate() {
            assert_eq!(core_math::exp10(k as f64), p);
            assert_eq!(core_math::log10(p), k as f64);
        }
    }
}
