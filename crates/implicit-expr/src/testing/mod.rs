//! Helpers for property tests of code that evaluates formulas over boxes: a soundness check
//! of an interval value against the formula's value at a point, computed in higher
//! precision ([`check_value_in`], [`check_sound`], [`assert_sound`]), and, with the
//! `proptest` cargo feature, the module `strategy`: random expressions over every operation, and
//! random regions with points inside.
//!
//! The reference is the formula's value at the point enclosed in double-double interval
//! arithmetic ([`DdInterval`], about 104 bits; its constants are the formula's `f64`
//! enclosures of the literals), decorated, so that it is known whether the formula is
//! defined there. An interval value over a region holding the point must meet the
//! reference wherever the formula is defined at the point (IEEE 1788's set-based model:
//! outside the domain there is nothing to enclose). The check answers:
//!
//! * [`Verdict::Enclosed`]: the reference lies inside the value, the value is sound there;
//! * [`Verdict::Undefined`]: the formula is undefined at the point, nothing to check;
//! * [`Verdict::Unresolved`]: the reference straddles a bound of the value (it is within
//!   about `2^-100` of a bound), or the point may lie on the edge of the domain;
//! * [`CheckError::Unsound`]: the value misses the formula's value, a bug.
//!
//! ```
//! use implicit_expr::testing::{Verdict, check_sound, check_value_in};
//! use implicit_expr::{Context, Tape, parse::parse};
//! use interval_core::Interval;
//!
//! let mut ctx = Context::new();
//! let f = parse(&mut ctx, "x * (1 - x) - 0.1", &[])?;
//! let tape = Tape::new(&ctx, &[f])?;
//! let iv = |a, b| Interval::new(a, b).unwrap();
//! let region = [iv(0.0, 0.5), iv(0.0, 0.0), iv(0.0, 0.0)];
//! // The crate's own interval evaluation over the region, against the point 0.25.
//! assert_eq!(check_sound(&tape, &region, &[0.25, 0.0, 0.0])?, Verdict::Enclosed);
//! // Someone's value over the region that forgot the constant's rounding: caught.
//! let wrong = iv(-0.1, 0.1499);
//! assert!(check_value_in(wrong, &tape, &[0.5, 0.0, 0.0]).is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#[cfg(feature = "proptest")]
pub mod strategy;

use interval_core::{Dd, DdInterval, Decoration, Float, Interval};

use crate::error::Error;
use crate::eval::Evaluator;
use crate::tape::Tape;

/// What a soundness check found (see the [module documentation](self)).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// The formula's value at the point is proven inside the interval value.
    Enclosed,
    /// The formula is undefined at the point: an interval value has nothing to enclose.
    Undefined,
    /// Neither proven inside nor outside: the reference straddles a bound of the value, or
    /// the formula may be undefined at the point (an argument on the edge of a domain).
    Unresolved,
}

/// Why a soundness check failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CheckError {
    /// The interval value excludes the formula's value at the point.
    #[error(
        "unsound: the interval value [{inf:e}, {sup:e}] excludes the formula's value at \
         {point:?}, which lies in [{reference_lo:e}, {reference_hi:e}]"
    )]
    Unsound {
        /// The lower bound of the value checked (`+inf` when empty).
        inf: f64,
        /// Its upper bound (`-inf` when empty).
        sup: f64,
        /// The reference enclosure's lower bound, rounded down to `f64`.
        reference_lo: f64,
        /// The reference enclosure's upper bound, rounded up to `f64`.
        reference_hi: f64,
        /// The point.
        point: Vec<f64>,
    },
    /// A coordinate of the point lies outside the region (or is not a number).
    #[error("point coordinate {slot} is {value}, outside the region's [{lo}, {hi}]")]
    PointOutside {
        /// The variable slot.
        slot: usize,
        /// The coordinate.
        value: f64,
        /// The region's lower bound in that slot.
        lo: f64,
        /// The region's upper bound in that slot.
        hi: f64,
    },
    /// The region and the point have different numbers of coordinates.
    #[error("the region has {region} coordinates, the point {point}")]
    Dimensions {
        /// Coordinates of the region.
        region: usize,
        /// Coordinates of the point.
        point: usize,
    },
    /// The tape could not be evaluated (too few variables given).
    #[error(transparent)]
    Eval(#[from] Error),
}

/// The formula's value at `point` in double-double interval arithmetic, and its decoration
/// (at least `def` where the formula is proven defined at the point).
///
/// # Errors
/// [`CheckError::Eval`] when the point has fewer coordinates than the tape has variables.
pub fn reference<T: Float>(
    tape: &Tape,
    point: &[T],
) -> Result<(DdInterval, Decoration), CheckError> {
    let p: Vec<DdInterval> = point
        .iter()
        .map(|v| DdInterval::point(v.to_f64()))
        .collect();
    Ok(Evaluator::<DdInterval>::new(tape).eval_decorated(&p)?)
}

