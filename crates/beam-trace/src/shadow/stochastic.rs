//! Stochastic soft shadows (distributed ray tracing): `N` shadow segments from the point to
//! jittered-stratified points of the light; the visible fraction is the share of segments
//! proven free. The baseline the interval methods are measured against.
//!
//! Samples are deterministic: the jitter comes from a hash of the query's seed (the renderer
//! derives it from the pixel, the primary sample and the light), so images do not depend
//! on the thread count. Each segment is a reliable root search, so a thin occluder is never
//! passed through by a segment that crosses it; occluders *between* the segments are
//! missed, which is what the beam methods are for.
//!
//! With the last-occluder cache (the Minkowski paper's shadow buffer), a segment is first
//! tested against the top-level object that blocked the previous one; only a proven root
//! of that object decides, so the cache changes the cost, never the answer.

use super::hard::Visibility;
use super::method::{LightVisibility, Occluders, ShadowMethod, ShadowQuery, ShadowWork};
use super::spec::ShadowSpec;

/// Stochastic sampling of the light with `samples` shadow segments.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Stochastic {
    /// Segments per query.
    pub samples: u32,
    /// Whether the last-occluder cache is used.
    pub cache: bool,
}

impl ShadowMethod for Stochastic {
    fn name(&self) -> String {
        ShadowSpec::Stochastic {
            samples: self.samples,
            cache: self.cache,
        }
        .to_string()
    }

    fn visibility(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        work: &mut ShadowWork,
    ) -> LightVisibility {
        work.queries += 1;
        estimate(occluders, q, 0.0, self.samples, self.cache, work)
    }
}

/// The stochastic estimate of `q` with `samples` segments searched from `start` on (also
/// the Minkowski method's fine step, after a beam cleared every segment up to `start`).
pub fn estimate(
    occluders: &mut dyn Occluders,
    q: &ShadowQuery,
    start: f64,
    samples: u32,
    cache: bool,
    work: &mut ShadowWork,
) -> LightVisibility {
    let mut free = 0u32;
    let mut last: Option<u32> = None;
    for (u, v) in strata(samples, q.seed) {
        let to = q.light.point(u, v);
        work.rays += 1;
        if let Some(object) = last
            && occluders.segment_meets_object(object, q.origin, to, &mut work.root)
        {
            work.cache_hits += 1;
            continue;
        }
        let o = occluders.segment(q.origin, to, start, &mut work.root);
        if o.visibility == Visibility::Lit {
            free += 1;
        } else if cache {
            // Which object blocked it: only looked up when the cache will use it.
            last =
                o.at.map(|t| occluders.object_at(q.origin + t * (to - q.origin)));
        }
    }
    LightVisibility::estimate(free as f32 / samples as f32)
}

/// `n` jittered-stratified points of the unit square: rows of equal-area cells (`⌊√n⌋` rows
/// of `n / rows` or one more cells, row heights proportional to their cell counts), one
/// point placed by the hash of `seed` in each cell.
pub fn strata(n: u32, seed: u64) -> impl Iterator<Item = (f64, f64)> {
    let rows = (f64::from(n).sqrt().floor() as u32).max(1);
    let (base, extra) = (n / rows, n % rows);
    let nf = f64::from(n);
    let mut k = 0u64;
    let mut v0 = 0.0;
    (0..rows).flat_map(move |r| {
        let cols = base + u32::from(r < extra);
        let height = f64::from(cols) / nf;
        let row_start = v0;
        v0 += height;
        let first = k;
        k += u64::from(cols);
        (0..cols).map(move |c| {
            let h = mix(seed ^ (first + u64::from(c)).wrapping_mul(0x9E37_79B9_7F4A_7C15));
            let (ju, jv) = (unit(h), unit(mix(h)));
            (
                (f64::from(c) + ju) / f64::from(cols),
                row_start + jv * height,
            )
        })
    })
}

/// The seed of the samples of primary sample `sample` of pixel `pixel` for light `light`.
pub fn seed(pixel: u64, sample: u32, light: u32) -> u64 {
    mix(mix(pixel ^ 0xA076_1D64_78BD_642F) ^ (u64::from(sample) << 32 | u64::from(light)))
}

/// The splitmix64 finaliser: a well-mixed 64-bit hash.
pub(crate) fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A number in `[0, 1)` from the top 53 bits.
pub(crate) fn unit(h: u64) -> f64 {
    (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strata_cover_equal_areas_once() {
        for n in [1u32, 2, 5, 7, 16, 32, 49, 100] {
            let pts: Vec<(f64, f64)> = strata(n, 42).collect();
            assert_eq!(pts.len(), n as usize);
            assert!(
                pts.iter()
                    .all(|&(u, v)| (0.0..1.0).contains(&u) && (0.0..1.0).contains(&v))
            );
            // Fraction of points in the lower half close to a half: stratified, not clumped.
            let low = pts.iter().filter(|p| p.1 < 0.5).count() as f64 / f64::from(n);
            assert!(
                (low - 0.5).abs() <= 1.0 / f64::from(n).sqrt() + 1e-9,
                "n={n}: {low}"
            );
        }
    }

    #[test]
    fn samples_are_deterministic_and_seeded() {
        let a: Vec<_> = strata(16, seed(7, 0, 1)).collect();
        let b: Vec<_> = strata(16, seed(7, 0, 1)).collect();
        let c: Vec<_> = strata(16, seed(8, 0, 1)).collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
    }
}
