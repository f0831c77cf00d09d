//! The pipeline prepared once for a scene (plan, backends, grid) and run on windows of the
//! image: the whole image for a plain render, or the work units of a render shared among
//! processes, each returning a [`Piece`] that [`Pipeline::assemble`] puts together.

use std::time::Instant;

use glam::DVec3;

use super::classes::PixelClasses;
use super::output::RenderOutput;
use super::piece::{Piece, PieceShadows};
use super::pixels::Pixels;
use super::resolve::Flat;
use super::{hard_shadows, pixel_beams, primary, shading, soft_shadows};
use crate::backend::{Backend, Routed, Routing};
use crate::error::Error;
use crate::plan::{Pass, PixelBeams, Plan, Primary};
use crate::progress::Progress;
use crate::sample::Coverage;
use crate::scene::Scene;
use crate::stats::PassStats;
use crate::window::{Window, window_grid};

/// A render prepared for one scene and plan: the backends set up (the CPU backend's grid,
/// a GPU's kernels), ready to render any [`Window`] of the image.
pub struct Pipeline<'a> {
    scene: &'a Scene,
    plan: &'a Plan,
    queries: Routed<'a>,
    /// The set-up's passes (the grid).
    setup: Vec<PassStats>,
}

impl<'a> Pipeline<'a> {
    /// Prepares `backend` (and the CPU for the queries it leaves, see [`Routing`]) for
    /// `scene` rendered with `plan`.
    ///
    /// # Errors
    ///
    /// [`Error::Backend`] when the backend cannot run the scene.
    pub fn new(scene: &'a Scene, backend: &'a dyn Backend, plan: &'a Plan) -> Result<Self, Error> {
        let routing = Routing::new(backend, scene, plan);
        let (queries, setup) = routing.prepare(backend, scene, plan)?;
        Ok(Self {
            scene,
            plan,
            queries,
            setup,
        })
    }

    /// The plan the pipeline runs.
    pub fn plan(&self) -> &Plan {
        self.plan
    }

    /// The statistics of the set-up (the grid pass), done once for every window.
    pub fn setup_stats(&self) -> &[PassStats] {
        &self.setup
    }

    /// The grid that the sides of the windows this pipeline renders must lie on
    /// ([`window_grid`]).
    pub fn grid(&self) -> u32 {
        window_grid(self.plan)
    }

    /// The whole image's window.
    pub fn full_window(&self) -> Window {
        let cam = &self.scene.camera;
        Window::full(cam.width(), cam.height())
    }

    /// Every pass of the plan over the pixels of `window`: for each of them, bit for bit
    /// what a render of the whole image finds.
    ///
    /// # Errors
    ///
    /// [`Error::Backend`] when a backend fails; [`Error::Setting`] when `window` is not a
    /// window of this scene's image, or its sides are off the plan's [`grid`](Self::grid).
    pub fn render(&self, window: &Window, progress: &dyn Progress) -> Result<Piece, Error> {
        let (q, scene, plan) = (&self.queries, self.scene, self.plan);
        let cam = &scene.camera;
        if window.image_size() != (cam.width(), cam.height()) {
            return Err(Error::Setting {
                name: "window".into(),
                message: format!(
                    "a window of a {} x {} image, the camera's is {} x {}",
                    window.image_size().0,
                    window.image_size().1,
                    cam.width(),
                    cam.height()
                ),
            });
        }
        window.check_grid(self.grid())?;
        let npix = window.len();
        let mut passes = Vec::new();

        let (classes, traced) = if plan.runs(Pass::ScreenBoxes) {
            let (classes, traced, stats) = primary::structure(q, scene, plan, window, progress)?;
            passes.push(stats);
            (classes, traced)
        } else {
            passes.push(PassStats::skipped(Pass::ScreenBoxes.name()));
            (PixelClasses::filled(npix, None), Vec::new())
        };

        let (primaries, cost) = match plan.primary {
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
                    pixel_beams::pixel_beams(q, scene, window, &classes, refine, progress)?;
                passes.push(stats);
                (Primaries::Samples(samples), cost)
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
                let pixels = (&classes, &traced);
                let rays = (rays_per_undecided, start, plan.narrow_hits);
                // Unlit: no pass after this one reads a surface point, so each pixel's
                // colour and coverage are resolved at once.
                let (primaries, cost, stats) = if plan.shading {
                    let (samples, cost, stats) = primary::primary_rays(
                        q,
                        scene,
                        window,
                        pixels,
                        rays,
                        (|n, rays| Pixels::with_capacity(n, rays()), progress),
                    )?;
                    (Primaries::Samples(samples), cost, stats)
                } else {
                    let (flat, cost, stats) = primary::primary_rays(
                        q,
                        scene,
                        window,
                        pixels,
                        rays,
                        (|n, _| Flat::with_capacity(scene, n), progress),
                    )?;
                    (Primaries::Flat(flat.colors, flat.coverage), cost, stats)
                };
                passes.push(stats);
                passes.push(PassStats::skipped(Pass::PixelBeams.name()));
                (primaries, cost)
            }
        };
        let (colors, coverage, shadows, lights) = match primaries {
            Primaries::Samples(samples) => self.shade(samples, window, progress, &mut passes)?,
            Primaries::Flat(colors, coverage) => {
                for pass in [
                    Pass::Normals,
                    Pass::HardShadows,
                    Pass::SoftShadows,
                    Pass::Shading,
                ] {
                    passes.push(PassStats::skipped(pass.name()));
                }
                (colors, coverage, None, Vec::new())
            }
        };

