//! The value types a tape is evaluated on: the [`Number`] trait that every evaluator, and
//! [`Context::eval`](crate::Context::eval), is generic over, and the [`Choice`] record of a
//! `min`/`max` that tape pruning reads. The implementations live in [`eval`](crate::eval).

use interval_core::Decoration;

use crate::constant::Constant;
use crate::op::{BinaryOp, UnaryOp};

/// Which argument a `min` or `max` took over an interval evaluation: the basis of tape
/// pruning.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Choice {
    /// The first argument is the result everywhere in the region.
    Left,
    /// The second argument is the result everywhere in the region.
    Right,
    /// Either may be the result.
    Both,
}

/// A value type the tape can be evaluated on.
///
/// Implementations exist for `f64`, `f32`, `Interval<f64>`, `Interval<f32>`,
/// [`DecInterval<f64>`](interval_core::DecInterval), `DecInterval<f32>`,
/// [`DdInterval`](interval_core::DdInterval), `Modal<f64, Outer>`, `Modal<f64, Inner>`,
/// `Modal<f32, Outer>`, `Modal<f32, Inner>` and [`Grad<N>`](crate::eval::Grad) over the four
/// first. Each operation must be an inclusion (for set types:
/// the result encloses every real result of the operation on members of the arguments).
pub trait Number: Copy + Send + Sync + std::fmt::Debug + 'static {
    /// The value standing for constant `c` (for set types: an enclosure of the real constant).
    fn constant(c: &Constant) -> Self;

    /// `op(a)`.
    fn unary(op: UnaryOp, a: Self) -> Self;

    /// `op(a, b)`.
    fn binary(op: BinaryOp, a: Self, b: Self) -> Self;

    /// `a^n`.
    fn pown(a: Self, n: i32) -> Self;

    /// For set types, the decoration of `op` on the box `a` (IEEE 1788 §11.7, by the rules of
    /// [`interval_core::decorated::rules`]): [`Decoration::Com`] where `op` is defined and
    /// continuous at every point of `a`, [`Decoration::Def`] where it is defined but may jump
    /// (a step function across a jump), [`Decoration::Trv`] where part of `a`, or all of it,
    /// lies outside the domain, or `a` is empty. Point types answer `Com`.
    ///
    /// Decorated evaluations take the minimum over the operations
    /// ([`Evaluator::eval_decorated`](crate::Evaluator::eval_decorated)); traced evaluations
    /// prune nothing on a region where the formula is partly undefined (`Trv`), since
    /// pruning would define the formula there.
    #[inline(always)]
    fn decoration_unary(op: UnaryOp, a: Self) -> Decoration {
        let _ = (op, a);
        Decoration::Com
    }

    /// Like [`decoration_unary`](Self::decoration_unary) for `op(a, b)`. An undecided
    /// `domain(d, f)` (a test taking both signs over the box) is `Def`: the object is defined
    /// everywhere, but jumps to absent at the boundary.
    #[inline(always)]
    fn decoration_binary(op: BinaryOp, a: Self, b: Self) -> Decoration {
        let _ = (op, a, b);
        Decoration::Com
    }

    /// Like [`decoration_unary`](Self::decoration_unary) for `a^n`.
    #[inline(always)]
    fn decoration_pown(a: Self, n: i32) -> Decoration {
        let _ = (a, n);
        Decoration::Com
    }

    /// For set types, the best decoration the value itself can carry (IEEE 1788 `newDec`):
    /// `Com` when nonempty and bounded, `Dac` when unbounded, `Trv` when empty. Point types
    /// answer `Com`. A decorated evaluation is never better than any of its intermediate
    /// values.
    #[inline(always)]
    fn value_decoration(self) -> Decoration {
        Decoration::Com
    }

    /// `domain(d, f)` with an undecided test (one that takes both signs over the region)
    /// resolved to one side: `f` when `inside`, the absent object when not. Returns the
    /// value and whether the test was undecided. Types without regions (points) have no
    /// undecided test: the default is [`binary`](Self::binary) and `false`.
    #[inline(always)]
    fn domain_side(d: Self, f: Self, inside: bool) -> (Self, bool) {
        let _ = inside;
        (Self::binary(BinaryOp::Domain, d, f), false)
    }

    /// For set types, an undefined (empty) result widened to the whole line; the value
    /// itself otherwise and for point types.
    ///
    /// Derivative enclosures use it: a derivative that is undefined somewhere on a box where
    /// the function is defined (the slope of `sqrt` at 0, `0 · ∞` in the chain rule) must
    /// read as "unbounded", never as "no value".
    #[inline(always)]
    fn widen_undefined(self) -> Self {
        self
    }

    /// `min(a, b)` and which argument it took; point types answer [`Choice::Both`].
    #[inline(always)]
    fn min_choice(a: Self, b: Self) -> (Self, Choice) {
        (Self::binary(BinaryOp::Min, a, b), Choice::Both)
    }

    /// `max(a, b)` and which argument it took; point types answer [`Choice::Both`].
    #[inline(always)]
    fn max_choice(a: Self, b: Self) -> (Self, Choice) {
        (Self::binary(BinaryOp::Max, a, b), Choice::Both)
    }

    /// Evaluates `op` on whole slices (`out[i] = op(a[i])`); types with vectorised kernels
    /// override it.
    #[inline]
    fn unary_slice(op: UnaryOp, a: &[Self], out: &mut [Self]) {
        unary_slice_by_element(op, a, out)
    }

    /// Evaluates `op` on whole slices (`out[i] = op(a[i], b[i])`); types with vectorised
    /// kernels override it.
    #[inline]
    fn binary_slice(op: BinaryOp, a: &[Self], b: &[Self], out: &mut [Self]) {
        binary_slice_by_element(op, a, b, out)
    }
}

/// `out[i] = op(a[i])` with the operation chosen once, outside the loop, so each loop body is
/// one inlined operation that the compiler can vectorise.
#[inline]
pub fn unary_slice_by_element<N: Number>(op: UnaryOp, a: &[N], out: &mut [N]) {
    macro_rules! each {
        ($($v:ident),*) => {
            match op {
                $(UnaryOp::$v => {
                    for (o, &x) in out.iter_mut().zip(a) {
                        *o = N::unary(UnaryOp::$v, x);
                    }
                })*
            }
        };
    }
    each!(
        Neg, Abs, Sqr, Sqrt, Recip, Exp, Ln, Log10, Sin, Cos, Tan, Asin, Acos, Atan, Floor, Ceil,
        Round, Not, SlopeFloor, SlopeRound, SlopeNot
    );
}

/// `out[i] = op(a[i], b[i])` with the operation chosen once, outside the loop.
#[inline]
pub fn binary_slice_by_element<N: Number>(op: BinaryOp, a: &[N], b: &[N], out: &mut [N]) {
    macro_rules! each {
        ($($v:ident),*) => {
            match op {
                $(BinaryOp::$v => {
                    for ((o, &x), &y) in out.iter_mut().zip(a).zip(b) {
                        *o = N::binary(BinaryOp::$v, x, y);
                    }
                })*
            }
        };
    }
    each!(Add, Sub, Mul, Div, Min, Max, Pow, Domain);
}
