//! The pixel-beams pass: each pixel resolved by its beam, starting from the screen box
//! structure's class of the pixel (thesis 5.4-5.5; interval anti-aliasing, 5.5.2).
//!
//! A pixel in a Miss box is background; a pixel in a Hit box gets one central ray in the
//! box's `T_final`. The beam of an Undecided pixel is split in four, and each part is
//! classified starting from its parent's result (its search window and pruned tape), down
//! to a depth limit; at the limit an undecided part is shaded with the first surface its
//! beam may meet, so a feature thinner than a pixel is never lost. With anti-aliasing, a
//! Hit beam whose shading may vary by more than a threshold over its proven region
//! ([`shading_variation`](crate::aa::shading_variation)) is split too; the others are
//! shaded once.
//!
//! Each part's sample carries what its beam proved about its area ([`Area`]), from which
//! the pixel's [`Coverage`](crate::sample::Coverage) bounds follow. The parts of every
//! pixel of a batch are classified level by level, one batch of beams per level; a pixel's
//! samples come out in the order of a depth-first walk of its quadrants.

use std::time::Instant;

use interval_core::Interval;
use rayon::prelude::*;

use super::batches::{PixelSamples, ROWS_PER_BATCH, RowBatch, row_batches};
use super::buffers;
use super::classes::PixelClasses;
use super::pixels::{Pixels, offsets};
use crate::backend::{BeamQuery, HitQuery, Queries, RayQuery, VariationQuery};
use crate::beam::{BeamScope, BoxClass, child_window};
use crate::camera::Camera;
use crate::error::Error;
use crate::plan::Pass;
use crate::progress::Progress;
use crate::ray::{Beam, Ray};
use crate::root::RootResult;
use crate::sample::{Area, Sample};
use crate::scene::Scene;
use crate::stats::PassStats;
use crate::stats::counters::PixelBeamCounters;
use crate::window::Window;

/// How far the pass splits: the depth limit, and the shading-variation threshold above
/// which a Hit beam is split too (`None`: Hit beams are shaded once, no anti-aliasing).
#[derive(Copy, Clone, Debug)]
pub(super) struct Refinement {
    pub(super) max_depth: u32,
    pub(super) threshold: Option<f64>,
    /// Whether a Hit part's central ray narrows `T_final` ([`Plan::narrow_hits`]); else its
    /// root is the one `T_final` is proven to hold.
    ///
    /// [`Plan::narrow_hits`]: crate::plan::Plan::narrow_hits
    pub(super) narrow_hits: bool,
    /// Rays per side of an undecided part at the depth limit: its share of the surface is
    /// estimated from `limit_rays²` stratified rays (1: from its central ray alone).
    pub(super) limit_rays: u32,
}

/// The share of one of its `m²` stratified rays that an undecided part at the depth limit
/// keeps for the surface when all of them miss it, and for the background when all of them
/// meet it (the part's share is unknown: neither all nor none of it is proven). Parts left
/// undecided are mostly where an enclosure is loose, not where an edge crosses: a quarter
/// (the middle of `[0, 1/2]` for a straight edge missing the central ray) gave the default
/// scene's edges a 24 % larger RMSE (`aa-cost`, 160 × 120: 0.1015 against 0.0820).
const UNKNOWN_SHARE_FLOOR: f32 = 1.0 / 16.0;

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
    /// Its own class when already known (a whole pixel classified by the screen boxes).
    known: Option<BoxClass>,
    /// Whether its shading is already proven to vary by at most the threshold (a pixel
    /// its screen box proved so): it is shaded once.
    smooth: bool,
}

impl Part {
    /// The part's beam.
    fn beam(&self, cam: &Camera) -> Beam {
        cam.beam(self.x0, self.y0, self.x0 + self.size, self.y0 + self.size)
    }

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
                known: None,
                smooth: false,
            })
    }
}

