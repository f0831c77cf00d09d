//! Evaluation: one [`Number`] trait for every value type, one walk over the tape.
//!
//! | type | what an evaluation gives |
//! |---|---|
//! | `f64`, `f32` | the point value, each operation rounded to nearest (elementary functions correctly rounded, by CORE-MATH) |
//! | [`Interval<f64>`](interval_core::Interval), [`Interval<f32>`](interval_core::Interval) | a sound enclosure of the range over a box (inclusion function) |
//! | [`Modal<T, Outer>`](interval_core::Modal) | `Out(fR(X))`, the outer-rounded modal rational extension |
//! | [`Modal<T, Inner>`](interval_core::Modal) | `Inn(fR(X))`, the inner-rounded modal rational extension |
//! | [`DecInterval<f64>`](interval_core::DecInterval), [`DecInterval<f32>`](interval_core::DecInterval) | the enclosure and its IEEE 1788 decoration: whether every operation was defined (`def`) and continuous (`dac`, `com`) on the box |
//! | [`DdInterval`](interval_core::DdInterval) | an enclosure in double-double arithmetic, for queries that `f64` rounding keeps open |
//! | [`Grad<N>`] | the value and the gradient with respect to `x`, `y`, `z` (forward mode) |
//!
//! Point results lie inside interval results for any box holding the point, wherever the
//! formula is defined at the point: the point operations round to nearest (or correctly
//! round) the same real functions that the interval operations enclose outward. Where an
//! operation is undefined at the point (`sqrt` of a negative number), the point value is NaN
//! while the interval evaluation, following IEEE 1788's set-based model, encloses only the
//! values at the points of the box where the formula is defined.

mod dd;
mod decorated;
mod domain_op;
mod grad;
mod interval;
mod modal;
mod point;
mod tape_eval;

pub use grad::Grad;
pub use tape_eval::{Evaluator, SLICE_CHUNK, SliceEvaluator};

pub use crate::number::{Choice, Number, binary_slice_by_element, unary_slice_by_element};
