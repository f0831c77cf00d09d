//! What the primary-rays pass keeps of each pixel's rays: their samples, for the passes
//! after it (normals, shadows, shading), or, where none of those runs (an unlit scene),
//! the pixel's colour and coverage at once.
//!
//! An unlit pixel's colour is its rays' material colours weighed (the flat colour of the
//! first root's object, the background where a ray meets nothing), and its coverage what
//! its beams proved: neither needs a ray's surface point, its distance to the eye or its
//! normal. Resolving the pixel in the pass that found its rays' roots makes no sample
//! record (a hundred bytes a ray, most of the pass's memory), no camera ray for a root
//! known without a search, and no pass over the samples afterwards. A pixel whose one ray's
//! first root its box proved, and whose shading leaf the pass knows without a hit record
//! (a Hit box's pixel, hits not narrowed, a scene of one leaf), is *known*: the flat sink
//! takes it by that leaf, with no record of its ray at all ([`PixelSink::RESOLVES_KNOWN`]).

use rayon::prelude::*;

use super::buffers;
use super::pixels::Pixels;
use crate::sample::{Area, Coverage, Hit, Sample};
use crate::scene::Scene;

/// A batch of pixels of the primary-rays pass and their rays: pixel `k` of the batch owns
/// rays `first[k]..first[k + 1]`, and ray `j` belongs to pixel `owner[j]`.
#[derive(Copy, Clone)]
pub(super) struct RayBatch<'a> {
    /// Where each pixel's rays start, followed by the number of rays.
    pub(super) first: &'a [usize],
    /// Each ray's pixel in the batch.
    pub(super) owner: &'a [u32],
}

impl RayBatch<'_> {
    /// The weight of each ray of pixel `k` in it: its rays weigh the same.
    fn weight(&self, k: usize) -> f32 {
        weight(self.first[k + 1] - self.first[k])
    }
}

/// The weight of each of a pixel's `rays` rays: they weigh the same.
fn weight(rays: usize) -> f32 {
    1.0 / rays as f32
}

/// What a primary pass hands on of each batch of pixels: for each pixel the area its
/// beams proved covered (`area(k)`, the same for each of its rays), and for each ray the
/// leaf whose material shades its first root (`leaf(j)`) or its whole hit record
/// (`hit(j)`), `None` where it meets no surface. A sink asks for what it keeps only.
pub(super) trait PixelSink {
    /// Whether the sink takes a *known* pixel (one ray, whose first root its box proved,
    /// shaded by a leaf the pass knows without a hit record) by that leaf alone,
    /// `known(k)`, with no ray of it in the batch. Where it does not, every ray of every
    /// pixel is in the batch and `known(k)` is `None`.
    const RESOLVES_KNOWN: bool;

    /// Appends the pixels of `batch`, in order.
    fn extend<A, K, L, H>(&mut self, batch: RayBatch<'_>, pixel: (A, K), leaf: L, hit: H)
    where
        A: Fn(usize) -> Area + Sync,
        K: Fn(usize) -> Option<u32> + Sync,
        L: Fn(usize) -> Option<u32> + Sync,
        H: Fn(usize) -> Option<Hit> + Sync;
}

/// The samples of every pixel, for the passes that shade them.
impl PixelSink for Pixels {
    // Every ray is a sample.
    const RESOLVES_KNOWN: bool = false;

    fn extend<A, K, L, H>(&mut self, batch: RayBatch<'_>, (area, _): (A, K), _leaf: L, hit: H)
    where
        A: Fn(usize) -> Area + Sync,
        K: Fn(usize) -> Option<u32> + Sync,
        L: Fn(usize) -> Option<u32> + Sync,
        H: Fn(usize) -> Option<Hit> + Sync,
    {
        let samples = batch.owner.par_iter().enumerate().map(|(j, &k)| Sample {
            weight: batch.weight(k as usize),
            hit: hit(j),
            area: area(k as usize),
        });
        self.par_extend(samples, batch.first);
    }
}

/// Each pixel's flat colour and coverage, resolved from its rays' leaves (an unlit scene).
pub(super) struct Flat<'a> {
    scene: &'a Scene,
    /// Each pixel's colour.
    pub(super) colors: Vec<[f32; 3]>,
    /// Each pixel's proven coverage.
    pub(super) coverage: Vec<Coverage>,
}

impl<'a> Flat<'a> {
    /// No pixel yet, with room for `pixels` of `scene`.
    pub(super) fn with_capacity(scene: &'a Scene, pixels: usize) -> Self {
        Flat {
            scene,
            colors: buffers::with_room(pixels),
            coverage: buffers::with_room(pixels),
        }
    }
}

impl PixelSink for Flat<'_> {
    const RESOLVES_KNOWN: bool = true;

    fn extend<A, K, L, H>(&mut self, batch: RayBatch<'_>, (area, known): (A, K), leaf: L, _hit: H)
    where
        A: Fn(usize) -> Area + Sync,
        K: Fn(usize) -> Option<u32> + Sync,
        L: Fn(usize) -> Option<u32> + Sync,
        H: Fn(usize) -> Option<Hit> + Sync,
    {
        let (scene, background) = (self.scene, self.scene.background);
        let pixels = (0..batch.first.len() - 1).into_par_iter().map(|k| {
            if let Some(l) = known(k) {
                // Its one ray, shaded by `l`, as below.
                let color = scene.material_of(l).color;
                return (
                    weighed(std::iter::once((weight(1), color)), background),
                    Coverage::of_shares(std::iter::once((weight(1), area(k)))),
                );
            }
            // The pixel's rays share its weight and its area.
            let rays = batch.first[k]..batch.first[k + 1];
            let (weight, area) = (batch.weight(k), area(k));
            let colors = rays.clone().map(|j| {
                let color = leaf(j).map_or(background, |l| scene.material_of(l).color);
                (weight, color)
            });
            (
                weighed(colors, background),
                Coverage::of_shares(std::iter::repeat_n((weight, area), rays.len())),
            )
        });
        let mut both = (
            std::mem::take(&mut self.colors),
            std::mem::take(&mut self.coverage),
        );
        both.par_extend(pixels);
        (self.colors, self.coverage) = both;
    }
}

/// The mean of a pixel's colours, each given with its weight (`background` where none
/// weighs anything, as for a pixel without samples).
pub(super) fn weighed(
    colors: impl Iterator<Item = (f32, [f32; 3])>,
    background: [f32; 3],
) -> [f32; 3] {
    let mut acc = [0f32; 3];
    let mut wsum = 0f32;
    for (weight, c) in colors {
        for k in 0..3 {
            acc[k] += weight * c[k];
        }
        wsum += weight;
    }
    if wsum > 0.0 {
        acc.map(|a| a / wsum)
    } else {
        background
    }
}
