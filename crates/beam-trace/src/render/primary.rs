//! Primary visibility with beams and rays: the screen box structure (thesis 5.4), level by
//! level, and the rays of each pixel searched where its box left them open.

use std::time::Instant;

use super::{PixelSamples, ROWS_PER_BATCH};
use crate::backend::cpu::{child_window, forward};
use crate::backend::{BeamQuery, HitQuery, Queries, RayQuery};
use crate::beam::BoxClass;
use crate::error::Error;
use crate::plan::{Pass, Plan};
use crate::progress::Progress;
use crate::root::{Proof, RootResult};
use crate::sample::Sample;
use crate::scene::Scene;
use crate::screen::{PixelRect, needs_split, tiles};
use crate::stats::PassStats;
use crate::stats::counters::{PrimaryRayCounters, ScreenBoxCounters};

/// Side of the tiles the screen box structure starts from.
const TILE: u32 = 32;

/// Each pixel's screen box class, and whether the pixel lies on its box's top or left edge.
pub(super) type PixelClasses = Vec<Option<(BoxClass, bool)>>;

/// The screen box pass: tiles classified in one batch, the boxes to split in the next
/// batch, down to single pixels (Undecided boxes and wide Hit boxes are split; a part
/// searches only what its parent left open).
pub(super) fn screen_boxes(
    q: &dyn Queries,
    scene: &Scene,
    plan: &Plan,
    progress: &dyn Progress,
) -> Result<(PixelClasses, PassStats), Error> {
    let cam = &scene.camera;
    let (w, h) = (cam.width(), cam.height());
    let t0 = Instant::now();
    progress.begin(Pass::ScreenBoxes.name(), u64::from(w) * u64::from(h));
    let mut classes: PixelClasses = vec![None; w as usize * h as usize];
    let mut c = ScreenBoxCounters::default();
    let mut level: Vec<(PixelRect, Option<BoxClass>)> =
        tiles(w, h, TILE).into_iter().map(|t| (t, None)).collect();
    while !level.is_empty() {
        let queries: Vec<BeamQuery> = level
            .iter()
            .map(|(r, parent)| BeamQuery {
                beam: cam.beam(
                    f64::from(r.x0),
                    f64::from(r.y0),
                    f64::from(r.x1),
                    f64::from(r.y1),
                ),
                parent: *parent,
            })
            .collect();
        let answers = q.beams(&queries)?;
        c.beams += queries.len() as u64;
        c.search.add(&answers.search);
        let mut next = Vec::new();
        for ((rect, _), class) in level.iter().zip(answers.values) {
            if needs_split(rect, &class, plan.t_final_width) {
                next.extend(rect.split().into_iter().map(|r| (r, Some(class))));
                continue;
            }
            let count = match class {
                BoxClass::Miss => &mut c.miss_pixels,
                BoxClass::Hit { .. } => &mut c.hit_pixels,
                BoxClass::Undecided { .. } => &mut c.undecided_pixels,
            };
            *count += rect.area();
            for (x, y) in rect.pixels() {
                let edge = x == rect.x0 || y == rect.y0;
                classes[(y * w + x) as usize] = Some((class, edge));
            }
            progress.advance(rect.area());
        }
        level = next;
    }
    progress.end();
    Ok((classes, PassStats::of(Pass::ScreenBoxes, t0.elapsed(), &c)))
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

/// One ray of a pixel: the pixel (in the batch), its weight, the query, and whether its
/// window is a Hit box's `T_final`, where a root is known to exist.
struct PixelRay {
    pixel: usize,
    weight: f32,
    query: RayQuery,
    in_t_final: bool,
}

/// The primary-rays pass: in a Hit box one central ray per pixel searched in `T_final`
/// (the whole ray again if the search stops at a limit there); elsewhere `rays` stratified
/// rays per pixel, from where the pixel's beam proved them root-free; a Miss box's pixels
/// are background without a ray. `classes` holds each pixel's box (none in per-pixel
/// mode).
pub(super) fn primary_rays(
    q: &dyn Queries,
    scene: &Scene,
    classes: &[Option<(BoxClass, bool)>],
    rays: u32,
    progress: &dyn Progress,
) -> Result<PixelSamples, Error> {
    let cam = &scene.camera;
    let (w, h) = (cam.width(), cam.height());
    let offsets = pixel_offsets(rays);
    let t0 = Instant::now();
    progress.begin(Pass::PrimaryRays.name(), u64::from(h));
    let mut c = PrimaryRayCounters::default();
    let npix = w as usize * h as usize;
    let mut samples: Vec<Vec<Sample>> = Vec::with_capacity(npix);
    let mut cost: Vec<f32> = Vec::with_capacity(npix);
    for y0 in (0..h).step_by(ROWS_PER_BATCH as usize) {
        let y1 = (y0 + ROWS_PER_BATCH).min(h);
        let first = (y0 * w) as usize;
        let n = ((y1 - y0) * w) as usize;
        // The rays of every pixel of the batch.
        let mut batch: Vec<PixelRay> = Vec::new();
        for k in 0..n {
            let i = first + k;
            let (fx, fy) = (f64::from(i as u32 % w), f64::from(i as u32 / w));
            match classes[i].map(|c| c.0) {
                Some(BoxClass::Miss) => {}
                Some(BoxClass::Hit { t_final }) => batch.push(PixelRay {
                    pixel: k,
                    weight: 1.0,
                    query: RayQuery {
                        ray: cam.ray(fx + 0.5, fy + 0.5),
                        window: t_final,
                    },
                    in_t_final: true,
                }),
                class @ (Some(BoxClass::Undecided { .. }) | None) => {
                    // The pixel's beam proved its rays root-free before its undecided range.
                    let window = child_window(class.as_ref());
                    let weight = 1.0 / offsets.len() as f32;
                    batch.extend(offsets.iter().map(|&(ox, oy)| PixelRay {
                        pixel: k,
                        weight,
                        query: RayQuery {
                            ray: cam.ray(fx + ox, fy + oy),
                            window,
                        },
                        in_t_final: false,
                    }));
                }
            }
        }
        let mut pixel_cost = vec![0f32; n];
        let queries: Vec<RayQuery> = batch.iter().map(|r| r.query).collect();
        let first_try = q.roots(&queries)?;
        c.rays += queries.len() as u64;
        c.search.add(&first_try.search);
        let mut results = first_try.values;
        for (r, t) in batch.iter().zip(&first_try.cost) {
            pixel_cost[r.pixel] += t;
        }
        // A limit inside T_final: search the whole ray.
        let retry: Vec<usize> = (0..batch.len())
            .filter(|&j| batch[j].in_t_final && !matches!(results[j], RootResult::Root { .. }))
            .collect();
        if !retry.is_empty() {
            let queries: Vec<RayQuery> = retry
                .iter()
                .map(|&j| RayQuery {
                    ray: batch[j].query.ray,
                    window: forward(),
                })
                .collect();
            let again = q.roots(&queries)?;
            c.search.add(&again.search);
            for ((&j, r), t) in retry.iter().zip(again.values).zip(&again.cost) {
                results[j] = r;
                pixel_cost[batch[j].pixel] += t;
            }
        }
        // The shading points of the rays that meet (or may meet) a surface.
        let mut hit_rays = Vec::new();
        let mut hit_queries = Vec::new();
        for (j, r) in results.iter().enumerate() {
            let t = match *r {
                RootResult::Root { t, proof } => {
                    c.hits += 1;
                    match proof {
                        Proof::Unique => c.proven_unique += 1,
                        Proof::Possible => c.possible += 1,
                        Proof::Exists => {}
                    }
                    t
                }
                RootResult::Undecided { t } => {
                    c.undecided += 1;
                    t
                }
                RootResult::NoRoot => continue,
            };
            hit_rays.push(j);
            hit_queries.push(HitQuery {
                ray: batch[j].query.ray,
                t,
            });
        }
        let hits = q.hit_points(&hit_queries)?;
        c.search.add(&hits.search);
        let mut hit_of = vec![None; batch.len()];
        for ((&j, hit), t) in hit_rays.iter().zip(hits.values).zip(&hits.cost) {
            hit_of[j] = Some(hit);
            pixel_cost[batch[j].pixel] += t;
        }
        // Each pixel's samples, in the order of its rays.
        let mut pixels: Vec<Vec<Sample>> = vec![Vec::new(); n];
        for (r, hit) in batch.iter().zip(hit_of) {
            pixels[r.pixel].push(Sample {
                weight: r.weight,
                hit,
            });
        }
        for px in &mut pixels {
            if px.is_empty() {
                px.push(Sample {
                    weight: 1.0,
                    hit: None,
                });
            }
        }
        samples.extend(pixels);
        cost.extend(pixel_cost);
        progress.advance(u64::from(y1 - y0));
    }
    progress.end();
    Ok((
        samples,
        cost,
        PassStats::of(Pass::PrimaryRays, t0.elapsed(), &c),
    ))
}