/// A finished part: background, or its central ray's root search and the enclosure to
/// shade when that ray finds no root; what its beam proved about its area; and the
/// stratified rays that estimate the share of an undecided part at the depth limit (none:
/// its central ray alone).
struct Shaded {
    pixel: usize,
    path: u64,
    weight: f32,
    ray: Option<(RayQuery, Interval<f64>)>,
    area: Area,
    probes: Vec<Ray>,
}

/// A level of parts classified: each part's class and scope.
struct Classified {
    classes: Vec<BoxClass>,
    scopes: Vec<Option<BeamScope>>,
}

/// One level of parts classified (a known class is not asked again), the cost added to
/// each part's pixel.
fn classify(
    q: &dyn Queries,
    cam: &Camera,
    level: &mut [Part],
    pixel_cost: &mut [f32],
    c: &mut PixelBeamCounters,
) -> Result<Classified, Error> {
    let asked: Vec<usize> = (0..level.len())
        .filter(|&j| level[j].known.is_none())
        .collect();
    let queries: Vec<BeamQuery> = asked
        .par_iter()
        .map(|&j| BeamQuery {
            beam: level[j].beam(cam),
            parent: level[j].parent,
            scope: level[j].scope.clone(),
        })
        .collect();
    let answers = q.beams(&queries)?;
    c.beams += queries.len() as u64;
    c.search.add(&answers.search);
    let mut classes: Vec<BoxClass> = level
        .iter()
        .map(|p| p.known.unwrap_or(BoxClass::Miss))
        .collect();
    // A known class comes with the scope its screen box handed on.
    let mut scopes: Vec<Option<BeamScope>> = level.iter_mut().map(|p| p.scope.take()).collect();
    for ((&j, a), t) in asked.iter().zip(answers.values).zip(&answers.cost) {
        classes[j] = a.class;
        scopes[j] = a.scope;
        pixel_cost[level[j].pixel] += t;
    }
    Ok(Classified { classes, scopes })
}

/// Whether each Hit part of `judged` may be shaded once: its shading varies by at most
/// `threshold` over its proven region, and the shadow of each point light is proven the
/// same over it (lit, or blocked, everywhere).
fn smooth_hits(
    q: &dyn Queries,
    (cam, level): (&Camera, &[Part]),
    classes: &[BoxClass],
    judged: &[usize],
    threshold: f64,
    pixel_cost: &mut [f32],
) -> Result<Vec<bool>, Error> {
    let queries: Vec<VariationQuery> = judged
        .iter()
        .filter_map(|&j| match classes[j] {
            BoxClass::Hit { t_final } => Some(VariationQuery {
                beam: level[j].beam(cam),
                t_final,
                threshold,
            }),
            _ => None,
        })
        .collect();
    let variation = q.shading_variation(&queries)?;
    // A part already proven smooth (by its screen box) is not judged again.
    let mut smooth: Vec<bool> = level.iter().map(|p| p.smooth).collect();
    for ((&j, v), t) in judged.iter().zip(variation.values).zip(&variation.cost) {
        smooth[j] = v <= threshold;
        pixel_cost[level[j].pixel] += t;
    }
    Ok(smooth)
}

