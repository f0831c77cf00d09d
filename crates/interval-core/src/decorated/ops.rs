//! The operations of decorated intervals: every operation of [`Interval`] that is a point
//! function (arithmetic, elementary and integer functions, `pown`, `pow`, `atan2`, ...) with
//! the propagation rule of IEEE 1788 §11.7, and the set, cancellative and reverse operations
//! with the decoration `trv`.
//!
//! The interval part of each result is exactly the plain operation's result, so the accuracy
//! of every decorated operation is that of the plain one (see `docs/numerics.md`).

use super::rules;
use super::{DecInterval, Decoration};
use crate::float::Float;
use crate::interval::Interval;
use core::ops::{Add, Div, Mul, Neg, Sub};

impl<T: Float> DecInterval<T> {
    /// The decorated result `y = f(x…)` of an operation with local decoration `local` on
    /// inputs of decorations `inputs`: NaI if an input is NaI; otherwise
    /// `min(inputs, local, bounded(y) ? com : dac)`.
    fn result(y: Interval<T>, inputs: &[Decoration], local: Decoration) -> Self {
        if inputs.contains(&Decoration::Ill) {
            return Self::NAI;
        }
        let min_in = inputs.iter().copied().min().unwrap_or(Decoration::Com);
        let d = min_in.min(local);
        Self::set_dec(y, d)
    }

    /// A unary point function with its domain rule.
    fn unary(
        self,
        f: impl Fn(Interval<T>) -> Interval<T>,
        rule: fn(Interval<T>) -> Decoration,
    ) -> Self {
        if self.is_nai() {
            return Self::NAI;
        }
        Self::result(f(self.x), &[self.d], rule(self.x))
    }

    /// A binary point function with its domain rule.
    fn binary(
        self,
        y: Self,
        f: impl Fn(Interval<T>, Interval<T>) -> Interval<T>,
        rule: fn(Interval<T>, Interval<T>) -> Decoration,
    ) -> Self {
        if self.is_nai() || y.is_nai() {
            return Self::NAI;
        }
        Self::result(f(self.x, y.x), &[self.d, y.d], rule(self.x, y.x))
    }

    /// A set or reverse operation: the plain result, decorated `trv` (NaI propagates).
    fn trivial(inputs: &[Self], y: Interval<T>) -> Self {
        if inputs.iter().any(|v| v.is_nai()) {
            Self::NAI
        } else {
            Self::set_dec(y, Decoration::Trv)
        }
    }

