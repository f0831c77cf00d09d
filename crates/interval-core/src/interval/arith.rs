//! Tight interval arithmetic: `+ - * /`, `fma`, `sqr`, `sqrt`, `recip`, `neg`, `abs`,
//! `min`, `max`.
//!
//! Every bound is one directed-rounded operation on the exact real values of the operand
//! bounds (see [`crate::float`]), the extreme one among the candidates (IEEE 1788's case
//! tables for `fma` and the zero-divisor cases; the minimum/maximum of the four corners for
//! `*`; selects by sign for `/`), so the results are tight. `0 · ∞` is taken as 0 (the limit
//! over the set).

//!
//! The cheap operations (`neg`, `+`, `-`, the branching product, `sqr`, `sqrt`, `abs`,
//! `min`, `max`) are always inlined: an evaluator loop compiled for a wider instruction set
//! than the crate's (FMA under the error-free products) then computes them in that set too,
//! instead of calling a copy compiled for the baseline.

use super::Interval;
use crate::float::Float;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// Where an interval lies with respect to zero.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Sign {
    /// `inf ≥ 0`.
    Pos,
    /// `sup ≤ 0` and `inf < 0`.
    Neg,
    /// `inf < 0 < sup`.
    Mixed,
}

#[inline(always)]
fn sign<T: Float>(x: Interval<T>) -> Sign {
    if x.lo >= T::ZERO {
        Sign::Pos
    } else if x.hi <= T::ZERO {
        Sign::Neg
    } else {
        Sign::Mixed
    }
}

/// The hull of `{x·y : x ∈ a, y ∈ b}` with the extreme corner products rounded by `down`
/// and `up` (for `fma`: directed products plus the addend, one rounding each), selected by
/// the sign classes of IEEE 1788's case table.
#[inline(always)]
fn product_hull<T: Float>(
    a: Interval<T>,
    b: Interval<T>,
    down: impl Fn(T, T) -> T,
    up: impl Fn(T, T) -> T,
) -> Interval<T> {
    if a.is_empty() || b.is_empty() {
        return Interval::EMPTY;
    }
    let (al, ah, bl, bh) = (a.lo, a.hi, b.lo, b.hi);
    let (lo, hi) = match (sign(a), sign(b)) {
        (Sign::Pos, Sign::Pos) => (down(al, bl), up(ah, bh)),
        (Sign::Pos, Sign::Mixed) => (down(ah, bl), up(ah, bh)),
        (Sign::Pos, Sign::Neg) => (down(ah, bl), up(al, bh)),
        (Sign::Mixed, Sign::Pos) => (down(al, bh), up(ah, bh)),
        (Sign::Mixed, Sign::Mixed) => (
            down(al, bh).min_nan(down(ah, bl)),
            up(al, bl).max_nan(up(ah, bh)),
        ),
        (Sign::Mixed, Sign::Neg) => (down(ah, bl), up(al, bl)),
        (Sign::Neg, Sign::Pos) => (down(al, bh), up(ah, bl)),
        (Sign::Neg, Sign::Mixed) => (down(al, bh), up(al, bl)),
        (Sign::Neg, Sign::Neg) => (down(ah, bh), up(al, bl)),
    };
    Interval { lo, hi }
}

impl<T: Float> Interval<T> {
    /// `−x`. Exact.
    #[inline(always)]
    #[allow(clippy::should_implement_trait)]
    pub fn neg(self) -> Self {
        Self {
            lo: -self.hi,
            hi: -self.lo,
        }
    }

