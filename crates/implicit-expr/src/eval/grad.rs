//! Forward-mode gradients: a value with its partial derivatives by `x`, `y` and `z`.
//!
//! Over intervals, each derivative is an enclosure of the partial derivative over the box
//! (for `min`, `max` and `abs` where the branch is not decided: the hull of the branches'
//! derivatives, which holds Clarke's generalised gradient, so mean-value forms and
//! monotonicity tests stay sound).

use interval_core::{Float, Interval};

use crate::constant::Constant;
use crate::number::{Choice, Number};
use crate::op::{BinaryOp, UnaryOp};

/// `[e(0), e(1), e(2)]` for an expression `e` of `i`, written out: a closure called three
/// times (`std::array::from_fn`, `map`) may stay a function of its own, which is not
/// compiled for the evaluator loop's instruction set ([`interval_core::isa`]) and calls
/// libm's `fma` in every rounded product.
macro_rules! each {
    (|$i:ident| $e:expr) => {
        [
            {
                let $i = 0;
                $e
            },
            {
                let $i = 1;
                $e
            },
            {
                let $i = 2;
                $e
            },
        ]
    };
}

/// A value and its gradient with respect to the variable slots 0, 1, 2 (`x`, `y`, `z`).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Grad<N> {
    /// The value.
    pub v: N,
    /// `[∂/∂x, ∂/∂y, ∂/∂z]`.
    pub d: [N; 3],
}

/// What [`Grad`] needs of its value type beyond [`Number`]: implemented for `f64`, `f32`,
/// `Interval<f64>` and `Interval<f32>`.
pub trait GradScalar: Number {
    /// A subgradient enclosure of `|a|` at `a`: `-1`, `1`, or for intervals holding zero
    /// `[-1, 1]` (points at zero give `0`).
    fn abs_slope(a: Self) -> Self;

    /// `slope` where it is defined; where the argument `u` is defined but the slope is not
    /// (the derivative of `sqrt` at `[0, 0]`), the unbounded slope, so that the chain rule
    /// still multiplies it by the inner derivative (`[-inf, inf] · 0 = 0` for intervals).
    fn defined_slope(u: Self, slope: Self) -> Self;

    /// The derivative of `min(a, b)` (or `max` when `is_max`) given the arguments'
    /// derivatives: the taken branch's, or the hull of both where undecided.
    fn select(a: Self, b: Self, da: Self, db: Self, is_max: bool) -> Self;

    /// `s · d`, a slope times a derivative component: the product by default. Where many
    /// components are 0 (a value that depends on some of the variables only, as most of
    /// a sum of squares), a type may answer those without multiplying, with the same
    /// value.
    #[inline(always)]
    fn scale(s: Self, d: Self) -> Self {
        mul(s, d)
    }
}

macro_rules! point_grad_scalar {
    ($t:ty) => {
        impl GradScalar for $t {
            #[inline(always)]
            fn abs_slope(a: Self) -> Self {
                if a > 0.0 {
                    1.0
                } else if a < 0.0 {
                    -1.0
                } else {
                    0.0 * a
                }
            }

            #[inline(always)]
            fn select(a: Self, b: Self, da: Self, db: Self, is_max: bool) -> Self {
                if (a < b) != is_max { da } else { db }
            }

            #[inline(always)]
            fn defined_slope(_u: Self, slope: Self) -> Self {
                slope
            }
        }
    };
}

point_grad_scalar!(f64);
point_grad_scalar!(f32);

impl<T: Float> GradScalar for Interval<T> {
    #[inline(always)]
    fn abs_slope(a: Self) -> Self {
        match a.bounds() {
            None => a,
            Some((lo, _)) if lo > T::ZERO => Interval::ONE,
            Some((_, hi)) if hi < T::ZERO => -Interval::ONE,
            Some(_) => Interval::new_unchecked(-T::ONE, T::ONE),
        }
    }

    #[inline(always)]
    fn defined_slope(u: Self, slope: Self) -> Self {
        if slope.is_empty() && !u.is_empty() {
            Interval::ENTIRE
        } else {
            slope
        }
    }

    /// `[0, 0]` where `d` is `[0, 0]` and `s` is not empty (`s · 0 = 0` for every real
    /// `s`, unbounded ones included), without the product's directed roundings.
    #[inline(always)]
    fn scale(s: Self, d: Self) -> Self {
        if d.inf() == T::ZERO && d.sup() == T::ZERO && !s.is_empty() {
            Interval::ZERO
        } else {
            mul(s, d)
        }
    }

    #[inline(always)]
    fn select(a: Self, b: Self, da: Self, db: Self, is_max: bool) -> Self {
        let (_, choice) = if is_max {
            Self::max_choice(a, b)
        } else {
            Self::min_choice(a, b)
        };
        match choice {
            Choice::Left => da,
            Choice::Right => db,
            Choice::Both => da.convex_hull(db),
        }
    }
}

impl<N: GradScalar> Grad<N> {
    /// A constant (zero gradient).
    pub fn constant_value(v: N) -> Self {
        let zero = N::constant(&Constant::ZERO);
        Self { v, d: [zero; 3] }
    }

    /// The variable along `axis` (0, 1, 2 for `x`, `y`, `z`) at value `v`.
    ///
    /// # Panics
    /// If `axis > 2`.
    pub fn var(v: N, axis: usize) -> Self {
        let mut g = Self::constant_value(v);
        g.d[axis] = N::constant(&Constant::ONE);
        g
    }

