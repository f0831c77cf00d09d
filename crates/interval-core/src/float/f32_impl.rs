//! Directed rounding for `f32`.
//!
//! Products, squares and quotient remainders of `f32` values are exact in `f64` (24 + 24
//! significand bits fit in 53, and the exponent range of `f64` covers every such product),
//! so the exact result is compared with the `f32` round-to-nearest result in `f64`. Sums use
//! TwoSum in `f32`, which is exact for every pair whose sum does not overflow.

use super::eft::{down_by_sign, two_sum, up_by_sign};
use super::traits::Float;

/// The largest `f32` ≤ `x`.
#[inline(always)]
fn f32_down(x: f64) -> f32 {
    let r = x as f32;
    if f64::from(r) > x { r.next_down() } else { r }
}

/// The smallest `f32` ≥ `x`.
#[inline(always)]
fn f32_up(x: f64) -> f32 {
    let r = x as f32;
    if f64::from(r) < x { r.next_up() } else { r }
}

/// The product in `f64` (exact), with the interval convention `0 · ∞ = 0`.
#[inline(always)]
fn exact_product(a: f32, b: f32) -> f64 {
    let p = f64::from(a) * f64::from(b);
    if p.is_nan() && !a.is_nan() && !b.is_nan() {
        0.0
    } else {
        p
    }
}

/// A value with the sign of `a/b − q`, computed exactly in `f64`.
#[inline(always)]
fn quotient_error(a: f32, b: f32, q: f32) -> f64 {
    let r = f64::from(a) - f64::from(q) * f64::from(b);
    if b < 0.0 { -r } else { r }
}

/// Round-to-nearest `a/b`, or `None` where the remainder test does not apply (NaN, zero or
/// infinite operands), with the exact value returned in the second slot for those cases.
#[inline(always)]
fn div_special(a: f32, b: f32) -> Option<f32> {
    if a.is_nan() || b.is_nan() {
        Some(f32::NAN)
    } else if b == 0.0 || a.is_infinite() {
        Some(a / b)
    } else if a == 0.0 || b.is_infinite() {
        Some(0.0)
    } else {
        None
    }
}

/// `a·b + c` as an unevaluated `f64` sum `s + e` (exact): the product is exact in `f64`.
#[inline(always)]
fn fma_exact(a: f32, b: f32, c: f32) -> (f64, f64) {
    let p = exact_product(a, b);
    let (s, e) = two_sum(p, f64::from(c));
    if s.is_finite() { (s, e) } else { (s, 0.0) }
}

/// The largest `f32` ≤ `s + e`, where `s + e` is a non-overlapping `f64` pair.
#[inline(always)]
fn f32_down_pair(s: f64, e: f64) -> f32 {
    let r = s as f32;
    let d = f64::from(r) - s;
    if d > 0.0 || (d == 0.0 && e < 0.0) {
        r.next_down()
    } else {
        r
    }
}

/// The smallest `f32` ≥ `s + e`, where `s + e` is a non-overlapping `f64` pair.
#[inline(always)]
fn f32_up_pair(s: f64, e: f64) -> f32 {
    let r = s as f32;
    let d = f64::from(r) - s;
    if d < 0.0 || (d == 0.0 && e > 0.0) {
        r.next_up()
    } else {
        r
    }
}

impl Float for f32 {
    const NAME: &'static str = "f32";
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    const HALF: Self = 0.5;
    const INFINITY: Self = f32::INFINITY;
    const NEG_INFINITY: Self = f32::NEG_INFINITY;
    const MAX: Self = f32::MAX;
    const MIN_POSITIVE_SUBNORMAL: Self = 1.0e-45;
    const NAN: Self = f32::NAN;
    const MANTISSA_DIGITS: u32 = f32::MANTISSA_DIGITS;

    forward_inherent!(f32, u32);

    #[inline(always)]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    #[inline(always)]
    fn from_f64_rn(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn from_f64_down(x: f64) -> Self {
        f32_down(x)
    }
    #[inline(always)]
    fn from_f64_up(x: f64) -> Self {
        f32_up(x)
    }

    #[inline(always)]
    fn add_down(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::add_down(self, b);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        let (s, e) = two_sum(self, b);
        if s.is_finite() {
            down_by_sign(s, e)
        } else if s == f32::INFINITY && self.is_finite() && b.is_finite() {
            f32::MAX
        } else {
            s
        }
    }
    #[inline(always)]
    fn add_up(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::add_up(self, b);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        let (s, e) = two_sum(self, b);
        if s.is_finite() {
            up_by_sign(s, e)
        } else if s == f32::NEG_INFINITY && self.is_finite() && b.is_finite() {
            -f32::MAX
        } else {
            s
        }
    }
    #[inline(always)]
    fn mul_down(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::mul_down(self, b);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        f32_down(exact_product(self, b))
    }
    #[inline(always)]
    fn mul_up(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::mul_up(self, b);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        f32_up(exact_product(self, b))
    }
    #[inline(always)]
    fn div_down(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::div_down(self, b);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        if let Some(q) = div_special(self, b) {
            return q;
        }
        let q = self / b;
        if quotient_error(self, b, q) < 0.0 {
            q.next_down()
        } else {
            q
        }
    }
    #[inline(always)]
    fn div_up(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::div_up(self, b);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        if let Some(q) = div_special(self, b) {
            return q;
        }
        let q = self / b;
        if quotient_error(self, b, q) > 0.0 {
            q.next_up()
        } else {
            q
        }
    }
    #[inline(always)]
    fn sqrt_down(self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::sqrt_down(self);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        let s = self.sqrt();
        if s.is_finite() && s > 0.0 {
            let r = f64::from(self) - f64::from(s) * f64::from(s);
            if r < 0.0 { s.next_down() } else { s }
        } else {
            s
        }
    }
    #[inline(always)]
    fn sqrt_up(self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::sqrt_up(self);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        let s = self.sqrt();
        if s.is_finite() && s > 0.0 {
            let r = f64::from(self) - f64::from(s) * f64::from(s);
            if r > 0.0 { s.next_up() } else { s }
        } else {
            s
        }
    }
    #[inline]
    fn fma_down(self, b: Self, c: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::fma_down(self, b, c);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        let (s, e) = fma_exact(self, b, c);
        f32_down_pair(s, e)
    }
    #[inline]
    fn fma_up(self, b: Self, c: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::single::fma_up(self, b, c);
            if super::embedded::single::usable(r) {
                return r;
            }
        }
        let (s, e) = fma_exact(self, b, c);
        f32_up_pair(s, e)
    }
}
