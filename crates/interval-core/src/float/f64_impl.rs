//! Directed rounding for `f64` by error-free transformations.
//!
//! Each operation computes the round-to-nearest result `r`, obtains the exact sign of the
//! rounding error, and steps `r` by one ulp only when it lies on the wrong side. The fast
//! path covers operands and results away from overflow and from the subnormal range, where
//! the error term is exactly representable; the `*_slow` functions handle the rest by
//! scaling with powers of two (exact) so the error term is again exact.

use super::eft::{down_by_sign, two_prod, two_sum, up_by_sign};
use super::traits::Float;

/// `2^k` for `-1022 <= k <= 1023`, built from its bit pattern.
#[inline(always)]
const fn pow2(k: i32) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// Below this magnitude a product's FMA error term may fall under the subnormal quantum.
const PROD_EXACT_MIN: f64 = pow2(-967);
/// Below this magnitude a quotient's remainder may not be exact.
const QUOT_MIN: f64 = pow2(-1021);
/// Below this magnitude of the dividend the FMA remainder may not be exact.
const DIVIDEND_MIN: f64 = pow2(-960);
/// Below this magnitude `fma(-s, s, a)` may not be exact.
const SQRT_ARG_MIN: f64 = pow2(-960);
/// The range in which ErrFma's error terms are exact and free of overflow.
const FMA_MIN: f64 = pow2(-900);
const FMA_MAX: f64 = pow2(1000);
/// The power-of-two scale used to lift tiny operands out of the subnormal range.
const LIFT: i32 = 600;

/// Bounds `(down, up)` of an exact value known only to exceed the finite range.
#[inline]
fn overflow_bounds(positive: bool) -> (f64, f64) {
    if positive {
        (f64::MAX, f64::INFINITY)
    } else {
        (f64::NEG_INFINITY, -f64::MAX)
    }
}

/// Bounds of a nonzero exact value whose magnitude is below the smallest subnormal / 2.
#[inline]
fn underflow_bounds(positive: bool) -> (f64, f64) {
    if positive {
        (0.0, f64::MIN_POSITIVE_SUBNORMAL)
    } else {
        (-f64::MIN_POSITIVE_SUBNORMAL, -0.0)
    }
}

/// Bounds `(down, up)` of the exact value `r + err`, where `r` is its round-to-nearest value
/// and only the sign of `err` matters.
#[inline]
fn bracket(r: f64, err: f64) -> (f64, f64) {
    if err < 0.0 {
        (r.next_down(), r)
    } else if err > 0.0 {
        (r, r.next_up())
    } else {
        (r, r)
    }
}

/// Exponent and significand of a finite nonzero `x`: `x = m · 2^e` with `1 <= |m| < 2`.
fn frexp(x: f64) -> (f64, i32) {
    let (x, bias) = if x.abs() < f64::MIN_POSITIVE {
        (x * pow2(64), 64)
    } else {
        (x, 0)
    };
    let bits = x.to_bits();
    let e = ((bits >> 52) & 0x7ff) as i32 - 1023;
    let m = f64::from_bits((bits & !(0x7ff << 52)) | (1023 << 52));
    (m, e - bias)
}

/// `x · 2^k` rounded to nearest with a single rounding, for finite `x`.
///
/// Steps toward large magnitudes are exact until they overflow (and an overflowed
/// intermediate means the exact result overflows too). Toward small magnitudes the value is
/// first normalized exactly, then rounded once: in the subnormal range by rounding the scaled
/// significand to an integer (ties to even), which is what the hardware does.
fn ldexp_rn(x: f64, k: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let mut k = k.clamp(-2400, 2400);
    let mut x = x;
    while k > 1023 {
        x *= pow2(1023);
        k -= 1023;
    }
    if k >= -1022 {
        return x * pow2(k);
    }
    // k < -1022: normalize x to [1, 2) exactly, then round once.
    let (m, e) = frexp(x);
    let k1 = k + e;
    if k1 >= -1022 {
        m * pow2(k1)
    } else if k1 < -1075 {
        0.0 * m
    } else {
        // |m · 2^k1| < 2^-1022: the subnormal grid is 2^-1074, so round m · 2^(k1 + 1074)
        // (exact, |.| < 2^52) to an integer and scale back (exact).
        (m * pow2(k1 + 1074)).round_ties_even() * f64::MIN_POSITIVE_SUBNORMAL
    }
}

