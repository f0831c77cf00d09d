//! Shared helpers of the example programs.
//!
//! * [`catalog_view`]: a catalog surface set up for ray casting (the root finder
//!   comparisons of the `root-finders` example and the benchmarks).
//! * [`soft_scene`]: catalog surfaces under a square area light (the soft-shadow paper's
//!   set-up).
//! * [`report`]: printing and saving a markdown report, and the exit status.

pub mod catalog_view;
pub mod report;
pub mod soft_scene;
