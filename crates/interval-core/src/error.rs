//! The error type of this crate.

use thiserror::Error;

/// Why an interval could not be constructed.
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
}
