//! The render pipeline: the passes of the [`Plan`], in parallel with rayon, into an image
//! and per-pass statistics.
//!
//! Each pass is a pure function of the scene and the previous passes' results over
//! independent pieces (tiles, rows, samples) that rayon schedules; counters are sums of
//! per-piece counts, so images and counters do not depend on the thread count.

use std::time::{Duration, Instant};

use glam::DVec3;
use interval_core::Interval;
use rayon::prelude::*;

mod soft_shadows;

pub use soft_shadows::shadow_class_image;

use crate::aa;
use crate::beam::{BoxClass, Extent, evaluate_box};
use crate::camera::Camera;
use crate::error::Error;
use crate::grid::{Grid, GridEval};
use crate::image::Image;
use crate::plan::{Plan, Primary};
use crate::ray::{Beam, Ray};
use crate::root::{RayFn, RootCounters, RootFinder, RootResult};
use crate::scene::geometry::GeometryEval;
use crate::scene::{AreaLight, Scene};
use crate::screen::{PixelRect, ScreenBox, subdivide};
use crate::shading::{Incoming, phong};
use crate::shadow::ShadowClass;
use crate::shadow::hard::{Visibility, segment_visibility};
use crate::stats::{PassStats, RenderStats};

/// Reports progress of long passes (the render binary shows a progress bar).
pub trait Progress: Sync {
    /// A pass with `total` units of work begins.
    fn begin(&self, pass: &str, total: u64) {
        let _ = (pass, total);
    }
    /// `n` more units are done.
    fn advance(&self, n: u64) {
        let _ = n;
    }
    /// The pass is over.
    fn end(&self) {}
}

/// Progress that shows nothing.
#[derive(Copy, Clone, Debug, Default)]
pub struct NoProgress;

impl Progress for NoProgress {}

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
    /// Time spent per pixel by primary visibility, as a heat map (thesis fig. 5.8).
    pub cost_map: Image,
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
    /// The classes as an image (the soft-shadow paper's Fig. 7): proven lit green, proven
    /// umbra blue, penumbra orange, facing away from every area light blue-grey, no shaded
    /// surface dark grey.
    pub image: Image,
}

/// A surface point seen by a primary sample.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Hit {
    /// Enclosure of the ray parameter of the first root.
    pub t: Interval<f64>,
    /// The point (central ray at the middle of `t`).
    pub point: DVec3,
    /// Unit vector from the point to the eye.
    pub to_eye: DVec3,
    /// The leaf surface whose material shades it.
    pub leaf: u32,
    /// Unit normal (set by the normals pass).
    pub normal: DVec3,
}

impl Hit {
    /// The normal turned towards the eye (the side of the surface the sample sees).
    pub fn facing_normal(&self) -> DVec3 {
        if self.normal.dot(self.to_eye) < 0.0 {
            -self.normal
        } else {
            self.normal
        }
    }

    /// Where shadow rays from the hit start: `offset` off the surface along the facing
    /// normal (see [`SHADOW_OFFSET`]).
    pub fn shadow_origin(&self, offset: f64) -> DVec3 {
        self.point + self.facing_normal() * offset
    }
}

/// One primary sample of a pixel: its weight (area fraction) and what it sees.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Sample {
    /// Weight of the sample in its pixel (the weights of a pixel sum to 1).
    pub weight: f32,
    /// The surface point, or `None` for background.
    pub hit: Option<Hit>,
}

/// Per-thread evaluators.
pub(crate) struct Evals {
    pub(crate) geo: GeometryEval,
    pub(crate) grid: Option<GridEval>,
}

/// The ray and beam queries every pass shares.
pub(crate) struct Tracer<'a> {
    pub(crate) scene: &'a Scene,
    pub(crate) plan: &'a Plan,
    pub(crate) grid: Option<&'a Grid>,
    pub(crate) finder: &'static dyn RootFinder,
}

