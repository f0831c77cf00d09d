//! Double-double interval evaluation ([`DdInterval`]): the precision a query escalates to
//! when rounding, not the width of its box, keeps `f64` intervals from deciding it.
//!
//! `+ − × /`, `sqr`, `√`, `pown`, `abs`, `min`, `max` and `domain` run in double-double
//! (within a few units of `2^-104` per operation), `exp`, `sin`, `cos`, `ln`, `log` and `pow`
//! too (within about `2^-80` to `2^-95`); the other operations, and the definedness
//! checks, take the `f64` hull of their arguments (outward, so every check that holds on the
//! hull holds on the double-double interval) and the `f64` interval operation: sound, no
//! tighter than `f64` there. Constants are the `f64` enclosures of the formula's literals
//! (exact for integers and dyadic fractions, the usual large terms of a cancellation).

use interval_core::{Dd, DdInterval, Interval};

use crate::constant::Constant;
use crate::number::Number;
use crate::op::{BinaryOp, UnaryOp};

/// The absent object (`+inf`), as `[MAX, +inf]`.
fn absent() -> DdInterval {
    DdInterval::from_interval(Interval::new_unchecked(f64::MAX, f64::INFINITY))
}

/// Whether the domain test `d` has one answer over the region.
fn decided(d: DdInterval) -> bool {
    d.bounds()
        .is_some_and(|(lo, hi)| hi.signum() <= 0 || lo.signum() > 0)
}

/// `domain(d, f)`, as [`Interval`]'s.
fn domain(d: DdInterval, f: DdInterval) -> DdInterval {
    match d.bounds() {
        Some((_, hi)) if hi.signum() <= 0 => f,
        Some((lo, _)) if lo.signum() > 0 => absent(),
        _ => match f.bounds() {
            Some((lo, _)) => DdInterval::new(lo, Dd::INFINITY).unwrap_or(DdInterval::ENTIRE),
            None => absent(),
        },
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
            BinaryOp::Domain => domain(a, b),
            BinaryOp::Pow => a.pow(b),
        }
    }

    fn pown(a: Self, n: i32) -> Self {
        a.pown(n)
    }

    fn defined_unary(op: UnaryOp, a: Self) -> bool {
        <F64 as Number>::defined_unary(op, a.to_interval())
    }

    fn defined_binary(op: BinaryOp, a: Self, b: Self) -> bool {
        match op {
            BinaryOp::Domain => !a.is_empty() && !b.is_empty() && decided(a),
            _ => <F64 as Number>::defined_binary(op, a.to_interval(), b.to_interval()),
        }
    }

    fn defined_pown(a: Self, n: i32) -> bool {
        <F64 as Number>::defined_pown(a.to_interval(), n)
    }

    fn domain_side(d: Self, f: Self, inside: bool) -> (Self, bool) {
        if decided(d) {
            (domain(d, f), false)
        } else if inside && !f.is_empty() {
            (f, true)
        } else {
            (absent(), true)
        }
    }

    fn widen_undefined(self) -> Self {
        if self.is_empty() {
            DdInterval::ENTIRE
        } else {
            self
        }
    }
}
