//! Double-double interval evaluation ([`DdInterval`]): the precision a query escalates to
//! when rounding, not the width of its box, keeps `f64` intervals from deciding it.
//!
//! `+ − × /`, `sqr`, `√`, `pown`, `abs`, `min`, `max` and `domain` run in double-double
//! (within a few units of `2^-104` per operation), `exp`, `sin`, `cos`, `tan`, `asin`,
//! `acos`, `atan`, `ln`, `log` and `pow` too (within about `2^-80` to `2^-95`); the other
//! operations (the step functions), and the definedness
//! checks, take the `f64` hull of their arguments (outward, so every check that holds on the
//! hull holds on the double-double interval) and the `f64` interval operation: sound, no
//! tighter than `f64` there. Constants are the `f64` enclosures of the formula's literals
//! (exact for integers and dyadic fractions, the usual large terms of a cancellation).

use interval_core::{Dd, DdInterval, DecInterval, Decoration, Interval};

use super::domain_op::{self, Region, Side};
use crate::constant::Constant;
use crate::number::Number;
use crate::op::{BinaryOp, UnaryOp};

impl Region for DdInterval {
    fn side(d: Self) -> Side {
        match d.bounds() {
            Some((_, hi)) if hi.signum() <= 0 => Side::Inside,
            Some((lo, _)) if lo.signum() > 0 => Side::Outside,
            _ => Side::Both,
        }
    }

    fn absent() -> Self {
        DdInterval::from_interval(<Interval<f64> as Region>::absent())
    }

    fn with_absent(f: Self) -> Self {
        match f.bounds() {
            Some((lo, _)) => DdInterval::new(lo, Dd::INFINITY).unwrap_or(DdInterval::ENTIRE),
            None => Self::absent(),
        }
    }

    fn is_empty_set(self) -> bool {
        self.is_empty()
    }
}

/// The `f64` interval evaluator's answer on the hulls.
type F64 = Interval<f64>;

impl Number for DdInterval {
    fn constant(c: &Constant) -> Self {
        DdInterval::from_interval(<F64 as Number>::constant(c))
    }

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
            _ => a.map_f64(|x| <F64 as Number>::unary(op, x)),
        }
    }

    fn binary(op: BinaryOp, a: Self, b: Self) -> Self {
        match op {
            BinaryOp::Add => a + b,
            BinaryOp::Sub => a - b,
            BinaryOp::Mul => a * b,
            BinaryOp::Div => a / b,
            BinaryOp::Min => a.min(b),
            BinaryOp::Max => a.max(b),
            BinaryOp::Domain => domain_op::value(a, b),
            BinaryOp::Pow => a.pow(b),
        }
    }

    fn pown(a: Self, n: i32) -> Self {
        a.pown(n)
    }

    fn decoration_unary(op: UnaryOp, a: Self) -> Decoration {
        <F64 as Number>::decoration_unary(op, a.to_interval())
    }

    fn decoration_binary(op: BinaryOp, a: Self, b: Self) -> Decoration {
        match op {
            BinaryOp::Domain => domain_op::decoration(a, b),
            _ => <F64 as Number>::decoration_binary(op, a.to_interval(), b.to_interval()),
        }
    }

    fn decoration_pown(a: Self, n: i32) -> Decoration {
        <F64 as Number>::decoration_pown(a.to_interval(), n)
    }

    #[inline]
    fn value_decoration(self) -> Decoration {
        DecInterval::new(self.to_interval()).decoration()
    }

    fn domain_side(d: Self, f: Self, inside: bool) -> (Self, bool) {
        domain_op::resolved(d, f, inside)
    }

    fn widen_undefined(self) -> Self {
        if self.is_empty() {
            DdInterval::ENTIRE
        } else {
            self
        }
    }
}
