//! Shared helpers of the example programs.
//!
//! * [`render2d`]: the quadtree interval renderer of planar implicit regions behind the
//!   `render2d` example (also timed by the benchmarks).

pub mod render2d;