    /// `x + y`; defined and continuous everywhere.
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, y: Self) -> Self {
        self.binary(y, Interval::add, |_, _| Decoration::Com)
    }

    /// `x − y`; defined and continuous everywhere.
    #[allow(clippy::should_implement_trait)]
    pub fn sub(self, y: Self) -> Self {
        self.binary(y, Interval::sub, |_, _| Decoration::Com)
    }

    /// `x · y`; defined and continuous everywhere.
    #[allow(clippy::should_implement_trait)]
    pub fn mul(self, y: Self) -> Self {
        self.binary(y, Interval::mul, |_, _| Decoration::Com)
    }

    /// `x / y`; defined and continuous where `0 ∉ y`, `trv` otherwise.
    #[allow(clippy::should_implement_trait)]
    pub fn div(self, y: Self) -> Self {
        self.binary(y, Interval::div, rules::div)
    }

    /// `−x`; defined and continuous everywhere.
    #[allow(clippy::should_implement_trait)]
    pub fn neg(self) -> Self {
        self.unary(Interval::neg, rules::everywhere)
    }

    /// `x · y + z` with one rounding per bound; defined and continuous everywhere.
    pub fn fma(self, y: Self, z: Self) -> Self {
        if self.is_nai() || y.is_nai() || z.is_nai() {
            return Self::NAI;
        }
        Self::result(self.x.fma(y.x, z.x), &[self.d, y.d, z.d], Decoration::Com)
    }

    /// `xⁿ`; everywhere for `n ≥ 0`, where `0 ∉ x` for `n < 0`.
    pub fn pown(self, n: i32) -> Self {
        if self.is_nai() {
            return Self::NAI;
        }
        Self::result(self.x.pown(n), &[self.d], rules::pown(self.x, n))
    }

    /// `x^(1/n)`; see [`rules::rootn`] for the domain.
    pub fn rootn(self, n: i32) -> Self {
        if self.is_nai() {
            return Self::NAI;
        }
        Self::result(self.x.rootn(n), &[self.d], rules::rootn(self.x, n))
    }

    /// `xʸ` on `{x > 0} ∪ {x = 0, y > 0}`.
    pub fn pow(self, y: Self) -> Self {
        self.binary(y, Interval::pow, rules::pow)
    }

    /// `atan2(self, x)`: `trv` if the box holds the origin, `def` if it crosses the cut.
    pub fn atan2(self, x: Self) -> Self {
        self.binary(x, Interval::atan2, rules::atan2)
    }

    /// `√(x² + y²)`; defined and continuous everywhere.
    pub fn hypot(self, y: Self) -> Self {
        self.binary(y, Interval::hypot, |_, _| Decoration::Com)
    }

    /// Pointwise minimum; defined and continuous everywhere.
    pub fn min(self, y: Self) -> Self {
        self.binary(y, Interval::min, |_, _| Decoration::Com)
    }

    /// Pointwise maximum; defined and continuous everywhere.
    pub fn max(self, y: Self) -> Self {
        self.binary(y, Interval::max, |_, _| Decoration::Com)
    }

    /// `self ∩ y`, decorated `trv` (a set operation).
    pub fn intersection(self, y: Self) -> Self {
        Self::trivial(&[self, y], self.x.intersection(y.x))
    }

    /// The convex hull of `self ∪ y`, decorated `trv` (a set operation).
    pub fn convex_hull(self, y: Self) -> Self {
        Self::trivial(&[self, y], self.x.convex_hull(y.x))
    }

    /// `cancelMinus(self, y)`, decorated `trv`.
    pub fn cancel_minus(self, y: Self) -> Self {
        Self::trivial(&[self, y], self.x.cancel_minus(y.x))
    }

    /// `cancelPlus(self, y)`, decorated `trv`.
    pub fn cancel_plus(self, y: Self) -> Self {
        Self::trivial(&[self, y], self.x.cancel_plus(y.x))
    }

    /// `mulRev(self, c, x)`, decorated `trv` (a reverse operation).
    pub fn mul_rev_in(self, c: Self, x: Self) -> Self {
        Self::trivial(&[self, c, x], self.x.mul_rev_in(c.x, x.x))
    }

    /// `sqrRev(self, x)`, decorated `trv`.
    pub fn sqr_rev_in(self, x: Self) -> Self {
        Self::trivial(&[self, x], self.x.sqr_rev_in(x.x))
    }

    /// `absRev(self, x)`, decorated `trv`.
    pub fn abs_rev_in(self, x: Self) -> Self {
        Self::trivial(&[self, x], self.x.abs_rev_in(x.x))
    }

    /// `pownRev(self, x, n)`, decorated `trv`.
    pub fn pown_rev_in(self, x: Self, n: i32) -> Self {
        Self::trivial(&[self, x], self.x.pown_rev_in(x.x, n))
    }

    /// `coshRev(self, x)`, decorated `trv`.
    pub fn cosh_rev_in(self, x: Self) -> Self {
        Self::trivial(&[self, x], self.x.cosh_rev_in(x.x))
    }

    /// `sinRev(self, x)`, decorated `trv`.
    pub fn sin_rev_in(self, x: Self) -> Self {
        Self::trivial(&[self, x], self.x.sin_rev_in(x.x))
    }

    /// `cosRev(self, x)`, decorated `trv`.
    pub fn cos_rev_in(self, x: Self) -> Self {
        Self::trivial(&[self, x], self.x.cos_rev_in(x.x))
    }

    /// `tanRev(self, x)`, decorated `trv`.
    pub fn tan_rev_in(self, x: Self) -> Self {
        Self::trivial(&[self, x], self.x.tan_rev_in(x.x))
    }

    /// `powRev1(self, c, x)`, decorated `trv`.
    pub fn pow_rev1_in(self, c: Self, x: Self) -> Self {
        Self::trivial(&[self, c, x], self.x.pow_rev1_in(c.x, x.x))
    }

    /// `powRev2(self, c, y)`, decorated `trv`.
    pub fn pow_rev2_in(self, c: Self, y: Self) -> Self {
        Self::trivial(&[self, c, y], self.x.pow_rev2_in(c.x, y.x))
    }

    /// `inf` of the interval part (`−0` for a zero lower bound); NaN for NaI.
    pub fn inf(self) -> T {
        if self.is_nai() { T::NAN } else { self.x.inf() }
    }

    /// `sup` of the interval part (`+0` for a zero upper bound); NaN for NaI.
    pub fn sup(self) -> T {
        if self.is_nai() { T::NAN } else { self.x.sup() }
    }

    /// `mid` of the interval part; NaN for NaI and empty.
    pub fn mid(self) -> T {
        if self.is_nai() { T::NAN } else { self.x.mid() }
    }

    /// `wid` of the interval part, rounded up; NaN for NaI and empty.
    pub fn wid(self) -> T {
        if self.is_nai() { T::NAN } else { self.x.wid() }
    }

    /// `rad` of the interval part, rounded up; NaN for NaI and empty.
    pub fn rad(self) -> T {
        if self.is_nai() { T::NAN } else { self.x.rad() }
    }

    /// `mag` of the interval part; NaN for NaI and empty.
    pub fn mag(self) -> T {
        if self.is_nai() { T::NAN } else { self.x.mag() }
    }

    /// `mig` of the interval part; NaN for NaI and empty.
    pub fn mig(self) -> T {
        if self.is_nai() { T::NAN } else { self.x.mig() }
    }
}