/// Bounds of `(hi + lo) · 2^k`, where `hi` is normal and `|lo| <= ulp(hi)/2`.
///
/// `q = RN(hi · 2^k)` is within one grid step of the exact value; the sign of
/// `exact − q` is that of `d + lo` with `d = hi − q·2^(−k)` computed exactly (Sterbenz), and
/// `d`, when nonzero, is at least one ulp of `hi`, so it dominates `lo`.
fn round_scaled(hi: f64, lo: f64, k: i32) -> (f64, f64) {
    let q = ldexp_rn(hi, k);
    if q.is_infinite() {
        return overflow_bounds(hi > 0.0);
    }
    if q == 0.0 {
        return underflow_bounds(hi > 0.0);
    }
    let back = ldexp_rn(q, -k);
    let d = hi - back;
    bracket(q, if d != 0.0 { d } else { lo })
}

/// Directed bounds of `a + b` when the round-to-nearest sum is not finite.
#[inline]
fn add_nonfinite(a: f64, b: f64, s: f64) -> (f64, f64) {
    if s.is_infinite() && a.is_finite() && b.is_finite() {
        overflow_bounds(s > 0.0)
    } else {
        (s, s)
    }
}

/// Whether `a · b` is exactly 0 both ways: a zero factor and no NaN (an infinite factor
/// too: `0 · ∞ = 0` in interval arithmetic). The fast path's callers ask it before the cold
/// path: the gradients' derivatives of constants multiply zeros all the time.
#[inline(always)]
fn zero_product(a: f64, b: f64) -> bool {
    (a == 0.0 || b == 0.0) && !a.is_nan() && !b.is_nan()
}

/// Directed bounds of `a · b` outside the fast path: NaN, zeros, infinities, overflow and
/// products near or below the subnormal range.
#[cold]
fn mul_slow(a: f64, b: f64) -> (f64, f64) {
    if zero_product(a, b) {
        return (0.0, 0.0);
    }
    if a.is_nan() || b.is_nan() {
        return (f64::NAN, f64::NAN);
    }
    let p = a * b;
    if p.is_infinite() {
        if a.is_infinite() || b.is_infinite() {
            return (p, p);
        }
        return overflow_bounds(p > 0.0);
    }
    // |a·b| < 2^-967, so the smaller factor is below 2^-483 and can be lifted exactly.
    let (x, y) = if a.abs() <= b.abs() { (a, b) } else { (b, a) };
    let (ps, es) = two_prod(x * pow2(LIFT), y);
    if ps.abs() >= PROD_EXACT_MIN {
        round_scaled(ps, es, -LIFT)
    } else {
        // |a·b| < 2^-1566: far below the smallest subnormal.
        underflow_bounds((a > 0.0) == (b > 0.0))
    }
}

/// Directed bounds of `a / b` outside the fast path.
#[cold]
fn div_slow(a: f64, b: f64) -> (f64, f64) {
    if a.is_nan() || b.is_nan() {
        return (f64::NAN, f64::NAN);
    }
    if b == 0.0 || a.is_infinite() {
        let q = a / b;
        return (q, q);
    }
    if a == 0.0 || b.is_infinite() {
        return (0.0, 0.0);
    }
    let q = a / b;
    if q.is_infinite() {
        return overflow_bounds(q > 0.0);
    }
    // Normalize both operands to [1, 2): the remainder of the scaled quotient is exact.
    let (ma, ea) = frexp(a);
    let (mb, eb) = frexp(b);
    let qs = ma / mb;
    let r = (-qs).mul_add(mb, ma);
    round_scaled(qs, r / mb, ea - eb)
}

