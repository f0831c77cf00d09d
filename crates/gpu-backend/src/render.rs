//! The GPU render path: the CPU renderer's plan and output, with every beam and ray search
//! on the GPU ([`BeamKernel`]) and Phong on the GPU, and the light CPU work (shading points,
//! normals) in parallel on the CPU.
//!
//! * **Primary visibility**: the screen box structure (the default primary mode: tiles of
//!   16 × 16 pixels split level by level where undecided, one batch per level), or one beam
//!   per pixel (`primary = "per-pixel"` and anti-aliasing). A hit is shaded at the pixel's
//!   central ray inside the proven section; a miss is background. An undecided pixel gets its central
//!   ray searched on the GPU, or, with anti-aliasing asked for (`aa = "iaa"`), the adaptive
//!   scheme of thesis 7.3.5: the pixel is split into 3 × 3 sub-beams only where its beam
//!   crosses a border, and the parts are averaged.
//! * **Hard shadows**: one shadow segment per shaded sample and point light.
//! * **Soft shadows**: the beam method of the reliable soft-shadow paper: one beam over the
//!   whole light (rejected: proven lit; with an inclusion proof: proven umbra), then `n × n`
//!   sub-beams from where it stopped; the `n` of the scene's `beam`, `beam-all`,
//!   `beam-quadtree` or `minkowski:beam` method, 7 for the stochastic ones (the GPU path
//!   traces beams only).

use std::time::{Duration, Instant};

use beam_trace::beam::BoxClass;
use beam_trace::ray::{Beam, IBox, Ray, ival, point_box};
use beam_trace::render::{
    Hit, SHADOW_OFFSET, Sample, box_class_color, child_window, cost_image, shading_parameter,
    shadow_class_image,
};
use beam_trace::shading::{Incoming, phong};
use beam_trace::shadow::{Fine, Patch, ShadowClass, ShadowSpec};
use beam_trace::stats::{PassStats, RenderStats};
use beam_trace::{Image, Plan, Progress, RenderOutput, RootCounters, Scene, ShadowMaps};
use glam::DVec3;
use interval_core::Interval;
use rayon::prelude::*;

use crate::beams::{BeamKernel, BeamQuery, BeamSettings, GpuBeam, GpuClass};
use crate::device::Gpu;
use crate::error::GpuError;
use crate::shading::{MAX_LIGHTS, ShadingInput, ShadingKernel, ShadingLight};

/// The passes of the GPU path, in the order they run.
pub const GPU_PASSES: [&str; 9] = [
    "gpu-compile",
    "screen-boxes",
    "primary-beams",
    "primary-rays",
    "normals",
    "hard-shadows",
    "soft-shadows",
    "shading",
    "total-gpu",
];

