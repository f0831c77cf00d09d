//! Interval evaluation: `Interval<f64>` and `Interval<f32>` from interval-core (tight
//! arithmetic, elementary functions within one ulp), plus the step functions of the `.vm`
//! format and their slopes.

use interval_core::decorated::rules;
use interval_core::interval::batch;
use interval_core::{DecInterval, Decoration, Float, Interval};

use super::domain_op::{self, Region, Side};
use crate::constant::Constant;
use crate::number::{Choice, Number};
use crate::op::{BinaryOp, UnaryOp};

/// `[lo, hi]` without checks; callers pass ordered, non-NaN bounds.
#[inline(always)]
fn iv<T: Float>(lo: T, hi: T) -> Interval<T> {
    Interval::new_unchecked(lo, hi)
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

/// `Com` where an operation defined on the whole box is continuous there, `Def` where it
/// may jump.
#[inline]
fn continuous_if(continuous: bool) -> Decoration {
    if continuous {
        Decoration::Com
    } else {
        Decoration::Def
    }
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
            UnaryOp::Floor => a.floor(),
            UnaryOp::Ceil => a.ceil(),
            UnaryOp::Round => a.round_ties_to_away(),
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
    fn decoration_unary(op: UnaryOp, a: Self) -> Decoration {
        if a.is_empty() {
            return Decoration::Trv;
        }
        match op {
            UnaryOp::Sqrt => rules::non_negative(a),
            UnaryOp::Ln | UnaryOp::Log10 => rules::positive(a),
            UnaryOp::Asin | UnaryOp::Acos => rules::unit(a),
            UnaryOp::Recip => rules::nonzero(a),
            UnaryOp::Tan => rules::tan(a),
            UnaryOp::Floor => rules::step(a, Interval::floor, rules::integer),
            UnaryOp::Ceil => rules::step(a, Interval::ceil, rules::integer),
            UnaryOp::Round => rules::step(a, Interval::round_ties_to_away, rules::half_integer),
            // Not a monotone step: 1 at 0 only, so continuous at every point of a box
            // without 0, and its restriction to `[0, 0]` is continuous (dac).
            UnaryOp::Not if !a.contains(T::ZERO) => Decoration::Com,
            UnaryOp::Not if a.is_singleton() => Decoration::Dac,
            UnaryOp::Not => Decoration::Def,
            // A slope is continuous (zero) where its step function has no jump, and
            // defined everywhere (the whole line across a jump).
            UnaryOp::SlopeFloor | UnaryOp::SlopeRound | UnaryOp::SlopeNot => {
                continuous_if(Self::unary(op, a) == Interval::ZERO)
            }
            _ => Decoration::Com,
        }
    }

    #[inline]
    fn decoration_binary(op: BinaryOp, a: Self, b: Self) -> Decoration {
        if a.is_empty() || b.is_empty() {
            return Decoration::Trv;
        }
        match op {
            BinaryOp::Div => rules::div(a, b),
            BinaryOp::Pow => rules::pow(a, b),
            BinaryOp::Domain => domain_op::decoration(a, b),
            _ => Decoration::Com,
        }
    }

    #[inline]
    fn decoration_pown(a: Self, n: i32) -> Decoration {
        if a.is_empty() {
            Decoration::Trv
        } else {
            rules::pown(a, n)
        }
    }

    #[inline]
    fn value_decoration(self) -> Decoration {
        DecInterval::new(self).decoration()
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