    /// `x + y`, tight.
    #[inline(always)]
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, rhs: Self) -> Self {
        Self {
            lo: self.lo.add_down(rhs.lo),
            hi: self.hi.add_up(rhs.hi),
        }
    }

    /// `x − y`, tight.
    #[inline(always)]
    #[allow(clippy::should_implement_trait)]
    pub fn sub(self, rhs: Self) -> Self {
        Self {
            lo: self.lo.sub_down(rhs.hi),
            hi: self.hi.sub_up(rhs.lo),
        }
    }

    /// `x · y`, tight.
    ///
    /// The bounds are the minimum of the four corner products rounded down and the maximum
    /// rounded up: directed rounding is monotone, so this equals the sign-case selection of
    /// IEEE 1788 bit for bit, without its data-dependent branches (`0 · ∞ = 0` holds corner by
    /// corner).
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn mul(self, rhs: Self) -> Self {
        if self.is_empty() || rhs.is_empty() {
            return Self::EMPTY;
        }
        let (a, b, c, d) = (self.lo, self.hi, rhs.lo, rhs.hi);
        let min = |x: T, y: T| if y < x { y } else { x };
        let max = |x: T, y: T| if y > x { y } else { x };
        Self::new_unchecked(
            min(
                min(a.mul_down(c), a.mul_down(d)),
                min(b.mul_down(c), b.mul_down(d)),
            ),
            max(max(a.mul_up(c), a.mul_up(d)), max(b.mul_up(c), b.mul_up(d))),
        )
    }

    /// `x · y`, tight: the same interval as [`mul`](Self::mul) (a zero bound may carry the
    /// other sign), by IEEE 1788's sign-case table: branches on the sign classes of `x` and `y` choose the corner
    /// products, so a call takes two directed products (four when both straddle 0) where
    /// `mul` takes eight. Faster than `mul` where the signs repeat from call to call (the
    /// scalar evaluation of one formula along a ray, where the branches predict: about 12 %
    /// off the whole default render), slower on random signs, where they mispredict (see
    /// `docs/benchmarks.md`).
    #[inline(always)]
    pub fn mul_sign_cases(self, rhs: Self) -> Self {
        if self.is_empty() || rhs.is_empty() {
            return Self::EMPTY;
        }
        let (a, b, c, d) = (self.lo, self.hi, rhs.lo, rhs.hi);
        let zero = T::ZERO;
        let (lo, hi) = if a >= zero {
            if c >= zero {
                (a.mul_down(c), b.mul_up(d))
            } else if d <= zero {
                (b.mul_down(c), a.mul_up(d))
            } else {
                (b.mul_down(c), b.mul_up(d))
            }
        } else if b <= zero {
            if c >= zero {
                (a.mul_down(d), b.mul_up(c))
            } else if d <= zero {
                (b.mul_down(d), a.mul_up(c))
            } else {
                (a.mul_down(d), a.mul_up(c))
            }
        } else if c >= zero {
            (a.mul_down(d), b.mul_up(d))
        } else if d <= zero {
            (b.mul_down(c), a.mul_up(c))
        } else {
            let min = |x: T, y: T| if y < x { y } else { x };
            let max = |x: T, y: T| if y > x { y } else { x };
            (
                min(a.mul_down(d), b.mul_down(c)),
                max(a.mul_up(c), b.mul_up(d)),
            )
        };
        Self::new_unchecked(lo, hi)
    }

    /// `x · y + z` with one rounding per bound (IEEE 1788 `fma`), tight.
    #[inline]
    pub fn fma(self, y: Self, z: Self) -> Self {
        if z.is_empty() {
            return Self::EMPTY;
        }
        product_hull(
            self,
            y,
            |a, b| a.fma_down(b, z.lo),
            |a, b| a.fma_up(b, z.hi),
        )
    }

    /// `x / y`, tight. When `y` contains 0 the result is the hull of the set
    /// `{x/y : y ≠ 0}` (possibly unbounded); `x / [0, 0]` is empty. See
    /// [`Interval::mul_rev_to_pair`] for the two-piece division.
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn div(self, rhs: Self) -> Self {
        if self.is_empty() || rhs.is_empty() {
            return Self::EMPTY;
        }
        let (al, ah, bl, bh) = (self.lo, self.hi, rhs.lo, rhs.hi);
        let z = T::ZERO;
        if bl > z || bh < z {
            // 0 ∉ y: the extreme quotients, chosen by selects rather than branches. The lower
            // bound divides x̲ (y > 0) or x̅ (y < 0) by y̅ if that numerator is ≥ 0, else by y̲;
            // the upper bound divides the other endpoint by y̲ if it is ≥ 0, else by y̅.
            use core::hint::select_unpredictable as select;
            let positive = bl > z;
            let n_lo = select(positive, al, ah);
            let n_hi = select(positive, ah, al);
            let d_lo = select(n_lo >= z, bh, bl);
            let d_hi = select(n_hi >= z, bl, bh);
            Self::new_unchecked(n_lo.div_down(d_lo), n_hi.div_up(d_hi))
        } else if bl == z && bh == z {
            Self::EMPTY
        } else if al == z && ah == z {
            Self::ZERO
        } else if (al < z && z < ah) || (bl < z && z < bh) {
            Self::ENTIRE
        } else if bl == z {
            // y = [0, bh] with bh > 0; x lies on one side of 0 (possibly touching it).
            if al >= z {
                Self::new_unchecked(al.div_down(bh), T::INFINITY)
            } else {
                Self::new_unchecked(T::NEG_INFINITY, ah.div_up(bh))
            }
        } else {
            // y = [bl, 0] with bl < 0.
            if al >= z {
                Self::new_unchecked(T::NEG_INFINITY, al.div_up(bl))
            } else {
                Self::new_unchecked(ah.div_down(bl), T::INFINITY)
            }
        }
    }

    /// `1 / x`, tight (hull of the set when `x` contains 0).
    #[inline]
    pub fn recip(self) -> Self {
        Self::ONE.div(self)
    }

    /// `x²`, tight (and tighter than `x · x` when `x` contains 0): `[mig(x)²↓, mag(x)²↑]`,
    /// with the mignitude chosen by selects rather than branches.
    #[inline(always)]
    pub fn sqr(self) -> Self {
        if self.is_empty() {
            return self;
        }
        use core::hint::select_unpredictable as select;
        let (a, b) = (self.lo, self.hi);
        let mig = select(a > T::ZERO, a, select(b < T::ZERO, -b, T::ZERO));
        let (ma, mb) = (a.abs(), b.abs());
        let mag = select(ma > mb, ma, mb);
        Self::new_unchecked(mig.mul_down(mig), mag.mul_up(mag))
    }

    /// `√x` over `x ∩ [0, +∞]`, tight; empty when `x < 0`.
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        if self.is_empty() || self.hi < T::ZERO {
            return Self::EMPTY;
        }
        let lo = if self.lo > T::ZERO { self.lo } else { T::ZERO };
        Self::new_unchecked(lo.sqrt_down(), self.hi.sqrt_up())
    }

    /// `|x|`. Exact.
    #[inline(always)]
    pub fn abs(self) -> Self {
        if self.is_empty() {
            return self;
        }
        // [mig, mag] by selects: the sign of the interval is data, not a branch to predict.
        use core::hint::select_unpredictable as select;
        let (a, b) = (self.lo, self.hi);
        let mig = select(a > T::ZERO, a, select(b < T::ZERO, -b, T::ZERO));
        let (ma, mb) = (a.abs(), b.abs());
        Self::new_unchecked(mig, select(ma > mb, ma, mb))
    }

    /// `min(x, y)` taken pointwise. Exact.
    #[inline(always)]
    pub fn min(self, rhs: Self) -> Self {
        if self.is_empty() || rhs.is_empty() {
            return Self::EMPTY;
        }
        Self::new_unchecked(self.lo.min_nan(rhs.lo), self.hi.min_nan(rhs.hi))
    }

    /// `max(x, y)` taken pointwise. Exact.
    #[inline(always)]
    pub fn max(self, rhs: Self) -> Self {
        if self.is_empty() || rhs.is_empty() {
            return Self::EMPTY;
        }
        Self::new_unchecked(self.lo.max_nan(rhs.lo), self.hi.max_nan(rhs.hi))
    }
}

