//! The [`Float`] trait: the operations and directed roundings intervals need of their
//! bound type, sealed to `f64` and `f32`.

use core::fmt::{Debug, Display, LowerExp};
use core::ops::{Add, Div, Mul, Neg, Sub};

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A binary floating-point type with outward (directed) rounding: `f64` or `f32`.
///
/// This trait is sealed: the directed-rounding proofs are specific to IEEE 754 binary64 and
/// binary32.
pub trait Float:
    sealed::Sealed
    + Copy
    + Default
    + Debug
    + Display
    + LowerExp
    + PartialEq
    + PartialOrd
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The type name, for messages (`"f64"` or `"f32"`).
    const NAME: &'static str;
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 0.5.
    const HALF: Self;
    /// +∞.
    const INFINITY: Self;
    /// −∞.
    const NEG_INFINITY: Self;
    /// The largest finite value.
    const MAX: Self;
    /// The smallest positive (subnormal) value.
    const MIN_POSITIVE_SUBNORMAL: Self;
    /// Not a number (used for the empty interval's bounds).
    const NAN: Self;
    /// Number of significand bits, including the implicit bit (53 or 24).
    const MANTISSA_DIGITS: u32;

    /// The next representable value toward +∞ (`f64::next_up`).
    fn next_up(self) -> Self;
    /// The next representable value toward −∞ (`f64::next_down`).
    fn next_down(self) -> Self;
    /// `next_down(self)` if `cond`, else `self`, as a branch-free select (the rounding
    /// direction of random data is unpredictable, and a mispredicted branch costs more than
    /// the step). Precondition: when `cond` holds, `self` is finite and nonzero.
    fn next_down_if(self, cond: bool) -> Self;
    /// `next_up(self)` if `cond`, else `self`, branch-free; same precondition as
    /// [`Float::next_down_if`].
    fn next_up_if(self, cond: bool) -> Self;
    /// True for NaN.
    fn is_nan(self) -> bool;
    /// True for finite values (not ±∞, not NaN).
    fn is_finite(self) -> bool;
    /// True for ±∞.
    fn is_infinite(self) -> bool;
    /// True if the sign bit is set (−0 included).
    fn is_sign_negative(self) -> bool;
    /// Absolute value.
    fn abs(self) -> Self;
    /// Minimum of two numbers; NaN if either is NaN.
    #[inline(always)]
    fn min_nan(self, other: Self) -> Self {
        if self.is_nan() || other.is_nan() {
            Self::NAN
        } else if self < other {
            self
        } else {
            other
        }
    }
    /// Maximum of two numbers; NaN if either is NaN.
    #[inline(always)]
    fn max_nan(self, other: Self) -> Self {
        if self.is_nan() || other.is_nan() {
            Self::NAN
        } else if self > other {
            self
        } else {
            other
        }
    }
    /// Square root, rounded to nearest.
    fn sqrt_rn(self) -> Self;
    /// Exact conversion to `f64`.
    fn to_f64(self) -> f64;
    /// Conversion from `f64`, rounded to nearest.
    fn from_f64_rn(x: f64) -> Self;
    /// The largest value of this type ≤ `x` (rounding toward −∞).
    fn from_f64_down(x: f64) -> Self;
    /// The smallest value of this type ≥ `x` (rounding toward +∞).
    fn from_f64_up(x: f64) -> Self;
    /// Conversion from `i32`, rounded toward −∞.
    fn from_i32_down(n: i32) -> Self {
        Self::from_f64_down(f64::from(n))
    }
    /// Conversion from `i32`, rounded toward +∞.
    fn from_i32_up(n: i32) -> Self {
        Self::from_f64_up(f64::from(n))
    }

    /// `a + b` rounded toward −∞.
    fn add_down(self, b: Self) -> Self;
    /// `a + b` rounded toward +∞.
    fn add_up(self, b: Self) -> Self;
    /// `a − b` rounded toward −∞.
    #[inline]
    fn sub_down(self, b: Self) -> Self {
        self.add_down(-b)
    }
    /// `a − b` rounded toward +∞.
    #[inline]
    fn sub_up(self, b: Self) -> Self {
        self.add_up(-b)
    }
    /// `a · b` rounded toward −∞ (with `0 · ∞ = 0`, the interval convention).
    fn mul_down(self, b: Self) -> Self;
    /// `a · b` rounded toward +∞ (with `0 · ∞ = 0`).
    fn mul_up(self, b: Self) -> Self;
    /// `a / b` rounded toward −∞.
    fn div_down(self, b: Self) -> Self;
    /// `a / b` rounded toward +∞.
    fn div_up(self, b: Self) -> Self;
    /// `√a` rounded toward −∞ (NaN for `a < 0`).
    fn sqrt_down(self) -> Self;
    /// `√a` rounded toward +∞ (NaN for `a < 0`).
    fn sqrt_up(self) -> Self;
    /// `a · b + c` with one rounding toward −∞ (with `0 · ∞ = 0`).
    fn fma_down(self, b: Self, c: Self) -> Self;
    /// `a · b + c` with one rounding toward +∞ (with `0 · ∞ = 0`).
    fn fma_up(self, b: Self, c: Self) -> Self;
}
