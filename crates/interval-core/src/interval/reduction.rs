//! Exact reduction operations (IEEE 1788 §12.12.12, after IEEE 754 §9.4): `sum`, `dot`,
//! `sum_sqr` and `sum_abs` of slices of `f64` or `f32`, with **correctly rounded** results in
//! both directions.
//!
//! **Method: a long accumulator.** Every term (a value, a product of two values, a square) is
//! an exact dyadic rational `m · 2^e` with `e ≥ 2·emin` (`emin = −1074` for `f64`); the terms
//! are added without any rounding into an exact dyadic accumulator (a big-integer
//! significand over a common power of two, a few thousand bits at most), and the exact total
//! is rounded once toward −∞ and once toward +∞ on the true grid of `T` (subnormals
//! included; beyond `MAX` the bounds are `MAX` and `+∞`). The results are therefore the
//! tightest: `down ≤ exact ≤ up`, with `down = up` exactly when the total is a value of `T`,
//! otherwise adjacent. The cost is linear in the length, with a big-integer addition per
//! term.
//!
//! Each function returns `(down, up)`. Infinite and NaN inputs follow IEEE 754: a NaN, or
//! infinities of both signs (and, for `dot`, `0 · ∞`), give `(NaN, NaN)`; otherwise an
//! infinite term gives that infinity for both. An empty slice sums to `(0, 0)`.
//! `Interval::new(down, up)` turns a finite result into an interval.
//!
//! ```
//! use interval_core::interval::reduction;
//! // 1e16 + 1 − 1e16: naive summation loses the 1.
//! let (down, up) = reduction::sum(&[1e16, 1.0, -1e16]);
//! assert_eq!((down, up), (1.0, 1.0));
//! // 0.1·3 + 0.2·3 with the doubles 0.1 and 0.2 lies just above the double 0.9.
//! let (d, u) = reduction::dot(&[0.1f64, 0.2], &[3.0, 3.0])?;
//! assert!(d == 0.9 && u == d.next_up());
//! # Ok::<(), interval_core::IntervalError>(())
//! ```

use crate::IntervalError;
use crate::float::Float;
use crate::float::dyadic::Dyadic;

/// Adds the exact terms and rounds the total both ways; handles the non-finite terms.
fn reduce<T: Float>(terms: impl Iterator<Item = Term>) -> (T, T) {
    let mut acc = Dyadic::zero();
    let (mut pos_inf, mut neg_inf, mut nan) = (false, false, false);
    for t in terms {
        match t {
            Term::Exact(d) => acc = acc.add(&d),
            Term::Infinite(neg) => {
                if neg {
                    neg_inf = true;
                } else {
                    pos_inf = true;
                }
            }
            Term::Nan => nan = true,
        }
    }
    if nan || (pos_inf && neg_inf) {
        (T::NAN, T::NAN)
    } else if pos_inf {
        (T::INFINITY, T::INFINITY)
    } else if neg_inf {
        (T::NEG_INFINITY, T::NEG_INFINITY)
    } else {
        (acc.round(false), acc.round(true))
    }
}

/// One term of a reduction: exact, infinite with a sign, or invalid.
enum Term {
    /// A finite exact value.
    Exact(Dyadic),
    /// `−∞` (`true`) or `+∞`.
    Infinite(bool),
    /// NaN (also `0 · ∞`).
    Nan,
}

/// The exact term `x`.
fn value<T: Float>(x: T) -> Term {
    if x.is_nan() {
        Term::Nan
    } else if x.is_infinite() {
        Term::Infinite(x < T::ZERO)
    } else {
        Term::Exact(Dyadic::of(x))
    }
}

/// The exact term `x · y` (`0 · ∞` is NaN, as in IEEE 754).
fn product<T: Float>(x: T, y: T) -> Term {
    if x.is_nan() || y.is_nan() {
        Term::Nan
    } else if x.is_infinite() || y.is_infinite() {
        if x == T::ZERO || y == T::ZERO {
            Term::Nan
        } else {
            Term::Infinite((x < T::ZERO) != (y < T::ZERO))
        }
    } else {
        Term::Exact(Dyadic::of(x).mul(&Dyadic::of(y)))
    }
}

/// `Σ xᵢ`, rounded down and up (IEEE 1788 `sum`). Correctly rounded: see the module
/// documentation.
pub fn sum<T: Float>(xs: &[T]) -> (T, T) {
    reduce(xs.iter().map(|&x| value(x)))
}

/// `Σ xᵢ·yᵢ`, rounded down and up (IEEE 1788 `dot`). Correctly rounded.
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if the slices differ in length.
pub fn dot<T: Float>(xs: &[T], ys: &[T]) -> Result<(T, T), IntervalError> {
    if xs.len() != ys.len() {
        return Err(IntervalError::LengthMismatch {
            operation: "reduction::dot",
            argument: "ys",
            expected: xs.len(),
            found: ys.len(),
        });
    }
    Ok(reduce(xs.iter().zip(ys).map(|(&x, &y)| product(x, y))))
}

/// `Σ xᵢ²`, rounded down and up (IEEE 1788 `sumSquare`). Correctly rounded.
pub fn sum_sqr<T: Float>(xs: &[T]) -> (T, T) {
    reduce(xs.iter().map(|&x| product(x, x)))
}

/// `Σ |xᵢ|`, rounded down and up (IEEE 1788 `sumAbs`). Correctly rounded.
pub fn sum_abs<T: Float>(xs: &[T]) -> (T, T) {
    reduce(xs.iter().map(|&x| value(x.abs())))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_totals_and_special_values() {
        let inf = f64::INFINITY;
        assert_eq!(sum::<f64>(&[]), (0.0, 0.0));
        assert_eq!(sum(&[1e16, 1.0, -1e16]), (1.0, 1.0));
        assert_eq!(sum(&[f64::MAX, f64::MAX, -f64::MAX]), (f64::MAX, f64::MAX));
        assert_eq!(sum(&[f64::MAX, f64::MAX]), (f64::MAX, inf));
        assert_eq!(sum(&[1.0, 2f64.powi(-60)]), (1.0, 1.0f64.next_up()));
        assert_eq!(sum(&[-1.0, -(2f64.powi(-60))]), (-(1.0f64.next_up()), -1.0));
        let (d, u) = sum(&[1.0, inf, 2.0]);
        assert_eq!((d, u), (inf, inf));
        assert!(sum(&[inf, -inf]).0.is_nan());
        assert!(sum(&[1.0, f64::NAN]).1.is_nan());
        assert!(dot(&[0.0], &[inf]).unwrap().0.is_nan());
        assert!(dot(&[1.0], &[]).is_err());
        assert_eq!(dot(&[5e-324], &[0.5]).unwrap(), (0.0, 5e-324));
        assert_eq!(sum_sqr(&[3.0f32, 4.0]), (25.0, 25.0));
        assert_eq!(sum_abs(&[-1.5, 2.0, -0.5]), (4.0, 4.0));
        let (d, u) = sum(&[0.1f32, 0.2, 0.3]);
        assert_eq!(u, d.next_up());
    }
}
