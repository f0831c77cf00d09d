//! The rounding of modal results: [`Outer`] for `Out(fR(X))` (*-semantics) and [`Inner`]
//! for `Inn(fR(X))` (**-semantics).
//!
//! A modal interval `[a, b]` is rounded by rounding its two canonical bounds separately:
//!
//! | marker | first bound `a` | second bound `b` | result vs exact `E` | serves |
//! |---|---|---|---|---|
//! | [`Outer`] | toward −∞ | toward +∞ | `E ⊆ Out(E)` | `f*(X) ⊆ Out(fR(X))` |
//! | [`Inner`] | toward +∞ | toward −∞ | `Inn(E) ⊆ E` | `Inn(fR(X)) ⊆ f**(X)` |
//!
//! The inclusion is the modal one, `[x1, x2] ⊆ [y1, y2] ⇔ x1 ≥ y1, x2 ≤ y2`, so outer
//! rounding makes a proper result wider and an improper one narrower, and inner rounding the
//! reverse. Exchanging the two bounds (`dual`) exchanges the two roundings.

use crate::float::Float;
use core::fmt::Debug;
use core::hash::Hash;

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::Outer {}
    impl Sealed for super::Inner {}
}

/// The direction in which the bounds of modal results are rounded: [`Outer`] or [`Inner`].
///
/// The trait is sealed; it only carries the choice in the type, so that one generic
/// expression evaluated on `Modal<T, Outer>` gives `Out(fR(X))` and on `Modal<T, Inner>`
/// gives `Inn(fR(X))`.
pub trait Rounding:
    sealed::Sealed + Copy + Default + Debug + PartialEq + Eq + Hash + Send + Sync + 'static
{
    /// The rounding with both directions exchanged (`Outer` ↔ `Inner`). For `+ − ·`, and
    /// for `/` when `0 ∉ Prop(Y)`, `dual(X ∘ Y)` rounded by `R` equals `dual X ∘ dual Y`
    /// rounded by `R::Dual`.
    type Dual: Rounding<Dual = Self>;
    /// `"outer"` or `"inner"`, for messages.
    const NAME: &'static str;
    /// True for [`Outer`]: the first bound is rounded toward −∞ and the second toward +∞.
    const IS_OUTER: bool;
}

/// Outer rounding: first bound toward −∞, second toward +∞. The computed interval contains
/// the exact one in the modal inclusion (`Out`, for the *-semantic theorem). This is the
/// default rounding of [`Modal`](super::Modal).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Outer;

/// Inner rounding: first bound toward +∞, second toward −∞. The computed interval is
/// contained in the exact one in the modal inclusion (`Inn`, for the **-semantic theorem).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Inner;

impl Rounding for Outer {
    type Dual = Inner;
    const NAME: &'static str = "outer";
    const IS_OUTER: bool = true;
}

impl Rounding for Inner {
    type Dual = Outer;
    const NAME: &'static str = "inner";
    const IS_OUTER: bool = false;
}

// One directed-rounded operation per result bound. `*1` rounds a first (canonical lower)
// bound, `*2` a second one. `R::IS_OUTER` is a constant, so each call is one branch-free
// directed operation after inlining.

/// The value a first bound takes when it is undefined (`∞ − ∞`, `∞ / ∞`): the least
/// informative one for the rounding, −∞ for outer and +∞ for inner.
#[inline(always)]
pub(crate) fn unbounded1<T: Float, R: Rounding>() -> T {
    if R::IS_OUTER {
        T::NEG_INFINITY
    } else {
        T::INFINITY
    }
}

/// The value a second bound takes when it is undefined: +∞ for outer, −∞ for inner.
#[inline(always)]
pub(crate) fn unbounded2<T: Float, R: Rounding>() -> T {
    if R::IS_OUTER {
        T::INFINITY
    } else {
        T::NEG_INFINITY
    }
}

/// Replaces a NaN first bound by [`unbounded1`].
#[inline(always)]
pub(crate) fn fix1<T: Float, R: Rounding>(x: T) -> T {
    if x.is_nan() { unbounded1::<T, R>() } else { x }
}

/// Replaces a NaN second bound by [`unbounded2`].
#[inline(always)]
pub(crate) fn fix2<T: Float, R: Rounding>(x: T) -> T {
    if x.is_nan() { unbounded2::<T, R>() } else { x }
}

/// The smaller of two bounds (modal bounds are never NaN).
#[inline(always)]
pub(crate) fn fmin<T: Float>(x: T, y: T) -> T {
    if y < x { y } else { x }
}

/// The larger of two bounds (modal bounds are never NaN).
#[inline(always)]
pub(crate) fn fmax<T: Float>(x: T, y: T) -> T {
    if y > x { y } else { x }
}

/// `x + y` rounded toward +∞ (`up`) or −∞.
#[inline(always)]
fn add_dir<T: Float>(x: T, y: T, up: bool) -> T {
    if up { x.add_up(y) } else { x.add_down(y) }
}

/// `x + y` rounded for a first bound.
#[inline(always)]
pub(crate) fn add1<T: Float, R: Rounding>(x: T, y: T) -> T {
    fix1::<T, R>(add_dir(x, y, !R::IS_OUTER))
}

/// `x + y` rounded for a second bound.
#[inline(always)]
pub(crate) fn add2<T: Float, R: Rounding>(x: T, y: T) -> T {
    fix2::<T, R>(add_dir(x, y, R::IS_OUTER))
}

