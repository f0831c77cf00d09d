//! The normals pass and the shading pass.

use std::time::Instant;

use rayon::prelude::*;

use super::starts;
use crate::backend::{Queries, ShadeBatch, ShadeLight, ShadeSample};
use crate::error::Error;
use crate::plan::Pass;
use crate::progress::Progress;
use crate::sample::Sample;
use crate::scene::Scene;
use crate::stats::PassStats;
use crate::stats::counters::{NormalCounters, ShadingCounters};

/// Unit normals of the hit samples from the gradient.
pub(super) fn normals(
    q: &dyn Queries,
    samples: &mut [Vec<Sample>],
    progress: &dyn Progress,
) -> Result<PassStats, Error> {
    let t0 = Instant::now();
    let points: Vec<_> = samples
        .par_iter()
        .flat_map_iter(|px| px.iter().filter_map(|s| s.hit.map(|h| h.point)))
        .collect();
    progress.begin(Pass::Normals.name(), 1);
    let answers = q.normals(&points)?;
    progress.end();
    let mut c = NormalCounters {
        normals: points.len() as u64,
        search: answers.search,
        ..NormalCounters::default()
    };
    // Each pixel reads its answers in the order of its hits.
    let first = starts(
        samples
            .iter()
            .map(|px| px.iter().filter(|s| s.hit.is_some()).count()),
    );
    c.degenerate = samples
        .par_iter_mut()
        .zip(first)
        .map(|(px, mut k)| {
            let mut degenerate = 0;
            for hit in px.iter_mut().filter_map(|s| s.hit.as_mut()) {
                match answers.values[k] {
                    Some(n) => hit.normal = n,
                    None => degenerate += 1,
                }
                k += 1;
            }
            degenerate
        })
        .sum();
    Ok(PassStats::of(Pass::Normals, t0.elapsed(), &c))
}

/// Each pixel's colour: the weighted sum of its samples' Phong colours under the lights'
/// visible fractions `vis` (the flat material colour when the scene has no lights, and the
/// pass does not run: `lit` is false).
pub(super) fn shading(
    q: &dyn Queries,
    scene: &Scene,
    lit: bool,
    samples: &[Vec<Sample>],
    vis: &[Vec<f32>],
) -> Result<(Vec<[f32; 3]>, PassStats), Error> {
    let t0 = Instant::now();
    let leaves = scene.geometry.leaves();
    let nl = scene.lights.len();
    let hits = || samples.iter().flatten().filter_map(|s| s.hit);
    let colors: Vec<[f32; 3]> = if lit {
        let lights: Vec<ShadeLight> = scene
            .lights
            .iter()
            .map(|l| ShadeLight {
                position: l.center(),
                color: l.color(),
            })
            .collect();
        let count: usize = samples
            .par_iter()
            .map(|px| px.iter().filter(|s| s.hit.is_some()).count())
            .sum();
        let mut shade: Vec<ShadeSample> = Vec::with_capacity(count);
        let mut fractions: Vec<f32> = Vec::with_capacity(count * nl);
        for (px, v) in samples.iter().zip(vis) {
            for (si, s) in px.iter().enumerate() {
                let Some(h) = s.hit else { continue };
                shade.push(ShadeSample {
                    point: h.point,
                    normal: h.normal,
                    to_eye: h.to_eye,
                    material: leaves[h.leaf as usize].material,
                });
                fractions.extend_from_slice(&v[si * nl..(si + 1) * nl]);
            }
        }
        q.shade(&ShadeBatch {
            lights: &lights,
            ambient: scene.ambient,
            samples: &shade,
            fractions: &fractions,
        })?
        .values
    } else {
        hits()
            .map(|h| leaves[h.leaf as usize].material.color)
            .collect()
    };
    // Each pixel's first colour: its hit samples' colours are consecutive.
    let first = starts(
        samples
            .iter()
            .map(|px| px.iter().filter(|s| s.hit.is_some()).count()),
    );
    let pixels = samples
        .par_iter()
        .zip(first)
        .map(|(px, mut k)| {
            let mut acc = [0f32; 3];
            let mut wsum = 0f32;
            for s in px {
                let c = match s.hit {
                    None => scene.background,
                    Some(_) => {
                        k += 1;
                        colors[k - 1]
                    }
                };
                for j in 0..3 {
                    acc[j] += s.weight * c[j];
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
        let c = ShadingCounters {
            shaded_samples: hits().count() as u64,
        };
        PassStats::of(Pass::Shading, t0.elapsed(), &c)
    } else {
        PassStats::skipped(Pass::Shading.name())
    };
    Ok((pixels, stats))
}
