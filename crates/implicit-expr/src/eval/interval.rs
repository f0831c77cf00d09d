//! Interval evaluation: `Interval<f64>` and `Interval<f32>` from interval-core (tight
//! arithmetic, elementary functions within one ulp), plus the step functions of the `.vm`
//! format and their slopes.

use interval_core::interval::batch;
use interval_core::{Float, Interval};

use super::domain_op::{self, Region, Side};
use crate::constant::Constant;
use crate::number::{Choice, Number};
use crate::op::{BinaryOp, UnaryOp};

/// `[lo, hi]` without checks; callers pass ordered, non-NaN bounds.
#[inline(always)]
fn iv<T: Float>(lo: T, hi: T) -> Interval<T> {
    Interval::new_unchecked(lo, hi)
}

/// A monotone non-decreasing step function applied bound by bound (exact: the image of a
/// float is a float of the same format).
#[inline]
fn step<T: Float>(x: Interval<T>, f: fn(f64) -> f64) -> Interval<T> {
    match x.bounds() {
        Some((lo, hi)) => iv(
            T::from_f64_rn(f(lo.to_f64())),
            T::from_f64_rn(f(hi.to_f64())),
        ),
        None => x,
    }
}

/// Zero when `constant` says the step function has no jump on the interval, else entire.
#[inline]
fn slope<T: Float>(x: Interval<T>, constant: impl Fn(f64, f64) -> bool) -> Interval<T> {
    match x.bounds() {
        Some((lo, hi)) if constant(lo.to_f64(), hi.to_f64()) => Interval::ZERO,
        Some(_) => Interval::ENTIRE,
        None => x,
    }
}

/// Whether `[lo, hi]` touches a jump of `round` (the half-integers).
fn round_constant(lo: f64, hi: f64) -> bool {
    lo.round() == hi.round() && lo.fract().abs() != 0.5 && hi.fract().abs() != 0.5
}

/// Whether `floor` and `ceil` are both constant on `[lo, hi]` (no integer inside or at an
/// end, unless the interval is that one integer).
fn floor_constant(lo: f64, hi: f64) -> bool {
    lo.floor() == hi.floor() && lo.ceil() == hi.ceil()
}

impl<T: Float> Region for Interval<T> {
    #[inline]
    fn side(d: Self) -> Side {
        match d.bounds() {
            Some((_, hi)) if hi <= T::ZERO => Side::Inside,
            Some((lo, _)) if lo > T::ZERO => Side::Outside,
            _ => Side::Both,
        }
    }

    /// `[MAX, +inf]`: above every finite value but the largest, and `-[MAX, +inf]` below.
    #[inline(always)]
    fn absent() -> Self {
        iv(T::MAX, T::INFINITY)
    }

    #[inline]
    fn with_absent(f: Self) -> Self {
        match f.bounds() {
            Some((lo, _)) => iv(lo, T::INFINITY),
            None => Self::absent(),
        }
    }

    #[inline(always)]
    fn is_empty_set(self) -> bool {
        self.is_empty()
    }
}

impl<T: Float> Number for Interval<T> {
    #[inline(always)]
    fn constant(c: &Constant) -> Self {
        iv(T::from_f64_down(c.lo()), T::from_f64_up(c.hi()))
    }

    #[inline(always)]
    fn unary(op: UnaryOp, a: Self) -> Self {
        match op {
            UnaryOp::Neg => -a,
            UnaryOp::Abs => a.abs(),
            UnaryOp::Sqr => a.sqr(),
            UnaryOp::Sqrt => a.sqrt(),
            UnaryOp::Recip => a.recip(),
            UnaryOp::Exp => a.exp(),
            UnaryOp::Ln => a.ln(),
            UnaryOp::Log10 => a.log10(),
            UnaryOp::Sin => a.sin(),
            UnaryOp::Cos => a.cos(),
            UnaryOp::Tan => a.tan(),
            UnaryOp::Asin => a.asin(),
            UnaryOp::Acos => a.acos(),
            UnaryOp::Atan => a.atan(),
            UnaryOp::Floor => step(a, f64::floor),
            UnaryOp::Ceil => step(a, f64::ceil),
            UnaryOp::Round => step(a, f64::round),
            UnaryOp::Not => match a.bounds() {
                None => a,
                Some((lo, hi)) if lo == T::ZERO && hi == T::ZERO => Interval::ONE,
                Some((lo, hi)) if lo <= T::ZERO && T::ZERO <= hi => iv(T::ZERO, T::ONE),
                Some(_) => Interval::ZERO,
            },
            UnaryOp::SlopeFloor => slope(a, floor_constant),
            UnaryOp::SlopeRound => slope(a, round_constant),
            UnaryOp::SlopeNot => slope(a, |lo, hi| lo > 0.0 || hi < 0.0),
        }
    }

