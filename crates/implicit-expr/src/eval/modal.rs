//! Modal evaluation: the modal rational extension `fR(X)` (thesis 3.5.1) with outer
//! rounding (`Modal<T, Outer>`, giving `Out(fR(X))`) or inner rounding (`Modal<T, Inner>`,
//! giving `Inn(fR(X))`).
//!
//! `+ - * /` are Kaucher's operations from interval-core; `min` and `max` are the lattice
//! operations (exact). A one-variable continuous function `f` has the semantic extension
//! `f*(X) = f**(X)`: over `P = Prop(X)` it is `[min f, max f]` for a proper `X` and
//! `[max f, min f]` for an improper one. Each bound is rounded from one of two enclosures:
//!
//! * `R`, the interval extension over `P` (outward, so `R.inf <= min f`, `R.sup >= max f`);
//! * the values of `f` at sample points of `P` (both ends and the interior critical points
//!   where known): their largest lower bound is `<= max f`, their smallest upper bound
//!   is `>= min f`.
//!
//! | `X` | outer rounding | inner rounding |
//! |---|---|---|
//! | proper | `[R.inf, R.sup]` | `[min upper(f(s)), max lower(f(s))]` |
//! | improper | `[max lower(f(s)), min upper(f(s))]` | `[R.sup, R.inf]` |
//!
//! The samples include both ends, so for monotone `f` (`sqrt exp ln ...`) every bound is
//! within one ulp of the exact one; for `sqr`, `abs` and even powers `0` is a sample when it
//! lies in `P`; for `sin` and `cos` only the ends are sampled, so their inner-type bounds may
//! be loose, never wrong. Where `f` is undefined somewhere on `P`, or unbounded on `P` with
//! finite values at the ends (a pole), the result is the least informative value of the
//! rounding: `[-inf, +inf]` outer, `[+inf, -inf]` inner (as interval-core's division does).

use interval_core::{Float, Interval, Modal, Rounding};

use crate::constant::Constant;
use crate::number::Number;
use crate::op::{BinaryOp, UnaryOp};

/// Enclosure of `f` at the end `x` of a modal interval (a half-line near ±∞).
fn at<T: Float>(x: T) -> Interval<T> {
    if x.is_finite() {
        Interval::new_unchecked(x, x)
    } else if x > T::ZERO {
        Interval::new_unchecked(T::MAX, T::INFINITY)
    } else {
        Interval::new_unchecked(T::NEG_INFINITY, -T::MAX)
    }
}

fn undefined<T: Float, R: Rounding>() -> Modal<T, R> {
    if R::IS_OUTER {
        Modal::ENTIRE
    } else {
        Modal::DUAL_ENTIRE
    }
}

/// The semantic extension of a continuous one-variable function, rounded as the module
/// documentation tables. `f` is the interval extension; `critical` lists interior points of
/// `P` where `f` may take its extremes (besides the ends).
fn one_variable<T: Float, R: Rounding>(
    x: Modal<T, R>,
    f: impl Fn(Interval<T>) -> Interval<T>,
    critical: &[T],
) -> Modal<T, R> {
    let p = x.prop();
    let Some((plo, phi)) = p.bounds() else {
        return undefined();
    };
    let range = f(p);
    let Some((rlo, rhi)) = range.bounds() else {
        return undefined();
    };
    // Largest lower bound and smallest upper bound of f over the samples.
    let mut max_lower = T::NEG_INFINITY;
    let mut min_upper = T::INFINITY;
    let mut finite = true;
    let ends = [plo, phi];
    let inside = critical.iter().copied().filter(|&c| plo < c && c < phi);
    for s in ends.into_iter().chain(inside) {
        let Some((lo, hi)) = f(at(s)).bounds() else {
            return undefined();
        };
        finite &= lo.is_finite() && hi.is_finite();
        if lo > max_lower {
            max_lower = lo;
        }
        if hi < min_upper {
            min_upper = hi;
        }
    }
    if finite && !(rlo.is_finite() && rhi.is_finite()) {
        return undefined(); // a pole inside P
    }
    let proper = x.first() <= x.second();
    let (first, second) = match (proper, R::IS_OUTER) {
        (true, true) => (rlo, rhi),
        (true, false) => (min_upper, max_lower),
        (false, true) => (max_lower, min_upper),
        (false, false) => (rhi, rlo),
    };
    Modal::new_unchecked(first, second)
}

impl<T: Float, R: Rounding> Number for Modal<T, R> {
    #[inline]
    fn constant(c: &Constant) -> Self {
        let i = <Interval<T> as Number>::constant(c);
        if R::IS_OUTER {
            Modal::new_unchecked(i.inf(), i.sup())
        } else {
            Modal::new_unchecked(i.sup(), i.inf())
        }
    }

    fn unary(op: UnaryOp, a: Self) -> Self {
        let interval = |x: Interval<T>| <Interval<T> as Number>::unary(op, x);
        match op {
            UnaryOp::Neg => -a,
            UnaryOp::Recip => a.recip(),
            UnaryOp::Sqr | UnaryOp::Abs => one_variable(a, interval, &[T::ZERO]),
            _ => one_variable(a, interval, &[]),
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
            // a^b = exp(b · ln a): another computing program of the same function on its
            // domain a > 0, so the interpretability theorems apply to it as well.
            BinaryOp::Pow => {
                let l = Self::unary(UnaryOp::Ln, a);
                Self::unary(UnaryOp::Exp, b * l)
            }
            // A jump where `a` crosses 0: no semantic extension of a discontinuous function
            // is built here; the least informative value of the rounding is always sound.
            BinaryOp::Domain => undefined(),
        }
    }

    fn pown(a: Self, n: i32) -> Self {
        let interval = |x: Interval<T>| x.pown(n);
        if n > 0 && n % 2 == 0 {
            one_variable(a, interval, &[T::ZERO])
        } else {
            one_variable(a, interval, &[])
        }
    }
}