macro_rules! binary_op {
    ($trait:ident, $method:ident) => {
        impl<T: Float> $trait for Interval<T> {
            type Output = Interval<T>;
            #[inline]
            fn $method(self, rhs: Self) -> Self {
                Interval::$method(self, rhs)
            }
        }
        impl<T: Float> $trait<&Interval<T>> for Interval<T> {
            type Output = Interval<T>;
            #[inline]
            fn $method(self, rhs: &Self) -> Self {
                Interval::$method(self, *rhs)
            }
        }
        impl<T: Float> $trait<Interval<T>> for &Interval<T> {
            type Output = Interval<T>;
            #[inline]
            fn $method(self, rhs: Interval<T>) -> Interval<T> {
                Interval::$method(*self, rhs)
            }
        }
        impl<T: Float> $trait<&Interval<T>> for &Interval<T> {
            type Output = Interval<T>;
            #[inline]
            fn $method(self, rhs: &Interval<T>) -> Interval<T> {
                Interval::$method(*self, *rhs)
            }
        }
    };
}

binary_op!(Add, add);
binary_op!(Sub, sub);
binary_op!(Mul, mul);
binary_op!(Div, div);

impl<T: Float> Neg for Interval<T> {
    type Output = Interval<T>;
    #[inline]
    fn neg(self) -> Self {
        Interval::neg(self)
    }
}

