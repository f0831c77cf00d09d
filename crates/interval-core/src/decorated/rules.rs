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

/// A monotone step function `f` on the box `x`, with `jumps_at` telling its points of
/// discontinuity: `def` where it takes two values (a jump inside); otherwise `f` is
/// constant on `x`, so its restriction to `x` is continuous (`dac`), and it is continuous at
/// every point of `x` (`com`, IEEE 1788 §11.7) unless an end of `x` is a jump (`floor` on
/// `[1, 1.5]` or `[1, 1]` is `dac`, on `[1.2, 1.5]` `com`).
pub fn step<T: Float>(
    x: Interval<T>,
    f: fn(Interval<T>) -> Interval<T>,
    jumps_at: fn(f64) -> bool,
) -> Decoration {
    match x.bounds() {
        None => Decoration::Com,
        Some((lo, hi)) => {
            // At an infinite end the value is the function's limit there: `floor` jumps
            // infinitely often on `[a, +∞]` (its limit is `+∞`), `sign` not at all.
            let at = |v: T| f(Interval::new_unchecked(v, v)).inf();
            if at(lo) != at(hi) {
                Decoration::Def
            } else if jumps_at(lo.to_f64()) || jumps_at(hi.to_f64()) {
                Decoration::Dac
            } else {
                Decoration::Com
            }
        }
    }
}

/// The jumps of `floor` and `ceil`: the integers.
pub fn integer(v: f64) -> bool {
    v.is_finite() && v.fract() == 0.0
}

/// The jumps of `trunc`: the integers but 0.
pub fn nonzero_integer(v: f64) -> bool {
    integer(v) && v != 0.0
}

/// The jumps of the rounding functions: the half-integers `k + 1/2`.
pub fn half_integer(v: f64) -> bool {
    v.is_finite() && (v - v.floor()) == 0.5
}

/// The jump of `sign`: 0.
pub fn zero(v: f64) -> bool {
    v == 0.0
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

/// `atan2(y, x)`: undefined at the origin (`trv` if the box holds it); discontinuous at
/// the points of the cut `{x < 0, y = 0}`: `def` when the box reaches below the cut (a jump
/// from `π` to `−π` inside it), `dac` when it only touches the cut from above (its
/// restriction is continuous, the function is not at those points), `com` otherwise.
pub fn atan2<T: Float>(y: Interval<T>, x: Interval<T>) -> Decoration {
    if y.contains(T::ZERO) && x.contains(T::ZERO) {
        Decoration::Trv
    } else if x.inf() < T::ZERO && y.contains(T::ZERO) {
        if y.inf() < T::ZERO {
            Decoration::Def
        } else {
            Decoration::Dac
        }
    } else {
        Decoration::Com
    }
}
