//! Shared helpers of the example programs.
//!
//! * `accuracy` (with the `plots` feature): the soft-shadow accuracy-against-cost experiment
//!   of the `accuracy-cost` example, its metrics, plots and report.
//! * [`catalog_view`]: a catalog surface set up for ray casting (the root finder
//!   comparisons of the `root-finders` example and the benchmarks).
//! * [`exact_sweeps`]: the exact soft-shadow method's experiments through the renderer
//!   (the `soft-shadows exact` example).
//! * [`soft_scene`]: catalog surfaces under a square area light (the soft-shadow paper's
//!   set-up).
//! * [`pass_bars`]: a progress bar per pass of a render.
//! * [`report`]: printing and saving a markdown report, and the exit status.

#[cfg(feature = "plots")]
pub mod accuracy;
pub mod catalog_view;
pub mod exact_sweeps;
pub mod pass_bars;
pub mod polygon_scene;
pub mod report;
pub mod soft_scene;
