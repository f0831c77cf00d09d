//! Reverse operations of the periodic functions (IEEE 1788 §10.5.4): `sin_rev`, `cos_rev`,
//! `tan_rev` and their `*_in` forms, `{z ∈ x : f(z) ∈ c}`.
//!
//! **Method.** Over one period the preimage of `c` is at most two intervals given by the
//! inverse function (`asin c` and `π − asin c` for `sin`; `±acos c` for `cos`; `atan c` for
//! `tan`, whose period is π), enclosed outward; the preimage over the line is their
//! translates by `k·2π` (`k·π`), enclosed with `2π ∈ [2π↓, 2π↑]`. The result is the hull of the
//! translates that meet `x`: all of them when `x` spans a few periods, otherwise those within
//! two periods of each end (every period holds a piece, so the hull's ends lie there). A
//! bound of `x` that is infinite, or beyond `2⁴⁰` in magnitude (where the translates are
//! coarse), is kept as it is.
//!
//! Each end of that hull is then shaved ([`shave`](super::shave)): moved inward past the
//! floats where the forward function proves `f(z) ∉ c`.
//!
//! **Accuracy:** valid (an enclosure of the preimage within `x`); after shaving, each bound
//! is the tight one away from the extrema of `sin` and `cos` (`tests/rev_tightness.rs`
//! measures it against MPFR).

use super::Interval;
use super::shave::{dd_of, misses, shave};
use super::trig::{PI_DOWN, PI_UP, TWO_PI_DOWN};
use crate::float::Float;

type I64 = Interval<f64>;

/// Bounds of `x` beyond this magnitude are not refined.
const LIMIT: f64 = 1099511627776.0; // 2^40

/// The hull of `(⋃ₖ pieces + k·period) ∩ x`, see the module documentation.
fn periodic_preimage<T: Float>(pieces: &[I64], period: I64, x: Interval<T>) -> Interval<T> {
    let Some((a, b)) = x.bounds() else {
        return Interval::EMPTY;
    };
    let xf: I64 = x.cast();
    let (a, b) = (a.to_f64(), b.to_f64());
    let p = period.sup();
    let collect = |k0: f64, k1: f64| {
        let mut acc = I64::EMPTY;
        let mut k = k0;
        while k <= k1 {
            let shift = I64::new_unchecked(k, k) * period;
            for q in pieces {
                acc = acc.convex_hull((*q + shift).intersection(xf));
            }
            k += 1.0;
        }
        acc
    };
    let lo_ok = a.is_finite() && a.abs() <= LIMIT;
    let hi_ok = b.is_finite() && b.abs() <= LIMIT;
    let (ka, kb) = ((a / p).floor() - 2.0, (b / p).floor() + 2.0);
    let r = if lo_ok && hi_ok && kb - ka <= 12.0 {
        collect(ka, kb)
    } else {
        // Wide, unbounded or huge: every period of x holds a piece, so the result is
        // nonempty and its ends lie within two periods of x's ends.
        let lo = if lo_ok {
            collect(ka, ka + 4.0).inf()
        } else {
            a
        };
        let hi = if hi_ok {
            collect(kb - 4.0, kb).sup()
        } else {
            b
        };
        I64::new_unchecked(lo, hi)
    };
    r.cast()
}

/// `[π↓, π↑]`.
fn pi() -> I64 {
    I64::new_unchecked(PI_DOWN, PI_UP)
}

/// `[2π↓, 2π↑]`.
fn two_pi() -> I64 {
    I64::new_unchecked(TWO_PI_DOWN, TWO_PI_DOWN.next_up())
}

impl<T: Float> Interval<T> {
    /// `sinRev(c)` with `self = c`: `{z : sin z ∈ c}`.
    pub fn sin_rev(self) -> Self {
        self.sin_rev_in(Self::ENTIRE)
    }

