//! Error-free transformations.
//!
//! An error-free transformation returns the rounded result of an operation together with
//! its rounding error, both as floating-point numbers whose exact sum is the exact result.

use super::traits::Float;

/// Error-free sum: `(s, e)` with `s = RN(a + b)` and `s + e = a + b` exactly, for all
/// finite `a`, `b` whose sum does not overflow, in any binary format (subnormal results are
/// fine: the error of an addition is always representable).
///
/// Knuth's branch-free TwoSum is used first. Its intermediate `s − a` can overflow although
/// the sum is finite (e.g. `a = −4.77e307, b = MAX`); that case, recognised by the
/// non-finite intermediate, is redone by Fast2Sum after ordering the operands by magnitude,
/// where `s − x` with `|x| ≥ |y|` stays below `|y|·(1 + 2^−52)`.
#[inline(always)]
pub fn two_sum<T: Float>(a: T, b: T) -> (T, T) {
    let s = a + b;
    let bb = s - a;
    if bb.is_finite() {
        (s, (a - (s - bb)) + (b - bb))
    } else {
        two_sum_ordered(a, b)
    }
}

/// Fast2Sum after ordering by magnitude: the overflow-free form of [`two_sum`].
#[cold]
fn two_sum_ordered<T: Float>(a: T, b: T) -> (T, T) {
    let (x, y) = if a.abs() < b.abs() { (b, a) } else { (a, b) };
    let s = x + y;
    (s, y - (s - x))
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
///
/// `r` is the round-to-nearest result and `err` the exact sign of the error, so a nonzero
/// `err` means `r` is finite and nonzero (a zero or infinite `r` is exact on the fast paths),
/// as [`Float::next_down_if`] requires.
#[inline(always)]
pub(crate) fn down_by_sign<T: Float>(r: T, err: T) -> T {
    r.next_down_if(err < T::ZERO)
}

/// Steps `r` one ulp toward +∞ when the exact result lies above it (`err > 0`).
#[inline(always)]
pub(crate) fn up_by_sign<T: Float>(r: T, err: T) -> T {
    r.next_up_if(err > T::ZERO)
}