/// Directed bounds of `√a` outside the fast path.
#[cold]
fn sqrt_slow(a: f64) -> (f64, f64) {
    if a.is_nan() || a < 0.0 {
        return (f64::NAN, f64::NAN);
    }
    if a == 0.0 || a.is_infinite() {
        return (a, a);
    }
    // Tiny a: √(a · 2^600) = √a · 2^300, all scalings exact.
    let scaled = a * pow2(LIFT);
    let s = scaled.sqrt();
    let r = (-s).mul_add(s, scaled);
    let (lo, hi) = bracket(s, r);
    (lo * pow2(-LIFT / 2), hi * pow2(-LIFT / 2))
}

/// Round-to-nearest `a·b + c` and a value with the sign of its rounding error, by
/// Boldo–Muller's ErrFma; valid when `|a·b|` (as `RN(a·b)`) and `|c|` are zero or lie in
/// `[2^-900, 2^1000]`, where every error term is exact and nothing overflows.
#[inline(always)]
fn err_fma(a: f64, b: f64, c: f64) -> (f64, f64) {
    let (u1, u2) = two_prod(a, b);
    let r1 = a.mul_add(b, c);
    let (alpha1, alpha2) = two_sum(c, u2);
    let (beta1, beta2) = two_sum(u1, alpha1);
    let gamma = (beta1 - r1) + beta2;
    // γ + α2 is the exact error (Boldo & Muller 2011); its rounding keeps the sign.
    (r1, gamma + alpha2)
}

/// Whether ErrFma applies to `a·b + c` (see [`err_fma`]).
#[inline(always)]
fn fma_in_range(p: f64, c: f64) -> bool {
    let in_range = |v: f64| (FMA_MIN..=FMA_MAX).contains(&v.abs());
    in_range(p) && (c == 0.0 || in_range(c))
}

/// [`err_fma`] on the fast path, `None` outside its range.
#[inline]
fn fma_err(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    if fma_in_range(a * b, c) {
        Some(err_fma(a, b, c))
    } else {
        None
    }
}

/// Bounds of `c + δ` for a nonzero `δ` of the given sign smaller than the gap between `c`
/// and its neighbours.
#[inline]
fn nudge(c: f64, delta_positive: bool) -> (f64, f64) {
    if delta_positive {
        (c, c.next_up())
    } else {
        (c.next_down(), c)
    }
}

