//! # beam-trace
//!
//! Reliable ray and beam tracing of implicit surfaces with interval arithmetic: one render
//! pipeline, its queries answered by the CPU backend here or by another backend (a GPU).
//!
//! The pipeline (see `docs/` of the repository for the method's papers):
//!
//! 1. [`scene`]: a TOML scene (camera, lights, surfaces combined by CSG, settings) is
//!    compiled into one scene function `f` and its ray restriction `g(t) = f(c + t·D)`.
//! 2. [`plan`]: the effect plan decides which passes run.
//! 3. [`grid`]: a regular grid of cells classified by `0 ∈ F(cell)` limits every search.
//! 4. [`beam`] and [`screen`]: beams over screen boxes are classified Miss / Hit /
//!    Undecided by the rejection and inclusion tests; [`root`] finders search single rays.
//! 5. [`aa`], [`shading`], [`shadow`]: anti-aliasing, Phong shading, hard shadows from
//!    point lights and soft shadows from area lights (stochastic, beam and Minkowski
//!    methods behind one [`shadow::ShadowMethod`] trait).
//! 6. [`render()`](mod@render): the one render pipeline. Its passes turn their work into
//!    batches of plain-data queries that a [`backend::Backend`] answers: the CPU backend
//!    ([`Cpu`], rayon through the grid) here, a GPU backend in the `gpu-backend` crate; the
//!    [`Routing`] says which backend answers which query, and sends to the CPU what a
//!    backend cannot answer. The result is an image and per-pass statistics (named counters
//!    per [`Pass`]).
//!
//! ## A first render
//!
//! ```
//! use beam_trace::{NoProgress, Scene, render};
//!
//! let scene = Scene::from_toml(
//!     r#"
//!     [camera]
//!     eye = [0.0, 0.0, 4.0]
//!     look_at = [0.0, 0.0, 0.0]
//!     width = 24
//!     height = 16
//!
//!     [[surfaces]]
//!     formula = "x^2 + y^2 + z^2 - 1"
//!     bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
//!
//!     [[lights]]
//!     type = "point"
//!     position = [2.0, 3.0, 4.0]
//!     "#,
//!     "ball.toml",
//!     None,
//! )?;
//! let out = render(&scene, &NoProgress)?;
//! // The centre pixel sees the ball, a corner pixel the background.
//! assert_ne!(out.image.get(12, 8), scene.background);
//! assert_eq!(out.image.get(0, 0), scene.background);
//! // The plan ran primary visibility (screen boxes, then the pixels they left undecided
//! // resolved by their beams), normals, shadows and shading, and no point-ray pass.
//! assert!(out.stats.pass("screen-boxes").unwrap().ran);
//! assert!(out.stats.pass("pixel-beams").unwrap().ran);
//! assert!(!out.stats.pass("primary-rays").unwrap().ran);
//! println!("{}", out.stats);
//! # Ok::<(), beam_trace::Error>(())
//! ```
//!
//! Scene errors name the file, the field and the problem:
//!
//! ```
//! let text = "[camera]\nfov = 0.0\n[[surfaces]]\ncatalog = \"sphere\"\n";
//! let err = beam_trace::Scene::from_toml(text, "bad.toml", None).unwrap_err();
//! assert!(err.to_string().starts_with("bad.toml: camera.fov"), "{err}");
//! ```

pub mod aa;
pub mod backend;
pub mod beam;
pub mod blocks;
pub mod camera;
pub mod centred;
pub mod error;
pub mod float_map;
pub mod free_ranges;
pub mod frustum;
pub mod grid;
pub mod ibox;
pub mod image;
pub mod mesh;
pub mod plan;
pub mod progress;
pub mod ray;
pub mod render;
pub mod root;
pub mod sample;
pub mod scene;
pub mod screen;
pub mod shading;
pub mod shadow;
pub mod stats;
pub mod window;

pub use backend::{Backend, Routing, cpu::Cpu};
pub use camera::Camera;
pub use error::Error;
pub use float_map::FloatMap;
pub use image::Image;
pub use plan::{Pass, Plan};
pub use progress::{NoProgress, Progress};
pub use ray::{Beam, BeamEval, IBox, Precision, Ray};
pub use render::{RenderOutput, ShadowMaps, render, render_on};
pub use root::{Proof, RayFn, RootCounters, RootFinder, RootMethod, RootResult, RootSettings};
pub use sample::{Area, Coverage, Hit, Sample};
pub use scene::{Geometry, Light, Material, Scene};
pub use stats::RenderStats;