/// The parameters a beam lying inside a classified parent beam needs to search: every ray
/// of an Undecided parent is root-free before the parent's undecided range, and every ray
/// of a Hit parent has its first root in the parent's `T_final`. A part of a beam has a
/// subset of its rays, so the same holds for it. For an Undecided parent the window starts
/// a few widths of its undecided range earlier (still in the rejected prefix), so that `g`
/// has one strict sign at the window's start, which the inclusion test needs.
pub fn child_window(parent: Option<&BoxClass>) -> Interval<f64> {
    match parent {
        None => forward(),
        Some(BoxClass::Hit { t_final }) => *t_final,
        Some(BoxClass::Undecided { t }) => {
            let start = (t.inf() - 8.0 * t.wid()).max(0.0);
            Interval::new_unchecked(start, f64::INFINITY)
        }
        Some(BoxClass::Miss) => Interval::EMPTY,
    }
}

/// `[0, +∞]`: rays start at their origin.
pub(crate) fn forward() -> Interval<f64> {
    Interval::new_unchecked(0.0, f64::INFINITY)
}

impl Tracer<'_> {
    /// Per-thread evaluators; every evaluator of `g` and `g'` runs in the plan's precision.
    pub(crate) fn evals(&self) -> Evals {
        let precision = self.plan.precision;
        let mut geo = self.scene.geometry.evaluator();
        geo.beam.set_precision(precision);
        for e in &mut geo.objects {
            e.set_precision(precision);
        }
        Evals {
            geo,
            grid: self.grid.map(|g| g.evaluator_with(precision)),
        }
    }

    /// The parameter ranges a beam must search inside `window`: the grid's non-empty
    /// cells, or the scene bounds, from the origin on.
    pub(crate) fn beam_ranges(&self, beam: &Beam, window: Interval<f64>) -> Vec<Interval<f64>> {
        let window = window.intersection(forward());
        if window.is_empty() {
            return Vec::new();
        }
        match self.grid {
            Some(g) => g.beam_t_ranges_within(beam, window),
            None => beam
                .t_range_within(&self.scene.geometry.bounds(), window)
                .into_iter()
                .collect(),
        }
    }

    /// EvaluateBox of a beam against the whole scene function. A beam lying inside a
    /// classified `parent` beam searches only what the parent left open (see
    /// [`child_window`]); inside a Hit parent, exactly the parent's `T_final`, whose ends
    /// already have one strict sign for every ray.
    pub(crate) fn classify(
        &self,
        ev: &mut Evals,
        beam: &Beam,
        parent: Option<&BoxClass>,
        c: &mut RootCounters,
    ) -> BoxClass {
        let ranges = match parent {
            Some(BoxClass::Hit { t_final }) => vec![*t_final],
            _ => self.beam_ranges(beam, child_window(parent)),
        };
        if ranges.is_empty() {
            return BoxClass::Miss;
        }
        ev.geo.beam.set_beam(beam);
        let bounds = self.scene.geometry.bounds();
        let extent = Extent {
            beam,
            bounds: &bounds,
        };
        evaluate_box(&mut ev.geo.beam, &ranges, Some(&extent), &self.plan.beam, c)
    }

    /// The first root along `ray` for parameters in `t` (clipped to `t ≥ 0`): through the
    /// grid's cells when there is a grid (each with its reduced function), else with the
    /// whole scene function inside the scene bounds.
    pub(crate) fn cast(
        &self,
        ev: &mut Evals,
        ray: &Ray,
        t: Interval<f64>,
        c: &mut RootCounters,
    ) -> RootResult {
        let root = &self.plan.root;
        let t = t.intersection(forward());
        if t.is_empty() {
            return RootResult::NoRoot;
        }
        match (self.grid, ev.grid.as_mut()) {
            (Some(g), Some(gev)) => g.first_root_within(gev, ray, t, self.finder, root, c),
            _ => match ray.beam().t_range_within(&self.scene.geometry.bounds(), t) {
                Some(t) => {
                    ev.geo.beam.set_ray(ray);
                    self.finder.first_root(&mut ev.geo.beam, t, root, c)
                }
                None => RootResult::NoRoot,
            },
        }
    }

    /// Whether the segment from `from` to `to` is free of surface points (a hard shadow
    /// ray): a reliable "no root" is a proof that it is lit.
    pub(crate) fn segment(
        &self,
        ev: &mut Evals,
        from: DVec3,
        to: DVec3,
        c: &mut RootCounters,
    ) -> Visibility {
        let ray = Ray {
            origin: from,
            dir: to - from,
        };
        let r = self.cast(ev, &ray, Interval::new_unchecked(0.0, 1.0), c);
        segment_visibility(r, self.finder.is_reliable())
    }

    /// A hit record for the first root `t` of `ray` (or the first undecided range).
    ///
    /// The point is placed inside `t` where the floating-point values of `g` change sign
    /// (bisection on point values, for shading only: the proof is `t`), on the side of the
    /// ray's origin, so that shadow segments start outside the surface they leave.
    pub(crate) fn hit(
        &self,
        ev: &mut Evals,
        ray: &Ray,
        t: Interval<f64>,
        c: &mut RootCounters,
    ) -> Hit {
        let tm = shading_parameter(&mut ev.geo.beam, ray, t, c);
        let point = ray.at(tm);
        Hit {
            t,
            point,
            to_eye: (-ray.dir).normalize_or_zero(),
            leaf: ev.geo.leaf_at(point) as u32,
            normal: -ray.dir.normalize_or_zero(),
        }
    }
}

