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

mod fingerprint;
mod hard_shadows;
mod images;
mod piece;
mod pipeline;
mod pixel_beams;
mod pixels;
mod primary;
mod shading;
mod soft_shadows;

pub use images::{box_class_color, classification_image, cost_image, shadow_class_image};
pub use piece::{Piece, PieceShadows};
pub use pipeline::Pipeline;

use crate::backend::cpu::Cpu;
use crate::backend::{Backend, Routing};
use crate::beam::BoxClass;
use crate::error::Error;
use crate::float_map::FloatMap;
use crate::image::Image;
use crate::plan::{Pass, Plan, Primary};
use crate::progress::Progress;
use crate::sample::Coverage;
use crate::scene::Scene;
use crate::shadow::ShadowClass;
use crate::stats::{PassStats, RenderStats};
use crate::window::Window;
use pixels::Pixels;

/// What a render produces.
#[derive(Clone, Debug)]
pub struct RenderOutput {
    /// The image.
    pub image: Image,
    /// Per-pass time and counters.
    pub stats: RenderStats,
    /// Proven-miss (blue), proven-hit (red) and undecided (yellow) screen boxes, with box
    /// outlines (thesis fig. 5.13); grey where no beam classified the pixel.
    pub classification: Image,
    /// The cost of primary visibility per pixel, as a heat map (thesis fig. 5.8), in the
    /// backend's unit of cost (time on the CPU).
    pub cost_map: Image,
    /// Each pixel's screen box class (`None` where no screen box pass ran).
    pub box_classes: Vec<Option<BoxClass>>,
    /// Each pixel's proven bounds on the share of its area whose rays meet a surface.
    pub coverage: Vec<Coverage>,
    /// Soft shadows per pixel; `None` without a soft-shadow pass.
    pub shadows: Option<ShadowMaps>,
    /// The plan that ran.
    pub plan: Plan,
}

/// What the soft-shadow pass found, per pixel (row-major).
#[derive(Clone, Debug)]
pub struct ShadowMaps {
    /// The class over every area light: `Lit` or `Umbra` when every shaded sample of the
    /// pixel is proven so for every area light, `BackFacing` when every one faces away from
    /// every area light, else `Penumbra`; `None` where no sample is shaded.
    pub classes: Vec<Option<ShadowClass>>,
    /// Per area light (in the scene's order of area lights), the visible fraction averaged
    /// over the pixel's shaded samples; NaN where none is shaded.
    pub fractions: Vec<Vec<f32>>,
    /// Per area light, the proven lower bound of each pixel's mean visible fraction (the
    /// fraction the shading uses: 0 for samples facing away from the light); NaN where no
    /// sample is shaded.
    pub lower: Vec<Vec<f32>>,
    /// Per area light, the proven upper bound, likewise.
    pub upper: Vec<Vec<f32>>,
    /// Width of the maps in pixels.
    pub width: u32,
    /// Height of the maps in pixels.
    pub height: u32,
    /// The classes as an image (the soft-shadow paper's Fig. 7): proven lit green, proven
    /// umbra blue, penumbra orange, facing away from every area light blue-grey, no shaded
    /// surface dark grey.
    pub image: Image,
}

impl ShadowMaps {
    /// Area light `light`'s fraction, lower and upper bound maps, `None` past the last area
    /// light.
    pub fn light_maps(&self, light: usize) -> Option<[FloatMap; 3]> {
        let map = |v: &Vec<Vec<f32>>| FloatMap {
            width: self.width,
            height: self.height,
            values: v[light].clone(),
        };
        (light < self.fractions.len())
            .then(|| [map(&self.fractions), map(&self.lower), map(&self.upper)])
    }

    /// Area light `light`'s bound widths as an image: black where the fraction is proven
    /// exactly, brighter with the width (`sqrt(width)`, white for the unknown `[0, 1]`),
    /// dark red where no sample is shaded; `None` past the last area light.
    pub fn bound_width_image(&self, light: usize) -> Option<Image> {
        let (lower, upper) = (self.lower.get(light)?, self.upper.get(light)?);
        let pixels = lower
            .iter()
            .zip(upper)
            .map(|(&lo, &hi)| {
                let w = hi - lo;
                if w.is_finite() {
                    [w.max(0.0).sqrt(); 3]
                } else {
                    [0.25, 0.0, 0.0]
                }
            })
            .collect();
        Some(Image {
            width: self.width,
            height: self.height,
            pixels,
        })
    }
}

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
    let (classes, _, _, stats) = primary::structure(&queries, scene, plan, &window, progress)?;
    passes.push(stats);
    Ok((passes, classes.iter().map(|c| c.map(|c| c.class)).collect()))
}

/// Rows of pixels a pass hands the backend per batch: batches big enough to keep every
/// core (or the GPU) busy, small enough to show progress and bound memory.
const ROWS_PER_BATCH: u32 = 256;

/// A batch of whole image rows: the pixels `first..first + n` (row-major).
struct RowBatch {
    /// Rows in the batch.
    rows: u32,
    /// Its first pixel.
    first: usize,
    /// Its number of pixels.
    n: usize,
}

/// The batches of [`ROWS_PER_BATCH`] rows that cover a `w × h` image, top to bottom.
fn row_batches(w: u32, h: u32) -> impl Iterator<Item = RowBatch> {
    (0..h).step_by(ROWS_PER_BATCH as usize).map(move |y0| {
        let rows = ROWS_PER_BATCH.min(h - y0);
        RowBatch {
            rows,
            first: (y0 * w) as usize,
            n: (rows * w) as usize,
        }
    })
}

/// The samples of every pixel from a primary pass, the cost of each pixel, and the pass's
/// statistics.
type PixelSamples = (Pixels, Vec<f32>, PassStats);