/// Renders `scene` on `gpu`.
///
/// # Errors
///
/// [`GpuError`] if the scene function cannot run on the GPU or the GPU fails.
pub fn render(gpu: &Gpu, scene: &Scene, progress: &dyn Progress) -> Result<RenderOutput, GpuError> {
    let start = Instant::now();
    let plan = Plan::for_scene(scene);
    let geometry = &scene.geometry;
    let cam = &scene.camera;
    let (w, h) = (cam.width(), cam.height());
    let mut passes = Vec::new();
    let mut gpu_time = Duration::ZERO;

    let t = Instant::now();
    progress.begin("gpu-compile", 1);
    let kernel = BeamKernel::new(gpu, geometry.tape(), geometry.bounds())?;
    progress.end();
    passes.push(PassStats::new(
        "gpu-compile",
        t.elapsed(),
        &[
            ("instructions", geometry.tape().len() as u64),
            ("proves_hits", u64::from(kernel.proves_hits())),
        ],
    ));

    // Primary beams, one per pixel.
    let bounds = geometry.bounds();
    let diag = geometry.diagonal();
    let primary_settings = BeamSettings {
        epsilon: (plan.beam.epsilon) as f32,
        ..BeamSettings::default()
    };
    let pixel_rects: Vec<[f64; 4]> = (0..w * h)
        .map(|i| {
            let (x, y) = (f64::from(i % w), f64::from(i / w));
            [x, y, x + 1.0, y + 1.0]
        })
        .collect();
    let t = Instant::now();
    let pixel_classes = if let beam_trace::plan::Primary::ScreenBoxes { .. } = plan.primary {
        progress.begin("screen-boxes", 1);
        let (classes, beams) = timed(&mut gpu_time, || {
            screen_boxes(gpu, &kernel, scene, &bounds, &primary_settings)
        })?;
        progress.end();
        let count =
            |f: fn(&GpuClass) -> bool| classes.iter().filter(|b| f(&b.class)).count() as u64;
        passes.push(PassStats::new(
            "screen-boxes",
            t.elapsed(),
            &[
                ("beams", beams.len() as u64),
                ("miss_pixels", count(|c| matches!(c, GpuClass::Miss))),
                ("hit_pixels", count(|c| matches!(c, GpuClass::Hit { .. }))),
                (
                    "undecided_pixels",
                    count(|c| matches!(c, GpuClass::Undecided { .. })),
                ),
                ("steps", steps(&beams)),
            ],
        ));
        passes.push(PassStats::skipped("primary-beams"));
        classes
    } else {
        passes.push(PassStats::skipped("screen-boxes"));
        progress.begin("primary-beams", 1);
        let queries: Vec<BeamQuery> = pixel_rects
            .par_iter()
            .map(|r| primary_query(scene, &bounds, r, None))
            .collect();
        let classes = timed(&mut gpu_time, || {
            kernel.classify(gpu, &queries, &primary_settings)
        })?;
        progress.end();
        passes.push(beam_stats("primary-beams", t.elapsed(), &classes));
        classes
    };

    // Undecided pixels: 3 × 3 sub-beams with anti-aliasing, else the central ray.
    let aa = matches!(plan.primary, beam_trace::plan::Primary::Iaa { .. });
    let t = Instant::now();
    progress.begin("primary-rays", 1);
    let parts: Vec<Vec<[f64; 4]>> = pixel_rects
        .iter()
        .zip(&pixel_classes)
        .map(|(r, c)| match (c.class, aa) {
            (GpuClass::Undecided { .. }, true) => split3(r),
            _ => vec![*r],
        })
        .collect();
    let mut sub_beams_traced = 0;
    let part_classes: Vec<Vec<GpuBeam>> = if aa {
        let flat: Vec<BeamQuery> = parts
            .iter()
            .zip(&pixel_classes)
            .filter(|(_, c)| matches!(c.class, GpuClass::Undecided { .. }))
            .flat_map(|(p, _)| p.iter().map(|r| primary_query(scene, &bounds, r, None)))
            .collect();
        sub_beams_traced = flat.len();
        let mut results = timed(&mut gpu_time, || {
            kernel.classify(gpu, &flat, &primary_settings)
        })?
        .into_iter();
        parts
            .iter()
            .zip(&pixel_classes)
            .map(|(p, c)| match c.class {
                GpuClass::Undecided { .. } => results.by_ref().take(p.len()).collect(),
                _ => vec![*c],
            })
            .collect()
    } else {
        pixel_classes.iter().map(|c| vec![*c]).collect()
    };
    // Central rays of every part that may see a surface: searched inside the section of a
    // hit (which holds every ray's first root, and maybe later ones: the ray's own search
    // finds its first), and from where an undecided beam stopped.
    let ray_settings = BeamSettings {
        epsilon: (1e-6 * diag) as f32,
        rel_epsilon: 1e-6,
        narrow_hits: true,
        ..BeamSettings::default()
    };
    let mut ray_jobs = Vec::new();
    let mut ray_queries = Vec::new();
    for (pi, (p, cs)) in parts.iter().zip(&part_classes).enumerate() {
        for (k, (r, c)) in p.iter().zip(cs).enumerate() {
            let window = match c.class {
                GpuClass::Miss => continue,
                GpuClass::Hit { t } => t,
                GpuClass::Undecided { t } => ival(t.inf().max(0.0), f64::MAX),
            };
            let ray = center_ray(scene, r);
            let range = ray
                .beam()
                .t_range(&bounds)
                .map_or(Interval::EMPTY, |b| b.intersection(window));
            ray_jobs.push((pi, k));
            ray_queries.push(BeamQuery {
                beam: ray.beam(),
                t: range,
            });
        }
    }
    let ray_results = timed(&mut gpu_time, || {
        kernel.classify(gpu, &ray_queries, &ray_settings)
    })?;
    let mut part_classes = part_classes;
    for (&(pi, k), r) in ray_jobs.iter().zip(&ray_results) {
        part_classes[pi][k] = *r;
    }
    // Samples: a hit at the central ray of each part inside its section.
    let samples: Vec<Vec<Sample>> = parts
        .par_iter()
        .zip(&part_classes)
        .map_init(
            || geometry.evaluator(),
            |ev, (p, cs)| {
                let weight = 1.0 / p.len() as f32;
                p.iter()
                    .zip(cs)
                    .map(|(r, c)| Sample {
                        weight,
                        hit: match c.class {
                            GpuClass::Miss => None,
                            GpuClass::Hit { t } | GpuClass::Undecided { t } => {
                                Some(shading_hit(ev, &center_ray(scene, r), t))
                            }
                        },
                    })
                    .collect()
            },
        )
        .collect();
    progress.end();
    let mut rays_pass = beam_stats("primary-rays", t.elapsed(), &ray_results);
    rays_pass
        .counters
        .push(("aa_sub_beams".into(), sub_beams_traced as u64));
    passes.push(rays_pass);

    // Normals on the CPU.
    let t = Instant::now();
    let mut samples = samples;
    let degenerate: u64 = if plan.runs("normals") {
        samples
            .par_iter_mut()
            .map_init(
                || geometry.evaluator(),
                |ev, px| {
                    let mut bad = 0;
                    for hit in px.iter_mut().filter_map(|s| s.hit.as_mut()) {
                        match ev.normal(hit.point) {
                            Some(n) => hit.normal = n,
                            None => bad += 1,
                        }
                    }
                    bad
                },
            )
            .sum()
    } else {
        0
    };
    passes.push(if plan.runs("normals") {
        PassStats::new("normals", t.elapsed(), &[("degenerate", degenerate)])
    } else {
        PassStats::skipped("normals")
    });

    // Shadows: the visible fraction of each light from each sample.
    let nl = scene.lights.len();
    let mut vis: Vec<Vec<f32>> = samples.iter().map(|s| vec![1.0; s.len() * nl]).collect();
    let offset = SHADOW_OFFSET * diag;
    // A segment is a single ray: its sections shrink to the root-finder scale; shadow
    // beams stop where a section is small against their cross-section (1/16 of t).
    let segment_settings = BeamSettings {
        epsilon: (1e-3 * offset) as f32,
        rel_epsilon: 1e-6,
        ..BeamSettings::default()
    };
    let shadow_settings = BeamSettings {
        epsilon: (1e-3 * offset) as f32,
        rel_epsilon: 1.0 / 16.0,
        ..BeamSettings::default()
    };
    let hits: Vec<(usize, usize, Hit)> = samples
        .iter()
        .enumerate()
        .flat_map(|(p, px)| {
            px.iter()
                .enumerate()
                .filter_map(move |(s, sm)| sm.hit.map(|h| (p, s, h)))
        })
        .collect();
    if plan.runs("hard-shadows") {
        let t = Instant::now();
        let mut all = Vec::new();
        for (li, light) in scene.lights.iter().enumerate() {
            let Some(pl) = light.as_point() else { continue };
            let jobs: Vec<(usize, usize)> = hits
                .iter()
                .enumerate()
                .filter(|(_, (_, _, h))| h.facing_normal().dot(pl.position - h.point) > 0.0)
                .map(|(k, _)| (k, li))
                .collect();
            let queries: Vec<BeamQuery> = jobs
                .iter()
                .map(|&(k, _)| {
                    let from = hits[k].2.shadow_origin(offset);
                    BeamQuery {
                        beam: Ray {
                            origin: from,
                            dir: pl.position - from,
                        }
                        .beam(),
                        t: ival(0.0, 1.0),
                    }
                })
                .collect();
            let results = timed(&mut gpu_time, || {
                kernel.classify(gpu, &queries, &segment_settings)
            })?;
            // Facing away from the light: no direct light anyway.
            for (p, s, h) in &hits {
                if h.facing_normal().dot(pl.position - h.point) <= 0.0 {
                    vis[*p][s * nl + li] = 0.0;
                }
            }
            for (&(k, li), r) in jobs.iter().zip(&results) {
                let (p, s, _) = hits[k];
                vis[p][s * nl + li] = if r.class == GpuClass::Miss { 1.0 } else { 0.0 };
            }
            all.extend(results);
        }
        passes.push(beam_stats("hard-shadows", t.elapsed(), &all));
    } else {
        passes.push(PassStats::skipped("hard-shadows"));
    }
    let mut light_stats = Vec::new();
    let mut shadow_maps = None;
    if plan.runs("soft-shadows") {
        let t = Instant::now();
        let n = sub_beams(&plan.shadow_method);
        let mut classes: Vec<Option<ShadowClass>> = vec![None; samples.len()];
        let mut fractions = Vec::new();
        let mut total = Vec::new();
        for (li, light) in scene.lights.iter().enumerate() {
            let Some(area) = light.as_area() else {
                continue;
            };
            let tl = Instant::now();
            let soft = soft_shadows(
                gpu,
                &kernel,
                &hits,
                &area.patch,
                n,
                offset,
                &shadow_settings,
                &mut gpu_time,
            )?;
            let mut per_pixel = vec![(0f32, 0f32); samples.len()];
            let mut pixel_class: Vec<Option<ShadowClass>> = vec![None; samples.len()];
            for (k, (p, s, _)) in hits.iter().enumerate() {
                let (fraction, class) = soft.results[k];
                vis[*p][s * nl + li] = fraction;
                let wgt = samples[*p][*s].weight;
                per_pixel[*p].0 += wgt * fraction;
                per_pixel[*p].1 += wgt;
                pixel_class[*p] = Some(ShadowClass::merge(pixel_class[*p], class));
            }
            for (c, pc) in classes.iter_mut().zip(&pixel_class) {
                if let Some(pc) = pc {
                    *c = Some(ShadowClass::merge(*c, *pc));
                }
            }
            fractions.push(
                per_pixel
                    .iter()
                    .map(|(f, wsum)| if *wsum > 0.0 { f / wsum } else { f32::NAN })
                    .collect(),
            );
            let count =
                |c: ShadowClass| pixel_class.iter().filter(|&&x| x == Some(c)).count() as u64;
            let in_shadow = per_pixel
                .iter()
                .filter(|(f, wsum)| *wsum > 0.0 && f / wsum < 1.0)
                .count() as u64;
            light_stats.push(PassStats::new(
                &format!("light {li} (gpu beam:{n})"),
                tl.elapsed(),
                &[
                    ("pixels_in_shadow", in_shadow),
                    ("lit_pixels", count(ShadowClass::Lit)),
                    ("umbra_pixels", count(ShadowClass::Umbra)),
                    ("penumbra_pixels", count(ShadowClass::Penumbra)),
                    ("queries", soft.initial.len() as u64),
                    ("back_facing", soft.back_facing),
                    ("initial_beams", soft.initial.len() as u64),
                    ("initial_beams_occluded", soft.occluded),
                    ("umbra_proofs", soft.umbra),
                    ("sub_beams", soft.sub.len() as u64),
                    ("steps", steps(&soft.initial) + steps(&soft.sub)),
                ],
            ));
            total.extend(soft.initial);
            total.extend(soft.sub);
        }
        passes.push(beam_stats("soft-shadows", t.elapsed(), &total));
        shadow_maps = Some(ShadowMaps {
            image: shadow_class_image(w, h, &classes),
            classes,
            fractions,
        });
    } else {
        passes.push(PassStats::skipped("soft-shadows"));
    }

    // Phong on the GPU (on the CPU beyond the kernel's light count), then each pixel's
    // weighted average.
    let t = Instant::now();
    let lit = plan.runs("shading");
    let leaves = geometry.leaves();
    let colors: Vec<[f32; 3]> = if lit {
        let inputs: Vec<ShadingInput> = hits
            .iter()
            .map(|(p, s, h)| {
                let mut fractions = [0f32; MAX_LIGHTS];
                for (li, f) in fractions.iter_mut().enumerate().take(nl) {
                    *f = vis[*p][s * nl + li];
                }
                ShadingInput {
                    point: h.point,
                    normal: h.normal,
                    to_eye: h.to_eye,
                    material: leaves[h.leaf as usize].material,
                    fractions,
                }
            })
            .collect();
        if nl <= MAX_LIGHTS {
            let lights: Vec<ShadingLight> = scene
                .lights
                .iter()
                .map(|l| ShadingLight {
                    position: l.center(),
                    color: l.color(),
                })
                .collect();
            let shader = ShadingKernel::new(gpu)?;
            timed(&mut gpu_time, || {
                shader.shade(gpu, &lights, scene.ambient, &inputs)
            })?
        } else {
            hits.par_iter()
                .map(|(p, s, h)| {
                    let incoming: Vec<Incoming> = scene
                        .lights
                        .iter()
                        .enumerate()
                        .map(|(li, l)| Incoming {
                            dir: (l.center() - h.point).normalize_or_zero(),
                            color: l.color().map(|c| c * vis[*p][s * nl + li]),
                        })
                        .collect();
                    phong(
                        &leaves[h.leaf as usize].material,
                        scene.ambient,
                        h.normal,
                        h.to_eye,
                        &incoming,
                    )
                })
                .collect()
        }
    } else {
        hits.iter()
            .map(|(_, _, h)| leaves[h.leaf as usize].material.color)
            .collect()
    };
    let mut acc = vec![([0f32; 3], 0f32); samples.len()];
    for ((p, s, _), c) in hits.iter().zip(&colors) {
        let wgt = samples[*p][*s].weight;
        for (a, v) in acc[*p].0.iter_mut().zip(c) {
            *a += wgt * v;
        }
        acc[*p].1 += wgt;
    }
    let pixels: Vec<[f32; 3]> = samples
        .iter()
        .zip(&acc)
        .map(|(px, (sum, hit_weight))| {
            // Background for the samples that see none.
            let total: f32 = px.iter().map(|s| s.weight).sum();
            let bg = total - hit_weight;
            if total > 0.0 {
                std::array::from_fn(|k| (sum[k] + bg * scene.background[k]) / total)
            } else {
                scene.background
            }
        })
        .collect();
    passes.push(if lit {
        PassStats::new(
            "shading",
            t.elapsed(),
            &[("shaded_samples", hits.len() as u64)],
        )
    } else {
        PassStats::skipped("shading")
    });
    passes.push(PassStats::new("total-gpu", gpu_time, &[]));

    let classification = Image {
        width: w,
        height: h,
        pixels: pixel_classes
            .iter()
            .map(|c| box_class_color(&to_box_class(c.class)))
            .collect(),
    };
    let cost: Vec<f32> = pixel_classes.iter().map(|c| c.steps as f32).collect();
    Ok(RenderOutput {
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
        classification,
        cost_map: cost_image(w, h, &cost),
        shadows: shadow_maps,
        plan,
    })
}

