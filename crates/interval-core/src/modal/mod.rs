//! Modal intervals (thesis §3.5): intervals `[a, b]` whose bounds may come in either order,
//! with Kaucher arithmetic rounded outward or inward.
//!
//! A modal interval pairs a classical interval with a quantifier. In canonical coordinates
//! `[a, b]`:
//!
//! | bounds | name | set `Prop` | quantifier |
//! |---|---|---|---|
//! | `a < b` | proper | `[a, b]'` | `∃` |
//! | `a > b` | improper | `[b, a]'` | `∀` |
//! | `a = b` | point-wise | `{a}` | either |
//!
//! [`Modal`] stores the two canonical bounds and a rounding marker in its type:
//! [`Outer`] (the default) rounds every result so that it *includes* the exact Kaucher result
//! in the modal inclusion — what the *-semantic theorem needs, `f*(X) ⊆ Out(fR(X))` —
//! and [`Inner`] so that it is *included* in it, `Inn(fR(X)) ⊆ f**(X)`. Generic code over
//! `std::ops` thus evaluates one formula both ways. See [`rounding`] for the directions,
//! [`arith`] for the arithmetic tables and [`lattice`] for inclusion, meet, join, min, max.
//!
//! ```
//! use interval_core::modal::{Inner, Modal, Outer};
//!
//! // The thesis's sum: [1, 3] + [3, 2] = [4, 5].
//! let x: Modal = Modal::proper(1.0, 3.0)?;
//! let y = Modal::improper(3.0, 2.0)?;
//! assert_eq!(x + y, Modal::proper(4.0, 5.0)?);
//!
//! // Outer and inner rounding of the same formula bracket the exact 1/3 from both sides.
//! let one: Modal<f64, Outer> = Modal::point(1.0)?;
//! let out = one / Modal::point(3.0)?;
//! let inn = one.with_rounding::<Inner>() / Modal::point(3.0)?;
//! assert!(out.first() < inn.first() && inn.second() < out.second());
//! assert!(inn.with_rounding::<Outer>().subset(out));
//! # Ok::<(), interval_core::IntervalError>(())
//! ```

pub mod arith;
pub mod lattice;
pub mod rounding;

pub use rounding::{Inner, Outer, Rounding};

use crate::IntervalError;
use crate::float::Float;
use crate::interval::Interval;
use core::fmt;
use core::marker::PhantomData;

/// A modal interval `[a, b]` over `f64` or `f32` bounds, in canonical coordinates: proper for
/// `a ≤ b` (`∃` over `[a, b]'`), improper for `a ≥ b` (`∀` over `[b, a]'`), point-wise for
/// `a = b`. The marker `R` ([`Outer`] or [`Inner`]) fixes how results of arithmetic are
/// rounded; it changes no bound by itself ([`Modal::with_rounding`] switches it).
///
/// Bounds are never NaN. They may be infinite: a bound at `±∞` stands for an unbounded side
/// (`[+∞, 5]` is `∀` over `[5, +∞)`). The degenerate points `[+∞, +∞]` and `[−∞, −∞]` are
/// accepted, since outer and inner arithmetic on unbounded arguments can reach them as limits,
/// but denote no real number.
///
/// Equality (`==`) compares the two bounds (and so the modality); `0` and `−0` are equal.
///
/// ```
/// use interval_core::modal::Modal;
/// let x: Modal = Modal::new(2.0, 3.0)?;
/// let y: Modal = Modal::new(4.0, 3.0)?;
/// assert!(x.is_proper() && y.is_improper());
/// assert_eq!(y.dual(), Modal::new(3.0, 4.0)?);
/// assert_eq!(y.prop(), interval_core::Interval::new(3.0, 4.0)?);
/// assert_eq!(format!("{y}"), "[4, 3] (improper)");
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
#[derive(Clone, Copy)]
pub struct Modal<T: Float = f64, R: Rounding = Outer> {
    /// First canonical bound.
    pub(crate) a: T,
    /// Second canonical bound.
    pub(crate) b: T,
    rounding: PhantomData<R>,
}

