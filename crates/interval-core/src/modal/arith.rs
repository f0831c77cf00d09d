//! Kaucher arithmetic on modal intervals: `+ − · /` and negation, each bound computed by one
//! directed-rounded operation in the direction the rounding marker asks for.
//!
//! For the four arithmetic operators the semantic extensions coincide, `f* = f**`, and
//! Kaucher's formulas compute them from the bounds. With `A = [a1, a2]`, `B = [b1, b2]`:
//!
//! * `−A = [−a2, −a1]` (exact),
//! * `A + B = [a1 + b1, a2 + b2]`,
//! * `A − B = A + (−B) = [a1 − b2, a2 − b1]`,
//! * `A · B` by the classes of `A` and `B` (table below),
//! * `A / B = A · [1/b2, 1/b1]` when `0 ∉ Prop(B)`, computed as single rounded quotients.
//!
//! Classes (a point `[0, 0]` counts as `P`; on the overlaps the formulas agree):
//!
//! | class | bounds | meaning |
//! |---|---|---|
//! | `P` | `a1 ≥ 0, a2 ≥ 0` | non-negative, proper or improper |
//! | `−P` | `a1 ≤ 0, a2 ≤ 0`, not both 0 | non-positive |
//! | `Z` | `a1 < 0 < a2` | proper, 0 inside |
//! | `dual Z` | `a1 > 0 > a2` | improper, 0 inside |
//!
//! Multiplication `A · B` (rows: class of `A`, columns: class of `B`):
//!
//! | `A \ B` | `P` | `Z` | `−P` | `dual Z` |
//! |---|---|---|---|---|
//! | `P` | `[a1b1, a2b2]` | `[a2b1, a2b2]` | `[a2b1, a1b2]` | `[a1b1, a1b2]` |
//! | `Z` | `[a1b2, a2b2]` | `[min(a1b2, a2b1), max(a1b1, a2b2)]` | `[a2b1, a1b1]` | `[0, 0]` |
//! | `−P` | `[a1b2, a2b1]` | `[a1b2, a1b1]` | `[a2b2, a1b1]` | `[a2b2, a2b1]` |
//! | `dual Z` | `[a1b1, a2b1]` | `[0, 0]` | `[a2b2, a1b2]` | `[max(a1b1, a2b2), min(a1b2, a2b1)]` |
//!
//! Division `A / B` for `0 ∉ Prop(B)` (`B` in `P` or `−P` with no zero bound):
//!
//! | `A \ B` | `P` | `−P` |
//! |---|---|---|
//! | `P` | `[a1/b2, a2/b1]` | `[a2/b2, a1/b1]` |
//! | `Z` | `[a1/b1, a2/b1]` | `[a2/b2, a1/b2]` |
//! | `−P` | `[a1/b1, a2/b2]` | `[a2/b1, a1/b2]` |
//! | `dual Z` | `[a1/b2, a2/b2]` | `[a2/b1, a1/b1]` |
//!
//! Division when `0 ∈ Prop(B)` (including `B = [0, 0]`) is undefined in Kaucher
//! arithmetic. [`Modal::checked_div`] returns `None`; `/` returns the least informative
//! answer that is still sound for the rounding:
//!
//! | rounding | `A`, `B` | result |
//! |---|---|---|
//! | [`Outer`](super::Outer) | both proper (finite points count, the points at `±∞` do not), `B ≠ [0, 0]` | classical hull division [`Interval::div`](crate::Interval::div) of the sets (a half-line or `[−∞, +∞]`) |
//! | [`Outer`](super::Outer) | otherwise | [`Modal::ENTIRE`] `= [−∞, +∞]`, which includes every `f*` |
//! | [`Inner`](super::Inner) | any | [`Modal::DUAL_ENTIRE`] `= [+∞, −∞]`, included in everything |
//!
//! Infinite bounds: `0 · ∞ = 0` as for classical intervals. A bound that would be
//! undefined (`∞ − ∞` in a sum, `∞ / ∞` in a quotient) is replaced by the least informative
//! value for the rounding (`−∞` for an outer first bound, `+∞` for an outer second bound,
//! the opposite for inner), so no result ever holds NaN.
//!
//! With finite bounds every result is *tight*: outer rounding returns the exact Kaucher
//! result with its first bound rounded down and its second rounded up to the nearest
//! representable numbers, inner rounding the opposite (checked against an exact rational
//! oracle of `f*` and `f**` in the test suite).

