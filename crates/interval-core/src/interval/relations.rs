//! Boolean relations between intervals (IEEE 1788-2015 §10.5.10, thesis §3.3).
//!
//! | thesis §3.3 | here | bounds (non-empty) |
//! |---|---|---|
//! | equal `A = B` | [`Interval::equal`], `==` | `a̲ = b̲, a̅ = b̅` |
//! | less `A < B` (every a < every b) | [`Interval::strict_precedes`] | `a̅ < b̲` |
//! | less or equal `A ≤ B` | [`Interval::less`] | `a̲ ≤ b̲, a̅ ≤ b̅` |
//! | inclusion `A ⊆ B` | [`Interval::subset`] | `b̲ ≤ a̲, a̅ ≤ b̅` |
//! | incidence `A =ₕ B` (`A ∩ B ≠ ∅`) | [`Interval::incident`] | `max(a̲, b̲) ≤ min(a̅, b̅)` |
//!
//! Empty intervals follow IEEE 1788: the empty set is a subset of everything, `less` and
//! `precedes` hold vacuously, `interior` holds for it, and it is disjoint from everything.

use super::Interval;
use crate::float::Float;

impl<T: Float> Interval<T> {
    /// `self = rhs` as sets.
    #[inline]
    pub fn equal(self, rhs: Self) -> bool {
        (self.is_empty() && rhs.is_empty()) || (self.lo == rhs.lo && self.hi == rhs.hi)
    }

    /// `self ⊆ rhs`.
    #[inline]
    pub fn subset(self, rhs: Self) -> bool {
        self.is_empty() || (rhs.lo <= self.lo && self.hi <= rhs.hi)
    }

    /// `self ≤ rhs` in the interval order: `inf ≤ inf` and `sup ≤ sup`.
    #[inline]
    pub fn less(self, rhs: Self) -> bool {
        (self.is_empty() && rhs.is_empty()) || (self.lo <= rhs.lo && self.hi <= rhs.hi)
    }

    /// Every element of `self` is ≤ every element of `rhs`: `sup ≤ inf`.
    #[inline]
    pub fn precedes(self, rhs: Self) -> bool {
        self.is_empty() || rhs.is_empty() || self.hi <= rhs.lo
    }

    /// `self` lies in the topological interior of `rhs`.
    #[inline]
    pub fn interior(self, rhs: Self) -> bool {
        let left = rhs.lo < self.lo || (rhs.lo == T::NEG_INFINITY && self.lo == rhs.lo);
        let right = self.hi < rhs.hi || (rhs.hi == T::INFINITY && self.hi == rhs.hi);
        self.is_empty() || (left && right)
    }

    /// Strict interval order: `inf < inf` (or both −∞) and `sup < sup` (or both +∞).
    #[inline]
    pub fn strict_less(self, rhs: Self) -> bool {
        if self.is_empty() || rhs.is_empty() {
            return self.is_empty() && rhs.is_empty();
        }
        let left = self.lo < rhs.lo || (self.lo == T::NEG_INFINITY && rhs.lo == self.lo);
        let right = self.hi < rhs.hi || (self.hi == T::INFINITY && rhs.hi == self.hi);
        left && right
    }

    /// Every element of `self` is < every element of `rhs` (the thesis' `A < B`).
    #[inline]
    pub fn strict_precedes(self, rhs: Self) -> bool {
        self.is_empty() || rhs.is_empty() || self.hi < rhs.lo
    }

    /// `self ∩ rhs = ∅`.
    #[inline]
    pub fn disjoint(self, rhs: Self) -> bool {
        self.is_empty() || rhs.is_empty() || self.hi < rhs.lo || rhs.hi < self.lo
    }

    /// Incidence (thesis §3.3.5): some element of `self` equals some element of `rhs`, i.e.
    /// the intersection is non-empty. The negation of [`Interval::disjoint`].
    #[inline]
    pub fn incident(self, rhs: Self) -> bool {
        !self.disjoint(rhs)
    }
}

impl<T: Float> PartialEq for Interval<T> {
    /// Set equality ([`Interval::equal`]); the empty interval equals itself.
    fn eq(&self, other: &Self) -> bool {
        self.equal(*other)
    }
}

impl<T: Float> Eq for Interval<T> {}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn thesis_relations() {
        let (a, b) = (iv(1.0, 2.0), iv(3.0, 4.0));
        assert!(a.strict_precedes(b) && a.less(b) && !a.incident(b));
        assert!(iv(1.5, 2.0).subset(iv(1.0, 2.0)));
        assert!(!iv(1.5, 2.0).interior(iv(1.0, 2.0)));
        assert!(iv(1.5, 1.8).interior(iv(1.0, 2.0)));
        assert!(iv(1.0, 3.0).incident(iv(3.0, 4.0)));
        assert!(iv(1.0, 3.0).precedes(iv(3.0, 4.0)));
        assert!(!iv(1.0, 3.0).strict_precedes(iv(3.0, 4.0)));
        let e = Interval::<f64>::EMPTY;
        assert!(e.subset(a) && e.disjoint(a) && e == e && e != a);
    }
}