impl<T: Float, R: Rounding> Modal<T, R> {
    /// `[0, 0]`.
    pub const ZERO: Self = Self::new_unchecked(T::ZERO, T::ZERO);
    /// `[1, 1]`.
    pub const ONE: Self = Self::new_unchecked(T::ONE, T::ONE);
    /// `[−∞, +∞]`: `∃` over the whole line, the greatest element of the modal inclusion
    /// (it includes every modal interval).
    pub const ENTIRE: Self = Self::new_unchecked(T::NEG_INFINITY, T::INFINITY);
    /// `[+∞, −∞]`: `∀` over the whole line, the least element of the modal inclusion (it is
    /// included in every modal interval); `dual` of [`Modal::ENTIRE`].
    pub const DUAL_ENTIRE: Self = Self::new_unchecked(T::INFINITY, T::NEG_INFINITY);

    /// The modal interval with canonical bounds `[a, b]`, in either order.
    ///
    /// # Errors
    /// [`IntervalError::NanBound`] if a bound is NaN (`which` is `"first"` or `"second"`).
    pub fn new(a: T, b: T) -> Result<Self, IntervalError> {
        if a.is_nan() {
            return Err(IntervalError::NanBound { which: "first" });
        }
        if b.is_nan() {
            return Err(IntervalError::NanBound { which: "second" });
        }
        Ok(Self::new_unchecked(a, b))
    }

    /// The proper interval `[lo, hi]` (`∃` over `[lo, hi]'`); `lo = hi` gives a point.
    ///
    /// # Errors
    /// [`IntervalError::NanBound`] for a NaN bound, [`IntervalError::Reversed`] if `lo > hi`.
    pub fn proper(lo: T, hi: T) -> Result<Self, IntervalError> {
        let m = Self::new(lo, hi)?;
        if lo > hi {
            return Err(IntervalError::Reversed {
                lo: lo.to_f64(),
                hi: hi.to_f64(),
            });
        }
        Ok(m)
    }

    /// The improper interval `[a, b]` with `a ≥ b` (`∀` over `[b, a]'`); `a = b` gives a
    /// point.
    ///
    /// # Errors
    /// [`IntervalError::NanBound`] for a NaN bound. If `a < b`, [`IntervalError::Reversed`]
    /// with `lo = b`, `hi = a`: the set `[b, a]'` the quantifier would range over is reversed.
    pub fn improper(a: T, b: T) -> Result<Self, IntervalError> {
        let m = Self::new(a, b)?;
        if a < b {
            return Err(IntervalError::Reversed {
                lo: b.to_f64(),
                hi: a.to_f64(),
            });
        }
        Ok(m)
    }

    /// The point-wise interval `[x, x]`.
    ///
    /// # Errors
    /// [`IntervalError::NanBound`] if `x` is NaN, [`IntervalError::InfiniteEndpoint`] if `x`
    /// is infinite.
    pub fn point(x: T) -> Result<Self, IntervalError> {
        if x.is_infinite() {
            return Err(IntervalError::InfiniteEndpoint {
                lo: x.to_f64(),
                hi: x.to_f64(),
            });
        }
        Self::new(x, x)
    }

    /// The real number `x` (given as `f64`) rounded as `R` says: for [`Outer`] the proper
    /// one-ulp interval `[down(x), up(x)] ⊇ [x, x]`, for [`Inner`] the improper
    /// `[up(x), down(x)] ⊆ [x, x]`. A point when `x` is representable in `T` (always for
    /// `f64`).
    ///
    /// # Errors
    /// [`IntervalError`] if `x` is NaN or infinite.
    pub fn from_f64(x: f64) -> Result<Self, IntervalError> {
        if x.is_nan() {
            return Err(IntervalError::NanBound { which: "first" });
        }
        if x.is_infinite() {
            return Err(IntervalError::InfiniteEndpoint { lo: x, hi: x });
        }
        Ok(Self::new_unchecked(
            rounding::from_f64_1::<T, R>(x),
            rounding::from_f64_2::<T, R>(x),
        ))
    }

