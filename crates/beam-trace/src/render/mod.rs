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
//! and counters do not depend on the thread count, nor on how a pass cuts its batches.

mod hard_shadows;
mod images;
mod pixel_beams;
mod pixels;
mod primary;
mod shading;
mod soft_shadows;

pub use images::{box_class_color, classification_image, cost_image, shadow_class_image};

use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;

use crate::backend::cpu::Cpu;
use crate::backend::{Backend, Routing};
use crate::beam::BoxClass;
use crate::error::Error;
use crate::float_map::FloatMap;
use crate::image::Image;
use crate::plan::{Pass, PixelBeams, Plan, Primary};
use crate::progress::Progress;
use crate::sample::Coverage;
use crate::scene::Scene;
use crate::shadow::ShadowClass;
use crate::stats::{PassStats, RenderStats};
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
pub fn render_on<'a>(
    scene: &'a Scene,
    backend: &'a dyn Backend,
    progress: &dyn Progress,
) -> Result<RenderOutput, Error> {
    let start = Instant::now();
    let plan = Plan::for_scene(scene);
    let routing = Routing::new(backend, scene, &plan);
    let (queries, mut passes) = routing.prepare(backend, scene, &plan)?;
    let q = &queries;
    let cam = &scene.camera;
    let (w, h) = (cam.width(), cam.height());
    let npix = w as usize * h as usize;

    let (classes, scopes, traced) = if plan.runs(Pass::ScreenBoxes) {
        let (classes, scopes, traced, stats) = primary::structure(q, scene, &plan, progress)?;
        passes.push(stats);
        (classes, scopes, traced)
    } else {
        passes.push(PassStats::skipped(Pass::ScreenBoxes.name()));
        (vec![None; npix], vec![None; npix], Vec::new())
    };

    let (mut samples, cost) = match plan.primary {
        Primary::ScreenBoxes { .. } | Primary::Iaa { .. } => {
            let PixelBeams {
                max_depth,
                threshold,
                limit_rays,
            } = plan
                .primary
                .pixel_beams()
                .expect("the beam modes resolve pixels by their beams");
            let refine = pixel_beams::Refinement {
                max_depth,
                threshold,
                narrow_hits: plan.narrow_hits,
                limit_rays,
            };
            passes.push(PassStats::skipped(Pass::PrimaryRays.name()));
            let (samples, cost, stats) =
                pixel_beams::pixel_beams(q, scene, &classes, &scopes, refine, progress)?;
            passes.push(stats);
            (samples, cost)
        }
        Primary::ScreenRays { rays_per_undecided }
        | Primary::Octree { rays_per_undecided }
        | Primary::PerPixel {
            rays_per_pixel: rays_per_undecided,
        } => {
            let start = match plan.primary {
                Primary::Octree { .. } => primary::RayStart::FirstCell,
                _ => primary::RayStart::BoxWindow,
            };
            let (samples, cost, stats) = primary::primary_rays(
                q,
                scene,
                (&classes, &scopes, &traced),
                (rays_per_undecided, start, plan.narrow_hits),
                progress,
            )?;
            passes.push(stats);
            passes.push(PassStats::skipped(Pass::PixelBeams.name()));
            (samples, cost)
        }
    };
    let coverage: Vec<Coverage> = (0..samples.len())
        .into_par_iter()
        .map(|p| Coverage::of(samples.pixel(p)))
        .collect();

    if plan.runs(Pass::Normals) {
        passes.push(shading::normals(q, &mut samples, progress)?);
    } else {
        passes.push(PassStats::skipped(Pass::Normals.name()));
    }

    // The visible fraction of each light from each sample (1 without a shadow pass):
    // sample-major, light-minor.
    let nl = scene.lights.len();
    let mut vis: Vec<f32> = vec![1.0; samples.samples.len() * nl];
    if plan.runs(Pass::HardShadows) {
        let points: Vec<Option<DVec3>> = scene
            .lights
            .iter()
            .map(|l| l.as_point().map(|p| p.position))
            .collect();
        passes.push(hard_shadows::hard_shadows(
            q, scene, &samples, &points, &mut vis, progress,
        )?);
    } else {
        passes.push(PassStats::skipped(Pass::HardShadows.name()));
    }
    let mut light_stats = Vec::new();
    let mut shadows = None;
    if plan.runs(Pass::SoftShadows) {
        let soft = soft_shadows::soft_shadows(q, scene, &plan, &samples, &mut vis, progress)?;
        passes.push(soft.pass);
        light_stats = soft.lights;
        shadows = Some(ShadowMaps {
            image: shadow_class_image(w, h, &soft.classes),
            classes: soft.classes,
            fractions: soft.fractions,
            lower: soft.lower,
            upper: soft.upper,
            width: w,
            height: h,
        });
    } else {
        passes.push(PassStats::skipped(Pass::SoftShadows.name()));
    }

    let (pixels, stats) = shading::shading(q, scene, plan.runs(Pass::Shading), &samples, &vis)?;
    passes.push(stats);
    // The queries borrow the plan, which the output takes.
    drop(queries);

    Ok(RenderOutput {
        classification: classification_image(
            w,
            h,
            &classes
                .iter()
                .map(|c| c.map(|c| (c.class, c.edge)))
                .collect::<Vec<_>>(),
        ),
        box_classes: classes.par_iter().map(|c| c.map(|c| c.class)).collect(),
        coverage,
        cost_map: cost_image(w, h, &cost),
        shadows,
        image: Image {
            width: w,
            height: h,
            pixels,
        },
        stats: RenderStats {
            passes,
            lights: light_stats,
            total: start.elapsed(),
        },
        plan,
    })
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
    let (classes, _, _, stats) = primary::structure(&queries, scene, plan, progress)?;
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
