//! The hard-shadow pass: one shadow segment per hit sample and point light.

use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;

use super::starts;
use crate::backend::{Queries, SegmentQuery};
use crate::error::Error;
use crate::plan::Pass;
use crate::progress::Progress;
use crate::sample::{SHADOW_OFFSET, Sample};
use crate::scene::Scene;
use crate::shadow::hard::Visibility;
use crate::stats::PassStats;
use crate::stats::counters::HardShadowCounters;

/// For each hit sample and point light (`Some` position; area lights are `None`), the
/// visible fraction (0 or 1) from a shadow segment search, written to `vis` (sample-major,
/// light-minor per pixel). A sample facing away from the light gets no direct light and no
/// segment.
pub(super) fn hard_shadows(
    q: &dyn Queries,
    scene: &Scene,
    samples: &[Vec<Sample>],
    lights: &[Option<DVec3>],
    vis: &mut [Vec<f32>],
    progress: &dyn Progress,
) -> Result<PassStats, Error> {
    let nl = lights.len();
    let t0 = Instant::now();
    let offset = SHADOW_OFFSET * scene.geometry.diagonal();
    let mut c = HardShadowCounters::default();
    // Samples facing away from a light get no direct light from it and no segment.
    let counts: Vec<(usize, u64)> = samples
        .par_iter()
        .zip(vis.par_iter_mut())
        .map(|(px, v)| {
            let (mut facing, mut away) = (0, 0);
            for (k, query) in segments(px, lights, nl, offset) {
                match query {
                    Some(_) => facing += 1,
                    None => {
                        away += 1;
                        v[k] = 0.0;
                    }
                }
            }
            (facing, away)
        })
        .collect();
    c.back_facing = counts.iter().map(|c| c.1).sum();
    let first = starts(counts.iter().map(|c| c.0));
    let queries: Vec<SegmentQuery> = samples
        .par_iter()
        .flat_map_iter(|px| segments(px, lights, nl, offset).filter_map(|(_, q)| q))
        .collect();
    c.segments = queries.len() as u64 + c.back_facing;
    progress.begin(Pass::HardShadows.name(), queries.len() as u64);
    let mut answers = Vec::with_capacity(queries.len());
    for qs in queries.chunks(BATCH) {
        let a = q.segments(qs)?;
        c.search.add(&a.search);
        answers.extend(a.values);
        progress.advance(qs.len() as u64);
    }
    for v in &answers {
        match v {
            Visibility::Lit => c.lit += 1,
            Visibility::Occluded => c.occluded += 1,
            Visibility::Undecided => c.undecided += 1,
        }
    }
    // Each pixel reads its answers in the order it asked them.
    samples
        .par_iter()
        .zip(vis.par_iter_mut())
        .zip(first)
        .for_each(|((px, v), mut j)| {
            for (k, query) in segments(px, lights, nl, offset) {
                if query.is_some() {
                    v[k] = if answers[j] == Visibility::Lit {
                        1.0
                    } else {
                        0.0
                    };
                    j += 1;
                }
            }
        });
    progress.end();
    Ok(PassStats::of(Pass::HardShadows, t0.elapsed(), &c))
}

/// The shadow segments of a pixel's hit samples to the point lights (`Some` position),
/// each with the index of its visible fraction in the pixel's `vis` (sample-major,
/// light-minor): the query, or `None` where the sample faces away from the light.
fn segments<'a>(
    px: &'a [Sample],
    lights: &'a [Option<DVec3>],
    nl: usize,
    offset: f64,
) -> impl Iterator<Item = (usize, Option<SegmentQuery>)> + 'a {
    px.iter().enumerate().flat_map(move |(si, s)| {
        s.hit.into_iter().flat_map(move |hit| {
            let n = hit.facing_normal();
            lights.iter().enumerate().filter_map(move |(li, pos)| {
                let pos = (*pos)?;
                let query = (n.dot(pos - hit.point) > 0.0).then(|| SegmentQuery {
                    from: hit.shadow_origin(offset),
                    to: pos,
                });
                Some((si * nl + li, query))
            })
        })
    })
}

/// Segments per batch.
const BATCH: usize = 1 << 16;
