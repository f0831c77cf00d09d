//! Inverse hyperbolic functions: `asinh`, `acosh`, `atanh`.
//!
//! The method is that of the `elementary` module: correctly rounded CORE-MATH values at the
//! endpoints, one outward step, intersected with exact range facts — here
//! `|asinh x| ≤ |x|`, `|atanh x| ≥ |x|` (same sign), `acosh 1 = 0` — which make the bounds
//! tight at 0 and 1 and for arguments so small that the function rounds to the argument.
//! All three are increasing on their domains.

use super::Interval;
use super::elementary::increasing_known;
use crate::float::Float;

/// Exact brackets of `asinh x`: between 0 and `x`.
fn asinh_known(x: f64) -> (f64, f64) {
    if x >= 0.0 { (0.0, x) } else { (x, 0.0) }
}

/// Exact brackets of `acosh x` for `x ≥ 1`: 0 at 1, nonnegative elsewhere.
fn acosh_known(x: f64) -> (f64, f64) {
    if x == 1.0 {
        (0.0, 0.0)
    } else {
        (0.0, f64::INFINITY)
    }
}

/// Exact brackets of `atanh x` for `|x| ≤ 1`: beyond `x` away from 0 (`±∞` at `±1`).
fn atanh_known(x: f64) -> (f64, f64) {
    if x == 1.0 {
        (f64::INFINITY, f64::INFINITY)
    } else if x == -1.0 {
        (f64::NEG_INFINITY, f64::NEG_INFINITY)
    } else if x >= 0.0 {
        (x, f64::INFINITY)
    } else {
        (f64::NEG_INFINITY, x)
    }
}

impl<T: Float> Interval<T> {
    /// Inverse hyperbolic sine.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0`, on
    /// infinite bounds, and wherever `asinh x` rounds to `x` (`|asinh x| ≤ |x|`).
    /// **Why:** CORE-MATH `asinh` is correctly rounded, so one outward step encloses;
    /// increasing.
    ///
    /// | `self`      | result        |
    /// |-------------|---------------|
    /// | ∅           | ∅             |
    /// | `[−∞, +∞]`  | `[−∞, +∞]`    |
    /// | `[0, 0]`    | `[0, 0]`      |
    ///
    /// ```
    /// use interval_core::Interval;
    /// let y = Interval::new(0.0, 1.0)?.asinh();
    /// assert_eq!(y.inf(), 0.0);
    /// assert!(y.contains(0.881373587019543));
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn asinh(self) -> Self {
        if self.is_empty() {
            return self;
        }
        increasing_known(
            self.lo,
            self.hi,
            core_math::asinh,
            asinh_known,
            f64::NEG_INFINITY,
            f64::INFINITY,
        )
    }

    /// Inverse hyperbolic cosine over `self ∩ [1, +∞]`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 1`
    /// (`acosh 1 = 0`) and at `+∞`.
    /// **Why:** CORE-MATH `acosh` is correctly rounded, so one outward step encloses;
    /// increasing, nonnegative.
    ///
    /// | `self`      | result        |
    /// |-------------|---------------|
    /// | ∅, `[−1, 0.5]` | ∅          |
    /// | `[−∞, +∞]`  | `[0, +∞]`     |
    /// | `[0, 1]`    | `[0, 0]`      |
    pub fn acosh(self) -> Self {
        if self.is_empty() || self.hi < T::ONE {
            return Self::EMPTY;
        }
        let lo = self.lo.max_nan(T::ONE);
        increasing_known(
            lo,
            self.hi,
            core_math::acosh,
            acosh_known,
            0.0,
            f64::INFINITY,
        )
    }

    /// Inverse hyperbolic tangent over `self ∩ (−1, 1)`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0` and
    /// wherever `atanh x` rounds to `x`; an interval reaching `±1` is unbounded on that side.
    /// **Why:** CORE-MATH `atanh` is correctly rounded, so one outward step encloses;
    /// increasing, with the poles `±∞` at `±1` (outside the open domain: `[1, 1]` gives ∅).
    ///
    /// | `self`        | result        |
    /// |---------------|---------------|
    /// | ∅, `[1, 2]`   | ∅             |
    /// | `[−∞, +∞]`    | `[−∞, +∞]`    |
    /// | `[0, 1]`      | `[0, +∞]`     |
    /// | `[0, 0]`      | `[0, 0]`      |
    pub fn atanh(self) -> Self {
        if self.is_empty() || self.hi <= -T::ONE || self.lo >= T::ONE {
            return Self::EMPTY;
        }
        let lo = self.lo.max_nan(-T::ONE);
        let hi = self.hi.min_nan(T::ONE);
        increasing_known(
            lo,
            hi,
            core_math::atanh,
            atanh_known,
            f64::NEG_INFINITY,
            f64::INFINITY,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn domains_and_special_values() {
        let inf = f64::INFINITY;
        assert_eq!(iv(0.0, 0.0).asinh(), iv(0.0, 0.0));
        assert_eq!(Interval::<f64>::ENTIRE.asinh(), Interval::ENTIRE);
        assert_eq!(iv(1e-300, 1e-300).asinh().sup(), 1e-300);
        assert_eq!(iv(-1.0, 1.0).acosh(), iv(0.0, 0.0));
        assert!(iv(-1.0, 0.5).acosh().is_empty());
        assert_eq!(Interval::<f64>::ENTIRE.acosh(), iv(0.0, inf));
        assert!(iv(1.0, 2.0).atanh().is_empty());
        assert!(iv(-3.0, -1.0).atanh().is_empty());
        assert_eq!(iv(0.0, 1.0).atanh(), iv(0.0, inf));
        assert_eq!(Interval::<f64>::ENTIRE.atanh(), Interval::ENTIRE);
        assert_eq!(iv(1e-300, 1e-300).atanh().inf(), 1e-300);
    }
}
