//! Error-free transformations.
//!
//! An error-free transformation returns the rounded result of an operation together with
//! its rounding error, both as floating-point numbers whose exact sum is the exact result.

use super::Float;

/// Error-free sum: `(s, e)` with `s = RN(a + b)` and `s + e = a + b` exactly.
///
/// Computed as Fast2Sum (Dekker) after ordering the operands by magnitude, which is exact
/// for all finite `a`, `b` whose sum does not overflow, in any binary format; subnormal
/// results are fine (the error of an addition is always representable). Ordering first
/// matters near overflow: Knuth's branch-free TwoSum computes `s − a`, which overflows for
/// e.g. `a = −4.77e307, b = MAX` although `a + b` is finite; Fast2Sum's `s − x` with
/// `|x| ≥ |y|` stays below `|y|·(1 + 2^−52)` in magnitude.
#[inline(always)]
pub fn two_sum<T: Float>(a: T, b: T) -> (T, T) {
    let swap = a.abs() < b.abs();
    let x = if swap { b } else { a };
    let y = if swap { a } else { b };
    let s = x + y;
    let z = s - x;
    (s, y - z)
}

/// TwoProd with FMA: `(p, e)` with `p = RN(a · b)` and `p + e = a · b` exactly.
///
/// Exact when `a · b` does not overflow and `|a · b| ≥ 2^-969` (so the error term, a
/// multiple of `ulp(a)·ulp(b)`, is not below the subnormal quantum), or when it is exact.
#[inline(always)]
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Steps `r` one ulp toward −∞ when the exact result lies below it (`err < 0`).
#[inline(always)]
pub(crate) fn down_by_sign<T: Float>(r: T, err: T) -> T {
    if err < T::ZERO { r.next_down() } else { r }
}

/// Steps `r` one ulp toward +∞ when the exact result lies above it (`err > 0`).
#[inline(always)]
pub(crate) fn up_by_sign<T: Float>(r: T, err: T) -> T {
    if err > T::ZERO { r.next_up() } else { r }
}