/// Unary point functions of decorated intervals: name, domain rule, documentation.
macro_rules! decorated_unary {
    ($($name:ident => $rule:expr, $doc:literal;)*) => {
        impl<T: Float> DecInterval<T> {
            $(
                #[doc = $doc]
                pub fn $name(self) -> Self {
                    self.unary(Interval::$name, $rule)
                }
            )*
        }
    };
}

decorated_unary! {
    recip => rules::nonzero, "`1/x`; defined and continuous where `0 ∉ x`.";
    sqr => rules::everywhere, "`x²`; defined and continuous everywhere.";
    sqrt => rules::non_negative, "`√x`; defined and continuous on `x ≥ 0`.";
    abs => rules::everywhere, "`|x|`; defined and continuous everywhere.";
    exp => rules::everywhere, "`eˣ`; defined and continuous everywhere.";
    exp2 => rules::everywhere, "`2ˣ`; defined and continuous everywhere.";
    exp10 => rules::everywhere, "`10ˣ`; defined and continuous everywhere.";
    expm1 => rules::everywhere, "`eˣ − 1`; defined and continuous everywhere.";
    log => rules::positive, "`ln x`; defined and continuous on `x > 0`.";
    log2 => rules::positive, "`log2 x`; defined and continuous on `x > 0`.";
    log10 => rules::positive, "`log10 x`; defined and continuous on `x > 0`.";
    log1p => rules::above_minus_one, "`ln(1 + x)`; defined and continuous on `x > −1`.";
    sin => rules::everywhere, "`sin x`; defined and continuous everywhere.";
    cos => rules::everywhere, "`cos x`; defined and continuous everywhere.";
    tan => rules::tan, "`tan x`; continuous on a box proved free of poles, `trv` otherwise.";
    asin => rules::unit, "`asin x`; defined and continuous on `[−1, 1]`.";
    acos => rules::unit, "`acos x`; defined and continuous on `[−1, 1]`.";
    atan => rules::everywhere, "`atan x`; defined and continuous everywhere.";
    sinh => rules::everywhere, "`sinh x`; defined and continuous everywhere.";
    cosh => rules::everywhere, "`cosh x`; defined and continuous everywhere.";
    tanh => rules::everywhere, "`tanh x`; defined and continuous everywhere.";
    asinh => rules::everywhere, "`asinh x`; defined and continuous everywhere.";
    acosh => rules::at_least_one, "`acosh x`; defined and continuous on `x ≥ 1`.";
    atanh => rules::open_unit, "`atanh x`; defined and continuous on `(−1, 1)`.";
    floor => |x| rules::step(x, Interval::floor, rules::integer), "`⌊x⌋`; `def` where the box holds a jump.";
    ceil => |x| rules::step(x, Interval::ceil, rules::integer), "`⌈x⌉`; `def` where the box holds a jump.";
    trunc => |x| rules::step(x, Interval::trunc, rules::nonzero_integer), "Truncation; `def` where the box holds a jump.";
    sign => |x| rules::step(x, Interval::sign, rules::zero), "Sign; `def` where the box holds the jump at 0.";
    round_ties_to_even => |x| rules::step(x, Interval::round_ties_to_even, rules::half_integer), "Rounding, ties to even; `def` at a jump.";
    round_ties_to_away => |x| rules::step(x, Interval::round_ties_to_away, rules::half_integer), "Rounding, ties away; `def` at a jump.";
}

macro_rules! decorated_op {
    ($trait:ident, $method:ident) => {
        impl<T: Float> $trait for DecInterval<T> {
            type Output = DecInterval<T>;
            #[inline]
            fn $method(self, rhs: Self) -> Self {
                DecInterval::$method(self, rhs)
            }
        }
    };
}