/// Directed bounds of `a·b + c` outside ErrFma's range.
///
/// Either one term is negligible against the other — then the result is the other term
/// nudged by the sign of the negligible one (or of the product's exact error) — or the two
/// are within a factor `2^110` of each other, and scaling the larger factor of the product
/// and the addend by the same power of two (exact) brings both into ErrFma's range; the
/// result is scaled back with a single rounding.
#[cold]
fn fma_slow(a: f64, b: f64, c: f64) -> (f64, f64) {
    if a.is_nan() || b.is_nan() || c.is_nan() {
        return (f64::NAN, f64::NAN);
    }
    if a == 0.0 || b == 0.0 {
        return (c, c);
    }
    let product_positive = (a > 0.0) == (b > 0.0);
    if a.is_infinite() || b.is_infinite() {
        let p = if product_positive {
            f64::INFINITY
        } else {
            f64::NEG_INFINITY
        };
        // ∞ − ∞ is undefined, as in IEEE 754.
        return if c.is_infinite() && (c > 0.0) != (p > 0.0) {
            (f64::NAN, f64::NAN)
        } else {
            (p, p)
        };
    }
    if c.is_infinite() {
        return (c, c);
    }
    if c == 0.0 {
        return mul_slow_or_fast(a, b);
    }
    let p = a * b;
    // The product is negligible: |a·b| < |c|·2^-55 is below half the gap around c.
    if p.abs() < c.abs() * pow2(-56) {
        return nudge(c, product_positive);
    }
    // The addend is negligible: below the quantum of the product's exact error.
    if p.is_finite() && p.abs() >= PROD_EXACT_MIN && c.abs() < p.abs() * pow2(-108) {
        let e = a.mul_add(b, -p);
        return bracket(p, if e != 0.0 { e } else { c });
    }
    // Comparable magnitudes: scale into ErrFma's range.
    let (x, y) = if a.abs() <= b.abs() { (a, b) } else { (b, a) };
    if p.abs().max(c.abs()) > FMA_MAX {
        // Huge terms (the product may even overflow): scale the larger factor and the addend
        // down by 2^-128 at a time (exact) until they fit, or until the addend is negligible.
        let (mut ys, mut cs) = (y, c);
        for k in [128, 256, 384] {
            ys *= pow2(-128);
            cs *= pow2(-128);
            let ps = x * ys;
            if !ps.is_finite() || cs.abs() < ps.abs() * pow2(-108) {
                // |c| < |a·b|·2^-107: if a·b overflows, so does a·b + c.
                if p.is_infinite() {
                    return overflow_bounds(product_positive);
                }
                let e = a.mul_add(b, -p);
                return bracket(p, if e != 0.0 { e } else { c });
            }
            if fma_in_range(ps, cs) {
                let (r, e) = err_fma(x, ys, cs);
                let scale = |v: f64| (0..k / 128).fold(v, |v, _| v * pow2(128));
                if scale(r).is_infinite() {
                    return overflow_bounds(r > 0.0);
                }
                let (lo, hi) = bracket(r, e);
                return (scale(lo), scale(hi));
            }
        }
    } else {
        // Lifting keeps the ratio of the terms but takes the tests out of the subnormal range.
        let (xs, cs) = (x * pow2(LIFT), c * pow2(LIFT));
        let ps = xs * y;
        if ps.abs() < cs.abs() * pow2(-56) {
            return nudge(c, product_positive);
        }
        if ps.abs() >= PROD_EXACT_MIN && cs.abs() < ps.abs() * pow2(-108) {
            let es = xs.mul_add(y, -ps);
            return round_scaled(ps, if es != 0.0 { es } else { cs }, -LIFT);
        }
        if fma_in_range(ps, cs) {
            let (r, e) = err_fma(xs, y, cs);
            if r == 0.0 {
                return (0.0, 0.0);
            }
            return round_scaled(r, e, -LIFT);
        }
    }
    // Not reached for finite inputs (the cases above cover them); kept as a sound fallback.
    let (pd, pu) = mul_slow_or_fast(a, b);
    (pd.add_down(c), pu.add_up(c))
}

#[inline]
fn mul_slow_or_fast(a: f64, b: f64) -> (f64, f64) {
    (a.mul_down(b), a.mul_up(b))
}

impl Float for f64 {
    const NAME: &'static str = "f64";
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const TWO: Self = 2.0;
    const HALF: Self = 0.5;
    const INFINITY: Self = f64::INFINITY;
    const NEG_INFINITY: Self = f64::NEG_INFINITY;
    const MAX: Self = f64::MAX;
    const MIN_POSITIVE_SUBNORMAL: Self = 5e-324;
    const NAN: Self = f64::NAN;
    const MANTISSA_DIGITS: u32 = f64::MANTISSA_DIGITS;

