//! The set-based interval type [`Interval`] and its operations.
//!
//! Operations live in one file per family, after IEEE 1788-2015: arithmetic (`arith`),
//! cancellative operations (`cancel`), reverse operations (`rev`, `rev_trig`, `rev_pow`),
//! elementary functions (`elementary`, `trig`, `inverse_hyperbolic`, `exp_log1p`, `roots`),
//! integer functions (`integer`), numeric functions (this file), boolean relations
//! (`relations`, `overlap`), set operations (`set_ops`), slice operations (`batch`), exact
//! reductions of float slices (`reduction`), formatting (`fmt`) and reading literals
//! (`parse`).

mod arith;
pub mod batch;
mod cancel;
mod elementary;
mod exp_log1p;
mod fmt;
mod integer;
mod inverse_hyperbolic;
pub mod overlap;
mod parse;
pub mod reduction;
mod relations;
mod rev;
mod rev_pow;
mod rev_trig;
mod roots;
mod set_ops;
mod shave;
mod trig;

use crate::IntervalError;
use crate::float::Float;

/// A closed, connected set of real numbers `{x : inf ≤ x ≤ sup}`, possibly empty or
/// unbounded: the *set-based* interval of IEEE 1788-2015, over `f64` or `f32` bounds.
///
/// Every operation returns an interval that contains the exact result of the real operation
/// on every point of its arguments (the inclusion property). Arithmetic `+ - * /`, `fma`,
/// `sqr`, `sqrt` and `recip` are *tight*: their bounds are the exact result rounded
/// outward to the nearest representable numbers. Elementary functions state their accuracy in
/// their documentation.
///
/// The empty set is a valid interval ([`Interval::EMPTY`]); so are `[−∞, b]`, `[a, +∞]` and
/// [`Interval::ENTIRE`]. Bounds are never NaN except in the empty interval's representation.
///
/// ```
/// use interval_core::Interval;
/// let x = Interval::new(1.0, 2.0)?;
/// let y = Interval::new(-1.0, 3.0)?;
/// assert_eq!(x * y, Interval::new(-2.0, 6.0)?);
/// let third: Interval<f64> = Interval::point(1.0)? / Interval::point(3.0)?;
/// assert!(third.contains(1.0 / 3.0));
/// assert_eq!(third.sup(), third.inf().next_up()); // tight: one ulp wide
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Interval<T: Float = f64> {
    /// Lower bound; NaN for the empty interval.
    pub(crate) lo: T,
    /// Upper bound; NaN for the empty interval.
    pub(crate) hi: T,
}