/// Checks `value`, an interval value of the tape's formula over some region that holds
/// `point`, against the formula's value at `point` (see the [module documentation](self)).
///
/// # Errors
/// [`CheckError::Unsound`] when `value` provably excludes the formula's value;
/// [`CheckError::Eval`] when the point has too few coordinates.
pub fn check_value_in<T: Float>(
    value: Interval<T>,
    tape: &Tape,
    point: &[T],
) -> Result<Verdict, CheckError> {
    let (r, dec) = reference(tape, point)?;
    let Some((lo, hi)) = r.bounds() else {
        return Ok(Verdict::Undefined);
    };
    let (inf, sup) = match value.bounds() {
        Some((a, b)) => (a.to_f64(), b.to_f64()),
        None => (f64::INFINITY, f64::NEG_INFINITY),
    };
    let (vinf, vsup) = (Dd::from_f64(inf), Dd::from_f64(sup));
    if vinf <= lo && hi <= vsup {
        return Ok(Verdict::Enclosed);
    }
    let disjoint = value.is_empty() || hi < vinf || vsup < lo;
    if disjoint && dec >= Decoration::Def {
        return Err(CheckError::Unsound {
            inf,
            sup,
            reference_lo: lo.to_f64_down(),
            reference_hi: hi.to_f64_up(),
            point: point.iter().map(|v| v.to_f64()).collect(),
        });
    }
    Ok(Verdict::Unresolved)
}

/// Evaluates the tape over `region` with `Interval<T>` and checks the value against the
/// formula's value at `point`, which must lie in the region ([`check_value_in`]).
///
/// # Errors
/// [`CheckError::Unsound`] for an unsound value; [`CheckError::PointOutside`] and
/// [`CheckError::Dimensions`] for a point that is not in the region; [`CheckError::Eval`]
/// when the region has fewer coordinates than the tape has variables.
pub fn check_sound<T: Float>(
    tape: &Tape,
    region: &[Interval<T>],
    point: &[T],
) -> Result<Verdict, CheckError> {
    if region.len() != point.len() {
        return Err(CheckError::Dimensions {
            region: region.len(),
            point: point.len(),
        });
    }
    for (slot, (x, &v)) in region.iter().zip(point).enumerate() {
        if !x.contains(v) {
            let (lo, hi) = x
                .bounds()
                .map_or((f64::NAN, f64::NAN), |(a, b)| (a.to_f64(), b.to_f64()));
            return Err(CheckError::PointOutside {
                slot,
                value: v.to_f64(),
                lo,
                hi,
            });
        }
    }
    let value = Evaluator::<Interval<T>>::new(tape).eval(region)?;
    check_value_in(value, tape, point)
}

/// [`check_sound`], panicking with the reason when the value is unsound or the input
/// malformed.
///
/// # Panics
/// When [`check_sound`] returns an error.
#[track_caller]
pub fn assert_sound<T: Float>(tape: &Tape, region: &[Interval<T>], point: &[T]) -> Verdict {
    match check_sound(tape, region, point) {
        Ok(v) => v,
        Err(e) => panic!("{e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Context;
    use crate::parse::parse;

    fn tape(text: &str) -> Tape {
        let mut c = Context::new();
        let f = parse(&mut c, text, &[]).unwrap();
        Tape::new(&c, &[f]).unwrap()
    }

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn verdicts() {
        let t = tape("sqrt(x) - 0.1");
        let region = [iv(-1.0, 4.0), iv(0.0, 0.0), iv(0.0, 0.0)];
        assert_eq!(
            check_sound(&t, &region, &[1.0, 0.0, 0.0]),
            Ok(Verdict::Enclosed)
        );
        assert_eq!(
            check_sound(&t, &region, &[-0.5, 0.0, 0.0]),
            Ok(Verdict::Undefined)
        );
        // 0.1 is not a double: the reference straddles the double nearest to 1.9...
        let near = [iv(1.0, 4.0), iv(0.0, 0.0), iv(0.0, 0.0)];
        assert_eq!(
            check_sound(&t, &near, &[4.0, 0.0, 0.0]),
            Ok(Verdict::Enclosed)
        );
        // ... and a value that ends at that double is caught or left open, never enclosed.
        let v = check_value_in(iv(0.0, 1.9), &t, &[4.0, 0.0, 0.0]);
        assert!(!matches!(v, Ok(Verdict::Enclosed)), "{v:?}");
        // A plainly wrong value.
        let e = check_value_in(iv(0.0, 1.0), &t, &[4.0, 0.0, 0.0]).unwrap_err();
        assert!(e.to_string().starts_with("unsound"), "{e}");
        // The empty set is wrong where the formula is defined.
        assert!(check_value_in(Interval::<f64>::EMPTY, &t, &[4.0, 0.0, 0.0]).is_err());
    }

    #[test]
    fn malformed_inputs_are_errors() {
        let t = tape("x + y");
        let region = [iv(0.0, 1.0), iv(0.0, 1.0), iv(0.0, 0.0)];
        assert!(matches!(
            check_sound(&t, &region, &[2.0, 0.5, 0.0]),
            Err(CheckError::PointOutside { slot: 0, .. })
        ));
        assert!(matches!(
            check_sound(&t, &region, &[0.5, 0.5]),
            Err(CheckError::Dimensions {
                region: 3,
                point: 2
            })
        ));
        assert!(matches!(
            check_sound(&t, &region[..1], &[0.5]),
            Err(CheckError::Eval(_))
        ));
        assert_eq!(
            check_sound(&t, &region, &[0.5, 0.5, 0.0]),
            Ok(Verdict::Enclosed)
        );
    }

    #[test]
    fn f32_values() {
        let t = tape("x * 0.1");
        let r = [Interval::<f32>::new(1.0, 2.0).unwrap(); 3];
        assert_eq!(
            check_sound(&t, &r, &[1.5f32, 1.0, 1.0]),
            Ok(Verdict::Enclosed)
        );
        let wrong = Interval::<f32>::new(0.0, 0.1).unwrap();
        assert!(check_value_in(wrong, &t, &[1.5f32, 1.0, 1.0]).is_err());
    }
}