    #[inline(always)]
    fn binary(op: BinaryOp, a: Self, b: Self) -> Self {
        match op {
            BinaryOp::Add => a + b,
            BinaryOp::Sub => a - b,
            // One formula along a ray repeats its sign patterns: the branching form wins.
            BinaryOp::Mul => a.mul_sign_cases(b),
            BinaryOp::Div => a / b,
            BinaryOp::Min => a.min(b),
            BinaryOp::Max => a.max(b),
            BinaryOp::Pow => a.pow(b),
            BinaryOp::Domain => domain_op::value(a, b),
        }
    }

    #[inline(always)]
    fn pown(a: Self, n: i32) -> Self {
        a.pown(n)
    }

    #[inline]
    fn defined_unary(op: UnaryOp, a: Self) -> bool {
        let Some((lo, hi)) = a.bounds() else {
            return false;
        };
        let (zero, one) = (T::ZERO, T::ONE);
        match op {
            UnaryOp::Sqrt => lo >= zero,
            UnaryOp::Ln | UnaryOp::Log10 => lo > zero,
            UnaryOp::Asin | UnaryOp::Acos => -one <= lo && hi <= one,
            UnaryOp::Recip => lo > zero || hi < zero,
            UnaryOp::Tan => a
                .tan()
                .bounds()
                .is_some_and(|(l, h)| l.is_finite() && h.is_finite()),
            _ => true,
        }
    }

    #[inline]
    fn defined_binary(op: BinaryOp, a: Self, b: Self) -> bool {
        let (Some((alo, _)), Some((blo, bhi))) = (a.bounds(), b.bounds()) else {
            return false;
        };
        match op {
            BinaryOp::Div => blo > T::ZERO || bhi < T::ZERO,
            BinaryOp::Pow => alo > T::ZERO || (alo >= T::ZERO && blo > T::ZERO),
            // Continuous (and defined) only where the domain test has one answer.
            BinaryOp::Domain => domain_op::decided(a, b),
            _ => true,
        }
    }

    #[inline]
    fn defined_pown(a: Self, n: i32) -> bool {
        match a.bounds() {
            None => false,
            Some((lo, hi)) => n >= 0 || lo > T::ZERO || hi < T::ZERO,
        }
    }

    #[inline]
    fn domain_side(d: Self, f: Self, inside: bool) -> (Self, bool) {
        domain_op::resolved(d, f, inside)
    }

    #[inline(always)]
    fn widen_undefined(self) -> Self {
        if self.is_empty() {
            Interval::ENTIRE
        } else {
            self
        }
    }

    #[inline(always)]
    fn min_choice(a: Self, b: Self) -> (Self, Choice) {
        let choice = if a.is_empty() || b.is_empty() {
            Choice::Both
        } else if a.sup() <= b.inf() {
            Choice::Left
        } else if b.sup() <= a.inf() {
            Choice::Right
        } else {
            Choice::Both
        };
        (a.min(b), choice)
    }

    #[inline(always)]
    fn max_choice(a: Self, b: Self) -> (Self, Choice) {
        let choice = if a.is_empty() || b.is_empty() {
            Choice::Both
        } else if a.inf() >= b.sup() {
            Choice::Left
        } else if b.inf() >= a.sup() {
            Choice::Right
        } else {
            Choice::Both
        };
        (a.max(b), choice)
    }

    fn unary_slice(op: UnaryOp, a: &[Self], out: &mut [Self]) {
        let done = match op {
            UnaryOp::Sqr => batch::sqr(a, out).is_ok(),
            UnaryOp::Sqrt => batch::sqrt(a, out).is_ok(),
            UnaryOp::Exp => batch::exp(a, out).is_ok(),
            UnaryOp::Ln => batch::ln(a, out).is_ok(),
            UnaryOp::Sin => batch::sin(a, out).is_ok(),
            UnaryOp::Cos => batch::cos(a, out).is_ok(),
            _ => false,
        };
        if !done {
            crate::number::unary_slice_by_element(op, a, out);
        }
    }

    fn binary_slice(op: BinaryOp, a: &[Self], b: &[Self], out: &mut [Self]) {
        let done = match op {
            BinaryOp::Add => batch::add(a, b, out).is_ok(),
            BinaryOp::Sub => batch::sub(a, b, out).is_ok(),
            BinaryOp::Mul => batch::mul(a, b, out).is_ok(),
            BinaryOp::Div => batch::div(a, b, out).is_ok(),
            _ => false,
        };
        if !done {
            crate::number::binary_slice_by_element(op, a, b, out);
        }
    }
}