impl<T: Float> Default for Interval<T> {
    /// The empty interval, the neutral element of [`Interval::convex_hull`].
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<T: Float> Interval<T> {
    /// The empty set.
    pub const EMPTY: Self = Self {
        lo: T::NAN,
        hi: T::NAN,
    };
    /// The whole real line `[−∞, +∞]`.
    pub const ENTIRE: Self = Self {
        lo: T::NEG_INFINITY,
        hi: T::INFINITY,
    };
    /// `[0, 0]`.
    pub const ZERO: Self = Self {
        lo: T::ZERO,
        hi: T::ZERO,
    };
    /// `[1, 1]`.
    pub const ONE: Self = Self {
        lo: T::ONE,
        hi: T::ONE,
    };

    /// The interval `[lo, hi]`.
    ///
    /// # Errors
    /// [`IntervalError`] if a bound is NaN, `lo > hi`, `lo = +∞` or `hi = −∞`.
    pub fn new(lo: T, hi: T) -> Result<Self, IntervalError> {
        if lo.is_nan() {
            return Err(IntervalError::NanBound { which: "lower" });
        }
        if hi.is_nan() {
            return Err(IntervalError::NanBound { which: "upper" });
        }
        if lo > hi {
            return Err(IntervalError::Reversed {
                lo: lo.to_f64(),
                hi: hi.to_f64(),
            });
        }
        if lo == T::INFINITY || hi == T::NEG_INFINITY {
            return Err(IntervalError::InfiniteEndpoint {
                lo: lo.to_f64(),
                hi: hi.to_f64(),
            });
        }
        Ok(Self { lo, hi })
    }

    /// The singleton `[x, x]`.
    ///
    /// # Errors
    /// [`IntervalError`] if `x` is NaN or infinite.
    pub fn point(x: T) -> Result<Self, IntervalError> {
        Self::new(x, x)
    }

    /// `[lo, hi]` without checks. The caller guarantees `lo ≤ hi`, no NaN, `lo ≠ +∞` and
    /// `hi ≠ −∞`, or both bounds NaN (the empty interval); violating this is not unsafe
    /// but makes later results meaningless.
    #[inline(always)]
    pub const fn new_unchecked(lo: T, hi: T) -> Self {
        Self { lo, hi }
    }

    /// The tightest interval containing the real number `x` (given as `f64`), for `f32`
    /// intervals a one-ulp interval when `x` is not an `f32`.
    ///
    /// # Errors
    /// [`IntervalError`] if `x` is NaN or infinite.
    pub fn from_f64(x: f64) -> Result<Self, IntervalError> {
        if !x.is_finite() {
            return Err(if x.is_nan() {
                IntervalError::NanBound { which: "lower" }
            } else {
                IntervalError::InfiniteEndpoint { lo: x, hi: x }
            });
        }
        Ok(Self {
            lo: T::from_f64_down(x),
            hi: T::from_f64_up(x),
        })
    }

    /// Lower bound; `+∞` for the empty interval (IEEE 1788 `inf`). A zero lower bound is
    /// returned as `−0` (IEEE 1788-2015 §12.12.8), whatever sign the stored zero carries.
    #[inline]
    pub fn inf(self) -> T {
        if self.is_empty() {
            T::INFINITY
        } else if self.lo == T::ZERO {
            -T::ZERO
        } else {
            self.lo
        }
    }

    /// Upper bound; `−∞` for the empty interval (IEEE 1788 `sup`). A zero upper bound is
    /// returned as `+0` (IEEE 1788-2015 §12.12.8), whatever sign the stored zero carries.
    #[inline]
    pub fn sup(self) -> T {
        if self.is_empty() {
            T::NEG_INFINITY
        } else if self.hi == T::ZERO {
            T::ZERO
        } else {
            self.hi
        }
    }

    /// Midpoint, rounded to nearest; NaN for the empty interval, 0 for `ENTIRE`, and
    /// `∓MAX` for half-unbounded intervals (IEEE 1788 `mid`).
    pub fn mid(self) -> T {
        let (a, b) = (self.lo, self.hi);
        if self.is_empty() {
            T::NAN
        } else if a == T::NEG_INFINITY {
            if b == T::INFINITY { T::ZERO } else { -T::MAX }
        } else if b == T::INFINITY {
            T::MAX
        } else {
            // One rounding, ties to even: a sum of subnormals is exact, and halving a normal
            // sum is exact; only an overflowing sum is halved operand-wise (exact there).
            let s = a + b;
            let m = if s.is_finite() {
                s * T::HALF
            } else {
                a * T::HALF + b * T::HALF
            };
            m.max_nan(a).min_nan(b)
        }
    }

    /// Radius: the smallest `r` (rounded up) with `[mid − r, mid + r] ⊇ self`; NaN for empty.
    pub fn rad(self) -> T {
        if self.is_empty() {
            return T::NAN;
        }
        let m = self.mid();
        (m.sub_up(self.lo)).max_nan(self.hi.sub_up(m))
    }

    /// Width `sup − inf`, rounded up; NaN for empty (IEEE 1788 `wid`).
    pub fn wid(self) -> T {
        if self.is_empty() {
            T::NAN
        } else {
            self.hi.sub_up(self.lo)
        }
    }

    /// Magnitude `max |x|` over the interval; NaN for empty.
    pub fn mag(self) -> T {
        if self.is_empty() {
            T::NAN
        } else {
            self.lo.abs().max_nan(self.hi.abs())
        }
    }

    /// Mignitude `min |x|` over the interval; NaN for empty.
    pub fn mig(self) -> T {
        if self.is_empty() {
            T::NAN
        } else if self.lo > T::ZERO {
            self.lo
        } else if self.hi < T::ZERO {
            -self.hi
        } else {
            T::ZERO
        }
    }

    /// True for the empty set.
    #[inline(always)]
    pub fn is_empty(self) -> bool {
        self.lo.is_nan()
    }

    /// True for `[−∞, +∞]`.
    #[inline]
    pub fn is_entire(self) -> bool {
        self.lo == T::NEG_INFINITY && self.hi == T::INFINITY
    }

    /// True for a non-empty interval with finite bounds (IEEE 1788 `isCommonInterval`).
    #[inline]
    pub fn is_common_interval(self) -> bool {
        !self.is_empty() && self.lo.is_finite() && self.hi.is_finite()
    }

    /// True for a one-point interval `[x, x]`.
    #[inline]
    pub fn is_singleton(self) -> bool {
        self.lo == self.hi
    }

    /// True if the real number `x` belongs to the interval (IEEE 1788 `isMember`).
    #[inline]
    pub fn contains(self, x: T) -> bool {
        self.lo <= x && x <= self.hi && x.is_finite()
    }

    /// The bounds `(inf, sup)` as stored; `None` for the empty interval.
    #[inline]
    pub fn bounds(self) -> Option<(T, T)> {
        if self.is_empty() {
            None
        } else {
            Some((self.lo, self.hi))
        }
    }

    /// Converts an `f32` interval to `f64` or back, rounding outward (exact toward `f64`).
    pub fn cast<U: Float>(self) -> Interval<U> {
        if self.is_empty() {
            Interval::EMPTY
        } else {
            Interval {
                lo: U::from_f64_down(self.lo.to_f64()),
                hi: U::from_f64_up(self.hi.to_f64()),
            }
        }
    }
}

impl<T: Float> TryFrom<(T, T)> for Interval<T> {
    type Error = IntervalError;
    fn try_from((lo, hi): (T, T)) -> Result<Self, IntervalError> {
        Self::new(lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mid_rounds_once_to_nearest() {
        let u = f64::MIN_POSITIVE_SUBNORMAL;
        let iv = |a: f64, b: f64| Interval::new(a, b).unwrap();
        assert_eq!(iv(u, 5.0 * u).mid(), 3.0 * u);
        assert_eq!(iv(3.0 * u, 7.0 * u).mid(), 5.0 * u);
        assert_eq!(iv(-2.0 * u, u).mid(), 0.0);
        assert_eq!(iv(f64::MAX, f64::MAX).mid(), f64::MAX);
        assert_eq!(iv(-f64::MAX, f64::MAX).mid(), 0.0);
        assert_eq!(iv(1.0, 2.0).mid(), 1.5);
        assert_eq!(Interval::<f64>::ENTIRE.mid(), 0.0);
        assert_eq!(iv(f64::NEG_INFINITY, 1.0).mid(), -f64::MAX);
    }

    #[test]
    fn zero_bounds_have_the_standard_signs() {
        // IEEE 1788-2015 §12.12.8: inf of a zero lower bound is −0, sup of a zero upper
        // bound is +0, whichever zero is stored.
        for (a, b) in [(0.0f64, 0.0), (-0.0, -0.0), (0.0, -0.0), (-0.0, 0.0)] {
            let x = Interval::new(a, b).unwrap();
            assert!(
                x.inf() == 0.0 && x.inf().is_sign_negative(),
                "inf of [{a}, {b}]"
            );
            assert!(
                x.sup() == 0.0 && x.sup().is_sign_positive(),
                "sup of [{a}, {b}]"
            );
        }
        let y = Interval::new(-0.0f32, 1.0).unwrap();
        assert!(y.inf().is_sign_negative() && y.sup() == 1.0);
        let z = Interval::new(-1.0f32, -0.0).unwrap();
        assert!(z.sup().is_sign_positive() && z.inf() == -1.0);
    }
}
