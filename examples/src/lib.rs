//! Shared helpers of the example programs.
//!
//! * [`catalog_view`]: a catalog surface set up for ray casting (the root finder
//!   comparisons of the `root-finders` example and the benchmarks).
//! * [`render2d`]: the quadtree interval renderer of planar implicit regions behind the
//!   `render2d` example (also timed by the benchmarks).
//! * [`soft_scene`]: catalog surfaces under a square area light (the soft-shadow paper's
//!   set-up).
//! * [`report`]: printing and saving a markdown report, and the exit status.

pub mod catalog_view;
pub mod render2d;
pub mod report;
pub mod soft_scene;