impl<T: Float> Neg for &Interval<T> {
    type Output = Interval<T>;
    #[inline]
    fn neg(self) -> Interval<T> {
        Interval::neg(*self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn sign_cases_of_mul() {
        assert_eq!(iv(1.0, 2.0) * iv(3.0, 4.0), iv(3.0, 8.0));
        assert_eq!(iv(-1.0, 2.0) * iv(3.0, 4.0), iv(-4.0, 8.0));
        assert_eq!(iv(-1.0, 2.0) * iv(-3.0, 4.0), iv(-6.0, 8.0));
        assert_eq!(iv(-2.0, -1.0) * iv(-3.0, 4.0), iv(-8.0, 6.0));
        assert_eq!(iv(0.0, 0.0) * Interval::ENTIRE, iv(0.0, 0.0));
        assert_eq!(
            iv(1.0, f64::INFINITY) * iv(0.0, 1.0),
            iv(0.0, f64::INFINITY)
        );
    }

    #[test]
    fn division_by_zero_containing() {
        assert_eq!(iv(1.0, 2.0) / iv(0.0, 0.0), Interval::EMPTY);
        assert_eq!(iv(1.0, 2.0) / iv(0.0, 4.0), iv(0.25, f64::INFINITY));
        assert_eq!(iv(1.0, 2.0) / iv(-4.0, 0.0), iv(f64::NEG_INFINITY, -0.25));
        assert_eq!(iv(-1.0, 2.0) / iv(-4.0, 0.0), Interval::ENTIRE);
        assert_eq!(iv(1.0, 2.0) / iv(-1.0, 1.0), Interval::ENTIRE);
        assert_eq!(iv(0.0, 0.0) / iv(-3.0, 3.0), iv(0.0, 0.0));
        assert_eq!(iv(-30.0, 0.0) / iv(0.0, 3.0), iv(f64::NEG_INFINITY, 0.0));
        assert_eq!(iv(-30.0, 0.0) / iv(-3.0, 0.0), iv(0.0, f64::INFINITY));
        assert_eq!(iv(0.0, 5.0) / iv(-3.0, 0.0), iv(f64::NEG_INFINITY, 0.0));
    }

    #[test]
    fn sqr_is_tighter_than_mul() {
        assert_eq!(iv(-1.0, 2.0).sqr(), iv(0.0, 4.0));
        assert_eq!(iv(-1.0, 2.0) * iv(-1.0, 2.0), iv(-2.0, 4.0));
    }

    #[test]
    fn fma_rounds_once() {
        // 0.1·10 − 1 is exactly 2^-54·(something); fma keeps it, mul-then-add loses it.
        let x = iv(0.1, 0.1);
        let r = x.fma(iv(10.0, 10.0), iv(-1.0, -1.0));
        assert!(r.inf() > 0.0);
        assert!(r.is_singleton());
    }
}