/// The parameter of the shading point of a hit with enclosure `t`: the end on the origin's
/// side of a floating-point sign change of `g` inside `t`, narrowed by bisection on point
/// values; the midpoint where `g` shows no sign change (a tangent, a possible root).
pub fn shading_parameter(
    eval: &mut crate::ray::BeamEval,
    ray: &Ray,
    t: Interval<f64>,
    c: &mut RootCounters,
) -> f64 {
    let (mut a, mut b) = (t.inf(), t.sup());
    if !(a.is_finite() && b.is_finite()) {
        return t.mid();
    }
    eval.set_ray(ray);
    let ga = eval.g_point(a);
    let gb = eval.g_point(b);
    c.point_evals += 2;
    if ga == 0.0 {
        return a;
    }
    if ga.is_nan() || gb.is_nan() || (ga > 0.0) == (gb > 0.0) && gb != 0.0 {
        return t.mid();
    }
    for _ in 0..64 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        let gm = eval.g_point(m);
        c.point_evals += 1;
        if gm.is_nan() {
            break;
        }
        if gm != 0.0 && (gm > 0.0) == (ga > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    a
}

/// Distance, as a fraction of the scene diagonal, by which a shadow segment starts off the
/// surface along the normal. It must exceed the width of a root enclosure along the segment
/// (`epsilon` times the segment's length) by a wide margin, or the search finds the surface
/// the segment leaves as a possible root (shadow acne); occluders thinner than it at the
/// very start of a segment are not seen.
pub const SHADOW_OFFSET: f64 = 1e-4;

/// Work counters of a pass, summed over pieces.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct Work {
    pub(crate) root: RootCounters,
    pub(crate) items: [u64; 8],
}

impl Work {
    fn add(mut self, o: Work) -> Work {
        self.root.add(&o.root);
        for (a, b) in self.items.iter_mut().zip(o.items) {
            *a += b;
        }
        self
    }

    fn stats(&self, name: &str, time: Duration, labels: &[&str]) -> PassStats {
        PassStats::with_search(name, time, labels, &self.items, &self.root)
    }
}

/// Stratified sample positions inside a pixel: `n` must be a square.
fn pixel_offsets(n: u32) -> Vec<(f64, f64)> {
    let k = (n as f64).sqrt().round().max(1.0) as u32;
    (0..k * k)
        .map(|i| {
            (
                (f64::from(i % k) + 0.5) / f64::from(k),
                (f64::from(i / k) + 0.5) / f64::from(k),
            )
        })
        .collect()
}