    /// `sinRev(c, x)` with `self = c`: `{z ∈ x : sin z ∈ c}`. Valid; see the module
    /// documentation for the accuracy.
    ///
    /// ```
    /// use interval_core::Interval;
    /// let c = Interval::new(0.5, 1.0)?;
    /// let z = c.sin_rev_in(Interval::new(0.0, 3.0)?);
    /// let pi = std::f64::consts::PI;
    /// assert!(z.contains(pi / 6.0 + 1e-9) && z.contains(5.0 * pi / 6.0 - 1e-9));
    /// assert!(z.inf() > 0.52 && z.sup() < 2.62);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn sin_rev_in(self, x: Self) -> Self {
        let c: I64 = self
            .cast::<f64>()
            .intersection(I64::new_unchecked(-1.0, 1.0));
        if c.is_empty() || x.is_empty() {
            return Self::EMPTY;
        }
        if c.inf() == -1.0 && c.sup() == 1.0 {
            return x;
        }
        let s = c.asin();
        let r = periodic_preimage(&[s, pi() - s], two_pi(), x);
        shave(r, |z| misses(dd_of(z).sin(), self))
    }

    /// `cosRev(c)` with `self = c`: `{z : cos z ∈ c}`.
    pub fn cos_rev(self) -> Self {
        self.cos_rev_in(Self::ENTIRE)
    }

    /// `cosRev(c, x)` with `self = c`: `{z ∈ x : cos z ∈ c}`. Valid; see the module
    /// documentation for the accuracy.
    pub fn cos_rev_in(self, x: Self) -> Self {
        let c: I64 = self
            .cast::<f64>()
            .intersection(I64::new_unchecked(-1.0, 1.0));
        if c.is_empty() || x.is_empty() {
            return Self::EMPTY;
        }
        if c.inf() == -1.0 && c.sup() == 1.0 {
            return x;
        }
        let s = c.acos();
        let r = periodic_preimage(&[s, -s], two_pi(), x);
        shave(r, |z| misses(dd_of(z).cos(), self))
    }

    /// `tanRev(c)` with `self = c`: `{z : tan z ∈ c}`.
    pub fn tan_rev(self) -> Self {
        self.tan_rev_in(Self::ENTIRE)
    }

    /// `tanRev(c, x)` with `self = c`: `{z ∈ x : tan z ∈ c}` (period π). Valid; see the
    /// module documentation for the accuracy.
    pub fn tan_rev_in(self, x: Self) -> Self {
        if self.is_empty() || x.is_empty() {
            return Self::EMPTY;
        }
        if self.is_entire() {
            return x;
        }
        let s = self.cast::<f64>().atan();
        let r = periodic_preimage(&[s], pi(), x);
        shave(r, |z| {
            let g = dd_of(z);
            misses(g.sin() / g.cos(), self)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn preimages() {
        let pi = core::f64::consts::PI;
        assert!(iv(2.0, 3.0).sin_rev().is_empty());
        assert_eq!(iv(-2.0, 2.0).sin_rev_in(iv(1.0, 5.0)), iv(1.0, 5.0));
        let z = iv(0.0, 0.0).sin_rev_in(iv(-1.0, 7.0));
        assert!(z.contains(0.0) && z.contains(2.0 * pi) && z.sup() < 6.3);
        assert!(iv(0.0, 0.0).sin_rev_in(iv(0.5, 3.0)).is_empty());
        let z = iv(1.0, 1.0).cos_rev_in(iv(-0.1, 0.1));
        assert!(z.contains(0.0) && z.inf() > -1e-7 && z.sup() < 1e-7);
        let z = iv(1.0, 1.0).tan_rev_in(iv(0.0, 4.0));
        assert!(z.contains(pi / 4.0) && z.contains(5.0 * pi / 4.0) && z.sup() < 4.0);
        let z = iv(0.0, 0.0).sin_rev_in(iv(1.0, f64::INFINITY));
        assert!(z.contains(pi) && z.inf() > 3.1 && z.inf() < 3.2 && z.sup() == f64::INFINITY);
        assert!(iv(0.0, 0.0).sin_rev().is_entire());
    }
}