/// The results of the soft-shadow work for one light.
struct SoftShadows {
    /// Per hit: the visible fraction and the class.
    results: Vec<(f32, ShadowClass)>,
    initial: Vec<GpuBeam>,
    sub: Vec<GpuBeam>,
    occluded: u64,
    umbra: u64,
    back_facing: u64,
}

/// The beam method on the GPU for every hit: initial beams over the light in one batch,
/// then the `n × n` sub-beams of the points they did not clear in another.
#[allow(clippy::too_many_arguments)]
fn soft_shadows(
    gpu: &Gpu,
    kernel: &BeamKernel,
    hits: &[(usize, usize, Hit)],
    light: &Patch,
    n: u32,
    offset: f64,
    settings: &BeamSettings,
    gpu_time: &mut Duration,
) -> Result<SoftShadows, GpuError> {
    let front: Vec<usize> = (0..hits.len())
        .filter(|&k| !light.is_behind(hits[k].2.point, hits[k].2.facing_normal()))
        .collect();
    let beam_over = |from: DVec3, part: &Patch| Beam {
        origin: point_box(from),
        dir: part.directions_from(from),
    };
    let initial_queries: Vec<BeamQuery> = front
        .iter()
        .map(|&k| BeamQuery {
            beam: beam_over(hits[k].2.shadow_origin(offset), light),
            t: ival(0.0, 1.0),
        })
        .collect();
    let initial = timed(gpu_time, || {
        kernel.classify(gpu, &initial_queries, settings)
    })?;
    let mut results = vec![(0.0, ShadowClass::BackFacing); hits.len()];
    let mut sub_points = Vec::new();
    let mut sub_queries = Vec::new();
    let (mut occluded, mut umbra) = (0, 0);
    for (&k, r) in front.iter().zip(&initial) {
        match r.class {
            GpuClass::Miss => results[k] = (1.0, ShadowClass::Lit),
            GpuClass::Hit { .. } => {
                occluded += 1;
                umbra += 1;
                results[k] = (0.0, ShadowClass::Umbra);
            }
            GpuClass::Undecided { t } => {
                occluded += 1;
                let from = hits[k].2.shadow_origin(offset);
                sub_points.push(k);
                for j in 0..n {
                    for i in 0..n {
                        sub_queries.push(BeamQuery {
                            beam: beam_over(from, &light.cell(i, j, n)),
                            t: ival(t.inf().max(0.0), 1.0),
                        });
                    }
                }
            }
        }
    }
    let sub_settings = BeamSettings {
        inclusion: false,
        ..*settings
    };
    let sub = timed(gpu_time, || {
        kernel.classify(gpu, &sub_queries, &sub_settings)
    })?;
    // The n² sub-beams of each point in a row: the share of them proven free.
    let total = (n * n) as usize;
    for (&k, cells) in sub_points.iter().zip(sub.chunks(total)) {
        let free = cells.iter().filter(|r| r.class == GpuClass::Miss).count();
        let class = if free == total {
            ShadowClass::Lit
        } else {
            ShadowClass::Penumbra
        };
        results[k] = (free as f32 / total as f32, class);
    }
    Ok(SoftShadows {
        back_facing: (hits.len() - front.len()) as u64,
        results,
        initial,
        sub,
        occluded,
        umbra,
    })
}

