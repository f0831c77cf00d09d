//! The interval anti-aliasing pass (thesis 5.5.2; the estimator is in [`crate::aa`]).
//!
//! Each pixel starts as one beam over its whole area. A rejected beam is background; a beam
//! the inclusion test proves to hit everywhere is shaded once if the normals vary little
//! over its hit region; any other beam is split in four, down to a depth limit. At the
//! limit an undecided part is shaded with the first surface its beam may meet, so a
//! feature thinner than a pixel is never lost. The parts of every pixel of a batch are
//! classified level by level, one batch of beams per level; a pixel's samples come out in
//! the order of a depth-first walk of its quadrants.

use std::time::Instant;

use interval_core::Interval;

use super::pixels::{Pixels, offsets};
use super::{PixelSamples, RowBatch, row_batches};
use crate::backend::{BeamQuery, HitQuery, Queries, RayQuery, VariationQuery};
use crate::beam::forward;
use crate::beam::{BeamScope, BoxClass};
use crate::error::Error;
use crate::plan::Pass;
use crate::progress::Progress;
use crate::root::RootResult;
use crate::sample::Sample;
use crate::scene::Scene;
use crate::stats::PassStats;
use crate::stats::counters::IaaCounters;

pub use crate::aa::normal_variation;

/// A sub-pixel waiting for its beam.
#[derive(Clone, Debug)]
struct Part {
    /// The pixel, in the batch.
    pixel: usize,
    /// Top-left corner and side, in pixels.
    x0: f64,
    y0: f64,
    size: f64,
    /// Subdivision depth (0: the whole pixel).
    depth: u32,
    /// The quadrant path, two bits per level from the top: sorting by it gives the
    /// depth-first order.
    path: u64,
    /// The class of the beam it was split from.
    parent: Option<BoxClass>,
    /// The backend's scope of the beam it was split from.
    scope: Option<BeamScope>,
}

impl Part {
    fn quadrants(
        &self,
        class: BoxClass,
        scope: Option<BeamScope>,
    ) -> impl Iterator<Item = Part> + '_ {
        let h = 0.5 * self.size;
        [(0.0, 0.0), (h, 0.0), (0.0, h), (h, h)]
            .into_iter()
            .enumerate()
            .map(move |(k, (dx, dy))| Part {
                pixel: self.pixel,
                x0: self.x0 + dx,
                y0: self.y0 + dy,
                size: h,
                depth: self.depth + 1,
                path: self.path | (k as u64) << (62 - 2 * self.depth),
                parent: Some(class),
                scope: scope.clone(),
            })
    }
}

/// A finished part: background, or its central ray's root search and the enclosure to
/// shade when that ray misses.
struct Shaded {
    pixel: usize,
    path: u64,
    weight: f32,
    ray: Option<(RayQuery, Interval<f64>)>,
}

