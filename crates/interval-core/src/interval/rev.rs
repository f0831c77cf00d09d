//! Reverse operations: the two-piece extended division `mul_rev_to_pair`.

use super::Interval;
use crate::float::Float;

impl<T: Float> Interval<T> {
    /// IEEE 1788 `mulRevToPair(b, c)` with `self = b`: encloses `{x : ∃ y ∈ b, z ∈ c, x·y = z}`
    /// (the extended division `c / b`) as two disjoint-or-empty intervals, ordered so the
    /// first precedes the second. When `b` has 0 in its interior and `c` excludes 0 the
    /// quotient set has two unbounded pieces, which the Alefeld–Hansen step of interval
    /// Newton keeps apart; otherwise the second piece is empty. Tight.
    ///
    /// ```
    /// use interval_core::Interval;
    /// let b = Interval::new(-1.0, 2.0)?;
    /// let c = Interval::new(1.0, 1.0)?;
    /// let (x1, x2) = b.mul_rev_to_pair(c);
    /// assert_eq!(x1, Interval::new(f64::NEG_INFINITY, -1.0)?);
    /// assert_eq!(x2, Interval::new(0.5, f64::INFINITY)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn mul_rev_to_pair(self, c: Self) -> (Self, Self) {
        let b = self;
        let z = T::ZERO;
        if b.is_empty() || c.is_empty() {
            return (Self::EMPTY, Self::EMPTY);
        }
        let b_has_zero = b.lo <= z && z <= b.hi;
        let c_has_zero = c.lo <= z && z <= c.hi;
        if !b_has_zero {
            return (c.div(b), Self::EMPTY);
        }
        if c_has_zero {
            return (Self::ENTIRE, Self::EMPTY);
        }
        if b.lo == z && b.hi == z {
            return (Self::EMPTY, Self::EMPTY);
        }
        if b.lo < z && z < b.hi {
            return if c.hi < z {
                (
                    Self::new_unchecked(T::NEG_INFINITY, c.hi.div_up(b.hi)),
                    Self::new_unchecked(c.hi.div_down(b.lo), T::INFINITY),
                )
            } else {
                (
                    Self::new_unchecked(T::NEG_INFINITY, c.lo.div_up(b.lo)),
                    Self::new_unchecked(c.lo.div_down(b.hi), T::INFINITY),
                )
            };
        }
        // b = [0, bh] or [bl, 0]: one unbounded piece, as the hull division gives.
        (c.div(b), Self::EMPTY)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn pieces() {
        let inf = f64::INFINITY;
        assert_eq!(
            iv(-2.0, 4.0).mul_rev_to_pair(iv(-8.0, -4.0)),
            (iv(-inf, -1.0), iv(2.0, inf))
        );
        assert_eq!(
            iv(0.0, 0.0).mul_rev_to_pair(iv(1.0, 2.0)),
            (Interval::EMPTY, Interval::EMPTY)
        );
        assert_eq!(
            iv(-1.0, 1.0).mul_rev_to_pair(iv(-1.0, 1.0)),
            (Interval::ENTIRE, Interval::EMPTY)
        );
        assert_eq!(
            iv(2.0, 4.0).mul_rev_to_pair(iv(1.0, 2.0)),
            (iv(0.25, 1.0), Interval::EMPTY)
        );
        assert_eq!(
            iv(0.0, 4.0).mul_rev_to_pair(iv(1.0, 2.0)),
            (iv(0.25, inf), Interval::EMPTY)
        );
    }
}