/// The pixel-beams pass over every pixel of `window`: `classes` is the screen box
/// structure's result per pixel, class and scope (no class where no screen box classified
/// the pixel: its beam is classified here).
pub(super) fn pixel_beams(
    q: &dyn Queries,
    scene: &Scene,
    window: &Window,
    classes: &PixelClasses,
    refine: Refinement,
    progress: &dyn Progress,
) -> Result<PixelSamples, Error> {
    let cam = &scene.camera;
    let (w, h) = (window.width(), window.height());
    let t0 = Instant::now();
    progress.begin(Pass::PixelBeams.name(), u64::from(h));
    let mut c = PixelBeamCounters::default();
    let npix = window.len();
    let mut pixels = Pixels::new();
    let mut cost: Vec<f32> = buffers::with_room(npix);
    for RowBatch { rows, first, n } in row_batches(w, h, ROWS_PER_BATCH) {
        let mut pixel_cost = vec![0f32; n];
        // With anti-aliasing a Hit pixel's own beam is classified inside its box's
        // `T_final`: its own, narrower section is the region whose shading is judged.
        let class = |k: usize| classes.get(first + k).map(|c| c.class);
        // A pixel of a Hit box whose shading the screen boxes judged smooth keeps the
        // box's class and is shaded once.
        let smooth = |k: usize| classes.get(first + k).is_some_and(|c| c.smooth);
        // A pixel its screen box proved missed is background with no part (counted as
        // rejected); the others start as whole-pixel parts.
        let missed = |k: usize| matches!(class(k), Some(BoxClass::Miss));
        let level: Vec<Part> = (0..n)
            .filter(|&k| !missed(k))
            .map(|k| {
                let (x, y) = window.pixel(first + k);
                Part {
                    pixel: k,
                    x0: f64::from(x),
                    y0: f64::from(y),
                    size: 1.0,
                    depth: 0,
                    path: 0,
                    parent: class(k),
                    scope: classes.scope(first + k).cloned(),
                    known: class(k).filter(|c| {
                        refine.threshold.is_none()
                            || smooth(k)
                            || !matches!(c, BoxClass::Hit { .. })
                    }),
                    smooth: smooth(k),
                }
            })
            .collect();
        c.rejected += (n - level.len()) as u64;
        let done = subdivide(q, cam, level, refine, &mut pixel_cost, &mut c)?;
        let samples = shade_parts(q, done, (n, refine.narrow_hits), &mut pixel_cost, &mut c)?;
        pixels.append(samples);
        cost.extend(pixel_cost);
        progress.advance(u64::from(rows));
    }
    progress.end();
    Ok((
        pixels,
        cost,
        PassStats::of(Pass::PixelBeams, t0.elapsed(), &c),
    ))
}

/// The parts of a batch's pixels, level by level, until every part is finished.
fn subdivide(
    q: &dyn Queries,
    cam: &Camera,
    mut level: Vec<Part>,
    refine: Refinement,
    pixel_cost: &mut [f32],
    c: &mut PixelBeamCounters,
) -> Result<Vec<Shaded>, Error> {
    let Refinement {
        max_depth,
        threshold,
        limit_rays,
        narrow_hits,
    } = refine;
    let mut done: Vec<Shaded> = Vec::new();
    while !level.is_empty() {
        let Classified { classes, scopes } = classify(q, cam, &mut level, pixel_cost, c)?;
        let open = |j: usize| level[j].depth < max_depth;
        let smooth = match threshold {
            Some(limit) => {
                let judged: Vec<usize> = (0..level.len())
                    .filter(|&j| {
                        open(j) && !level[j].smooth && matches!(classes[j], BoxClass::Hit { .. })
                    })
                    .collect();
                smooth_hits(q, (cam, &level), &classes, &judged, limit, pixel_cost)?
            }
            None => vec![true; level.len()],
        };
        let mut next = Vec::new();
        for (j, (p, class)) in level.iter().zip(&classes).enumerate() {
            let weight = (p.size * p.size) as f32;
            // The part's central ray, made only for the parts that are shaded.
            let centre = || cam.ray(p.x0 + 0.5 * p.size, p.y0 + 0.5 * p.size);
            let mut finish = |ray, area, probes| {
                done.push(Shaded {
                    pixel: p.pixel,
                    path: p.path,
                    weight,
                    ray,
                    area,
                    probes,
                });
            };
            match *class {
                BoxClass::Miss => {
                    c.rejected += 1;
                    // A whole pixel missed has no sample (background, proven missed); a
                    // part's background keeps its share of the pixel.
                    if p.depth > 0 {
                        finish(None, Area::Missed, Vec::new());
                    }
                }
                BoxClass::Hit { t_final } if !open(j) || smooth[j] => {
                    c.shaded_once += 1;
                    // Searched only where the plan narrows hits.
                    c.rays += u64::from(narrow_hits);
                    let query = RayQuery {
                        ray: centre(),
                        window: t_final,
                        scope: scopes[j].clone(),
                    };
                    finish(Some((query, t_final)), Area::Covered, Vec::new());
                }
                BoxClass::Hit { .. } => {
                    c.splits_variation += 1;
                    // Every ray of a quadrant is a ray of this beam: each quadrant is a Hit
                    // in the same `T_final`. Below the depth limit its own search narrows
                    // that section for the next judgement; at the limit nothing is judged,
                    // and the quadrant is shaded in this beam's section without one.
                    let at_limit = p.depth + 1 >= max_depth;
                    next.extend(p.quadrants(*class, scopes[j].clone()).map(|mut q| {
                        if at_limit {
                            q.known = Some(*class);
                        }
                        q
                    }));
                }
                BoxClass::Undecided { t } if !open(j) => {
                    // At the limit: the part's rays may all miss while some ray of the beam
                    // meets the surface in `t`: then `t` is shaded, and the feature kept.
                    c.depth_limit += 1;
                    let probes = stratified(cam, p, limit_rays);
                    c.rays += probes.len().max(1) as u64;
                    let query = RayQuery {
                        ray: centre(),
                        window: child_window(Some(class)),
                        scope: None,
                    };
                    finish(Some((query, t)), Area::Unknown, probes);
                }
                BoxClass::Undecided { .. } => {
                    c.splits_undecided += 1;
                    next.extend(p.quadrants(*class, scopes[j].clone()));
                }
            }
        }
        level = next;
    }
    Ok(done)
}

