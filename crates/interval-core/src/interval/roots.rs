//! `rootn` (real `n`-th roots) and `hypot`, tight by exact comparisons.
//!
//! Both start from a nearly correct `f64` candidate (CORE-MATH's correctly rounded `hypot`;
//! `pow(x, 1/n)`, which is within a few ulps) and then decide the exact position of the
//! candidate and its neighbours against the root by comparing powers exactly
//! (`c² ≷ a² + b²`, `cⁿ ≷ x`, as exact dyadic rationals). The result is the tightest `f64`
//! bracket, converted outward to the interval's type: two adjacent `f64`s around an exact
//! value that is not an `f64` hold no `f32` strictly inside, so the `f32` bounds are tight
//! too.

use super::Interval;
use super::elementary::outward;
use crate::float::Float;
use crate::float::dyadic::Dyadic;
use core::cmp::Ordering;

/// The largest `n` for which `rootn` decides its bounds exactly; larger `n` widen the `pow`
/// candidate by [`ROOT_SLACK`] ulps instead.
const EXACT_ROOT_MAX: u32 = 64;

/// Ulps added on each side of `pow(x, 1/n)` for `n > EXACT_ROOT_MAX`: rounding `1/n` changes
/// the exponent by a relative `2⁻⁵³`, which moves `x^(1/n)` by a relative
/// `|ln x|·2⁻⁵³/n ≤ 745·2⁻⁵³/65 < 12·2⁻⁵³`, at most 24 ulps, plus the half ulp of `pow`.
const ROOT_SLACK: u32 = 26;

/// `x` stepped `k` times toward +∞ (`up`) or −∞, stopping at `0` and at `±∞`.
fn steps(mut x: f64, k: u32, up: bool) -> f64 {
    for _ in 0..k {
        if up {
            x = x.next_up();
        } else if x > 0.0 {
            x = x.next_down();
        }
    }
    x
}

/// The tightest `f64` bracket `[lo, hi]` of `x^(1/k)` for finite `x ≥ 0` and `k ≥ 1`.
fn root_bracket(x: f64, k: u32) -> (f64, f64) {
    if x == 0.0 || x == 1.0 || k == 1 {
        return (x, x);
    }
    let r = match k {
        2 => x.sqrt(),
        3 => core_math::cbrt(x),
        _ => core_math::pow(x, 1.0 / f64::from(k)),
    };
    if k > EXACT_ROOT_MAX {
        return (steps(r, ROOT_SLACK, false), steps(r, ROOT_SLACK, true));
    }
    let target = Dyadic::of(x);
    // The sign of cᵏ − x: the position of c against the root.
    let vs_root = |c: f64| Dyadic::of(c).powi(k).cmp(&target);
    let mut c = r;
    // Walk to the largest c with cᵏ ≤ x (a few steps: r is within a few ulps).
    while c > 0.0 && vs_root(c) == Ordering::Greater {
        c = c.next_down();
    }
    while vs_root(c.next_up()) != Ordering::Greater {
        c = c.next_up();
    }
    if vs_root(c) == Ordering::Equal {
        (c, c)
    } else {
        (c, c.next_up())
    }
}