use super::Modal;
use super::rounding::{self as rnd, Rounding, fmax, fmin};
use crate::float::Float;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// The four Kaucher classes of a modal interval.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Class {
    /// `a1 ≥ 0, a2 ≥ 0` (includes `[0, 0]`).
    Pos,
    /// `a1 ≤ 0, a2 ≤ 0`, not both zero.
    Neg,
    /// `a1 < 0 < a2`.
    Zero,
    /// `a1 > 0 > a2`.
    DualZero,
}

#[inline(always)]
fn class<T: Float>(a1: T, a2: T) -> Class {
    let z = T::ZERO;
    if a1 >= z && a2 >= z {
        Class::Pos
    } else if a1 <= z && a2 <= z {
        Class::Neg
    } else if a1 < z {
        Class::Zero
    } else {
        Class::DualZero
    }
}

impl<T: Float, R: Rounding> Modal<T, R> {
    /// Kaucher negation `−[a1, a2] = [−a2, −a1]`. Exact; keeps the modality.
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn neg(self) -> Self {
        Self::new_unchecked(-self.b, -self.a)
    }

    /// Kaucher sum `[a1 + b1, a2 + b2]`, tight for the rounding `R`.
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, rhs: Self) -> Self {
        Self::new_unchecked(
            rnd::add1::<T, R>(self.a, rhs.a),
            rnd::add2::<T, R>(self.b, rhs.b),
        )
    }

    /// Kaucher difference `A + (−B) = [a1 − b2, a2 − b1]`, tight for the rounding `R`.
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn sub(self, rhs: Self) -> Self {
        Self::new_unchecked(
            rnd::sub1::<T, R>(self.a, rhs.b),
            rnd::sub2::<T, R>(self.b, rhs.a),
        )
    }

    /// Kaucher product by the 16-case table of the [module documentation](self), tight for
    /// the rounding `R`.
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn mul(self, rhs: Self) -> Self {
        let (a1, a2, b1, b2) = (self.a, self.b, rhs.a, rhs.b);
        let m1 = rnd::mul1::<T, R>;
        let m2 = rnd::mul2::<T, R>;
        let z = T::ZERO;
        let (lo, hi) = match (class(a1, a2), class(b1, b2)) {
            (Class::Pos, Class::Pos) => (m1(a1, b1), m2(a2, b2)),
            (Class::Pos, Class::Zero) => (m1(a2, b1), m2(a2, b2)),
            (Class::Pos, Class::Neg) => (m1(a2, b1), m2(a1, b2)),
            (Class::Pos, Class::DualZero) => (m1(a1, b1), m2(a1, b2)),
            (Class::Zero, Class::Pos) => (m1(a1, b2), m2(a2, b2)),
            (Class::Zero, Class::Zero) => {
                (fmin(m1(a1, b2), m1(a2, b1)), fmax(m2(a1, b1), m2(a2, b2)))
            }
            (Class::Zero, Class::Neg) => (m1(a2, b1), m2(a1, b1)),
            (Class::Zero, Class::DualZero) => (z, z),
            (Class::Neg, Class::Pos) => (m1(a1, b2), m2(a2, b1)),
            (Class::Neg, Class::Zero) => (m1(a1, b2), m2(a1, b1)),
            (Class::Neg, Class::Neg) => (m1(a2, b2), m2(a1, b1)),
            (Class::Neg, Class::DualZero) => (m1(a2, b2), m2(a2, b1)),
            (Class::DualZero, Class::Pos) => (m1(a1, b1), m2(a2, b1)),
            (Class::DualZero, Class::Zero) => (z, z),
            (Class::DualZero, Class::Neg) => (m1(a2, b2), m2(a1, b2)),
            (Class::DualZero, Class::DualZero) => {
                (fmax(m1(a1, b1), m1(a2, b2)), fmin(m2(a1, b2), m2(a2, b1)))
            }
        };
        Self::new_unchecked(lo, hi)
    }

    /// Kaucher quotient `A · [1/b2, 1/b1]` when `0 ∉ Prop(B)`, each bound one rounded
    /// quotient `ai / bj` (tight); `None` when `0 ∈ Prop(B)`, where Kaucher division is
    /// undefined.
    #[inline]
    pub fn checked_div(self, rhs: Self) -> Option<Self> {
        let (a1, a2, b1, b2) = (self.a, self.b, rhs.a, rhs.b);
        let z = T::ZERO;
        let d1 = rnd::div1::<T, R>;
        let d2 = rnd::div2::<T, R>;
        let (lo, hi) = if b1 > z && b2 > z {
            match class(a1, a2) {
                Class::Pos => (d1(a1, b2), d2(a2, b1)),
                Class::Zero => (d1(a1, b1), d2(a2, b1)),
                Class::Neg => (d1(a1, b1), d2(a2, b2)),
                Class::DualZero => (d1(a1, b2), d2(a2, b2)),
            }
        } else if b1 < z && b2 < z {
            match class(a1, a2) {
                Class::Pos => (d1(a2, b2), d2(a1, b1)),
                Class::Zero => (d1(a2, b2), d2(a1, b2)),
                Class::Neg => (d1(a2, b1), d2(a1, b2)),
                Class::DualZero => (d1(a2, b1), d2(a1, b1)),
            }
        } else {
            return None;
        };
        Some(Self::new_unchecked(lo, hi))
    }

    /// Kaucher quotient. When `0 ∉ Prop(B)` this is [`Modal::checked_div`]. Otherwise the
    /// operation is undefined and the result is, as tabled in the
    /// [module documentation](self): for outer rounding the classical hull division
    /// when both operands are proper (and `B ≠ [0, 0]`), else [`Modal::ENTIRE`]; for inner
    /// rounding [`Modal::DUAL_ENTIRE`].
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn div(self, rhs: Self) -> Self {
        if let Some(q) = self.checked_div(rhs) {
            return q;
        }
        if !R::IS_OUTER {
            return Self::DUAL_ENTIRE;
        }
        let zero_divisor = rhs.a == T::ZERO && rhs.b == T::ZERO;
        let (x, y) = (self.prop(), rhs.prop());
        // `prop` is empty for the points at ±∞, which denote no real number.
        if self.is_proper()
            && rhs.is_proper()
            && !zero_divisor
            && !x.is_empty()
            && !y.is_empty()
            && let Some((lo, hi)) = x.div(y).bounds()
        {
            return Self::new_unchecked(rnd::fix1::<T, R>(lo), rnd::fix2::<T, R>(hi));
        }
        Self::ENTIRE
    }

    /// `1 / self`, i.e. `[1, 1] / self`: `[1/a2, 1/a1]` when `0 ∉ Prop(self)`, rounded as
    /// [`Modal::div`] says otherwise.
    #[inline]
    pub fn recip(self) -> Self {
        Self::ONE.div(self)
    }
}

