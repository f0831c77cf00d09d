//! Point evaluation in `f64` and `f32`: each operation rounded to nearest, elementary
//! functions correctly rounded (CORE-MATH), so a point value always lies inside the interval
//! value of any box that holds the point.

use crate::constant::Constant;
use crate::number::{Choice, Number};
use crate::op::{BinaryOp, UnaryOp};

macro_rules! point_number {
    ($t:ty, $from:expr, { $($f:ident = $cm:path),* $(,)? }, pow = $pow:path) => {
        impl Number for $t {
            #[inline(always)]
            fn constant(c: &Constant) -> Self {
                $from(c.value())
            }

            #[inline(always)]
            fn unary(op: UnaryOp, a: Self) -> Self {
                match op {
                    UnaryOp::Neg => -a,
                    UnaryOp::Abs => a.abs(),
                    UnaryOp::Sqr => a * a,
                    UnaryOp::Sqrt => a.sqrt(),
                    UnaryOp::Recip => 1.0 / a,
                    $(UnaryOp::$f => $cm(a),)*
                    UnaryOp::Floor => a.floor(),
                    UnaryOp::Ceil => a.ceil(),
                    UnaryOp::Round => a.round(),
                    UnaryOp::Not => {
                        if a.is_nan() {
                            a
                        } else if a == 0.0 {
                            1.0
                        } else {
                            0.0
                        }
                    }
                    UnaryOp::SlopeFloor | UnaryOp::SlopeRound | UnaryOp::SlopeNot => {
                        if a.is_nan() { a } else { 0.0 }
                    }
                }
            }

            #[inline(always)]
            fn binary(op: BinaryOp, a: Self, b: Self) -> Self {
                match op {
                    BinaryOp::Add => a + b,
                    BinaryOp::Sub => a - b,
                    BinaryOp::Mul => a * b,
                    BinaryOp::Div => a / b,
                    // NaN (an undefined argument) propagates, as the empty set does for
                    // intervals.
                    BinaryOp::Min => {
                        if a.is_nan() || b.is_nan() { a + b } else { a.min(b) }
                    }
                    BinaryOp::Max => {
                        if a.is_nan() || b.is_nan() { a + b } else { a.max(b) }
                    }
                    // IEEE 1788's `pow` domain (`a > 0`, or `a = 0` with `b > 0`), as the
                    // interval `pow`: C's special cases (`pow(0, 0) = 1`, `pow(-2, 2) = 4`)
                    // would leave the interval value.
                    BinaryOp::Pow => {
                        if a > 0.0 || (a == 0.0 && b > 0.0) { $pow(a, b) } else { <$t>::NAN }
                    }
                    // Outside the domain: no object (+inf); an undefined test propagates.
                    BinaryOp::Domain => {
                        if a <= 0.0 { b } else if a > 0.0 { <$t>::INFINITY } else { a }
                    }
                }
            }

            #[inline(always)]
            fn pown(a: Self, n: i32) -> Self {
                match n {
                    0 => 1.0,
                    1 => a,
                    2 => a * a,
                    -1 => 1.0 / a,
                    _ => $pow(a, n as $t),
                }
            }

            #[inline(always)]
            fn min_choice(a: Self, b: Self) -> (Self, Choice) {
                (Self::binary(BinaryOp::Min, a, b), Choice::Both)
            }
        }
    };
}

point_number!(f64, |v: f64| v, {
    Exp = core_math::exp,
    Ln = core_math::log,
    Log10 = core_math::log10,
    Sin = core_math::sin,
    Cos = core_math::cos,
    Tan = core_math::tan,
    Asin = core_math::asin,
    Acos = core_math::acos,
    Atan = core_math::atan,
}, pow = core_math::pow);

point_number!(f32, |v: f64| v as f32, {
    Exp = core_math::expf,
    Ln = core_math::logf,
    Log10 = core_math::log10f,
    Sin = core_math::sinf,
    Cos = core_math::cosf,
    Tan = core_math::tanf,
    Asin = core_math::asinf,
    Acos = core_math::acosf,
    Atan = core_math::atanf,
}, pow = core_math::powf);
