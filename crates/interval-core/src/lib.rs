//! # interval-core
//!
//! Intervals with tight directed rounding over `f64` and `f32`, and modal intervals with
//! Kaucher arithmetic: the numerical foundation of reliable implicit-surface rendering.
//!
//! * [`Interval`]: the set-based interval of IEEE 1788-2015. Operation names are the
//!   standard's in snake_case (`sqr`, `pown`, `mul_rev_to_pair`, `precedes`, `interior`,
//!   `convex_hull`, ...). `+ - * /`, `fma`, `sqr`, `sqrt` and `recip` are tight, computed
//!   without changing the FPU rounding mode (see [`float`]); elementary functions are
//!   enclosures within one ulp of tight, built on correctly rounded CORE-MATH functions.
//! * [`DecInterval`]: decorated intervals (IEEE 1788 §8, §11) with [`Decoration`]s
//!   `com`, `dac`, `def`, `trv`, `ill` and the standard's propagation rules.
//! * [`Modal`]: modal intervals `[a, b]` with `a > b` allowed (improper), with `dual`,
//!   `prop`, `meet`/`join` and Kaucher arithmetic rounded outward (for `Out(fR(X))`,
//!   the *-semantics) or inward (for `Inn(fR(X))`, the **-semantics).
//!
//! ```
//! use interval_core::Interval;
//!
//! let x = Interval::new(-1.0, 2.0)?;
//! let y = x.sqr() - x;              // dependency: wider than the true range [-0.25, 2]
//! assert!(y.contains(-0.25) && y.contains(2.0));
//! let e = Interval::point(1.0)?.exp();
//! assert!(e.contains(std::f64::consts::E));
//! # Ok::<(), interval_core::IntervalError>(())
//! ```
//!
//! [`testing`] has soundness checks for users' tests against a reference value, and, with
//! the `proptest` cargo feature, proptest strategies for intervals with all the edge cases.
//!
//! The rounding model and the accuracy of every function are documented in
//! `docs/numerics.md` of the repository.

pub mod dd;
pub mod decorated;
pub mod float;
pub mod interval;
pub mod isa;
pub mod modal;
pub mod testing;

mod error;

pub use dd::{Dd, DdInterval};
pub use decorated::{DecInterval, Decoration};
pub use error::IntervalError;
pub use float::Float;
pub use interval::Interval;
pub use interval::overlap::Overlap;
pub use modal::{Inner, Modal, Outer, Rounding};
