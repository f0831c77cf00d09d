//! `expm1 = eˣ − 1` and `log1p = ln(1 + x)`, accurate near 0 where `exp(x) − 1` would cancel.
//!
//! The method is that of the `elementary` module: correctly rounded CORE-MATH values at the
//! endpoints, one outward step, intersected with the exact range facts `expm1 x ≥ x`,
//! `log1p x ≤ x`, their signs, `expm1 > −1`; both are increasing.

use super::Interval;
use super::elementary::increasing_known;
use crate::float::Float;

/// Exact brackets of `expm1 x`: `x ≤ expm1 x`, with the sign of `x`; `−1` at `−∞`.
fn expm1_known(x: f64) -> (f64, f64) {
    if x == 0.0 {
        (0.0, 0.0)
    } else if x < 0.0 {
        (x.max(-1.0), 0.0)
    } else {
        (x, f64::INFINITY)
    }
}

/// Exact brackets of `log1p x` for `x ≥ −1`: `log1p x ≤ x`, with the sign of `x`; `−∞` at −1.
fn log1p_known(x: f64) -> (f64, f64) {
    if x == -1.0 {
        (f64::NEG_INFINITY, f64::NEG_INFINITY)
    } else if x == 0.0 {
        (0.0, 0.0)
    } else if x < 0.0 {
        (f64::NEG_INFINITY, x)
    } else {
        (0.0, x)
    }
}

impl<T: Float> Interval<T> {
    /// `eˣ − 1`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0`, at `−∞`
    /// (`−1`), on overflow, and wherever `expm1 x` rounds to `x`.
    /// **Why:** CORE-MATH `expm1` is correctly rounded, so one outward step encloses;
    /// increasing, clamped to `[−1, +∞]`.
    ///
    /// | `self`      | result        |
    /// |-------------|---------------|
    /// | ∅           | ∅             |
    /// | `[−∞, +∞]`  | `[−1, +∞]`    |
    /// | `[0, 0]`    | `[0, 0]`      |
    ///
    /// ```
    /// use interval_core::Interval;
    /// let y = Interval::new(1e-20, 1e-20)?.expm1();
    /// assert!(y.contains(1e-20) && y.inf() == 1e-20);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn expm1(self) -> Self {
        if self.is_empty() {
            return self;
        }
        increasing_known(
            self.lo,
            self.hi,
            core_math::expm1,
            expm1_known,
            -1.0,
            f64::INFINITY,
        )
    }

    /// `ln(1 + x)` over `self ∩ (−1, +∞]`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0`, at `−1`
    /// (`−∞`) and `+∞`, and wherever `log1p x` rounds to `x`.
    /// **Why:** CORE-MATH `log1p` is correctly rounded, so one outward step encloses;
    /// increasing.
    ///
    /// | `self`      | result        |
    /// |-------------|---------------|
    /// | ∅, `[−3, −1]` | ∅           |
    /// | `[−1, 0]`   | `[−∞, 0]`     |
    /// | `[−∞, +∞]`  | `[−∞, +∞]`    |
    pub fn log1p(self) -> Self {
        if self.is_empty() || self.hi <= -T::ONE {
            return Self::EMPTY;
        }
        let lo = self.lo.max_nan(-T::ONE);
        increasing_known(
            lo,
            self.hi,
            core_math::log1p,
            log1p_known,
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
    fn special_values() {
        let inf = f64::INFINITY;
        assert_eq!(Interval::<f64>::ENTIRE.expm1(), iv(-1.0, inf));
        assert_eq!(iv(0.0, 0.0).expm1(), iv(0.0, 0.0));
        assert_eq!(iv(-1.0, 0.0).log1p(), iv(-inf, 0.0));
        assert!(iv(-3.0, -1.0).log1p().is_empty());
        assert_eq!(iv(1e-300, 1e-300).log1p().sup(), 1e-300);
        assert_eq!(iv(1e-300, 1e-300).expm1().inf(), 1e-300);
    }
}
