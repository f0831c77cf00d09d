//! Reverse operations of `pow` (IEEE 1788 §10.5.4): `pow_rev1` (for the base) and `pow_rev2`
//! (for the exponent), with their `*_in` forms.
//!
//! **Method.** On the domain of `pow`, `xʸ = w > 0` means `y·ln x = ln w`; so the base lies
//! in `exp(ln c / y)` and the exponent in `ln c / ln x`, where each quotient is the two-piece
//! extended division [`Interval::mul_rev_to_pair`] (so a divisor containing 0 keeps the two
//! unbounded pieces apart). The remaining points of the domain are added by their own rules:
//! `x = 0` with `y > 0` gives `w = 0`; `y = 0` or `x = 1` give `w = 1`.
//!
//! The ends of the result are then shaved ([`shave`](super::shave)): moved inward past the
//! floats where `pow` proves the value outside `c`.
//!
//! **Accuracy:** valid (an enclosure, computed with the outward `log`, `exp` and division,
//! then shaved in double-double); `tests/rev_tightness.rs` measures the distance of each
//! bound from the tight one against MPFR.

use super::Interval;
use super::shave::{dd_of, misses, shave};
use crate::float::Float;

impl<T: Float> Interval<T> {
    /// `powRev1(b, c)` with `self = b`: `{x : ∃ y ∈ b, xʸ ∈ c}`.
    pub fn pow_rev1(self, c: Self) -> Self {
        self.pow_rev1_in(c, Self::ENTIRE)
    }

    /// `powRev1(b, c, x)` with `self = b`: `{z ∈ x : ∃ y ∈ b, zʸ ∈ c}`. Valid.
    ///
    /// ```
    /// use interval_core::Interval;
    /// let b = Interval::new(2.0, 2.0)?;
    /// let c = Interval::new(4.0, 9.0)?;
    /// let z = b.pow_rev1(c);
    /// assert!(z.contains(2.0) && z.contains(3.0) && z.inf() > 1.99 && z.sup() < 3.01);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn pow_rev1_in(self, c: Self, x: Self) -> Self {
        let b = self;
        let x = x.intersection(Self::new_unchecked(T::ZERO, T::INFINITY));
        if b.is_empty() || c.is_empty() || x.is_empty() {
            return Self::EMPTY;
        }
        let zero_part = if x.contains(T::ZERO) && c.contains(T::ZERO) && b.hi > T::ZERO {
            Self::ZERO
        } else {
            Self::EMPTY
        };
        if b.contains(T::ZERO) && c.contains(T::ONE) {
            return x;
        }
        let l = c.log();
        let (p, q) = b.mul_rev_to_pair(l);
        let r = p.exp().intersection(x).convex_hull(q.exp().intersection(x));
        let r = shave(r, |z| misses(dd_of(z).pow(dd_of(b)), c));
        r.convex_hull(zero_part)
    }

    /// `powRev2(a, c)` with `self = a`: `{y : ∃ x ∈ a, xʸ ∈ c}`.
    pub fn pow_rev2(self, c: Self) -> Self {
        self.pow_rev2_in(c, Self::ENTIRE)
    }

    /// `powRev2(a, c, y)` with `self = a`: `{z ∈ y : ∃ x ∈ a, xᶻ ∈ c}`. Valid.
    ///
    /// ```
    /// use interval_core::Interval;
    /// let a = Interval::new(2.0, 2.0)?;
    /// let c = Interval::new(8.0, 8.0)?;
    /// let y = a.pow_rev2(c);
    /// assert!(y.contains(3.0) && y.inf() > 2.99 && y.sup() < 3.01);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn pow_rev2_in(self, c: Self, y: Self) -> Self {
        let a = self.intersection(Self::new_unchecked(T::ZERO, T::INFINITY));
        if a.is_empty() || c.is_empty() || y.is_empty() {
            return Self::EMPTY;
        }
        if a.contains(T::ONE) && c.contains(T::ONE) {
            return y;
        }
        let zero_part = if a.contains(T::ZERO) && c.contains(T::ZERO) {
            y.intersection(Self::new_unchecked(T::ZERO, T::INFINITY))
        } else {
            Self::EMPTY
        };
        let (p, q) = a.log().mul_rev_to_pair(c.log());
        let r = p.intersection(y).convex_hull(q.intersection(y));
        let r = shave(r, |z| misses(dd_of(a).pow(dd_of(z)), c));
        r.convex_hull(zero_part)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn special_cases() {
        assert!(iv(0.0, 1.0).pow_rev1(iv(1.0, 1.0)).contains(5.0));
        assert!(iv(1.0, 2.0).pow_rev1(iv(-2.0, -1.0)).is_empty());
        assert!(iv(1.0, 2.0).pow_rev1(iv(0.0, 0.0)).contains(0.0));
        assert_eq!(iv(1.0, 1.0).pow_rev2(iv(1.0, 1.0)), Interval::ENTIRE);
        assert!(iv(0.0, 0.0).pow_rev2(iv(0.0, 0.0)).contains(7.0));
        let y = iv(0.5, 0.5).pow_rev2(iv(4.0, 4.0));
        assert!(y.contains(-2.0) && y.inf() > -2.01 && y.sup() < -1.99);
    }
}