    forward_inherent!(f64, u64);

    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn from_f64_rn(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn from_f64_down(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn from_f64_up(x: f64) -> Self {
        x
    }

    #[inline(always)]
    fn add_down(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::add_down(self, b);
            if super::embedded::usable(r) {
                return r;
            }
        }
        let (s, e) = two_sum(self, b);
        if s.is_finite() {
            down_by_sign(s, e)
        } else {
            add_nonfinite(self, b, s).0
        }
    }
    #[inline(always)]
    fn add_up(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::add_up(self, b);
            if super::embedded::usable(r) {
                return r;
            }
        }
        let (s, e) = two_sum(self, b);
        if s.is_finite() {
            up_by_sign(s, e)
        } else {
            add_nonfinite(self, b, s).1
        }
    }
    #[inline(always)]
    fn mul_down(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::mul_down(self, b);
            if super::embedded::usable(r) {
                return r;
            }
        }
        let (p, e) = two_prod(self, b);
        if p.abs() >= PROD_EXACT_MIN && p.abs() <= f64::MAX {
            down_by_sign(p, e)
        } else if zero_product(self, b) {
            0.0
        } else {
            mul_slow(self, b).0
        }
    }
    #[inline(always)]
    fn mul_up(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::mul_up(self, b);
            if super::embedded::usable(r) {
                return r;
            }
        }
        let (p, e) = two_prod(self, b);
        if p.abs() >= PROD_EXACT_MIN && p.abs() <= f64::MAX {
            up_by_sign(p, e)
        } else if zero_product(self, b) {
            0.0
        } else {
            mul_slow(self, b).1
        }
    }
    #[inline(always)]
    fn div_down(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::div_down(self, b);
            if super::embedded::usable(r) {
                return r;
            }
        }
        let q = self / b;
        if q.abs() >= QUOT_MIN && q.abs() <= f64::MAX && self.abs() >= DIVIDEND_MIN {
            let r = (-q).mul_add(b, self);
            down_by_sign(q, if b < 0.0 { -r } else { r })
        } else {
            div_slow(self, b).0
        }
    }
    #[inline(always)]
    fn div_up(self, b: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::div_up(self, b);
            if super::embedded::usable(r) {
                return r;
            }
        }
        let q = self / b;
        if q.abs() >= QUOT_MIN && q.abs() <= f64::MAX && self.abs() >= DIVIDEND_MIN {
            let r = (-q).mul_add(b, self);
            up_by_sign(q, if b < 0.0 { -r } else { r })
        } else {
            div_slow(self, b).1
        }
    }
    #[inline(always)]
    fn sqrt_down(self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::sqrt_down(self);
            if super::embedded::usable(r) {
                return r;
            }
        }
        if (SQRT_ARG_MIN..=f64::MAX).contains(&self) {
            let s = self.sqrt();
            down_by_sign(s, (-s).mul_add(s, self))
        } else {
            sqrt_slow(self).0
        }
    }
    #[inline(always)]
    fn sqrt_up(self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::sqrt_up(self);
            if super::embedded::usable(r) {
                return r;
            }
        }
        if (SQRT_ARG_MIN..=f64::MAX).contains(&self) {
            let s = self.sqrt();
            up_by_sign(s, (-s).mul_add(s, self))
        } else {
            sqrt_slow(self).1
        }
    }
    #[inline]
    fn fma_down(self, b: Self, c: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::fma_down(self, b, c);
            if super::embedded::usable(r) {
                return r;
            }
        }
        match fma_err(self, b, c) {
            Some((r, e)) => down_by_sign(r, e),
            None => fma_slow(self, b, c).0,
        }
    }
    #[inline]
    fn fma_up(self, b: Self, c: Self) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx512f"))]
        {
            let r = super::embedded::fma_up(self, b, c);
            if super::embedded::usable(r) {
                return r;
            }
        }
        match fma_err(self, b, c) {
            Some((r, e)) => up_by_sign(r, e),
            None => fma_slow(self, b, c).1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ldexp_rounds_once_into_subnormals() {
        // 1.5 · 2^-1075 = 0.75 · 2^-1074 rounds up; 2^-1075 is a tie and goes to even (0).
        assert_eq!(ldexp_rn(1.5, -1075), f64::MIN_POSITIVE_SUBNORMAL);
        assert_eq!(ldexp_rn(1.0, -1075), 0.0);
        assert_eq!(ldexp_rn(1.0, -1074), f64::MIN_POSITIVE_SUBNORMAL);
        assert_eq!(ldexp_rn(1.0, 1024), f64::INFINITY);
        assert_eq!(ldexp_rn(1.0, -2000), 0.0);
        assert_eq!(ldexp_rn(f64::MIN_POSITIVE_SUBNORMAL, 1074), 1.0);
    }

    #[test]
    fn frexp_handles_subnormals() {
        assert_eq!(frexp(f64::MIN_POSITIVE_SUBNORMAL), (1.0, -1074));
        assert_eq!(frexp(-3.0), (-1.5, 1));
    }

    #[test]
    fn tiny_products_are_bracketed() {
        let a = f64::MIN_POSITIVE_SUBNORMAL;
        assert_eq!(a.mul_down(0.5), 0.0);
        assert_eq!(a.mul_up(0.5), a);
        assert_eq!(a.mul_down(1.5), a);
        assert_eq!(a.mul_up(1.5), 2.0 * a);
        assert_eq!(a.mul_down(-a), -a);
        assert_eq!(a.mul_up(-a), 0.0);
    }

    #[test]
    fn overflow_is_bracketed() {
        assert_eq!(f64::MAX.add_down(f64::MAX), f64::MAX);
        assert_eq!(f64::MAX.add_up(f64::MAX), f64::INFINITY);
        assert_eq!(f64::MAX.mul_down(2.0), f64::MAX);
        assert_eq!((-f64::MAX).mul_up(2.0), -f64::MAX);
        assert_eq!(f64::MAX.div_down(0.5), f64::MAX);
    }

    #[test]
    fn sums_near_max_are_bracketed() {
        // s − a overflows in branch-free TwoSum here although the sum is finite.
        let (a, b) = (-4.770813245647214e307, f64::MAX);
        let (lo, hi) = (a.add_down(b), a.add_up(b));
        assert!(lo < hi && hi == lo.next_up());
        assert_eq!(b.add_down(a), lo);
        let (a, b) = (-1.6203908e38f32, f32::MAX);
        let (lo, hi) = (a.add_down(b), a.add_up(b));
        assert!(lo < hi && hi == lo.next_up());
    }

    #[test]
    fn fma_far_outside_the_normal_range_is_tight() {
        // Cancellation of a huge product by a huge addend: exact result 2^906.
        let (a, b, c) = (
            pow2(1010) * (1.0 + pow2(-52)),
            1.0 + pow2(-52),
            -pow2(1010) * (1.0 + pow2(-51)),
        );
        assert_eq!(a.fma_down(b, c), pow2(906));
        assert_eq!(a.fma_up(b, c), pow2(906));
        // A product far below the subnormal range next to a subnormal addend.
        let u = f64::MIN_POSITIVE_SUBNORMAL;
        let t = pow2(-600);
        assert_eq!(t.fma_down(t, u), u);
        assert_eq!(t.fma_up(t, u), 2.0 * u);
        assert_eq!((-t).fma_down(t, u), 0.0);
        assert_eq!((-t).fma_up(t, u), u);
        // Overflowing product, infinite addend.
        assert_eq!(2.0.fma_down(f64::MAX, f64::NEG_INFINITY), f64::NEG_INFINITY);
        assert!(f64::INFINITY.fma_down(1.0, f64::NEG_INFINITY).is_nan());
    }

    #[test]
    fn one_third() {
        let lo = 1.0f64.div_down(3.0);
        let hi = 1.0f64.div_up(3.0);
        assert_eq!(hi, lo.next_up());
        // 3·lo < 1 < 3·hi, decided exactly by the sign of a single-rounding fma.
        assert!(3f64.mul_add(lo, -1.0) < 0.0 && 3f64.mul_add(hi, -1.0) > 0.0);
        assert_eq!(2.0f64.sqrt_up(), 2.0f64.sqrt_down().next_up());
        assert_eq!(4.0f64.sqrt_down(), 2.0);
        assert_eq!(4.0f64.sqrt_up(), 2.0);
    }
}
