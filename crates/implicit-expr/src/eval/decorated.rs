//! Decorated interval evaluation ([`DecInterval`], IEEE 1788 §8 and §11.7): each value
//! carries what is known of the evaluation that produced it, `com` or `dac` where every
//! operation was defined and continuous on its arguments, `def` where one may jump, `trv`
//! where one may be undefined on part of the region.
//!
//! The interval part of every result is the plain [`Interval`] evaluation's, and the local
//! decoration of each operation is the one the plain evaluation reports through
//! [`Number::decoration_unary`] and its siblings (the rules of
//! [`interval_core::decorated::rules`]), so the two kinds of evaluation agree by
//! construction: [`Evaluator::eval_decorated`](crate::Evaluator::eval_decorated) on plain
//! intervals gives the decoration of a decorated evaluation from `com` inputs without its
//! cost.

use interval_core::{DecInterval, Decoration, Float, Interval};

use crate::constant::Constant;
use crate::number::{Choice, Number};
use crate::op::{BinaryOp, UnaryOp};

/// `y` decorated by the standard's propagation: NaI if an input is NaI, else the least of
/// the inputs' decorations and the operation's own, lowered by `y`'s invariants (an
/// unbounded `y` is at most `dac`, an empty one `trv`).
#[inline]
fn propagate<T: Float>(
    y: Interval<T>,
    inputs: &[DecInterval<T>],
    local: Decoration,
) -> DecInterval<T> {
    if inputs.iter().any(|x| x.is_nai()) {
        return DecInterval::NAI;
    }
    let d = inputs
        .iter()
        .map(|x| x.decoration())
        .fold(local, Decoration::min);
    DecInterval::set_dec(y, d)
}

/// The plain interval evaluation on the interval parts.
type Plain<T> = Interval<T>;

impl<T: Float> Number for DecInterval<T> {
    #[inline]
    fn constant(c: &Constant) -> Self {
        DecInterval::new(<Plain<T> as Number>::constant(c))
    }

    #[inline]
    fn unary(op: UnaryOp, a: Self) -> Self {
        let x = a.interval();
        propagate(
            <Plain<T> as Number>::unary(op, x),
            &[a],
            <Plain<T> as Number>::decoration_unary(op, x),
        )
    }

    #[inline]
    fn binary(op: BinaryOp, a: Self, b: Self) -> Self {
        let (x, y) = (a.interval(), b.interval());
        propagate(
            <Plain<T> as Number>::binary(op, x, y),
            &[a, b],
            <Plain<T> as Number>::decoration_binary(op, x, y),
        )
    }

    #[inline]
    fn pown(a: Self, n: i32) -> Self {
        let x = a.interval();
        propagate(
            <Plain<T> as Number>::pown(x, n),
            &[a],
            <Plain<T> as Number>::decoration_pown(x, n),
        )
    }

    #[inline]
    fn decoration_unary(op: UnaryOp, a: Self) -> Decoration {
        <Plain<T> as Number>::decoration_unary(op, a.interval())
    }

    #[inline]
    fn decoration_binary(op: BinaryOp, a: Self, b: Self) -> Decoration {
        <Plain<T> as Number>::decoration_binary(op, a.interval(), b.interval())
    }

    #[inline]
    fn decoration_pown(a: Self, n: i32) -> Decoration {
        <Plain<T> as Number>::decoration_pown(a.interval(), n)
    }

    #[inline]
    fn value_decoration(self) -> Decoration {
        self.decoration()
    }

    /// One side of an undecided `domain`: the side's enclosure, decorated at most `def`
    /// (the other side, and the jump between them, are still in the region).
    #[inline]
    fn domain_side(d: Self, f: Self, inside: bool) -> (Self, bool) {
        let (x, y) = (d.interval(), f.interval());
        let (v, open) = <Plain<T> as Number>::domain_side(x, y, inside);
        let local = if open {
            Decoration::Def
        } else {
            <Plain<T> as Number>::decoration_binary(BinaryOp::Domain, x, y)
        };
        (propagate(v, &[d, f], local), open)
    }

    /// The empty set widened to the whole line, decorated `trv`: a derivative undefined
    /// somewhere says nothing.
    #[inline]
    fn widen_undefined(self) -> Self {
        if self.is_empty() && !self.is_nai() {
            DecInterval::set_dec(Interval::ENTIRE, Decoration::Trv)
        } else {
            self
        }
    }

    #[inline]
    fn min_choice(a: Self, b: Self) -> (Self, Choice) {
        let (v, c) = <Plain<T> as Number>::min_choice(a.interval(), b.interval());
        (propagate(v, &[a, b], Decoration::Com), c)
    }

    #[inline]
    fn max_choice(a: Self, b: Self) -> (Self, Choice) {
        let (v, c) = <Plain<T> as Number>::max_choice(a.interval(), b.interval());
        (propagate(v, &[a, b], Decoration::Com), c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Context;

    fn dec(lo: f64, hi: f64) -> DecInterval<f64> {
        DecInterval::new(Interval::new(lo, hi).unwrap())
    }

    fn eval(formula: &str, x: DecInterval<f64>) -> DecInterval<f64> {
        let mut ctx = Context::new();
        let root = crate::parse::parse(&mut ctx, formula, &[]).unwrap();
        let tape = crate::Tape::new(&ctx, &[root]).unwrap();
        let zero = dec(0.0, 0.0);
        crate::Evaluator::new(&tape).eval(&[x, zero, zero]).unwrap()
    }

    #[test]
    fn decorations_follow_the_standard() {
        assert_eq!(
            eval("sqrt(x) + 1", dec(1.0, 4.0)).decoration(),
            Decoration::Com
        );
        assert_eq!(
            eval("sqrt(x) + 1", dec(-1.0, 4.0)).decoration(),
            Decoration::Trv
        );
        assert_eq!(
            eval("floor(x)", dec(1.25, 1.5)).decoration(),
            Decoration::Com
        );
        // Continuous on the box, but not at 1, where floor jumps.
        assert_eq!(
            eval("floor(x)", dec(1.0, 1.5)).decoration(),
            Decoration::Dac
        );
        assert_eq!(
            eval("floor(x)", dec(0.5, 1.5)).decoration(),
            Decoration::Def
        );
        assert_eq!(eval("1 / x", dec(1.0, 2.0)).decoration(), Decoration::Com);
        assert_eq!(eval("1 / x", dec(-1.0, 2.0)).decoration(), Decoration::Trv);
        assert_eq!(
            eval("exp(x)", dec(1.0, 1e300)).decoration(),
            Decoration::Dac
        );
        let nai = DecInterval::<f64>::NAI;
        assert!(eval("x + 1", nai).is_nai());
    }
}
