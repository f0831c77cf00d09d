//! The render pipeline, written once for every backend: the passes of the [`Plan`] turn
//! their work into batches of queries that a [`Backend`] answers, and assemble the image
//! and per-pass statistics.
//!
//! ```text
//! plan -> backend set-up (grid | kernels) -> screen boxes -> primary rays | pixel beams
//!      -> normals -> hard shadows -> soft shadows -> shading -> images + statistics
//! ```
//!
//! Each answer depends on its query alone and counters are sums over queries, so images
//! and counters do not depend on the thread count, nor on how a pass cuts its batches,
//! nor on how the image is cut into [`Window`]s rendered apart ([`Pipeline`]) and put
//! together again.

mod batches;
mod box_map;
mod buffers;
mod classes;
mod fingerprint;
mod hard_shadows;
mod images;
mod output;
mod piece;
mod pipeline;
mod pixel_beams;
mod pixel_box;
mod pixels;
mod primary;
mod resolve;
mod shading;
mod soft_shadows;

pub use box_map::BoxMap;
pub use images::{box_class_color, classification_image, cost_image, shadow_class_image};
pub use output::{RenderOutput, ShadowMaps};
pub use piece::{Piece, PieceShadows};
pub use pipeline::Pipeline;
pub use pixel_box::PixelBox;

use crate::backend::cpu::Cpu;
use crate::backend::{Backend, Routing};
use crate::beam::BoxClass;
use crate::error::Error;
use crate::plan::{Pass, Plan, Primary};
use crate::progress::Progress;
use crate::scene::Scene;
use crate::stats::PassStats;
use crate::window::Window;

/// Renders `scene` on the CPU: plans the passes, runs them, and returns the image and
/// statistics.
///
/// # Errors
///
/// [`Error`] when a backend fails (the CPU does not).
pub fn render(scene: &Scene, progress: &dyn Progress) -> Result<RenderOutput, Error> {
    render_on(scene, &Cpu, progress)
}

/// Renders `scene` with `backend` answering the queries it supports and the CPU the others
/// (see [`Routing`]).
///
/// # Errors
///
/// [`Error::Backend`] when the backend cannot run the scene or fails.
pub fn render_on(
    scene: &Scene,
    backend: &dyn Backend,
    progress: &dyn Progress,
) -> Result<RenderOutput, Error> {
    pipeline::render_whole(scene, backend, progress)
}

/// The grid and screen-box passes alone, on the CPU, with `plan`: their statistics and
/// each pixel's box class (what a block of animation frames proves once for its frames,
/// [`crate::blocks`]). Nothing when the plan has no screen boxes.
///
/// # Errors
///
/// Never on the CPU; the error type is the pipeline's.
pub(crate) fn screen_box_pass(
    scene: &Scene,
    plan: &Plan,
    progress: &dyn Progress,
) -> Result<(Vec<PassStats>, Vec<Option<BoxClass>>), Error> {
    if !plan.runs(Pass::ScreenBoxes) {
        return Ok((Vec::new(), Vec::new()));
    }
    // The classes alone: the Hit boxes' shading is not judged.
    let mut plan = plan.clone();
    if let Primary::Iaa { max_depth, .. } = plan.primary {
        plan.primary = Primary::ScreenBoxes { max_depth };
    }
    let plan = &plan;
    let routing = Routing::new(&Cpu, scene, plan);
    let (queries, mut passes) = routing.prepare(&Cpu, scene, plan)?;
    let window = Window::full(scene.camera.width(), scene.camera.height());
    let (classes, _, stats) = primary::structure(&queries, scene, plan, &window, progress)?;
    passes.push(stats);
    Ok((
        passes,
        (0..classes.len())
            .map(|p| classes.get(p).map(|c| c.class))
            .collect(),
    ))
}
