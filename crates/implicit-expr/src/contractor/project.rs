//! The backward projections of HC4-revise: for a node `r = op(a, …)` with the enclosures
//! `r`, `a`, `b`, the parts of `a` and `b` that can produce a value of `r` with the other
//! argument in its enclosure. Each result is a subset of the argument's enclosure (an
//! intersection with it) and keeps every such value; operations without a reverse return
//! the argument unchanged.

use interval_core::{Float, Interval};

use crate::op::{BinaryOp, UnaryOp};

/// `a` narrowed to `{x ∈ a : op(x) ∈ r}` (a superset of it).
pub(super) fn unary<T: Float>(op: UnaryOp, r: Interval<T>, a: Interval<T>) -> Interval<T> {
    let nonnegative = Interval::new_unchecked(T::ZERO, T::INFINITY);
    match op {
        UnaryOp::Neg => a.intersection(-r),
        UnaryOp::Abs => r.abs_rev_in(a),
        UnaryOp::Sqr => r.sqr_rev_in(a),
        // √x = r ≥ 0 ⇒ x = r², and x ≥ 0 where √x is defined.
        UnaryOp::Sqrt => a
            .intersection(r.intersection(nonnegative).sqr())
            .intersection(nonnegative),
        // 1/x = r ⇒ x·r = 1.
        UnaryOp::Recip => r.mul_rev_in(Interval::ONE, a),
        UnaryOp::Exp => a.intersection(r.intersection(nonnegative).ln()),
        UnaryOp::Ln => a.intersection(r.exp()),
        UnaryOp::Log10 => a.intersection(r.exp10()),
        UnaryOp::Sin => r.sin_rev_in(a),
        UnaryOp::Cos => r.cos_rev_in(a),
        UnaryOp::Tan => r.tan_rev_in(a),
        // x = sin(asin x), cos(acos x), tan(atan x): the function of the result.
        UnaryOp::Asin => a.intersection(r.sin()),
        UnaryOp::Acos => a.intersection(r.cos()),
        UnaryOp::Atan => a.intersection(r.tan()),
        UnaryOp::Floor
        | UnaryOp::Ceil
        | UnaryOp::Round
        | UnaryOp::Not
        | UnaryOp::SlopeFloor
        | UnaryOp::SlopeRound
        | UnaryOp::SlopeNot => a,
    }
}

/// `(a, b)` narrowed to the values with `op(x, y) ∈ r` for some value of the other in its
/// enclosure.
pub(super) fn binary<T: Float>(
    op: BinaryOp,
    r: Interval<T>,
    a: Interval<T>,
    b: Interval<T>,
) -> (Interval<T>, Interval<T>) {
    match op {
        BinaryOp::Add => {
            let a = a.intersection(r - b);
            (a, b.intersection(r - a))
        }
        BinaryOp::Sub => {
            let a = a.intersection(r + b);
            (a, b.intersection(a - r))
        }
        BinaryOp::Mul => {
            let a = b.mul_rev_in(r, a);
            (a, a.mul_rev_in(r, b))
        }
        // r = a / b ⇒ a = r·b, and b·r = a.
        BinaryOp::Div => {
            let a = a.intersection(r * b);
            (a, r.mul_rev_in(a, b))
        }
        BinaryOp::Min => extreme(r, a, b, false),
        BinaryOp::Max => extreme(r, a, b, true),
        BinaryOp::Pow => {
            let a = b.pow_rev1_in(r, a);
            (a, a.pow_rev2_in(r, b))
        }
        BinaryOp::Domain => (a, b),
    }
}

/// The projections of `r = min(a, b)` (or `max` when `is_max`): both arguments are at least
/// `inf r` (at most `sup r`); one that cannot be the result (above `sup r`; below `inf r`)
/// leaves the other to be it, narrowed to `r`.
fn extreme<T: Float>(
    r: Interval<T>,
    a: Interval<T>,
    b: Interval<T>,
    is_max: bool,
) -> (Interval<T>, Interval<T>) {
    let Some((lo, hi)) = r.bounds() else {
        return (Interval::EMPTY, Interval::EMPTY);
    };
    let bound = if is_max {
        Interval::new_unchecked(T::NEG_INFINITY, hi)
    } else {
        Interval::new_unchecked(lo, T::INFINITY)
    };
    let (mut a, mut b) = (a.intersection(bound), b.intersection(bound));
    let cannot = |x: Interval<T>| x.is_empty() || if is_max { x.sup() < lo } else { x.inf() > hi };
    if cannot(a) {
        b = b.intersection(r);
    } else if cannot(b) {
        a = a.intersection(r);
    }
    (a, b)
}