macro_rules! binary_op {
    ($trait:ident, $method:ident) => {
        impl<T: Float, R: Rounding> $trait for Modal<T, R> {
            type Output = Modal<T, R>;
            #[inline]
            fn $method(self, rhs: Self) -> Self {
                Modal::$method(self, rhs)
            }
        }
        impl<T: Float, R: Rounding> $trait<&Modal<T, R>> for Modal<T, R> {
            type Output = Modal<T, R>;
            #[inline]
            fn $method(self, rhs: &Self) -> Self {
                Modal::$method(self, *rhs)
            }
        }
        impl<T: Float, R: Rounding> $trait<Modal<T, R>> for &Modal<T, R> {
            type Output = Modal<T, R>;
            #[inline]
            fn $method(self, rhs: Modal<T, R>) -> Modal<T, R> {
                Modal::$method(*self, rhs)
            }
        }
        impl<T: Float, R: Rounding> $trait<&Modal<T, R>> for &Modal<T, R> {
            type Output = Modal<T, R>;
            #[inline]
            fn $method(self, rhs: &Modal<T, R>) -> Modal<T, R> {
                Modal::$method(*self, *rhs)
            }
        }
    };
}

binary_op!(Add, add);
binary_op!(Sub, sub);
binary_op!(Mul, mul);
binary_op!(Div, div);