/// Renders `scene`: plans the passes, runs them, and returns the image and statistics.
pub fn render(scene: &Scene, progress: &dyn Progress) -> Result<RenderOutput, Error> {
    let start = Instant::now();
    let plan = Plan::for_scene(scene);
    let cam = &scene.camera;
    let (w, h) = (cam.width(), cam.height());
    let mut passes: Vec<PassStats> = Vec::new();

    let grid = plan.grid.map(|res| {
        let (g, stats) = grid_pass(scene, res, progress);
        passes.push(stats);
        g
    });
    if grid.is_none() {
        passes.push(PassStats::skipped("grid"));
    }
    let tracer = Tracer {
        scene,
        plan: &plan,
        grid: grid.as_ref(),
        finder: plan.root_finder.finder(),
    };

    let classes = if let Primary::ScreenBoxes { .. } = plan.primary {
        let (classes, stats) = screen_box_pass(&tracer, progress);
        passes.push(stats);
        classes
    } else {
        passes.push(PassStats::skipped("screen-boxes"));
        vec![None; w as usize * h as usize]
    };

    let (mut samples, cost) = match plan.primary {
        Primary::Iaa {
            max_depth,
            threshold,
        } => {
            passes.push(PassStats::skipped("primary-rays"));
            let (samples, cost, stats) =
                per_pixel_pass(&tracer, "iaa", &aa::COUNTERS, progress, |ev, x, y, work| {
                    aa::iaa_pixel(&tracer, ev, x, y, max_depth, threshold, work)
                });
            passes.push(stats);
            (samples, cost)
        }
        Primary::ScreenBoxes { rays_per_undecided }
        | Primary::PerPixel {
            rays_per_pixel: rays_per_undecided,
        } => {
            let per_pixel = matches!(plan.primary, Primary::PerPixel { .. });
            let offsets = pixel_offsets(rays_per_undecided);
            let (samples, cost, stats) = per_pixel_pass(
                &tracer,
                "primary-rays",
                &["rays", "hits", "proven_unique", "possible", "undecided"],
                progress,
                |ev, x, y, work| {
                    let class = if per_pixel {
                        None
                    } else {
                        classes[(y * w + x) as usize].map(|c| c.0)
                    };
                    primary_pixel(&tracer, ev, cam, x, y, class, &offsets, work)
                },
            );
            passes.push(stats);
            passes.push(PassStats::skipped("iaa"));
            (samples, cost)
        }
    };

    if plan.runs("normals") {
        passes.push(normals_pass(&tracer, &mut samples, progress));
    } else {
        passes.push(PassStats::skipped("normals"));
    }

    // Shading takes each light's direction from its centre.
    let lights: Vec<(DVec3, [f32; 3])> = scene
        .lights
        .iter()
        .map(|l| (l.center(), l.color()))
        .collect();
    let nl = lights.len();
    // The visible fraction of each light from each sample (1 without a shadow pass).
    let mut vis: Vec<Vec<f32>> = samples.iter().map(|s| vec![1.0; s.len() * nl]).collect();
    if plan.runs("hard-shadows") {
        let points: Vec<Option<DVec3>> = scene
            .lights
            .iter()
            .map(|l| l.as_point().map(|p| p.position))
            .collect();
        passes.push(hard_shadow_pass(
            &tracer, &samples, &points, &mut vis, progress,
        ));
    } else {
        passes.push(PassStats::skipped("hard-shadows"));
    }
    let mut light_stats = Vec::new();
    let mut shadows = None;
    if plan.runs("soft-shadows") {
        let areas: Vec<(usize, AreaLight)> = scene
            .lights
            .iter()
            .enumerate()
            .filter_map(|(i, l)| l.as_area().map(|a| (i, a)))
            .collect();
        let soft =
            soft_shadows::soft_shadow_pass(&tracer, &samples, &areas, nl, &mut vis, progress);
        passes.push(soft.pass);
        light_stats = soft.lights;
        shadows = Some(ShadowMaps {
            image: soft_shadows::shadow_class_image(w, h, &soft.classes),
            classes: soft.classes,
            fractions: soft.fractions,
        });
    } else {
        passes.push(PassStats::skipped("soft-shadows"));
    }

    let (pixels, stats) = shading_pass(&tracer, &samples, &lights, &vis);
    passes.push(stats);

    Ok(RenderOutput {
        classification: classification_image(w, h, &classes),
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

/// The regular grid pass.
fn grid_pass(scene: &Scene, resolution: u32, progress: &dyn Progress) -> (Grid, PassStats) {
    progress.begin("grid", 1);
    let t0 = Instant::now();
    let g = Grid::build(&scene.geometry, resolution);
    let s = g.stats();
    progress.end();
    let stats = PassStats::new(
        "grid",
        t0.elapsed(),
        &[
            ("cells", s.cells),
            ("non_empty", s.non_empty),
            ("functions", s.functions),
            ("leaf_evals", s.leaf_evals),
        ],
    );
    (g, stats)
}

/// Each pixel's screen box class, and whether the pixel lies on its box's top or left edge.
type PixelClasses = Vec<Option<(BoxClass, bool)>>;

/// The screen box pass: tiles of 32 × 32 pixels subdivided in parallel.
fn screen_box_pass(tracer: &Tracer<'_>, progress: &dyn Progress) -> (PixelClasses, PassStats) {
    let cam = &tracer.scene.camera;
    let (w, h) = (cam.width(), cam.height());
    let t0 = Instant::now();
    let tiles = tiles(w, h, 32);
    progress.begin("screen-boxes", tiles.len() as u64);
    let results: Vec<(Vec<ScreenBox>, Work)> = tiles
        .par_iter()
        .map_init(
            || tracer.evals(),
            |ev, tile| {
                let mut work = Work::default();
                let boxes = subdivide(*tile, tracer.plan.t_final_width, |r, parent| {
                    work.items[0] += 1;
                    let beam = cam.beam(
                        f64::from(r.x0),
                        f64::from(r.y0),
                        f64::from(r.x1),
                        f64::from(r.y1),
                    );
                    tracer.classify(ev, &beam, parent, &mut work.root)
                });
                for b in &boxes {
                    let k = match b.class {
                        BoxClass::Miss => 1,
                        BoxClass::Hit { .. } => 2,
                        BoxClass::Undecided { .. } => 3,
                    };
                    work.items[k] += b.rect.area();
                }
                progress.advance(1);
                (boxes, work)
            },
        )
        .collect();
    let mut classes = vec![None; w as usize * h as usize];
    let mut work = Work::default();
    for (boxes, wk) in results {
        work = work.add(wk);
        for b in boxes {
            for (x, y) in b.rect.pixels() {
                let edge = x == b.rect.x0 || y == b.rect.y0;
                classes[(y * w + x) as usize] = Some((b.class, edge));
            }
        }
    }
    progress.end();
    let stats = work.stats(
        "screen-boxes",
        t0.elapsed(),
        &["beams", "miss_pixels", "hit_pixels", "undecided_pixels"],
    );
    (classes, stats)
}

/// The normals pass: unit normals of the hit samples from the gradient.
fn normals_pass(
    tracer: &Tracer<'_>,
    samples: &mut [Vec<Sample>],
    progress: &dyn Progress,
) -> PassStats {
    let w = tracer.scene.camera.width() as usize;
    let t0 = Instant::now();
    progress.begin("normals", (samples.len() / w) as u64);
    let works: Vec<Work> = samples
        .par_chunks_mut(w)
        .map_init(
            || tracer.evals(),
            |ev, row| {
                let mut work = Work::default();
                for s in row.iter_mut().flatten() {
                    if let Some(hit) = s.hit.as_mut() {
                        work.items[0] += 1;
                        match ev.geo.normal(hit.point) {
                            Some(n) => hit.normal = n,
                            None => work.items[1] += 1,
                        }
                    }
                }
                progress.advance(1);
                work
            },
        )
        .collect();
    progress.end();
    let work = works.into_iter().fold(Work::default(), Work::add);
    work.stats("normals", t0.elapsed(), &["normals", "degenerate"])
}

/// The hard shadow pass: for each hit sample and point light (`Some` position; area lights
/// are `None`), the visible fraction (0 or 1) from a shadow segment search, written to
/// `vis` (sample-major, light-minor per pixel).
fn hard_shadow_pass(
    tracer: &Tracer<'_>,
    samples: &[Vec<Sample>],
    lights: &[Option<DVec3>],
    vis: &mut [Vec<f32>],
    progress: &dyn Progress,
) -> PassStats {
    let w = tracer.scene.camera.width() as usize;
    let nl = lights.len();
    let t0 = Instant::now();
    progress.begin("hard-shadows", (samples.len() / w) as u64);
    let diag = tracer.scene.geometry.diagonal();
    let works: Vec<Work> = samples
        .par_chunks(w)
        .zip(vis.par_chunks_mut(w))
        .map_init(
            || tracer.evals(),
            |ev, (srow, vrow)| {
                let mut work = Work::default();
                for (px, v) in srow.iter().zip(vrow.iter_mut()) {
                    for (si, s) in px.iter().enumerate() {
                        let Some(hit) = s.hit else { continue };
                        let n = hit.facing_normal();
                        for (li, pos) in lights.iter().enumerate() {
                            let Some(pos) = pos else { continue };
                            work.items[0] += 1;
                            if n.dot(*pos - hit.point) <= 0.0 {
                                // Facing away from the light: no direct light anyway.
                                work.items[4] += 1;
                                v[si * nl + li] = 0.0;
                                continue;
                            }
                            let from = hit.shadow_origin(SHADOW_OFFSET * diag);
                            let r = tracer.segment(ev, from, *pos, &mut work.root);
                            let (k, lit) = match r {
                                Visibility::Lit => (1, 1.0),
                                Visibility::Occluded => (2, 0.0),
                                Visibility::Undecided => (3, 0.0),
                            };
                            work.items[k] += 1;
                            v[si * nl + li] = lit;
                        }
                    }
                }
                progress.advance(1);
                work
            },
        )
        .collect();
    progress.end();
    let work = works.into_iter().fold(Work::default(), Work::add);
    work.stats(
        "hard-shadows",
        t0.elapsed(),
        &["segments", "lit", "occluded", "undecided", "back_facing"],
    )
}

/// The shading pass: each pixel's colour, the weighted sum of its samples' Phong colours
/// (the flat material colour when the scene has no lights, a pass that then does not run).
fn shading_pass(
    tracer: &Tracer<'_>,
    samples: &[Vec<Sample>],
    lights: &[(DVec3, [f32; 3])],
    vis: &[Vec<f32>],
) -> (Vec<[f32; 3]>, PassStats) {
    let scene = tracer.scene;
    let lit = tracer.plan.runs("shading");
    let nl = lights.len();
    let t0 = Instant::now();
    let leaves = scene.geometry.leaves();
    let pixels: Vec<[f32; 3]> = samples
        .par_iter()
        .zip(vis.par_iter())
        .map(|(px, v)| {
            let mut acc = [0f32; 3];
            let mut wsum = 0f32;
            let mut incoming = Vec::with_capacity(nl);
            for (si, s) in px.iter().enumerate() {
                let c = match s.hit {
                    None => scene.background,
                    Some(hit) => {
                        let m = &leaves[hit.leaf as usize].material;
                        if lit {
                            incoming.clear();
                            for (li, (pos, col)) in lights.iter().enumerate() {
                                let f = v[si * nl + li];
                                incoming.push(Incoming {
                                    dir: (*pos - hit.point).normalize_or_zero(),
                                    color: col.map(|c| c * f),
                                });
                            }
                            phong(m, scene.ambient, hit.normal, hit.to_eye, &incoming)
                        } else {
                            m.color
                        }
                    }
                };
                for k in 0..3 {
                    acc[k] += s.weight * c[k];
                }
                wsum += s.weight;
            }
            if wsum > 0.0 {
                acc.map(|a| a / wsum)
            } else {
                scene.background
            }
        })
        .collect();
    let stats = if lit {
        let shaded = samples.iter().flatten().filter(|s| s.hit.is_some()).count() as u64;
        PassStats::new("shading", t0.elapsed(), &[("shaded_samples", shaded)])
    } else {
        PassStats::skipped("shading")
    };
    (pixels, stats)
}

/// A pass that computes the samples of every pixel with `pixel`, row by row in parallel:
/// the samples in pixel order, the time spent per pixel (the cost map) and the pass's
/// statistics.
fn per_pixel_pass(
    tracer: &Tracer<'_>,
    name: &str,
    labels: &[&str],
    progress: &dyn Progress,
    pixel: impl Fn(&mut Evals, u32, u32, &mut Work) -> Vec<Sample> + Sync,
) -> (Vec<Vec<Sample>>, Vec<f32>, PassStats) {
    let (w, h) = (tracer.scene.camera.width(), tracer.scene.camera.height());
    let t0 = Instant::now();
    progress.begin(name, u64::from(h));
    let rows: Vec<(Vec<Vec<Sample>>, Vec<f32>, Work)> = (0..h)
        .into_par_iter()
        .map_init(
            || tracer.evals(),
            |ev, y| {
                let mut work = Work::default();
                let mut costs = Vec::with_capacity(w as usize);
                let row = (0..w)
                    .map(|x| {
                        let tp = Instant::now();
                        let s = pixel(ev, x, y, &mut work);
                        costs.push(tp.elapsed().as_secs_f32());
                        s
                    })
                    .collect();
                progress.advance(1);
                (row, costs, work)
            },
        )
        .collect();
    progress.end();
    let mut work = Work::default();
    let npix = w as usize * h as usize;
    let mut samples = Vec::with_capacity(npix);
    let mut cost = Vec::with_capacity(npix);
    for (row, costs, wk) in rows {
        work = work.add(wk);
        samples.extend(row);
        cost.extend(costs);
    }
    (samples, cost, work.stats(name, t0.elapsed(), labels))
}

fn tiles(w: u32, h: u32, size: u32) -> Vec<PixelRect> {
    let mut out = Vec::new();
    for y0 in (0..h).step_by(size as usize) {
        for x0 in (0..w).step_by(size as usize) {
            out.push(PixelRect {
                x0,
                y0,
                x1: (x0 + size).min(w),
                y1: (y0 + size).min(h),
            });
        }
    }
    out
}

/// The samples of one pixel for ray-based primary visibility.
#[allow(clippy::too_many_arguments)]
fn primary_pixel(
    tracer: &Tracer<'_>,
    ev: &mut Evals,
    cam: &Camera,
    x: u32,
    y: u32,
    class: Option<BoxClass>,
    offsets: &[(f64, f64)],
    work: &mut Work,
) -> Vec<Sample> {
    let (fx, fy) = (f64::from(x), f64::from(y));
    // `in_t_final`: the window is a Hit box's T_final, where a root is known to exist.
    let trace =
        |ev: &mut Evals, ray: &Ray, window: Interval<f64>, in_t_final: bool, work: &mut Work| {
            work.items[0] += 1;
            let mut r = tracer.cast(ev, ray, window, &mut work.root);
            if in_t_final && !matches!(r, RootResult::Root { .. }) {
                // A limit inside T_final: search the whole ray.
                r = tracer.cast(ev, ray, forward(), &mut work.root);
            }
            match r {
                RootResult::Root { t, proof } => {
                    work.items[1] += 1;
                    match proof {
                        crate::root::Proof::Unique => work.items[2] += 1,
                        crate::root::Proof::Possible => work.items[3] += 1,
                        crate::root::Proof::Exists => {}
                    }
                    Some(tracer.hit(ev, ray, t, &mut work.root))
                }
                RootResult::Undecided { t } => {
                    work.items[4] += 1;
                    Some(tracer.hit(ev, ray, t, &mut work.root))
                }
                RootResult::NoRoot => None,
            }
        };
    match class {
        Some(BoxClass::Miss) => vec![Sample {
            weight: 1.0,
            hit: None,
        }],
        Some(BoxClass::Hit { t_final }) => {
            let ray = cam.ray(fx + 0.5, fy + 0.5);
            let hit = trace(ev, &ray, t_final, true, work);
            vec![Sample { weight: 1.0, hit }]
        }
        Some(BoxClass::Undecided { .. }) | None => {
            // The pixel's beam proved its rays root-free before its undecided range.
            let window = child_window(class.as_ref());
            let wgt = 1.0 / offsets.len() as f32;
            offsets
                .iter()
                .map(|&(ox, oy)| {
                    let ray = cam.ray(fx + ox, fy + oy);
                    Sample {
                        weight: wgt,
                        hit: trace(ev, &ray, window, false, work),
                    }
                })
                .collect()
        }
    }
}

/// The colour of a beam class in classification images: proven miss blue, proven hit red,
/// undecided yellow.
pub fn box_class_color(class: &BoxClass) -> [f32; 3] {
    match class {
        BoxClass::Miss => [0.1, 0.25, 0.8],
        BoxClass::Hit { .. } => [0.85, 0.15, 0.1],
        BoxClass::Undecided { .. } => [0.95, 0.85, 0.1],
    }
}

fn classification_image(w: u32, h: u32, classes: &[Option<(BoxClass, bool)>]) -> Image {
    let pixels = classes
        .iter()
        .map(|c| match c {
            None => [0.5, 0.5, 0.5],
            Some((class, edge)) => {
                let base = box_class_color(class);
                if *edge { base.map(|v| v * 0.6) } else { base }
            }
        })
        .collect();
    Image {
        width: w,
        height: h,
        pixels,
    }
}

/// A heat map of per-pixel costs (logarithmic, blue cheap to red expensive; black where the
/// cost is zero).
pub fn cost_image(w: u32, h: u32, cost: &[f32]) -> Image {
    let max = cost.iter().copied().fold(0f32, f32::max).max(1e-9);
    let min = cost
        .iter()
        .copied()
        .filter(|&c| c > 0.0)
        .fold(f32::INFINITY, f32::min)
        .min(max);
    let (lmin, lmax) = (min.ln(), max.ln());
    let pixels = cost
        .iter()
        .map(|&c| {
            let s = if c <= 0.0 || lmax <= lmin {
                0.0
            } else {
                ((c.ln() - lmin) / (lmax - lmin)).clamp(0.0, 1.0)
            };
            heat(s)
        })
        .collect();
    Image {
        width: w,
        height: h,
        pixels,
    }
}

/// A blue → green → yellow → red colour ramp.
fn heat(s: f32) -> [f32; 3] {
    let stops = [
        [0.0, 0.0, 0.3],
        [0.0, 0.4, 1.0],
        [0.0, 0.9, 0.3],
        [1.0, 0.9, 0.0],
        [1.0, 0.1, 0.0],
    ];
    let x = s * (stops.len() - 1) as f32;
    let i = (x.floor() as usize).min(stops.len() - 2);
    let f = x - i as f32;
    std::array::from_fn(|k| stops[i][k] * (1.0 - f) + stops[i + 1][k] * f)
}
