//! The hard-shadow pass: one shadow segment per hit sample and point light.

use std::time::Instant;

use glam::DVec3;

use super::pixels::Pixels;
use crate::backend::{Queries, SegmentQuery};
use crate::error::Error;
use crate::plan::Pass;
use crate::progress::Progress;
use crate::sample::SHADOW_OFFSET;
use crate::scene::Scene;
use crate::shadow::hard::Visibility;
use crate::stats::PassStats;
use crate::stats::counters::HardShadowCounters;

/// For each hit sample and point light (`Some` position; area lights are `None`), the
/// visible fraction (0 or 1) from a shadow segment search, written to `vis` (sample-major,
/// light-minor). A sample facing away from the light gets no direct light and no segment.
pub(super) fn hard_shadows(
    q: &dyn Queries,
    scene: &Scene,
    pixels: &Pixels,
    lights: &[Option<DVec3>],
    vis: &mut [f32],
    progress: &dyn Progress,
) -> Result<PassStats, Error> {
    let nl = lights.len();
    let t0 = Instant::now();
    let offset = SHADOW_OFFSET * scene.diagonal();
    let mut c = HardShadowCounters::default();
    // Where each segment's answer goes in `vis`.
    let mut slots = Vec::new();
    let mut queries = Vec::new();
    for (j, s) in pixels.samples.iter().enumerate() {
        let Some(hit) = s.hit else { continue };
        let n = hit.facing_normal();
        for (li, pos) in lights.iter().enumerate() {
            let Some(pos) = pos else { continue };
            c.segments += 1;
            if n.dot(*pos - hit.point) <= 0.0 {
                c.back_facing += 1;
                vis[j * nl + li] = 0.0;
                continue;
            }
            slots.push(j * nl + li);
            queries.push(SegmentQuery {
                from: hit.shadow_origin(offset),
                to: *pos,
            });
        }
    }
    progress.begin(Pass::HardShadows.name(), queries.len() as u64);
    for (qs, ss) in queries.chunks(BATCH).zip(slots.chunks(BATCH)) {
        let answers = q.segments(qs)?;
        c.search.add(&answers.search);
        for (&k, v) in ss.iter().zip(answers.values) {
            vis[k] = match v {
                Visibility::Lit => {
                    c.lit += 1;
                    1.0
                }
                Visibility::Occluded => {
                    c.occluded += 1;
                    0.0
                }
                Visibility::Undecided => {
                    c.undecided += 1;
                    0.0
                }
            };
        }
        progress.advance(qs.len() as u64);
    }
    progress.end();
    Ok(PassStats::of(Pass::HardShadows, t0.elapsed(), &c))
}

/// Segments per batch.
const BATCH: usize = 1 << 16;