impl<T: Float> Interval<T> {
    /// The real `n`-th root `x^(1/n)` (IEEE 1788 `rootn`), for `n ≥ 1`: increasing, over
    /// `self ∩ [0, +∞]` for even `n`, odd (`rootn(−x) = −rootn(x)`) for odd `n`. `n = 0`
    /// gives ∅; `n < 0` gives `1 / rootn(x, −n)` (the root of the reciprocal power).
    ///
    /// **Accuracy:** tight for `1 ≤ n ≤ 64` (each candidate bound is decided by comparing its
    /// `n`-th power with the argument exactly); within 50 ulps for `n > 64` (the candidate's
    /// error of at most 24 ulps plus the widening of 26, in practice 27); for `n < 0` the
    /// reciprocal of the tight root, rounded outward again (within 2 ulps).
    ///
    /// | `self`      | `n`      | result       |
    /// |-------------|----------|--------------|
    /// | ∅           | any      | ∅            |
    /// | any         | 0        | ∅            |
    /// | `[−8, 27]`  | 3        | `[−2, 3]`    |
    /// | `[−4, 16]`  | 2, 4     | `[0, 4]`, `[0, 2]` |
    /// | `[−4, −1]`  | 2        | ∅            |
    ///
    /// ```
    /// use interval_core::Interval;
    /// assert_eq!(Interval::new(-8.0, 27.0)?.rootn(3), Interval::new(-2.0, 3.0)?);
    /// let r = Interval::new(2.0f64, 2.0)?.rootn(5);
    /// assert_eq!(r.sup(), r.inf().next_up());
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn rootn(self, n: i32) -> Self {
        if self.is_empty() || n == 0 {
            return Self::EMPTY;
        }
        if n < 0 {
            return self.rootn(-(n.max(-i32::MAX))).recip();
        }
        let k = n.unsigned_abs();
        let odd = k % 2 == 1;
        let x = if odd {
            self
        } else {
            if self.hi < T::ZERO {
                return Self::EMPTY;
            }
            Self::new_unchecked(self.lo.max_nan(T::ZERO), self.hi)
        };
        // Bounds of the root of one endpoint `v`: exact at ±∞ and by `root_bracket` else.
        let root = |v: f64| -> (f64, f64) {
            if v.is_infinite() {
                (v, v)
            } else if v < 0.0 {
                let (l, h) = root_bracket(-v, k);
                (-h, -l)
            } else {
                root_bracket(v, k)
            }
        };
        let (lo, _) = root(x.lo.to_f64());
        let (_, hi) = root(x.hi.to_f64());
        outward(lo, hi)
    }

    /// `√(x² + y²)` over the box `self × y` (`self = x`), tight.
    ///
    /// **Accuracy:** tight: the correctly rounded CORE-MATH `hypot` at the corners that give
    /// the extremes (the mignitudes for the minimum, the magnitudes for the maximum) is placed
    /// against the exact value by comparing its square with `x² + y²` exactly.
    ///
    /// ```
    /// use interval_core::Interval;
    /// let x = Interval::new(-3.0, 1.0)?;
    /// let y = Interval::new(4.0, 4.0)?;
    /// assert_eq!(x.hypot(y), Interval::new(4.0, 5.0)?);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn hypot(self, y: Self) -> Self {
        if self.is_empty() || y.is_empty() {
            return Self::EMPTY;
        }
        let bracket = |a: f64, b: f64| -> (f64, f64) {
            if a.is_infinite() || b.is_infinite() {
                return (f64::INFINITY, f64::INFINITY);
            }
            let r = core_math::hypot(a, b);
            if r.is_infinite() {
                return (f64::MAX, f64::INFINITY);
            }
            let s = Dyadic::of(a)
                .mul(&Dyadic::of(a))
                .add(&Dyadic::of(b).mul(&Dyadic::of(b)));
            match Dyadic::of(r).mul(&Dyadic::of(r)).cmp(&s) {
                Ordering::Equal => (r, r),
                Ordering::Greater => (r.next_down(), r),
                Ordering::Less => (r, r.next_up()),
            }
        };
        let (lo, _) = bracket(self.mig().to_f64(), y.mig().to_f64());
        let (_, hi) = bracket(self.mag().to_f64(), y.mag().to_f64());
        outward(lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn roots_and_hypot() {
        let inf = f64::INFINITY;
        assert_eq!(iv(-8.0, 27.0).rootn(3), iv(-2.0, 3.0));
        assert_eq!(iv(-4.0, 16.0).rootn(4), iv(0.0, 2.0));
        assert!(iv(-4.0, -1.0).rootn(2).is_empty());
        assert_eq!(iv(-inf, inf).rootn(3), Interval::ENTIRE);
        assert_eq!(
            iv(2.0, 2.0).rootn(2),
            iv(2f64.sqrt().next_down(), 2f64.sqrt())
        );
        assert_eq!(iv(4.0, 4.0).rootn(-2), iv(0.5, 0.5));
        assert!(iv(1.0, 1.0).rootn(0).is_empty());
        assert_eq!(iv(3.0, 3.0).hypot(iv(-4.0, -4.0)), iv(5.0, 5.0));
        assert_eq!(
            iv(f64::MAX, f64::MAX).hypot(iv(f64::MAX, f64::MAX)),
            iv(f64::MAX, inf)
        );
        assert_eq!(iv(0.0, 0.0).hypot(iv(5e-324, 5e-324)), iv(5e-324, 5e-324));
    }
}
