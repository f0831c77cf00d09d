//! The normals pass and the shading pass.

use std::time::Instant;

use rayon::prelude::*;

use super::buffers;
use super::pixels::Pixels;
use super::resolve::weighed;
use crate::backend::{Queries, ShadeBatch, ShadeLight, ShadeSample};
use crate::error::Error;
use crate::plan::Pass;
use crate::progress::Progress;
use crate::sample::{Coverage, Hit};
use crate::scene::Scene;
use crate::stats::PassStats;
use crate::stats::counters::{NormalCounters, ShadingCounters};

/// Unit normals of the hit samples of implicit surfaces from the gradient (a hit on a mesh
/// has its triangle's normal from its hit record).
pub(super) fn normals(
    q: &dyn Queries,
    scene: &Scene,
    pixels: &mut Pixels,
    progress: &dyn Progress,
) -> Result<PassStats, Error> {
    let t0 = Instant::now();
    let implicit = |h: &Hit| scene.mesh_of_leaf(h.leaf).is_none();
    let points: Vec<_> = pixels
        .samples
        .iter()
        .filter_map(|s| s.hit.filter(implicit).map(|h| h.point))
        .collect();
    progress.begin(Pass::Normals.name(), 1);
    let answers = q.normals(&points)?;
    progress.end();
    let mut c = NormalCounters {
        normals: points.len() as u64,
        search: answers.search,
        ..NormalCounters::default()
    };
    let hits = pixels
        .samples
        .iter_mut()
        .filter_map(|s| s.hit.as_mut())
        .filter(|h| implicit(h));
    for (hit, n) in hits.zip(answers.values) {
        match n {
            Some(n) => hit.normal = n,
            None => c.degenerate += 1,
        }
    }
    Ok(PassStats::of(Pass::Normals, t0.elapsed(), &c))
}

/// What the shading pass gives each pixel, and the pass's statistics.
pub(super) struct Shaded {
    /// The colour.
    pub(super) colors: Vec<[f32; 3]>,
    /// The proven bounds on the share of its area whose rays meet a surface.
    pub(super) coverage: Vec<Coverage>,
    /// The pass's statistics.
    pub(super) stats: PassStats,
}

/// Each pixel's colour and coverage: the colour is the weighted sum of its samples' Phong
/// colours under the lights' visible fractions `vis` (sample-major, light-minor; the flat
/// material colour when the scene has no lights, and the pass does not run: `lit` is
/// false); the coverage is [`Coverage::of`] its samples, found in the same pass over them.
pub(super) fn shading(
    q: &dyn Queries,
    scene: &Scene,
    lit: bool,
    pixels: &Pixels,
    vis: &[f32],
) -> Result<Shaded, Error> {
    let t0 = Instant::now();
    let nl = scene.lights.len();
    let samples = &pixels.samples;
    // Lit: the hit samples are shaded in one batch, each sample's colour found by its rank
    // among them. Unlit: a hit's colour is its material's, read where it is summed.
    let (rank, colors) = if lit {
        let mut hit_samples = Vec::new();
        let mut rank = Vec::with_capacity(samples.len());
        for (j, s) in samples.iter().enumerate() {
            rank.push(hit_samples.len());
            if s.hit.is_some() {
                hit_samples.push(j);
            }
        }
        let hit = |j: usize| samples[j].hit.expect("a hit sample");
        let lights: Vec<ShadeLight> = scene
            .lights
            .iter()
            .map(|l| ShadeLight {
                position: l.center(),
                color: l.color(),
            })
            .collect();
        let shade: Vec<ShadeSample> = hit_samples
            .par_iter()
            .map(|&j| {
                let h = hit(j);
                ShadeSample {
                    point: h.point,
                    normal: h.normal,
                    to_eye: h.to_eye,
                    material: scene.material_of(h.leaf),
                }
            })
            .collect();
        let mut fractions = vec![0f32; hit_samples.len() * nl];
        if nl > 0 {
            fractions
                .par_chunks_mut(nl)
                .zip(&hit_samples)
                .for_each(|(f, &j)| f.copy_from_slice(&vis[j * nl..(j + 1) * nl]));
        }
        let colors = q
            .shade(&ShadeBatch {
                lights: &lights,
                ambient: scene.ambient,
                samples: &shade,
                fractions: &fractions,
            })?
            .values;
        (rank, colors)
    } else {
        (Vec::new(), Vec::new())
    };
    let color = |j: usize, hit: &Hit| {
        if lit {
            colors[rank[j]]
        } else {
            scene.material_of(hit.leaf).color
        }
    };
    // Each pixel's colour, and its coverage from the same samples in the same pass over
    // them.
    let mut pixel_colors: Vec<[f32; 3]> = buffers::with_room(pixels.len());
    let mut coverage: Vec<Coverage> = buffers::with_room(pixels.len());
    (0..pixels.len())
        .into_par_iter()
        .map(|p| {
            let colors = pixels.range(p).map(|j| {
                let s = &samples[j];
                let c = match &s.hit {
                    Some(h) => color(j, h),
                    None => scene.background,
                };
                (s.weight, c)
            });
            (
                weighed(colors, scene.background),
                Coverage::of(pixels.pixel(p)),
            )
        })
        .unzip_into_vecs(&mut pixel_colors, &mut coverage);
    let stats = if lit {
        let c = ShadingCounters {
            shaded_samples: colors.len() as u64,
        };
        PassStats::of(Pass::Shading, t0.elapsed(), &c)
    } else {
        PassStats::skipped(Pass::Shading.name())
    };
    Ok(Shaded {
        colors: pixel_colors,
        coverage,
        stats,
    })
}
