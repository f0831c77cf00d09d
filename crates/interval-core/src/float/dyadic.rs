//! Exact dyadic rationals `±m · 2^e` (a [`BigUint`] significand): the exact arithmetic behind
//! the tight results that error-free transformations alone cannot give — exact reductions
//! (`sum`, `dot`), exact comparisons of candidate bounds (`pown`, `rootn`) and of decimal
//! literals with binary floats — and their directed rounding to `f64` or `f32`.
//!
//! Every finite float is a dyadic rational, and so are sums and products of floats, so all
//! of these are computed without any rounding; only [`Dyadic::round`] rounds, once, in the
//! requested direction, on the true grid of the target type (subnormals included, overflow to
//! `MAX` toward zero and to `∞` away from it).

use super::big::BigUint;
use super::traits::Float;
use core::cmp::Ordering;

/// An exact dyadic rational `±mag · 2^exp`.
#[derive(Clone, Debug)]
pub(crate) struct Dyadic {
    /// True for a negative value (never set for zero after [`Dyadic::normalize`]).
    neg: bool,
    /// The magnitude's integer significand.
    mag: BigUint,
    /// The power of two of the least significant bit.
    exp: i64,
}

/// `(m, e)` with `|x| = m · 2^e`, for a finite `f64`.
fn decompose(x: f64) -> (u64, i64) {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    if biased == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), biased - 1075)
    }
}

/// `2^k` as an `f64`, for `−1074 ≤ k ≤ 1023` (subnormal powers included).
fn pow2_f64(k: i64) -> f64 {
    if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (k + 1074))
    }
}

impl Dyadic {
    /// Zero.
    pub(crate) fn zero() -> Self {
        Self {
            neg: false,
            mag: BigUint::zero(),
            exp: 0,
        }
    }

    /// The exact value of a finite float.
    pub(crate) fn of<T: Float>(x: T) -> Self {
        let x = x.to_f64();
        debug_assert!(x.is_finite());
        let (m, e) = decompose(x);
        Self {
            neg: x < 0.0,
            mag: BigUint::from_u64(m),
            exp: e,
        }
        .normalize()
    }

    /// The integer `±m · 2^e` from its parts.
    pub(crate) fn from_parts(neg: bool, mag: BigUint, exp: i64) -> Self {
        Self { neg, mag, exp }.normalize()
    }

    /// Clears the sign of zero.
    fn normalize(mut self) -> Self {
        if self.mag.is_zero() {
            self.neg = false;
            self.exp = 0;
        }
        self
    }

    /// `−1`, `0` or `1`.
    pub(crate) fn signum(&self) -> i32 {
        if self.mag.is_zero() {
            0
        } else if self.neg {
            -1
        } else {
            1
        }
    }

    /// `−self`.
    pub(crate) fn neg(&self) -> Self {
        Self {
            neg: !self.neg,
            mag: self.mag.clone(),
            exp: self.exp,
        }
        .normalize()
    }

    /// `self + other`, exactly.
    pub(crate) fn add(&self, other: &Self) -> Self {
        if other.mag.is_zero() {
            return self.clone();
        }
        if self.mag.is_zero() {
            return other.clone();
        }
        let exp = self.exp.min(other.exp);
        let a = self.mag.shl((self.exp - exp) as u64);
        let b = other.mag.shl((other.exp - exp) as u64);
        let (neg, mag) = if self.neg == other.neg {
            (self.neg, a.add(&b))
        } else if a >= b {
            (self.neg, a.sub(&b))
        } else {
            (other.neg, b.sub(&a))
        };
        Self { neg, mag, exp }.normalize()
    }

    /// `self · other`, exactly.
    pub(crate) fn mul(&self, other: &Self) -> Self {
        Self {
            neg: self.neg != other.neg,
            mag: self.mag.mul(&other.mag),
            exp: self.exp + other.exp,
        }
        .normalize()
    }

    /// `self^k`, exactly.
    pub(crate) fn powi(&self, k: u32) -> Self {
        Self {
            neg: self.neg && k % 2 == 1,
            mag: self.mag.pow(u64::from(k)),
            exp: self.exp * i64::from(k),
        }
        .normalize()
    }

    /// The exact order of `self` and `other`.
    pub(crate) fn cmp(&self, other: &Self) -> Ordering {
        self.add(&other.neg()).signum().cmp(&0)
    }

