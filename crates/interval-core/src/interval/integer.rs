//! Integer-valued functions (IEEE 1788 §9.1): `sign`, `ceil`, `floor`, `trunc`,
//! `round_ties_to_even`, `round_ties_to_away`. All are increasing step functions, so the
//! result is the function at the two bounds; every result is exact (integers of the bound
//! type are representable).

use super::Interval;
use crate::float::Float;

impl<T: Float> Interval<T> {
    /// Applies an increasing integer-valued function bound by bound (exact: the function of
    /// a value of `T` is computed in `f64` and is again a value of `T`).
    fn step_fn(self, f: fn(f64) -> f64) -> Self {
        if self.is_empty() {
            return self;
        }
        let g = |x: T| T::from_f64_rn(f(x.to_f64()) + 0.0);
        Self::new_unchecked(g(self.lo), g(self.hi))
    }

    /// Sign: `[sign(inf), sign(sup)]` with `sign(0) = 0`, so a value in `{−1, 0, 1}` or the
    /// hull of two of them. Exact.
    ///
    /// ```
    /// use interval_core::Interval;
    /// assert_eq!(Interval::new(-2.0, 0.0)?.sign(), Interval::new(-1.0, 0.0)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn sign(self) -> Self {
        self.step_fn(|x| {
            if x > 0.0 {
                1.0
            } else if x < 0.0 {
                -1.0
            } else {
                0.0
            }
        })
    }

    /// Smallest integer `≥ x`, bound by bound. Exact.
    pub fn ceil(self) -> Self {
        self.step_fn(f64::ceil)
    }

    /// Largest integer `≤ x`, bound by bound. Exact.
    pub fn floor(self) -> Self {
        self.step_fn(f64::floor)
    }

    /// Integer part toward zero, bound by bound. Exact.
    pub fn trunc(self) -> Self {
        self.step_fn(f64::trunc)
    }

    /// Nearest integer, halves to even, bound by bound. Exact.
    pub fn round_ties_to_even(self) -> Self {
        self.step_fn(f64::round_ties_even)
    }

    /// Nearest integer, halves away from zero, bound by bound. Exact.
    pub fn round_ties_to_away(self) -> Self {
        self.step_fn(f64::round)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn standard_examples() {
        let inf = f64::INFINITY;
        assert_eq!(iv(-0.5, 2.5).round_ties_to_even(), iv(0.0, 2.0));
        assert_eq!(iv(-0.5, 2.5).round_ties_to_away(), iv(-1.0, 3.0));
        assert_eq!(iv(-1.5, 1.5).floor(), iv(-2.0, 1.0));
        assert_eq!(iv(-1.5, 1.5).ceil(), iv(-1.0, 2.0));
        assert_eq!(iv(-1.5, 1.5).trunc(), iv(-1.0, 1.0));
        assert_eq!(iv(-inf, 1.5).floor(), iv(-inf, 1.0));
        assert_eq!(iv(0.0, 0.0).sign(), iv(0.0, 0.0));
        assert_eq!(iv(-3.0, 5.0).sign(), iv(-1.0, 1.0));
        assert!(Interval::<f64>::EMPTY.floor().is_empty());
        assert_eq!(
            Interval::new(-2.5f32, 1e30).unwrap().round_ties_to_even(),
            Interval::new(-2.0f32, 1e30).unwrap()
        );
    }
}