impl<T: Float, R: Rounding> Neg for Modal<T, R> {
    type Output = Modal<T, R>;
    #[inline]
    fn neg(self) -> Self {
        Modal::neg(self)
    }
}

impl<T: Float, R: Rounding> Neg for &Modal<T, R> {
    type Output = Modal<T, R>;
    #[inline]
    fn neg(self) -> Modal<T, R> {
        Modal::neg(*self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::{Inner, Outer};

    fn m(a: f64, b: f64) -> Modal<f64> {
        Modal::new(a, b).unwrap()
    }

    #[test]
    fn classes() {
        assert_eq!(class(0.0, 0.0), Class::Pos);
        assert_eq!(class(0.0, 2.0), Class::Pos);
        assert_eq!(class(2.0, 0.0), Class::Pos);
        assert_eq!(class(-1.0, 0.0), Class::Neg);
        assert_eq!(class(0.0, -1.0), Class::Neg);
        assert_eq!(class(-1.0, 1.0), Class::Zero);
        assert_eq!(class(1.0, -1.0), Class::DualZero);
    }

    #[test]
    fn thesis_sum() {
        assert_eq!(m(1.0, 3.0) + m(3.0, 2.0), m(4.0, 5.0));
    }

    #[test]
    fn products_of_dual_classes() {
        assert_eq!(m(-1.0, 2.0) * m(3.0, -4.0), m(0.0, 0.0));
        assert_eq!(m(2.0, -1.0) * m(-4.0, 3.0), m(0.0, 0.0));
        assert_eq!(m(2.0, -1.0) * m(3.0, -4.0), m(6.0, -8.0));
        assert_eq!(m(-1.0, 2.0) * m(-4.0, 3.0), m(-8.0, 6.0));
    }

    #[test]
    fn division_by_zero_containing_divisors() {
        let one_two = m(1.0, 2.0);
        assert_eq!(one_two.checked_div(m(-1.0, 1.0)), None);
        assert_eq!(one_two / m(0.0, 4.0), m(0.25, f64::INFINITY));
        assert_eq!(one_two / m(0.0, 0.0), Modal::ENTIRE);
        assert_eq!(one_two / m(1.0, -1.0), Modal::ENTIRE);
        let inner = one_two.with_rounding::<Inner>();
        assert_eq!(inner / m(0.0, 4.0).with_rounding(), Modal::DUAL_ENTIRE);
        let _: Modal<f64, Outer> = one_two.recip();
    }

    #[test]
    fn no_nan_from_infinite_bounds() {
        let inf = f64::INFINITY;
        let x = m(inf, 5.0);
        let y = m(-inf, 0.0);
        assert_eq!(x + y, m(-inf, 5.0));
        let xi = x.with_rounding::<Inner>();
        let yi = y.with_rounding::<Inner>();
        let s = xi + yi;
        assert_eq!((s.first(), s.second()), (inf, 5.0));
        let q = m(inf, 1.0) / m(inf, 1.0);
        assert!(!q.first().is_nan() && !q.second().is_nan());
    }
}
