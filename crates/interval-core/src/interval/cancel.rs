//! Cancellative addition and subtraction (IEEE 1788 §9.2): `cancel_minus(x, y)` is the
//! interval `z` with `y + z = x`, the inverse of interval addition where it exists.

use super::Interval;
use crate::float::Float;
use crate::float::dyadic::Dyadic;
use core::cmp::Ordering;

impl<T: Float> Interval<T> {
    /// `cancelMinus(x, y)` with `self = x`: the interval `z = [x̲ − y̲, x̅ − y̅]` with
    /// `y + z = x`, rounded outward.
    ///
    /// **Accuracy:** tight (one directed subtraction per bound); the width comparison that
    /// decides whether `z` exists is exact.
    ///
    /// | `x`                    | `y`                    | result          |
    /// |------------------------|------------------------|-----------------|
    /// | ∅                      | ∅ or bounded           | ∅               |
    /// | unbounded              | any but ∅              | `[−∞, +∞]`      |
    /// | any                    | unbounded or ∅ (`x` ≠ ∅) | `[−∞, +∞]`    |
    /// | bounded, `wid x < wid y` | bounded              | `[−∞, +∞]`      |
    /// | bounded, `wid x ≥ wid y` | bounded              | `[x̲ − y̲, x̅ − y̅]` |
    ///
    /// ```
    /// use interval_core::Interval;
    /// let x = Interval::new(1.0, 5.0)?;
    /// let y = Interval::new(0.5, 2.0)?;
    /// assert_eq!(x.cancel_minus(y), Interval::new(0.5, 3.0)?);
    /// assert!(y.cancel_minus(x).is_entire());
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn cancel_minus(self, y: Self) -> Self {
        let x = self;
        if x.is_empty() && (y.is_empty() || y.is_common_interval()) {
            return Self::EMPTY;
        }
        if !x.is_common_interval() || !y.is_common_interval() {
            return Self::ENTIRE;
        }
        // wid x < wid y, decided exactly.
        let wid = |v: Self| Dyadic::of(v.hi).add(&Dyadic::of(v.lo).neg());
        if wid(x).cmp(&wid(y)) == Ordering::Less {
            return Self::ENTIRE;
        }
        let lo = x.lo.sub_down(y.lo);
        let hi = x.hi.sub_up(y.hi);
        Self::new_unchecked(lo, hi.max_nan(lo))
    }

    /// `cancelPlus(x, y) = cancelMinus(x, −y)`: the interval `z` with `(−y) + z = x`. Tight,
    /// with the same special cases as [`Interval::cancel_minus`].
    pub fn cancel_plus(self, y: Self) -> Self {
        self.cancel_minus(-y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn standard_cases() {
        let inf = f64::INFINITY;
        let e = Interval::<f64>::EMPTY;
        assert!(e.cancel_minus(e).is_empty());
        assert!(e.cancel_minus(iv(1.0, 2.0)).is_empty());
        assert!(e.cancel_minus(iv(1.0, inf)).is_entire());
        assert!(iv(1.0, 2.0).cancel_minus(e).is_entire());
        assert!(iv(-inf, 2.0).cancel_minus(iv(1.0, 2.0)).is_entire());
        assert_eq!(iv(-5.0, -1.0).cancel_minus(iv(-5.0, -1.0)), iv(0.0, 0.0));
        assert_eq!(iv(0.0, 1.0).cancel_plus(iv(-1.0, 0.0)), iv(0.0, 0.0));
        assert_eq!(iv(1.0, 3.0).cancel_plus(iv(1.0, 2.0)), iv(3.0, 4.0));
        // Outward rounding.
        let z = iv(1.0, 1.0).cancel_minus(iv(0.1, 0.1));
        assert!(z.contains(0.9) && z.sup() == z.inf().next_up());
        // Equal widths that are not representable: decided exactly.
        let x = iv(-f64::MAX, f64::MAX);
        assert_eq!(x.cancel_minus(x), iv(0.0, 0.0));
        assert!(
            iv(0.0, 1.0)
                .cancel_minus(iv(0.0, 1.0f64.next_up()))
                .is_entire()
        );
    }
}