    /// `(x, y, z)` as gradient variables.
    pub fn point(x: N, y: N, z: N) -> [Self; 3] {
        [Self::var(x, 0), Self::var(y, 1), Self::var(z, 2)]
    }

    #[inline(always)]
    fn chain(self, v: N, slope: N) -> Self {
        Self {
            v,
            d: each!(|i| N::scale(slope, self.d[i])),
        }
    }
}

#[inline(always)]
fn k<N: Number>(v: f64) -> N {
    N::constant(&Constant::exact(v).expect("finite"))
}

#[inline(always)]
fn mul<N: Number>(a: N, b: N) -> N {
    N::binary(BinaryOp::Mul, a, b)
}

#[inline(always)]
fn div<N: Number>(a: N, b: N) -> N {
    N::binary(BinaryOp::Div, a, b)
}

#[inline(always)]
fn add<N: Number>(a: N, b: N) -> N {
    N::binary(BinaryOp::Add, a, b)
}

#[inline(always)]
fn sub<N: Number>(a: N, b: N) -> N {
    N::binary(BinaryOp::Sub, a, b)
}

// Inlined into the evaluators' loops, so that the interval operations inside are compiled
// for the loop's instruction set ([`interval_core::isa`]) and the operation's `match`
// folds away.
impl<N: GradScalar> Number for Grad<N> {
    fn constant(c: &Constant) -> Self {
        Self::constant_value(N::constant(c))
    }

    #[inline(always)]
    fn unary(op: UnaryOp, a: Self) -> Self {
        let u = a.v;
        let v = N::unary(op, u);
        let slope = match op {
            UnaryOp::Neg => k(-1.0),
            UnaryOp::Abs => N::abs_slope(u),
            UnaryOp::Sqr => mul(k(2.0), u),
            UnaryOp::Sqrt => div(k(0.5), v),
            UnaryOp::Recip => N::unary(UnaryOp::Neg, N::unary(UnaryOp::Sqr, v)),
            UnaryOp::Exp => v,
            UnaryOp::Ln => N::unary(UnaryOp::Recip, u),
            UnaryOp::Log10 => {
                let ln10 = std::f64::consts::LN_10;
                let c = Constant::enclosed(ln10, ln10.next_down(), ln10.next_up()).expect("finite");
                N::unary(UnaryOp::Recip, mul(u, N::constant(&c)))
            }
            UnaryOp::Sin => N::unary(UnaryOp::Cos, u),
            UnaryOp::Cos => N::unary(UnaryOp::Neg, N::unary(UnaryOp::Sin, u)),
            UnaryOp::Tan => add(k(1.0), N::unary(UnaryOp::Sqr, v)),
            UnaryOp::Asin | UnaryOp::Acos => {
                let s = N::unary(UnaryOp::Sqrt, sub(k(1.0), N::unary(UnaryOp::Sqr, u)));
                let r = N::unary(UnaryOp::Recip, s);
                if op == UnaryOp::Acos {
                    N::unary(UnaryOp::Neg, r)
                } else {
                    r
                }
            }
            UnaryOp::Atan => N::unary(UnaryOp::Recip, add(k(1.0), N::unary(UnaryOp::Sqr, u))),
            UnaryOp::Floor | UnaryOp::Ceil => N::unary(UnaryOp::SlopeFloor, u),
            UnaryOp::Round => N::unary(UnaryOp::SlopeRound, u),
            UnaryOp::Not => N::unary(UnaryOp::SlopeNot, u),
            UnaryOp::SlopeFloor | UnaryOp::SlopeRound | UnaryOp::SlopeNot => N::unary(op, u),
        };
        a.chain(v, N::defined_slope(u, slope))
    }

    #[inline(always)]
    fn binary(op: BinaryOp, a: Self, b: Self) -> Self {
        let v = N::binary(op, a.v, b.v);
        let d = match op {
            BinaryOp::Add => each!(|i| add(a.d[i], b.d[i])),
            BinaryOp::Sub => each!(|i| sub(a.d[i], b.d[i])),
            BinaryOp::Mul => each!(|i| add(N::scale(a.v, b.d[i]), N::scale(b.v, a.d[i]))),
            BinaryOp::Div => {
                // (da - (a/b) db) / b
                each!(|i| div(sub(a.d[i], mul(v, b.d[i])), b.v))
            }
            BinaryOp::Min | BinaryOp::Max => {
                let is_max = op == BinaryOp::Max;
                each!(|i| N::select(a.v, b.v, a.d[i], b.d[i], is_max))
            }
            BinaryOp::Pow => {
                // d(a^b) = b a^(b-1) da + a^b ln(a) db
                let p = N::binary(BinaryOp::Pow, a.v, sub(b.v, k(1.0)));
                let sa = N::defined_slope(a.v, mul(b.v, p));
                let sb = N::defined_slope(a.v, mul(v, N::unary(UnaryOp::Ln, a.v)));
                each!(|i| add(mul(sa, a.d[i]), mul(sb, b.d[i])))
            }
            // As the symbolic derivative: `domain(d, f') + slope_not(d)`.
            BinaryOp::Domain => {
                let jump = N::unary(UnaryOp::SlopeNot, a.v);
                each!(|i| add(N::binary(BinaryOp::Domain, a.v, b.d[i]), jump))
            }
        };
        Self { v, d }
    }

    #[inline(always)]
    fn pown(a: Self, n: i32) -> Self {
        let v = N::pown(a.v, n);
        let slope = mul(k(f64::from(n)), N::pown(a.v, n - 1));
        a.chain(v, N::defined_slope(a.v, slope))
    }
}