decorated_op!(Add, add);
decorated_op!(Sub, sub);
decorated_op!(Mul, mul);
decorated_op!(Div, div);

impl<T: Float> Neg for DecInterval<T> {
    type Output = DecInterval<T>;
    #[inline]
    fn neg(self) -> Self {
        DecInterval::neg(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Decoration::*;

    fn d(a: f64, b: f64) -> DecInterval<f64> {
        DecInterval::new(Interval::new(a, b).unwrap())
    }

    fn check(got: DecInterval<f64>, lo: f64, hi: f64, dec: Decoration) {
        assert_eq!(got.interval(), Interval::new(lo, hi).unwrap(), "{got}");
        assert_eq!(got.decoration(), dec, "{got}");
    }

    #[test]
    fn standard_examples() {
        let inf = f64::INFINITY;
        let max = f64::MAX;
        check(d(1.0, 2.0) + d(3.0, 4.0), 4.0, 6.0, Com);
        check(d(1.0, max) + d(1.0, max), 2.0, inf, Dac);
        check(d(-1.0, 4.0).sqrt(), 0.0, 2.0, Trv);
        check(d(0.0, 4.0).sqrt(), 0.0, 2.0, Com);
        check(d(1.0, 2.0) / d(0.0, 1.0), 1.0, inf, Trv);
        check(d(0.5, 1.5).floor(), 0.0, 1.0, Def);
        check(d(1.0, 1.5).floor(), 1.0, 1.0, Dac); // continuous on the box, not at 1
        check(d(1.2, 1.5).floor(), 1.0, 1.0, Com);
        check(d(0.5, 1.0).ceil(), 1.0, 1.0, Dac);
        check(d(2.5, 2.5).round_ties_to_even(), 2.0, 2.0, Dac);
        check(d(3.0, 3.0).round_ties_to_even(), 3.0, 3.0, Com);
        check(d(0.0, 0.0).trunc(), 0.0, 0.0, Com);
        check(d(-1.0, 1.0).sign(), -1.0, 1.0, Def);
        check(d(0.0, 2.0).log(), -inf, 2f64.ln().next_up(), Trv);
        assert_eq!(d(-1.0, 1.0).atan2(d(-2.0, -1.0)).decoration(), Def);
        // On the cut from above: continuous on the box, not at the points of the cut.
        assert_eq!(d(0.0, 1.0).atan2(d(-2.0, -1.0)).decoration(), Dac);
        assert_eq!(d(0.5, 1.0).atan2(d(-2.0, -1.0)).decoration(), Com);
        assert_eq!(d(-1.0, 1.0).atan2(d(-1.0, 1.0)).decoration(), Trv);
        assert_eq!(d(-1.0, 1.0).pown(-2).decoration(), Trv);
        assert_eq!(d(1.0, 2.0).pown(-2).decoration(), Com);
        assert_eq!(d(0.0, 1.0).pow(d(0.5, 1.0)).decoration(), Com);
        assert_eq!(d(0.0, 1.0).pow(d(0.0, 1.0)).decoration(), Trv);
        assert_eq!(d(1.5, 1.6).tan().decoration(), Trv);
        assert_eq!(d(0.0, 1.0).tan().decoration(), Com);
        // Set and reverse operations are trv; NaI propagates; empty is trv.
        assert_eq!(d(1.0, 2.0).intersection(d(1.5, 3.0)).decoration(), Trv);
        assert!((DecInterval::NAI + d(1.0, 2.0)).is_nai());
        assert!(DecInterval::<f64>::NAI.sin().is_nai());
        assert!(DecInterval::<f64>::NAI.inf().is_nan());
        assert!(d(0.0, 1.0).inf().is_sign_negative());
        assert_eq!(d(-1.0, 1.0).sin_rev_in(d(-1.0, 1.0)).decoration(), Trv);
        assert_eq!(DecInterval::<f64>::EMPTY.exp().decoration(), Trv);
        // Decorations only decrease along a computation.
        let x = d(-1.0, 1.0);
        assert_eq!((x.sqr() + d(1.0, 1.0)).sqrt().decoration(), Com);
        assert_eq!(
            DecInterval::set_dec(Interval::<f64>::ENTIRE, Com).decoration(),
            Dac
        );
        assert_eq!(
            DecInterval::set_dec(Interval::<f64>::EMPTY, Com).decoration(),
            Trv
        );
    }
}