    /// `[a, b]` without checks. The caller guarantees that neither bound is NaN; violating
    /// this is not unsafe but makes later results meaningless.
    #[inline(always)]
    pub const fn new_unchecked(a: T, b: T) -> Self {
        Self {
            a,
            b,
            rounding: PhantomData,
        }
    }

    /// The first canonical bound `a` of `[a, b]` (the lower bound of a proper interval, the
    /// upper bound of the set of an improper one).
    #[inline(always)]
    pub fn first(self) -> T {
        self.a
    }

    /// The second canonical bound `b` of `[a, b]`.
    #[inline(always)]
    pub fn second(self) -> T {
        self.b
    }

    /// The canonical bounds `(a, b)`.
    #[inline(always)]
    pub fn bounds(self) -> (T, T) {
        (self.a, self.b)
    }

    /// `Prop([a, b])`: the set `[min(a, b), max(a, b)]'` as a classical [`Interval`]. The
    /// degenerate points `[+∞, +∞]` and `[−∞, −∞]` contain no real number and give
    /// [`Interval::EMPTY`].
    #[inline]
    pub fn prop(self) -> Interval<T> {
        let (lo, hi) = if self.a <= self.b {
            (self.a, self.b)
        } else {
            (self.b, self.a)
        };
        if lo == T::INFINITY || hi == T::NEG_INFINITY {
            Interval::EMPTY
        } else {
            Interval::new_unchecked(lo, hi)
        }
    }

    /// `Impr([a, b])`: the improper interval over the same set, `[max(a, b), min(a, b)]`.
    #[inline]
    pub fn impr(self) -> Self {
        if self.a >= self.b { self } else { self.dual() }
    }

    /// `Dual([a, b]) = [b, a]`: same set, opposite quantifier. Exact.
    #[inline]
    pub fn dual(self) -> Self {
        Self::new_unchecked(self.b, self.a)
    }

    /// The same bounds under another rounding marker (`Outer` ↔ `Inner`); no bound changes.
    #[inline]
    pub fn with_rounding<R2: Rounding>(self) -> Modal<T, R2> {
        Modal::new_unchecked(self.a, self.b)
    }

    /// Converts to another bound type (`f32` ↔ `f64`), rounding each bound as `R` says
    /// (exact toward `f64`).
    pub fn cast<U: Float>(self) -> Modal<U, R> {
        Modal::new_unchecked(
            rounding::from_f64_1::<U, R>(self.a.to_f64()),
            rounding::from_f64_2::<U, R>(self.b.to_f64()),
        )
    }

    /// True for `a ≤ b` (points included): the quantifier is `∃`.
    #[inline]
    pub fn is_proper(self) -> bool {
        self.a <= self.b
    }

    /// True for `a ≥ b` (points included): the quantifier is `∀`.
    #[inline]
    pub fn is_improper(self) -> bool {
        self.a >= self.b
    }

    /// True for a point-wise interval `a = b`.
    #[inline]
    pub fn is_point(self) -> bool {
        self.a == self.b
    }

    /// True if the real number `x` lies in `Prop(self)`, whatever the modality (e.g.
    /// `prop_contains(0)` tells whether Kaucher division by `self` is undefined).
    #[inline]
    pub fn prop_contains(self, x: T) -> bool {
        self.prop().contains(x)
    }
}

impl<T: Float, R: Rounding> PartialEq for Modal<T, R> {
    /// Equality of both canonical bounds.
    #[inline]
    fn eq(&self, other: &Self) -> bool {
        self.a == other.a && self.b == other.b
    }
}

impl<T: Float, R: Rounding> fmt::Debug for Modal<T, R> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Modal")
            .field("a", &self.a)
            .field("b", &self.b)
            .field("rounding", &R::default())
            .finish()
    }
}

/// A proper modal interval from a non-empty classical one (`[lo, hi]` ↦ `([lo, hi]', ∃)`).
impl<T: Float, R: Rounding> TryFrom<Interval<T>> for Modal<T, R> {
    type Error = IntervalError;
    /// # Errors
    /// The empty interval has no modal counterpart (every modal interval accepts some
    /// predicate): [`IntervalError::NanBound`], as its stored bounds are NaN.
    fn try_from(x: Interval<T>) -> Result<Self, IntervalError> {
        match x.bounds() {
            Some((lo, hi)) => Ok(Self::new_unchecked(lo, hi)),
            None => Err(IntervalError::NanBound { which: "first" }),
        }
    }
}