/// The number of sub-beams per side of the light for the scene's method.
fn sub_beams(spec: &ShadowSpec) -> u32 {
    match *spec {
        ShadowSpec::Beam { n, .. }
        | ShadowSpec::Minkowski {
            fine: Fine::Beams { n },
        } => n,
        _ => 7,
    }
}

/// The pixel rectangle `[x0, y0, x1, y1]` in 3 × 3 parts.
fn split3(r: &[f64; 4]) -> Vec<[f64; 4]> {
    let (dx, dy) = ((r[2] - r[0]) / 3.0, (r[3] - r[1]) / 3.0);
    (0..9)
        .map(|k| {
            let (i, j) = (f64::from(k % 3), f64::from(k / 3));
            [
                r[0] + i * dx,
                r[1] + j * dy,
                r[0] + (i + 1.0) * dx,
                r[1] + (j + 1.0) * dy,
            ]
        })
        .collect()
}

fn center_ray(scene: &Scene, r: &[f64; 4]) -> Ray {
    scene.camera.ray(0.5 * (r[0] + r[2]), 0.5 * (r[1] + r[3]))
}

/// The beam through a rectangle of the image, and its range inside the bounds and inside
/// what a classified `parent` beam left open ([`child_window`]).
fn primary_query(
    scene: &Scene,
    bounds: &IBox,
    r: &[f64; 4],
    parent: Option<&BoxClass>,
) -> BeamQuery {
    let beam = scene.camera.beam(r[0], r[1], r[2], r[3]);
    let window = child_window(parent).intersection(ival(0.0, f64::MAX));
    let t = beam
        .t_range(bounds)
        .map_or(Interval::EMPTY, |t| t.intersection(window));
    BeamQuery { beam, t }
}