/// The IAA pass over every pixel.
pub(super) fn iaa(
    q: &dyn Queries,
    scene: &Scene,
    max_depth: u32,
    threshold: f64,
    progress: &dyn Progress,
) -> Result<PixelSamples, Error> {
    let cam = &scene.camera;
    let (w, h) = (cam.width(), cam.height());
    let t0 = Instant::now();
    progress.begin(Pass::Iaa.name(), u64::from(h));
    let mut c = IaaCounters::default();
    let npix = w as usize * h as usize;
    let mut pixels = Pixels::new();
    let mut cost: Vec<f32> = Vec::with_capacity(npix);
    for RowBatch { rows, first, n } in row_batches(w, h) {
        let mut pixel_cost = vec![0f32; n];
        let mut done: Vec<Shaded> = Vec::new();
        let mut level: Vec<Part> = (0..n)
            .map(|k| {
                let i = (first + k) as u32;
                Part {
                    pixel: k,
                    x0: f64::from(i % w),
                    y0: f64::from(i / w),
                    size: 1.0,
                    depth: 0,
                    path: 0,
                    parent: None,
                    scope: None,
                }
            })
            .collect();
        while !level.is_empty() {
            let beams: Vec<BeamQuery> = level
                .iter()
                .map(|p| BeamQuery {
                    beam: cam.beam(p.x0, p.y0, p.x0 + p.size, p.y0 + p.size),
                    parent: p.parent,
                    scope: p.scope.clone(),
                })
                .collect();
            let answers = q.beams(&beams)?;
            c.beams += beams.len() as u64;
            c.search.add(&answers.search);
            for (p, t) in level.iter().zip(&answers.cost) {
                pixel_cost[p.pixel] += t;
            }
            let (classes, scopes): (Vec<BoxClass>, Vec<Option<BeamScope>>) = answers
                .values
                .into_iter()
                .map(|a| (a.class, a.scope))
                .unzip();
            // The normal variation of the hits that may be shaded once.
            let judged: Vec<usize> = (0..level.len())
                .filter(|&j| {
                    level[j].depth < max_depth && matches!(classes[j], BoxClass::Hit { .. })
                })
                .collect();
            let variation_queries: Vec<VariationQuery> = judged
                .iter()
                .map(|&j| VariationQuery {
                    beam: beams[j].beam,
                    t_final: match classes[j] {
                        BoxClass::Hit { t_final } => t_final,
                        _ => unreachable!("only hits are judged"),
                    },
                })
                .collect();
            let variation = q.normal_variation(&variation_queries)?;
            let mut smooth = vec![false; level.len()];
            for ((&j, v), t) in judged.iter().zip(variation.values).zip(&variation.cost) {
                smooth[j] = v <= threshold;
                pixel_cost[level[j].pixel] += t;
            }
            let mut next = Vec::new();
            for (j, (p, class)) in level.iter().zip(&classes).enumerate() {
                let weight = (p.size * p.size) as f32;
                let at_limit = p.depth >= max_depth;
                let centre = cam.ray(p.x0 + 0.5 * p.size, p.y0 + 0.5 * p.size);
                let mut finish = |ray: Option<(RayQuery, Interval<f64>)>| {
                    done.push(Shaded {
                        pixel: p.pixel,
                        path: p.path,
                        weight,
                        ray,
                    });
                };
                match *class {
                    BoxClass::Miss => {
                        c.rejected += 1;
                        finish(None);
                    }
                    BoxClass::Hit { t_final } if at_limit || smooth[j] => {
                        c.shaded_once += 1;
                        c.rays += 1;
                        let query = RayQuery {
                            ray: centre,
                            window: t_final,
                        };
                        finish(Some((query, t_final)));
                    }
                    BoxClass::Hit { .. } => {
                        c.splits_variation += 1;
                        next.extend(p.quadrants(*class, scopes[j].clone()));
                    }
                    BoxClass::Undecided { t } if at_limit => {
                        // The central ray may miss while some ray of the beam meets the
                        // surface in `t`: then `t` is shaded, and the feature kept.
                        c.depth_limit += 1;
                        c.rays += 1;
                        let query = RayQuery {
                            ray: centre,
                            window: forward(),
                        };
                        finish(Some((query, t)));
                    }
                    BoxClass::Undecided { .. } => {
                        c.splits_undecided += 1;
                        next.extend(p.quadrants(*class, scopes[j].clone()));
                    }
                }
            }
            level = next;
        }
        // The central rays of the parts shaded, then their shading points.
        let shaded: Vec<usize> = (0..done.len()).filter(|&k| done[k].ray.is_some()).collect();
        let ray_queries: Vec<RayQuery> = shaded
            .iter()
            .filter_map(|&k| done[k].ray.map(|r| r.0))
            .collect();
        let roots = q.roots(&ray_queries)?;
        c.search.add(&roots.search);
        let hit_queries: Vec<HitQuery> = shaded
            .iter()
            .zip(&roots.values)
            .zip(&roots.cost)
            .filter_map(|((&k, r), t)| {
                pixel_cost[done[k].pixel] += t;
                let (query, fallback) = done[k].ray?;
                let t = match *r {
                    RootResult::Root { t, .. } | RootResult::Undecided { t } => t,
                    RootResult::NoRoot => fallback,
                };
                Some(HitQuery { ray: query.ray, t })
            })
            .collect();
        let hits = q.hit_points(&hit_queries)?;
        c.search.add(&hits.search);
        let mut parts: Vec<(usize, u64, Sample)> = done
            .iter()
            .map(|d| {
                (
                    d.pixel,
                    d.path,
                    Sample {
                        weight: d.weight,
                        hit: None,
                    },
                )
            })
            .collect();
        for ((&k, hit), t) in shaded.iter().zip(hits.values).zip(&hits.cost) {
            parts[k].2.hit = Some(hit);
            pixel_cost[done[k].pixel] += t;
        }
        parts.sort_by_key(|&(pixel, path, _)| (pixel, path));
        let mut counts = vec![0; n];
        for &(pixel, _, _) in &parts {
            counts[pixel] += 1;
        }
        let samples = parts.into_iter().map(|(_, _, s)| s).collect();
        pixels.append(Pixels::from_offsets(samples, offsets(counts.into_iter())));
        cost.extend(pixel_cost);
        progress.advance(u64::from(rows));
    }
    progress.end();
    Ok((pixels, cost, PassStats::of(Pass::Iaa, t0.elapsed(), &c)))
}
