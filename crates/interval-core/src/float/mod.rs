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

pub(crate) mod big;
pub(crate) mod dyadic;
mod eft;
#[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
mod embedded;
mod f32_impl;
mod f64_impl;
mod traits;

pub use eft::{two_prod, two_sum};
pub use traits::Float;