/// Side of the tiles the screen box structure starts from.
const TILE: u32 = 16;

/// The screen box structure (thesis 5.4) on the GPU, level by level: tiles of
/// [`TILE`] pixels are classified in one batch; Miss and Hit boxes give their class to every
/// pixel (a Hit box's section holds every pixel ray's first root); Undecided boxes are
/// split in four for the next batch, searching only what their parent left open, down to
/// single pixels. Returns each pixel's class and every beam traced.
fn screen_boxes(
    gpu: &Gpu,
    kernel: &BeamKernel,
    scene: &Scene,
    bounds: &IBox,
    settings: &BeamSettings,
) -> Result<(Vec<GpuBeam>, Vec<GpuBeam>), GpuError> {
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let mut pixels = vec![
        GpuBeam {
            class: GpuClass::Miss,
            steps: 0,
        };
        (w * h) as usize
    ];
    let mut boxes: Vec<([u32; 4], Option<BoxClass>)> = Vec::new();
    for y0 in (0..h).step_by(TILE as usize) {
        for x0 in (0..w).step_by(TILE as usize) {
            boxes.push(([x0, y0, (x0 + TILE).min(w), (y0 + TILE).min(h)], None));
        }
    }
    let mut all = Vec::new();
    while !boxes.is_empty() {
        let queries: Vec<BeamQuery> = boxes
            .par_iter()
            .map(|(r, parent)| {
                let rect = r.map(f64::from);
                primary_query(scene, bounds, &rect, parent.as_ref())
            })
            .collect();
        let results = kernel.classify(gpu, &queries, settings)?;
        let mut next = Vec::new();
        for ((r, _), res) in boxes.iter().zip(&results) {
            let [x0, y0, x1, y1] = *r;
            let single = x1 - x0 == 1 && y1 - y0 == 1;
            if matches!(res.class, GpuClass::Undecided { .. }) && !single {
                let (xm, ym) = ((x0 + x1).div_ceil(2), (y0 + y1).div_ceil(2));
                for (a, b) in [(x0, xm), (xm, x1)] {
                    for (c, d) in [(y0, ym), (ym, y1)] {
                        if a < b && c < d {
                            next.push(([a, c, b, d], Some(to_box_class(res.class))));
                        }
                    }
                }
            } else {
                for y in y0..y1 {
                    for x in x0..x1 {
                        pixels[(y * w + x) as usize] = *res;
                    }
                }
            }
        }
        all.extend(results);
        boxes = next;
    }
    Ok((pixels, all))
}