/// `(a, b)` ↦ [`Modal::new`]`(a, b)`.
impl<T: Float, R: Rounding> TryFrom<(T, T)> for Modal<T, R> {
    type Error = IntervalError;
    fn try_from((a, b): (T, T)) -> Result<Self, IntervalError> {
        Self::new(a, b)
    }
}

/// `[a, b]` for proper and point-wise intervals, `[a, b] (improper)` for improper ones. The
/// format options (precision, ...) apply to both bounds, as for [`Interval`]'s `Display`.
impl<T: Float, R: Rounding> fmt::Display for Modal<T, R> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("[")?;
        fmt::Display::fmt(&self.a, f)?;
        f.write_str(", ")?;
        fmt::Display::fmt(&self.b, f)?;
        f.write_str("]")?;
        if self.a > self.b {
            f.write_str(" (improper)")?;
        }
        Ok(())
    }
}

/// As `Display`, with the bounds in `{:e}` notation.
impl<T: Float, R: Rounding> fmt::LowerExp for Modal<T, R> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("[")?;
        fmt::LowerExp::fmt(&self.a, f)?;
        f.write_str(", ")?;
        fmt::LowerExp::fmt(&self.b, f)?;
        f.write_str("]")?;
        if self.a > self.b {
            f.write_str(" (improper)")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constructors() {
        assert!(Modal::<f64>::new(f64::NAN, 1.0).is_err());
        assert!(Modal::<f64>::new(2.0, 1.0).unwrap().is_improper());
        assert!(Modal::<f64>::proper(2.0, 1.0).is_err());
        assert!(Modal::<f64>::improper(1.0, 2.0).is_err());
        assert!(Modal::<f64>::point(f64::INFINITY).is_err());
        let p = Modal::<f32>::point(1.5).unwrap();
        assert!(p.is_point() && p.is_proper() && p.is_improper());
        let e: Result<Modal<f64>, _> = Modal::try_from(Interval::<f64>::EMPTY);
        assert!(e.is_err());
        let x: Modal<f64> = Modal::try_from(Interval::new(1.0, 2.0).unwrap()).unwrap();
        assert_eq!(x.bounds(), (1.0, 2.0));
    }

    #[test]
    fn from_f64_rounds_by_marker() {
        let o = Modal::<f32, Outer>::from_f64(0.1).unwrap();
        let i = Modal::<f32, Inner>::from_f64(0.1).unwrap();
        assert!(o.is_proper() && !o.is_point() && o.prop().contains(0.1f32));
        assert!(i.is_improper() && !i.is_point());
        assert_eq!(i.dual().with_rounding::<Outer>(), o);
        let c = Modal::<f64, Outer>::new(0.1, 0.2).unwrap().cast::<f32>();
        assert!(f64::from(c.first()) <= 0.1 && f64::from(c.second()) >= 0.2);
    }

    #[test]
    fn prop_impr_dual() {
        let y = Modal::<f64>::new(4.0, 3.0).unwrap();
        assert_eq!(y.impr(), y);
        assert_eq!(y.dual().impr(), y);
        assert_eq!(y.dual().dual(), y);
        assert!(y.prop_contains(3.5) && !y.prop_contains(5.0));
        assert!(
            Modal::<f64>::new(f64::INFINITY, f64::INFINITY)
                .unwrap()
                .prop()
                .is_empty()
        );
        assert!(Modal::<f64>::DUAL_ENTIRE.prop().is_entire());
    }

    #[test]
    fn display() {
        let y = Modal::<f64>::new(4.0, 3.0).unwrap();
        assert_eq!(y.to_string(), "[4, 3] (improper)");
        assert_eq!(Modal::<f64>::point(2.0).unwrap().to_string(), "[2, 2]");
        assert_eq!(format!("{:.1}", y.dual()), "[3.0, 4.0]");
        assert_eq!(format!("{:e}", y), "[4e0, 3e0] (improper)");
    }
}
