//! Modal inclusion and the two lattices of modal intervals (thesis §3.5).
//!
//! | operation | here | bounds of `[x1, x2]`, `[y1, y2]` |
//! |---|---|---|
//! | inclusion `X ⊆ Y` | [`Modal::subset`] | `x1 ≥ y1, x2 ≤ y2` |
//! | order `X ≤ Y` | [`Modal::less`] | `x1 ≤ y1, x2 ≤ y2` |
//! | meet `X ∧ Y` (greatest lower bound for `⊆`) | [`Modal::meet`] | `[max(x1, y1), min(x2, y2)]` |
//! | join `X ∨ Y` (least upper bound for `⊆`) | [`Modal::join`] | `[min(x1, y1), max(x2, y2)]` |
//! | `min(X, Y)` (greatest lower bound for `≤`) | [`Modal::min`] | `[min(x1, y1), min(x2, y2)]` |
//! | `max(X, Y)` (least upper bound for `≤`) | [`Modal::max`] | `[max(x1, y1), max(x2, y2)]` |
//!
//! All of them are exact (no rounding) and total: unlike classical intervals, the meet of two
//! disjoint proper intervals exists — it is improper (`[1, 2] ∧ [4, 5] = [4, 2]`).
//! `dual` exchanges meet and join: `dual(X ∧ Y) = dual X ∨ dual Y`.
//!
//! The forms over a family ([`Modal::meet_all`], ...) return `None` for an empty family.
//! The lattice identities would be [`Modal::ENTIRE`] for `meet_all` and
//! [`Modal::DUAL_ENTIRE`] for `join_all` (use `unwrap_or` with them where that is meant);
//! for `min_all`/`max_all` they would be the points at `±∞`, which denote no real number.

use super::Modal;
use super::rounding::{Rounding, fmax, fmin};
use crate::float::Float;

impl<T: Float, R: Rounding> Modal<T, R> {
    /// Modal inclusion `self ⊆ rhs`: every predicate accepted by `self` is accepted by
    /// `rhs`; in bounds `self.first() ≥ rhs.first()` and `self.second() ≤ rhs.second()`.
    ///
    /// For proper intervals this is set inclusion; an improper interval is included in every
    /// interval whose bounds surround its own the other way (`[3, 2] ⊆ [2, 3]`).
    #[inline]
    pub fn subset(self, rhs: Self) -> bool {
        self.a >= rhs.a && self.b <= rhs.b
    }

    /// The order `self ≤ rhs`: `self.first() ≤ rhs.first()` and
    /// `self.second() ≤ rhs.second()`.
    #[inline]
    pub fn less(self, rhs: Self) -> bool {
        self.a <= rhs.a && self.b <= rhs.b
    }

    /// Meet `self ∧ rhs = [max(a1, b1), min(a2, b2)]`, the largest interval (for `⊆`)
    /// included in both. Exact.
    #[inline]
    pub fn meet(self, rhs: Self) -> Self {
        Self::new_unchecked(fmax(self.a, rhs.a), fmin(self.b, rhs.b))
    }

    /// Join `self ∨ rhs = [min(a1, b1), max(a2, b2)]`, the smallest interval (for `⊆`)
    /// including both. Exact.
    #[inline]
    pub fn join(self, rhs: Self) -> Self {
        Self::new_unchecked(fmin(self.a, rhs.a), fmax(self.b, rhs.b))
    }

    /// Lattice minimum for `≤`: `[min(a1, b1), min(a2, b2)]`. Exact.
    #[inline]
    pub fn min(self, rhs: Self) -> Self {
        Self::new_unchecked(fmin(self.a, rhs.a), fmin(self.b, rhs.b))
    }

    /// Lattice maximum for `≤`: `[max(a1, b1), max(a2, b2)]`. Exact.
    #[inline]
    pub fn max(self, rhs: Self) -> Self {
        Self::new_unchecked(fmax(self.a, rhs.a), fmax(self.b, rhs.b))
    }

    /// Meet of a family, `⋀ A(i) = [max a1(i), min a2(i)]`; `None` for an empty family
    /// (whose meet would be [`Modal::ENTIRE`]).
    pub fn meet_all<I: IntoIterator<Item = Self>>(family: I) -> Option<Self> {
        family.into_iter().reduce(Self::meet)
    }

    /// Join of a family, `⋁ A(i) = [min a1(i), max a2(i)]`; `None` for an empty family
    /// (whose join would be [`Modal::DUAL_ENTIRE`]).
    pub fn join_all<I: IntoIterator<Item = Self>>(family: I) -> Option<Self> {
        family.into_iter().reduce(Self::join)
    }

    /// Minimum of a family, `[min a1(i), min a2(i)]`; `None` for an empty family.
    pub fn min_all<I: IntoIterator<Item = Self>>(family: I) -> Option<Self> {
        family.into_iter().reduce(Self::min)
    }

    /// Maximum of a family, `[max a1(i), max a2(i)]`; `None` for an empty family.
    pub fn max_all<I: IntoIterator<Item = Self>>(family: I) -> Option<Self> {
        family.into_iter().reduce(Self::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(a: f64, b: f64) -> Modal<f64> {
        Modal::new(a, b).unwrap()
    }

    #[test]
    fn meet_of_disjoint_intervals_is_improper() {
        assert_eq!(m(1.0, 2.0).meet(m(4.0, 5.0)), m(4.0, 2.0));
        assert_eq!(m(1.0, 2.0).join(m(4.0, 5.0)), m(1.0, 5.0));
        assert!(m(3.0, 2.0).subset(m(2.0, 3.0)));
        assert!(!m(2.0, 3.0).subset(m(3.0, 2.0)));
    }

    #[test]
    fn min_max_and_families() {
        let xs = [m(1.0, 5.0), m(3.0, 2.0), m(-1.0, 4.0)];
        assert_eq!(Modal::min_all(xs), Some(m(-1.0, 2.0)));
        assert_eq!(Modal::max_all(xs), Some(m(3.0, 5.0)));
        assert_eq!(Modal::meet_all(xs), Some(m(3.0, 2.0)));
        assert_eq!(Modal::join_all(xs), Some(m(-1.0, 5.0)));
        assert_eq!(Modal::<f64>::meet_all([]), None);
        assert!(m(1.0, 2.0).less(m(1.0, 3.0)));
        // The identities named in the documentation.
        assert_eq!(m(3.0, 2.0).meet(Modal::ENTIRE), m(3.0, 2.0));
        assert_eq!(m(3.0, 2.0).join(Modal::DUAL_ENTIRE), m(3.0, 2.0));
    }
}
