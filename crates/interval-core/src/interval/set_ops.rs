//! Set operations: intersection, convex hull, bisection and splitting.

use super::Interval;
use crate::float::Float;

impl<T: Float> Interval<T> {
    /// `self ∩ rhs`.
    #[inline]
    pub fn intersection(self, rhs: Self) -> Self {
        if self.disjoint(rhs) {
            return Self::EMPTY;
        }
        Self::new_unchecked(self.lo.max_nan(rhs.lo), self.hi.min_nan(rhs.hi))
    }

    /// The smallest interval containing `self ∪ rhs`.
    #[inline]
    pub fn convex_hull(self, rhs: Self) -> Self {
        if self.is_empty() {
            return rhs;
        }
        if rhs.is_empty() {
            return self;
        }
        Self::new_unchecked(self.lo.min_nan(rhs.lo), self.hi.max_nan(rhs.hi))
    }

    /// Splits at `at`: `([inf, at], [at, sup])` intersected with `self`. A split point outside
    /// the interval leaves one piece empty; a NaN split point returns `(self, EMPTY)`.
    pub fn split(self, at: T) -> (Self, Self) {
        if self.is_empty() || at.is_nan() {
            return (self, Self::EMPTY);
        }
        let left = if at < self.lo || at == T::NEG_INFINITY {
            Self::EMPTY
        } else if at == T::INFINITY {
            self
        } else {
            Self::new_unchecked(self.lo, at.min_nan(self.hi))
        };
        let right = if at > self.hi || at == T::INFINITY {
            Self::EMPTY
        } else if at == T::NEG_INFINITY {
            self
        } else {
            Self::new_unchecked(at.max_nan(self.lo), self.hi)
        };
        (left, right)
    }

    /// Bisects at the midpoint ([`Interval::mid`]); both halves share the midpoint, so their
    /// union is `self`. A singleton bisects into two copies of itself.
    pub fn bisect(self) -> (Self, Self) {
        self.split(self.mid())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_and_hull() {
        let x = Interval::new(0.0, 4.0).unwrap();
        let (a, b) = x.bisect();
        assert_eq!(a, Interval::new(0.0, 2.0).unwrap());
        assert_eq!(b, Interval::new(2.0, 4.0).unwrap());
        assert_eq!(a.convex_hull(b), x);
        assert_eq!(a.intersection(b), Interval::point(2.0).unwrap());
        let (l, r) = x.split(5.0);
        assert_eq!((l, r), (x, Interval::EMPTY));
        let half = Interval::new(0.0, f64::INFINITY).unwrap();
        assert_eq!(half.split(f64::INFINITY), (half, Interval::EMPTY));
        assert_eq!(half.split(f64::NEG_INFINITY), (Interval::EMPTY, half));
        let (l, r) = Interval::<f64>::ENTIRE.bisect();
        assert_eq!(l, Interval::new(f64::NEG_INFINITY, 0.0).unwrap());
        assert_eq!(r, Interval::new(0.0, f64::INFINITY).unwrap());
    }
}
