//! The error type of this crate.

use thiserror::Error;

/// Errors of this crate: an interval that cannot be constructed, a literal that cannot be
/// read, or mismatched slice inputs.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum IntervalError {
    /// A bound was NaN.
    #[error("interval bound is NaN ({which} bound)")]
    NanBound {
        /// `"lower"` or `"upper"`.
        which: &'static str,
    },
    /// The lower bound exceeds the upper bound.
    #[error("lower bound {lo} exceeds upper bound {hi}")]
    Reversed {
        /// The lower bound, as `f64`.
        lo: f64,
        /// The upper bound, as `f64`.
        hi: f64,
    },
    /// A bound is an infinity on the wrong side (`[+∞, ·]` or `[·, −∞]`), which would denote
    /// no real number.
    #[error("interval [{lo}, {hi}] contains no real number (infinite bound on the wrong side)")]
    InfiniteEndpoint {
        /// The lower bound, as `f64`.
        lo: f64,
        /// The upper bound, as `f64`.
        hi: f64,
    },
    /// An interval literal (`"[0.1, 2]"`, `"[1.5]"`, `"[empty]"`, ...) could not be read.
    #[error("invalid interval literal at byte {position}: {reason}")]
    Parse {
        /// Byte offset in the text where the problem was found.
        position: usize,
        /// What was wrong, e.g. `"expected a number"`.
        reason: &'static str,
    },
    /// Slices passed to a batch operation have different lengths.
    #[error("{operation}: argument {argument} has length {found}, expected {expected}")]
    LengthMismatch {
        /// The batch operation, e.g. `"batch::add"`.
        operation: &'static str,
        /// Which argument has the wrong length (`"rhs"`, `"out"`, ...).
        argument: &'static str,
        /// The length of the first argument.
        expected: usize,
        /// The length found.
        found: usize,
    },
}
