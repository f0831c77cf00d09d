//! The floating-point types intervals are built on, and their directed rounding.
//!
//! [`Float`] is implemented for `f64` and `f32`. Besides the usual constants and
//! predicates it provides, for `+ - * /`, `sqrt` and `fma`, the result rounded toward
//! −∞ (`*_down`) and toward +∞ (`*_up`), **without touching the FPU rounding mode**:
//!
//! * `f64`: the round-to-nearest result `r` is computed, then an error-free transformation
//!   gives the sign of the rounding error exactly — TwoSum for `+`/`-`, the FMA remainder
//!   `fma(a, b, -r)` for `*`, `fma(-r, b, a)` for `/`, `fma(-r, r, a)` for `sqrt`, and
//!   Boldo–Muller's ErrFma for `fma`. If `r` lies on the wrong side of the exact result,
//!   it is stepped once with `next_down`/`next_up`. Where the error term could underflow
//!   (results near the subnormal range) the operands are scaled by a power of two first, so
//!   the error term is again exact; overflow is decided from the operands.
//! * `f32`: products, quotient remainders and squares of `f32` values are exact in `f64`,
//!   so the exact result is compared with the `f32` round-to-nearest result in `f64`;
//!   sums use TwoSum in `f32` itself.
//!
//! The result is bit-for-bit what round-toward-minus/plus-infinity hardware returns (up to the
//! sign of a zero result, which carries no meaning for set-based intervals). See
//! `docs/numerics.md` for the proofs.

/// Implements the [`Float`] methods that forward to the inherent methods of the same name.
macro_rules! forward_inherent {
    ($t:ty, $bits:ty) => {
        #[inline(always)]
        fn next_down_if(self, cond: bool) -> Self {
            // Toward −∞ the bit pattern decreases for positive and increases for negative
            // values: add 1 − 2·(sign = 0) as a wrapping integer.
            let bits = self.to_bits();
            let sign = bits >> (<$bits>::BITS - 1);
            let stepped = <$t>::from_bits(bits.wrapping_add((sign << 1).wrapping_sub(1)));
            core::hint::select_unpredictable(cond, stepped, self)
        }
        #[inline(always)]
        fn next_up_if(self, cond: bool) -> Self {
            let bits = self.to_bits();
            let sign = bits >> (<$bits>::BITS - 1);
            let stepped = <$t>::from_bits(bits.wrapping_add((1 as $bits).wrapping_sub(sign << 1)));
            core::hint::select_unpredictable(cond, stepped, self)
        }
        #[inline(always)]
        fn next_up(self) -> Self {
            <$t>::next_up(self)
        }
        #[inline(always)]
        fn next_down(self) -> Self {
            <$t>::next_down(self)
        }
        #[inline(always)]
        fn is_nan(self) -> bool {
            <$t>::is_nan(self)
        }
        #[inline(always)]
        fn is_finite(self) -> bool {
            <$t>::is_finite(self)
        }
        #[inline(always)]
        fn is_infinite(self) -> bool {
            <$t>::is_infinite(self)
        }
        #[inline(always)]
        fn is_sign_negative(self) -> bool {
            <$t>::is_sign_negative(self)
        }
        #[inline(always)]
        fn abs(self) -> Self {
            <$t>::abs(self)
        }
        #[inline(always)]
        fn sqrt_rn(self) -> Self {
            <$t>::sqrt(self)
        }
    };
}

mod eft;
#[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
mod embedded;
mod f32_impl;
mod f64_impl;

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

pub use eft::{two_prod, two_sum};