/// `x − y` rounded for a first bound.
#[inline(always)]
pub(crate) fn sub1<T: Float, R: Rounding>(x: T, y: T) -> T {
    add1::<T, R>(x, -y)
}

/// `x − y` rounded for a second bound.
#[inline(always)]
pub(crate) fn sub2<T: Float, R: Rounding>(x: T, y: T) -> T {
    add2::<T, R>(x, -y)
}

/// `x · y` rounded for a first bound (`0 · ∞ = 0`).
#[inline(always)]
pub(crate) fn mul1<T: Float, R: Rounding>(x: T, y: T) -> T {
    if R::IS_OUTER {
        x.mul_down(y)
    } else {
        x.mul_up(y)
    }
}

/// `x · y` rounded for a second bound (`0 · ∞ = 0`).
#[inline(always)]
pub(crate) fn mul2<T: Float, R: Rounding>(x: T, y: T) -> T {
    if R::IS_OUTER {
        x.mul_up(y)
    } else {
        x.mul_down(y)
    }
}

/// `x / y` (`y ≠ 0`) rounded for a first bound.
#[inline(always)]
pub(crate) fn div1<T: Float, R: Rounding>(x: T, y: T) -> T {
    fix1::<T, R>(if R::IS_OUTER {
        x.div_down(y)
    } else {
        x.div_up(y)
    })
}

/// `x / y` (`y ≠ 0`) rounded for a second bound.
#[inline(always)]
pub(crate) fn div2<T: Float, R: Rounding>(x: T, y: T) -> T {
    fix2::<T, R>(if R::IS_OUTER {
        x.div_up(y)
    } else {
        x.div_down(y)
    })
}

/// `x` given as `f64`, converted to `T` with the rounding of a first bound.
#[inline(always)]
pub(crate) fn from_f64_1<T: Float, R: Rounding>(x: f64) -> T {
    if R::IS_OUTER {
        T::from_f64_down(x)
    } else {
        T::from_f64_up(x)
    }
}

/// `x` given as `f64`, converted to `T` with the rounding of a second bound.
#[inline(always)]
pub(crate) fn from_f64_2<T: Float, R: Rounding>(x: f64) -> T {
    if R::IS_OUTER {
        T::from_f64_up(x)
    } else {
        T::from_f64_down(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions() {
        let third_lo = 1.0f64.div_down(3.0);
        let third_hi = 1.0f64.div_up(3.0);
        assert!(third_lo < third_hi);
        assert_eq!(div1::<f64, Outer>(1.0, 3.0), third_lo);
        assert_eq!(div2::<f64, Outer>(1.0, 3.0), third_hi);
        assert_eq!(div1::<f64, Inner>(1.0, 3.0), third_hi);
        assert_eq!(div2::<f64, Inner>(1.0, 3.0), third_lo);
    }

    #[test]
    fn undefined_bounds_become_least_informative() {
        let inf = f64::INFINITY;
        assert_eq!(add1::<f64, Outer>(inf, -inf), -inf);
        assert_eq!(add2::<f64, Outer>(inf, -inf), inf);
        assert_eq!(add1::<f64, Inner>(inf, -inf), inf);
        assert_eq!(add2::<f64, Inner>(inf, -inf), -inf);
        assert_eq!(
            div1::<f32, Outer>(f32::INFINITY, f32::INFINITY),
            f32::NEG_INFINITY
        );
        assert_eq!(
            div2::<f32, Inner>(f32::INFINITY, f32::INFINITY),
            f32::NEG_INFINITY
        );
    }

    /// Directed sums with an operand in the top binade, checked against exact rationals.
    #[test]
    fn sums_near_overflow_are_directed() {
        use rug::Rational;
        fn check<T: Float>(x: T, y: T) {
            let r = |v: T| Rational::from_f64(v.to_f64()).unwrap();
            let exact = r(x) + r(y);
            let max = r(T::MAX);
            let (lo, hi) = (add_dir(x, y, false), add_dir(x, y, true));
            // lo is the exact sum rounded down: lo ≤ exact < next_up(lo), or −∞ below −MAX.
            if lo == T::NEG_INFINITY {
                assert!(exact < -max.clone());
            } else {
                assert!(r(lo) <= exact);
                assert!(lo.next_up() == T::INFINITY || exact < r(lo.next_up()));
            }
            if hi == T::INFINITY {
                assert!(exact > max);
            } else {
                assert!(r(hi) >= exact);
                assert!(hi.next_down() == T::NEG_INFINITY || exact > r(hi.next_down()));
            }
        }
        check(-4.770813245647214e307, f64::MAX);
        check(-1.6203908e38f32, f32::MAX);
        check(f64::MAX, 5e-324);
        check(f64::MAX, -5e-324);
        check(f32::MAX, f32::MAX);
        check(-f32::MAX, -f32::MAX);
        check(f64::MAX, -f64::MAX);
        check(f32::MAX * 0.75, f32::MAX * 0.5);
        check(-f64::MAX * 0.75, 1.5);
        let mut v = 0.6f64;
        for _ in 0..200 {
            v = (v * 3.9 * (1.0 - v)).clamp(0.01, 0.99);
            check(f64::MAX * v, -f64::MAX * (1.0 - v) * 0.9);
            check(f32::MAX * v as f32, -f32::MAX * (0.5 + v as f32 / 3.0));
        }
    }
}
