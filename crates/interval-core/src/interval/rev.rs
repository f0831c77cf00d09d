//! Reverse operations (IEEE 1788 §10.5.4): for a function `f` and intervals `c` (the
//! result) and `x` (a constraint), `f_rev(c, x)` encloses `{z ∈ x : f(z) ∈ c}`, the values of
//! the argument that `f` can map into `c`. The one-argument forms take `x = [−∞, +∞]`; the
//! `*_in` forms take the constraint `x`, with which the result is intersected (piece by piece,
//! before the hull, so they can be tighter than `f_rev(c) ∩ x`). Also the two-piece extended
//! division `mul_rev_to_pair`.
//!
//! Each function's result is the hull of the (at most two) monotone pieces of the preimage,
//! each computed with the inverse function rounded outward. Trigonometric reverse operations
//! live in `rev_trig`, those of `pow` in `rev_pow`.

use super::Interval;
use crate::float::Float;

/// The hull of `p ∩ x` and `q ∩ x`.
fn hull_in<T: Float>(p: Interval<T>, q: Interval<T>, x: Interval<T>) -> Interval<T> {
    p.intersection(x).convex_hull(q.intersection(x))
}

impl<T: Float> Interval<T> {
    /// `sqrRev(c)` with `self = c`: `{z : z² ∈ c}`, the hull of `±√(c ∩ [0, ∞])`. Tight.
    ///
    /// ```
    /// use interval_core::Interval;
    /// let c = Interval::new(1.0, 4.0)?;
    /// assert_eq!(c.sqr_rev(), Interval::new(-2.0, 2.0)?);
    /// assert_eq!(c.sqr_rev_in(Interval::new(0.0, 10.0)?), Interval::new(1.0, 2.0)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn sqr_rev(self) -> Self {
        self.sqr_rev_in(Self::ENTIRE)
    }

    /// `sqrRev(c, x)` with `self = c`: `{z ∈ x : z² ∈ c}`. Tight (the pieces are the tight
    /// square roots, intersected with `x` exactly).
    pub fn sqr_rev_in(self, x: Self) -> Self {
        let c = self.intersection(Self::new_unchecked(T::ZERO, T::INFINITY));
        let r = c.sqrt();
        hull_in(r, -r, x)
    }

    /// `absRev(c)` with `self = c`: `{z : |z| ∈ c}`. Exact.
    pub fn abs_rev(self) -> Self {
        self.abs_rev_in(Self::ENTIRE)
    }

    /// `absRev(c, x)` with `self = c`: `{z ∈ x : |z| ∈ c}`, the hull of `±(c ∩ [0, ∞])`
    /// intersected with `x`. Exact.
    ///
    /// ```
    /// use interval_core::Interval;
    /// let c = Interval::new(1.0, 2.0)?;
    /// assert_eq!(c.abs_rev_in(Interval::new(-5.0, 0.5)?), Interval::new(-2.0, -1.0)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn abs_rev_in(self, x: Self) -> Self {
        let c = self.intersection(Self::new_unchecked(T::ZERO, T::INFINITY));
        hull_in(c, -c, x)
    }

    /// `pownRev(c, n)` with `self = c`: `{z : zⁿ ∈ c}`.
    pub fn pown_rev(self, n: i32) -> Self {
        self.pown_rev_in(Self::ENTIRE, n)
    }

    /// `pownRev(c, x, n)` with `self = c`: `{z ∈ x : zⁿ ∈ c}`.
    ///
    /// **Accuracy:** tight for `1 ≤ n ≤ 64` (the pieces are [`Interval::rootn`] of `c`, tight
    /// there); for `n > 64` within the accuracy of `rootn`; `n = 0` gives `x` when `1 ∈ c`,
    /// else ∅; for `n < 0` the roots of the reciprocal `1/c` (two outward roundings, within
    /// 2 ulps).
    ///
    /// ```
    /// use interval_core::Interval;
    /// let c = Interval::new(4.0, 9.0)?;
    /// assert_eq!(c.pown_rev(2), Interval::new(-3.0, 3.0)?);
    /// assert_eq!(c.pown_rev_in(Interval::new(-10.0, -2.5)?, 2), Interval::new(-3.0, -2.5)?);
    /// assert_eq!(Interval::new(-8.0, 27.0)?.pown_rev(3), Interval::new(-2.0, 3.0)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn pown_rev_in(self, x: Self, n: i32) -> Self {
        let c = self;
        if c.is_empty() || x.is_empty() {
            return Self::EMPTY;
        }
        if n == 0 {
            return if c.contains(T::ONE) { x } else { Self::EMPTY };
        }
        if n < 0 {
            // zⁿ = w ⇔ z^|n| = 1/w (z, w ≠ 0): the reciprocal set of c, in up to two pieces.
            let (p, q) = c.mul_rev_to_pair(Self::ONE);
            let k = n.checked_neg().unwrap_or(i32::MAX);
            return p.pown_rev_in(x, k).convex_hull(q.pown_rev_in(x, k));
        }
        if n % 2 == 1 {
            return c.rootn(n).intersection(x);
        }
        let r = c.rootn(n);
        hull_in(r, -r, x)
    }

    /// `mulRev(b, c)` with `self = b`: `{z : ∃ y ∈ b, z·y ∈ c}`, the hull of
    /// [`Interval::mul_rev_to_pair`]. Tight.
    pub fn mul_rev(self, c: Self) -> Self {
        self.mul_rev_in(c, Self::ENTIRE)
    }

    /// `mulRev(b, c, x)` with `self = b`: `{z ∈ x : ∃ y ∈ b, z·y ∈ c}`, each piece of
    /// [`Interval::mul_rev_to_pair`] intersected with `x` before the hull. Tight.
    ///
    /// ```
    /// use interval_core::Interval;
    /// let b = Interval::new(-1.0, 2.0)?;
    /// let c = Interval::new(1.0, 1.0)?;
    /// assert!(b.mul_rev(c).is_entire());
    /// assert_eq!(b.mul_rev_in(c, Interval::new(0.0, 4.0)?), Interval::new(0.5, 4.0)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn mul_rev_in(self, c: Self, x: Self) -> Self {
        let (p, q) = self.mul_rev_to_pair(c);
        hull_in(p, q, x)
    }

    /// `coshRev(c)` with `self = c`: `{z : cosh z ∈ c}`.
    pub fn cosh_rev(self) -> Self {
        self.cosh_rev_in(Self::ENTIRE)
    }

    /// `coshRev(c, x)` with `self = c`: `{z ∈ x : cosh z ∈ c}`, the hull of
    /// `±acosh(c ∩ [1, ∞])` intersected with `x`.
    ///
    /// **Accuracy:** each bound within 1 ulp of tight (that of [`Interval::acosh`]).
    pub fn cosh_rev_in(self, x: Self) -> Self {
        let r = self.acosh();
        hull_in(r, -r, x)
    }
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
    fn reverse_operations() {
        let inf = f64::INFINITY;
        assert_eq!(iv(-4.0, 4.0).sqr_rev(), iv(-2.0, 2.0));
        assert!(iv(-4.0, -1.0).sqr_rev().is_empty());
        assert_eq!(iv(0.0, inf).sqr_rev(), Interval::ENTIRE);
        assert_eq!(iv(1.0, 4.0).sqr_rev_in(iv(-1.5, 0.5)), iv(-1.5, -1.0));
        assert_eq!(iv(-1.0, 2.0).abs_rev(), iv(-2.0, 2.0));
        assert!(iv(1.0, 2.0).abs_rev_in(iv(-0.5, 0.5)).is_empty());
        assert_eq!(iv(1.0, 1.0).pown_rev(0), Interval::ENTIRE);
        assert!(iv(2.0, 3.0).pown_rev(0).is_empty());
        assert_eq!(iv(0.25, 0.25).pown_rev(-2), iv(-2.0, 2.0));
        assert_eq!(iv(0.25, 0.25).pown_rev_in(iv(0.0, 5.0), -2), iv(2.0, 2.0));
        assert_eq!(iv(-0.125, -0.125).pown_rev(-3), iv(-2.0, -2.0));
        assert_eq!(iv(2.0, 4.0).mul_rev(iv(2.0, 8.0)), iv(0.5, 4.0));
        assert_eq!(iv(1.0, 1.0).cosh_rev(), iv(0.0, 0.0));
        assert!(iv(-1.0, 0.5).cosh_rev().is_empty());
        let r = iv(1.0, 2.0).cosh_rev_in(iv(0.0, inf));
        assert!(r.inf() == 0.0 && r.contains(2f64.acosh()));
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