/// A hit record on `ray` inside the section `t` (the shading point as the CPU places it).
fn shading_hit(
    ev: &mut beam_trace::scene::geometry::GeometryEval,
    ray: &Ray,
    t: Interval<f64>,
) -> Hit {
    let tm = shading_parameter(&mut ev.beam, ray, t, &mut RootCounters::default());
    let point = ray.at(tm);
    Hit {
        t,
        point,
        to_eye: (-ray.dir).normalize_or_zero(),
        leaf: ev.leaf_at(point) as u32,
        normal: -ray.dir.normalize_or_zero(),
    }
}

fn to_box_class(c: GpuClass) -> BoxClass {
    match c {
        GpuClass::Miss => BoxClass::Miss,
        GpuClass::Hit { t } => BoxClass::Hit { t_final: t },
        GpuClass::Undecided { t } => BoxClass::Undecided { t },
    }
}

fn timed<T>(total: &mut Duration, f: impl FnOnce() -> T) -> T {
    let t = Instant::now();
    let v = f();
    *total += t.elapsed();
    v
}

fn steps(r: &[GpuBeam]) -> u64 {
    r.iter().map(|b| u64::from(b.steps)).sum()
}

fn beam_stats(name: &str, time: Duration, r: &[GpuBeam]) -> PassStats {
    let count = |f: fn(&GpuClass) -> bool| r.iter().filter(|b| f(&b.class)).count() as u64;
    PassStats::new(
        name,
        time,
        &[
            ("beams", r.len() as u64),
            ("miss", count(|c| matches!(c, GpuClass::Miss))),
            ("hit", count(|c| matches!(c, GpuClass::Hit { .. }))),
            (
                "undecided",
                count(|c| matches!(c, GpuClass::Undecided { .. })),
            ),
            ("steps", steps(r)),
        ],
    )
}
