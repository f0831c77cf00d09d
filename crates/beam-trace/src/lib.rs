//! # beam-trace
//!
//! Reliable CPU ray and beam tracing of implicit surfaces with interval arithmetic.
//!
//! The pipeline (see `docs/` of the repository for the method's papers):
//!
//! 1. [`scene`]: a TOML scene (camera, lights, surfaces combined by CSG, settings) is
//!    compiled into one scene function `f` and its ray restriction `g(t) = f(c + t·D)`.
//! 2. [`plan`]: the effect plan decides which passes run.
//! 3. [`grid`]: a regular grid of cells classified by `0 ∈ F(cell)` limits every search.
//! 4. [`beam`] and [`screen`]: beams over screen boxes are classified Miss / Hit /
//!    Undecided by the rejection and inclusion tests; [`root`] finders search single rays.
//! 5. [`aa`], [`shading`], [`shadow`]: anti-aliasing, Phong shading, shadows.
//! 6. [`render()`](mod@render): the passes in parallel, an image and per-pass statistics.

pub mod aa;
pub mod beam;
pub mod camera;
pub mod error;
pub mod grid;
pub mod image;
pub mod plan;
pub mod ray;
pub mod render;
pub mod root;
pub mod scene;
pub mod screen;
pub mod shading;
pub mod shadow;
pub mod stats;

pub use camera::Camera;
pub use error::Error;
pub use image::Image;
pub use plan::Plan;
pub use ray::{Beam, BeamEval, IBox, Ray};
pub use render::{NoProgress, Progress, RenderOutput, render};
pub use root::{Proof, RayFn, RootCounters, RootFinder, RootMethod, RootResult, RootSettings};
pub use scene::{Geometry, Light, Material, Scene};
pub use stats::RenderStats;