    /// `self` rounded toward −∞ (`up = false`) or toward +∞ (`up = true`) to `T`, on its
    /// subnormal grid, with `±MAX`/`±∞` where the value exceeds the finite range.
    pub(crate) fn round<T: Float>(&self, up: bool) -> T {
        if self.mag.is_zero() {
            return T::ZERO;
        }
        let p = i64::from(T::MANTISSA_DIGITS);
        // The exponent of the smallest subnormal of T (a power of two: m·2^e with m a power
        // of two too when T = f32, whose subnormals are normal f64s).
        let (mtiny, etiny) = decompose(T::MIN_POSITIVE_SUBNORMAL.to_f64());
        let emin_sub = etiny + i64::from(mtiny.trailing_zeros());
        let (mmax, emax) = decompose(T::MAX.to_f64());
        let top = emax + 64 - i64::from(mmax.leading_zeros()); // MAX < 2^top
        // Round the magnitude toward zero, remembering whether that was exact.
        let away = up != self.neg;
        let len = self.mag.bits() as i64;
        let (trunc, inexact) = if self.exp + len > top {
            (T::MAX, true)
        } else {
            let q = (self.exp + len - p).max(emin_sub);
            let (t, sticky) = if q >= self.exp {
                self.mag.shr_sticky((q - self.exp) as u64)
            } else {
                (self.mag.shl((self.exp - q) as u64), false)
            };
            let t = t.to_u64().expect("at most p bits") as f64;
            // t < 2^p and q ≥ emin_sub: t · 2^q is a value of T, so both steps are exact.
            (T::from_f64_rn(t * pow2_f64(q)), sticky)
        };
        let m = if inexact && away {
            trunc.next_up()
        } else {
            trunc
        };
        if self.neg { -m } else { m }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_on_the_true_grid() {
        let third = |x: f64| Dyadic::of(x);
        // 1 + 2^-60 lies strictly between 1 and its successor.
        let v = third(1.0).add(&third(2f64.powi(-60)));
        assert_eq!(v.round::<f64>(false), 1.0);
        assert_eq!(v.round::<f64>(true), 1.0f64.next_up());
        assert_eq!(v.neg().round::<f64>(false), -1.0f64.next_up());
        assert_eq!(v.round::<f32>(true), 1.0f32.next_up());
        // Below the smallest subnormal.
        let tiny = third(f64::MIN_POSITIVE_SUBNORMAL).mul(&third(0.5));
        assert_eq!(tiny.round::<f64>(false), 0.0);
        assert_eq!(tiny.round::<f64>(true), f64::MIN_POSITIVE_SUBNORMAL);
        // Beyond MAX.
        let huge = third(f64::MAX).add(&third(f64::MAX));
        assert_eq!(huge.round::<f64>(false), f64::MAX);
        assert_eq!(huge.round::<f64>(true), f64::INFINITY);
        assert_eq!(third(f64::MAX).round::<f32>(false), f32::MAX);
        assert_eq!(third(f64::MAX).round::<f32>(true), f32::INFINITY);
        // Exact values stay.
        for x in [0.1, -3.5, 5e-324, f64::MAX, -f64::MIN_POSITIVE] {
            assert_eq!(third(x).round::<f64>(false), x);
            assert_eq!(third(x).round::<f64>(true), x);
        }
        assert_eq!(third(0.1).round::<f32>(false), 0.1f32.next_down());
        assert_eq!(third(0.1).round::<f32>(true), 0.1f32);
        assert_eq!(third(3.0).powi(3).round::<f64>(false), 27.0);
        assert_eq!(third(0.5).cmp(&third(0.25)), Ordering::Greater);
        // f32 subnormals: 1.5 · 2^-149 lies between the two smallest.
        let t = third(f64::from(f32::from_bits(1))).mul(&third(1.5));
        assert_eq!(t.round::<f32>(false), f32::from_bits(1));
        assert_eq!(t.round::<f32>(true), f32::from_bits(2));
        let u = third(f64::from(f32::from_bits(1))).mul(&third(0.25));
        assert_eq!(
            (u.round::<f32>(false), u.round::<f32>(true)),
            (0.0, f32::from_bits(1))
        );
    }
}
