//! Helpers for testing code built on interval-core: soundness checks against a reference
//! value that the caller supplies ([`check_encloses`], [`assert_encloses`], and their
//! bracket forms), and, with the `proptest` cargo feature, `strategy`: proptest strategies
//! for floats of every class, intervals, decorated and modal intervals, and points inside an
//! interval.
//!
//! The reference value is the caller's: a value known exactly (an exact input, a closed
//! form), or a bracket `[lo, hi]` known to hold the exact value (for instance an MPFR or
//! double-double evaluation rounded outward). Comparisons are exact (`T` against `T`), so the
//! check never adds its own rounding error.
//!
//! ```
//! use interval_core::Interval;
//! use interval_core::testing::{assert_encloses, check_encloses_bracket};
//!
//! let x = Interval::new(1.0, 2.0)?;
//! let y = x.sqr() - x;
//! assert_encloses(y, 0.0); // the value at x = 1, known exactly
//! // The value at x = √2 is 2 − √2 ≈ 0.5858: a bracket known from elsewhere.
//! assert!(check_encloses_bracket(y, 0.5857, 0.5859).is_ok());
//! # Ok::<(), interval_core::IntervalError>(())
//! ```

#[cfg(feature = "proptest")]
pub mod strategy;

use crate::float::Float;
use crate::interval::Interval;
use core::fmt;

/// A failed soundness check: the result does not contain the reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NotEnclosed {
    /// The result's lower bound, as `f64` (`+∞` for an empty result).
    pub inf: f64,
    /// The result's upper bound, as `f64` (`−∞` for an empty result).
    pub sup: f64,
    /// The reference bracket's lower end, as `f64`.
    pub ref_lo: f64,
    /// The reference bracket's upper end, as `f64`.
    pub ref_hi: f64,
}

impl fmt::Display for NotEnclosed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.ref_lo == self.ref_hi {
            write!(
                f,
                "unsound result [{:e}, {:e}]: the reference value {:e} lies outside",
                self.inf, self.sup, self.ref_lo
            )
        } else {
            write!(
                f,
                "unsound result [{:e}, {:e}]: the reference bracket [{:e}, {:e}] is not inside",
                self.inf, self.sup, self.ref_lo, self.ref_hi
            )
        }
    }
}

impl std::error::Error for NotEnclosed {}

/// Checks that `result` contains the exact value, known to lie in `[lo, hi]` (`lo ≤ hi`):
/// `result ⊇ [lo, hi]`, compared exactly. A NaN or reversed bracket fails.
///
/// # Errors
/// [`NotEnclosed`] describing the result and the bracket.
pub fn check_encloses_bracket<T: Float>(
    result: Interval<T>,
    lo: T,
    hi: T,
) -> Result<(), NotEnclosed> {
    let ok = !lo.is_nan() && !hi.is_nan() && lo <= hi && result.inf() <= lo && hi <= result.sup();
    if ok {
        Ok(())
    } else {
        Err(NotEnclosed {
            inf: result.inf().to_f64(),
            sup: result.sup().to_f64(),
            ref_lo: lo.to_f64(),
            ref_hi: hi.to_f64(),
        })
    }
}

/// Checks that `result` contains the exact reference value `exact` (a value of `T`; an
/// infinite value is never contained, as intervals hold real numbers only).
///
/// # Errors
/// [`NotEnclosed`] describing the result and the value.
pub fn check_encloses<T: Float>(result: Interval<T>, exact: T) -> Result<(), NotEnclosed> {
    if result.contains(exact) {
        Ok(())
    } else {
        Err(NotEnclosed {
            inf: result.inf().to_f64(),
            sup: result.sup().to_f64(),
            ref_lo: exact.to_f64(),
            ref_hi: exact.to_f64(),
        })
    }
}

/// Asserts (in a test) that `result` contains the exact reference value; panics with the
/// message of [`NotEnclosed`] otherwise.
#[track_caller]
pub fn assert_encloses<T: Float>(result: Interval<T>, exact: T) {
    if let Err(e) = check_encloses(result, exact) {
        panic!("{e}");
    }
}

/// Asserts (in a test) that `result` contains the bracket `[lo, hi]` of the exact value;
/// panics with the message of [`NotEnclosed`] otherwise.
#[track_caller]
pub fn assert_encloses_bracket<T: Float>(result: Interval<T>, lo: T, hi: T) {
    if let Err(e) = check_encloses_bracket(result, lo, hi) {
        panic!("{e}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks() {
        let x = Interval::new(1.0, 2.0).unwrap();
        assert!(check_encloses(x, 1.5).is_ok());
        assert!(check_encloses(x, 2.5).is_err());
        assert!(check_encloses(x, f64::INFINITY).is_err());
        assert!(check_encloses(Interval::EMPTY, 0.0).is_err());
        assert!(check_encloses_bracket(x, 1.0, 2.0).is_ok());
        assert!(check_encloses_bracket(x, 0.5, 1.5).is_err());
        assert!(check_encloses_bracket(x, 1.5, 1.2).is_err());
        let e = check_encloses(x, 3.0).unwrap_err();
        assert!(e.to_string().contains("reference value 3e0"));
    }

    #[test]
    #[should_panic(expected = "unsound result")]
    fn assert_panics_in_tests() {
        assert_encloses(Interval::new(1.0, 2.0).unwrap(), 0.0);
    }
}