        Ok(Piece {
            window: *window,
            colors,
            classes: classes.into_map(),
            coverage,
            cost,
            shadows,
            passes,
            lights,
        })
    }

    /// The passes after the primary pass over the samples of `window`'s pixels: normals,
    /// hard and soft shadows and shading, each where the plan runs it (their statistics
    /// pushed on `passes`). Returns each pixel's colour and coverage, the soft shadows'
    /// maps and their statistics per light.
    fn shade(
        &self,
        mut samples: Pixels,
        window: &Window,
        progress: &dyn Progress,
        passes: &mut Vec<PassStats>,
    ) -> Result<Shades, Error> {
        let (q, scene, plan) = (&self.queries, self.scene, self.plan);
        if plan.runs(Pass::Normals) {
            passes.push(shading::normals(q, scene, &mut samples, progress)?);
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
        let mut lights = Vec::new();
        let mut shadows = None;
        if plan.runs(Pass::SoftShadows) {
            let soft =
                soft_shadows::soft_shadows(q, scene, plan, window, &samples, &mut vis, progress)?;
            passes.push(soft.pass);
            lights = soft.lights;
            shadows = Some(PieceShadows {
                classes: soft.classes,
                fractions: soft.fractions,
                lower: soft.lower,
                upper: soft.upper,
            });
        } else {
            passes.push(PassStats::skipped(Pass::SoftShadows.name()));
        }

        let shaded = shading::shading(q, scene, plan.runs(Pass::Shading), &samples, &vis)?;
        passes.push(shaded.stats);
        Ok((shaded.colors, shaded.coverage, shadows, lights))
    }

    /// The render of the whole image from `pieces` whose windows cover it, each pixel
    /// once: images, maps and statistics equal bit for bit to those of one piece over the
    /// whole image (the counters summed; the passes' times summed over the pieces, and
    /// the total the wall-clock time since `started`).
    ///
    /// # Errors
    ///
    /// [`Error::Data`] when the pieces miss a pixel, cover one twice, or belong to another
    /// image or plan.
    pub fn assemble(&self, pieces: Vec<Piece>, started: Instant) -> Result<RenderOutput, Error> {
        let cam = &self.scene.camera;
        super::piece::assemble(
            (cam.width(), cam.height()),
            self.plan,
            (&self.setup, pieces),
            started,
        )
    }
}

/// What the primary pass hands on: every pixel's samples, for the passes that shade them,
/// or (unlit) each pixel's colour and coverage.
enum Primaries {
    Samples(Pixels),
    Flat(Vec<[f32; 3]>, Vec<Coverage>),
}

/// Each pixel's colour and coverage, the soft shadows' maps, and their statistics per light.
type Shades = (
    Vec<[f32; 3]>,
    Vec<Coverage>,
    Option<PieceShadows>,
    Vec<PassStats>,
);

/// Renders `scene` with `backend`: the plan, the pipeline over the whole image, and the
/// output.
pub(super) fn render_whole(
    scene: &Scene,
    backend: &dyn Backend,
    progress: &dyn Progress,
) -> Result<RenderOutput, Error> {
    let start = Instant::now();
    let plan = Plan::for_scene(scene);
    let pipeline = Pipeline::new(scene, backend, &plan)?;
    let piece = pipeline.render(&pipeline.full_window(), progress)?;
    pipeline.assemble(vec![piece], start)
}