/// `m × m` stratified rays over part `p` (none for `m ≤ 1`: the part's central ray
/// stands for it).
fn stratified(cam: &Camera, p: &Part, m: u32) -> Vec<Ray> {
    if m <= 1 {
        return Vec::new();
    }
    let step = p.size / f64::from(m);
    (0..m * m)
        .map(|i| {
            let (u, v) = (f64::from(i % m) + 0.5, f64::from(i / m) + 0.5);
            cam.ray(p.x0 + u * step, p.y0 + v * step)
        })
        .collect()
}

/// The samples of a batch's `n` pixels' finished parts, pixel by pixel in depth-first
/// quadrant order: the rays are searched (a part's stratified rays where it has them, else
/// its central ray; a Hit part's only where `narrow`, else its root is the one its
/// `T_final` holds), then the shading point of each part's first ray that met a surface.
fn shade_parts(
    q: &dyn Queries,
    done: Vec<Shaded>,
    (n, narrow): (usize, bool),
    pixel_cost: &mut [f32],
    c: &mut PixelBeamCounters,
) -> Result<Pixels, Error> {
    let shaded: Vec<usize> = (0..done.len()).filter(|&k| done[k].ray.is_some()).collect();
    let known = |k: usize| match &done[k].ray {
        Some((_, t_final)) if !narrow && done[k].area == Area::Covered => {
            Some(RootResult::included(*t_final))
        }
        _ => None,
    };
    // The rays searched for shaded part `i`: `queries[first[i]..first[i + 1]]`, its
    // stratified rays where it has them, else its central ray unless its root is known.
    let mut queries: Vec<RayQuery> = Vec::with_capacity(shaded.len());
    let mut first = Vec::with_capacity(shaded.len() + 1);
    first.push(0);
    for &k in &shaded {
        let (query, _) = done[k].ray.as_ref().expect("a shaded part");
        if !done[k].probes.is_empty() {
            queries.extend(done[k].probes.iter().map(|&ray| RayQuery {
                ray,
                window: query.window,
                scope: query.scope.clone(),
            }));
        } else if known(k).is_none() {
            queries.push(query.clone());
        }
        first.push(queries.len());
    }
    let answers = q.roots(&queries)?;
    c.search.add(&answers.search);
    // Each shaded part's shading queries (every one of its rays that met a surface, or may
    // have; its central ray in the enclosure to shade where none did) are
    // `hit_queries[first_hit[i]..first_hit[i + 1]]`, and `met[i]` the share of its rays that
    // met one.
    let mut hit_queries: Vec<HitQuery> = Vec::with_capacity(shaded.len());
    let mut first_hit = Vec::with_capacity(shaded.len() + 1);
    let mut met = Vec::with_capacity(shaded.len());
    first_hit.push(0);
    for (i, &k) in shaded.iter().enumerate() {
        let (query, fallback) = done[k].ray.as_ref().expect("a shaded part");
        let rays = first[i]..first[i + 1];
        pixel_cost[done[k].pixel] += answers.cost[rays.clone()].iter().sum::<f32>();
        let hit = |ray, r: RootResult| HitQuery {
            ray,
            t: match r {
                RootResult::Root { t, .. } | RootResult::Undecided { t } => t,
                RootResult::NoRoot => *fallback,
            },
            scope: query.scope.clone(),
        };
        if let Some(r) = known(k) {
            hit_queries.push(hit(query.ray, r));
            met.push(1.0);
        } else {
            let roots = &answers.values[rays.clone()];
            let before = hit_queries.len();
            hit_queries.extend(
                (rays.clone())
                    .zip(roots)
                    .filter(|(_, r)| !matches!(r, RootResult::NoRoot))
                    .map(|(j, &r)| hit(queries[j].ray, r)),
            );
            let meeting = hit_queries.len() - before;
            met.push(meeting as f32 / roots.len().max(1) as f32);
            if meeting == 0 {
                hit_queries.push(hit(query.ray, RootResult::NoRoot));
            }
        }
        first_hit.push(hit_queries.len());
    }
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
                    area: d.area,
                },
            )
        })
        .collect();
    for (i, (&k, &met)) in shaded.iter().zip(&met).enumerate() {
        let range = first_hit[i]..first_hit[i + 1];
        pixel_cost[done[k].pixel] += hits.cost[range.clone()].iter().sum::<f32>();
        let part_hits = &hits.values[range];
        let (pixel, path) = (done[k].pixel, done[k].path);
        // An undecided part at the limit: its surface's share of it is unknown, but
        // neither all nor none of it is proven, so the share kept is inside (0, 1). With
        // `m²` stratified rays (m = 1: the central ray) of which a share `met` meets a
        // surface, `met` estimates the share, kept [`UNKNOWN_SHARE_FLOOR`] of a ray's share
        // inside (0, 1): a part whose rays all miss a feature its beam may meet still
        // shows it, with little bias where the beam's enclosure is merely loose. The share
        // is split evenly among the rays that met a surface, each shaded where it met its
        // own (a part across a silhouette sees two surfaces).
        let share = if done[k].area == Area::Unknown {
            let m2 = done[k].probes.len().max(1) as f32;
            let floor = UNKNOWN_SHARE_FLOOR / m2;
            met.clamp(floor, 1.0 - floor)
        } else {
            1.0
        };
        let weight = parts[k].2.weight;
        let each = weight * share / part_hits.len() as f32;
        parts[k].2.hit = Some(part_hits[0]);
        parts[k].2.weight = each;
        for &hit in &part_hits[1..] {
            parts.push((
                pixel,
                path,
                Sample {
                    weight: each,
                    hit: Some(hit),
                    area: done[k].area,
                },
            ));
        }
        if done[k].area == Area::Unknown {
            parts.push((
                pixel,
                path,
                Sample {
                    weight: weight * (1.0 - share),
                    hit: None,
                    area: Area::Unknown,
                },
            ));
        }
    }
    // Stable: a part's surface samples stay before its background sample.
    parts.sort_by_key(|&(pixel, path, _)| (pixel, path));
    let mut counts = vec![0; n];
    for &(pixel, _, _) in &parts {
        counts[pixel] += 1;
    }
    let samples = parts.into_iter().map(|(_, _, s)| s).collect();
    Ok(Pixels::from_offsets(samples, offsets(counts.into_iter())))
}
