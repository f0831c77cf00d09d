//! The local decorations of the operations (IEEE 1788 §11.7): what each function is on a
//! given argument box — [`Decoration::Com`] for "defined and continuous on the whole box",
//! [`Decoration::Def`] for "defined, possibly discontinuous", [`Decoration::Trv`] for "possibly
//! undefined somewhere". Whether the result is bounded (`com`) or not (`dac`) is decided
//! after the evaluation, in [`crate::decorated::ops`].
//!
//! The rules are decided from the bounds exactly: a domain test compares the bounds with the
//! domain's ends; a step function is continuous on the box exactly when it takes the same
//! value at both ends (it is monotone), so `floor([1, 1.5])` is continuous and
//! `floor([0.5, 1])` is not.

use super::Decoration;
use crate::float::Float;
use crate::interval::Interval;

/// `Com` when `cond` holds (defined and continuous on the box), else `Trv`.
pub fn defined_if(cond: bool) -> Decoration {
    if cond {
        Decoration::Com
    } else {
        Decoration::Trv
    }
}

/// Functions defined and continuous on the whole line (`+ − ×`, `exp`, `sin`, ...).
pub fn everywhere<T: Float>(_x: Interval<T>) -> Decoration {
    Decoration::Com
}

/// `x ⊆ [0, +∞]`: `sqrt`.
pub fn non_negative<T: Float>(x: Interval<T>) -> Decoration {
    defined_if(x.inf() >= T::ZERO)
}

/// `x ⊆ (0, +∞]`: the logarithms.
pub fn positive<T: Float>(x: Interval<T>) -> Decoration {
    defined_if(x.inf() > T::ZERO)
}

/// `x ⊆ (−1, +∞]`: `log1p`.
pub fn above_minus_one<T: Float>(x: Interval<T>) -> Decoration {
    defined_if(x.inf() > -T::ONE)
}

/// `x ⊆ [−1, 1]`: `asin`, `acos`.
pub fn unit<T: Float>(x: Interval<T>) -> Decoration {
    defined_if(x.inf() >= -T::ONE && x.sup() <= T::ONE)
}

/// `x ⊆ (−1, 1)`: `atanh`.
pub fn open_unit<T: Float>(x: Interval<T>) -> Decoration {
    defined_if(x.inf() > -T::ONE && x.sup() < T::ONE)
}

/// `x ⊆ [1, +∞]`: `acosh`.
pub fn at_least_one<T: Float>(x: Interval<T>) -> Decoration {
    defined_if(x.inf() >= T::ONE)
}

/// `0 ∉ x`: `recip`, negative powers.
pub fn nonzero<T: Float>(x: Interval<T>) -> Decoration {
    defined_if(!x.contains(T::ZERO))
}

/// `tan`: continuous where the interval evaluation proved the box free of poles (a bounded
/// result); `trv` when it returned `[−∞, +∞]` (a pole may lie inside).
pub fn tan<T: Float>(x: Interval<T>) -> Decoration {
    defined_if(x.is_empty() || !x.tan().is_entire())
}

/// A monotone step function `f` is continuous on the box exactly when it takes one value
/// on it, i.e. at both ends; otherwise it is defined but jumps (`def`).
pub fn step<T: Float>(x: Interval<T>, f: fn(Interval<T>) -> Interval<T>) -> Decoration {
    match x.bounds() {
        None => Decoration::Com,
        Some((lo, hi)) => {
            let at = |v: T| f(Interval::new_unchecked(v, v)).inf();
            if lo.is_finite() && hi.is_finite() && at(lo) == at(hi) {
                Decoration::Com
            } else {
                Decoration::Def
            }
        }
    }
}

/// `pown(x, n)`: everywhere for `n ≥ 0`, on `0 ∉ x` for `n < 0`.
pub fn pown<T: Float>(x: Interval<T>, n: i32) -> Decoration {
    if n >= 0 { Decoration::Com } else { nonzero(x) }
}

/// `rootn(x, n)`: everywhere for odd `n > 0`, on `x ≥ 0` for even `n > 0`, on `x > 0` (even)
/// or `0 ∉ x` (odd) for `n < 0`; never for `n = 0`.
pub fn rootn<T: Float>(x: Interval<T>, n: i32) -> Decoration {
    let odd = n % 2 != 0;
    match (n.signum(), odd) {
        (0, _) => Decoration::Trv,
        (1, true) => Decoration::Com,
        (1, false) => non_negative(x),
        (_, true) => nonzero(x),
        (_, false) => positive(x),
    }
}

/// `x / y`: continuous where `0 ∉ y`.
pub fn div<T: Float>(_x: Interval<T>, y: Interval<T>) -> Decoration {
    nonzero(y)
}

/// `pow(x, y)` on its domain `{x > 0} ∪ {x = 0, y > 0}` (continuous there).
pub fn pow<T: Float>(x: Interval<T>, y: Interval<T>) -> Decoration {
    defined_if(x.inf() > T::ZERO || (x.inf() >= T::ZERO && y.inf() > T::ZERO))
}

/// `atan2(y, x)`: undefined at the origin (`trv` if the box holds it), discontinuous across
/// the cut `{x < 0, y = 0}` when the box reaches below it (`def`), continuous otherwise.
pub fn atan2<T: Float>(y: Interval<T>, x: Interval<T>) -> Decoration {
    if y.contains(T::ZERO) && x.contains(T::ZERO) {
        Decoration::Trv
    } else if x.inf() < T::ZERO && y.inf() < T::ZERO && y.sup() >= T::ZERO {
        Decoration::Def
    } else {
        Decoration::Com
    }
}
