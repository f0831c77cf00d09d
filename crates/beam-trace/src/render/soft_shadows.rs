//! The soft-shadow pass: the visible fraction of each area light from each shaded sample,
//! by the plan's shadow method, with per-light counters and the proven shadow class of
//! every pixel.

use std::time::Instant;

use super::buffers;
use super::pixels::Pixels;
use crate::backend::Queries;
use crate::error::Error;
use interval_core::Interval;

use crate::ibox::ipoint;
use crate::plan::{Pass, Plan};
use crate::progress::Progress;
use crate::sample::SHADOW_OFFSET;
use crate::scene::Scene;
use crate::shadow::exact::ExactTimes;
use crate::shadow::{LightVisibility, ShadowClass, ShadowQuery, stochastic};
use crate::stats::PassStats;
use crate::stats::counters::SoftShadowCounters;
use crate::window::Window;

/// What the soft-shadow pass produces.
pub(super) struct SoftShadows {
    /// The pass's summed statistics.
    pub(super) pass: PassStats,
    /// Per area light: its statistics.
    pub(super) lights: Vec<PassStats>,
    /// Per pixel, the proven class over every area light (`None`: no shaded sample).
    pub(super) classes: Vec<Option<ShadowClass>>,
    /// Per area light, per pixel: the visible fraction averaged over the pixel's shaded
    /// samples (NaN where there is none).
    pub(super) fractions: Vec<Vec<f32>>,
    /// Per area light, per pixel: the proven lower bound of that mean (NaN likewise).
    pub(super) lower: Vec<Vec<f32>>,
    /// Per area light, per pixel: the proven upper bound of that mean (NaN likewise).
    pub(super) upper: Vec<Vec<f32>>,
}

/// For each area light in turn (so that each has its own time), the visible fraction from
/// every hit sample, written to `vis` at the light's index (sample-major, light-minor per
/// pixel). A sample whose tangent plane has the whole light behind it gets no direct light
/// (class [`ShadowClass::BackFacing`], no query); the others ask the method from the point
/// moved off the surface.
pub(super) fn soft_shadows(
    q: &dyn Queries,
    scene: &Scene,
    plan: &Plan,
    window: &Window,
    pixels: &Pixels,
    vis: &mut [f32],
    progress: &dyn Progress,
) -> Result<SoftShadows, Error> {
    let t0 = Instant::now();
    let nl = scene.lights.len();
    let offset = SHADOW_OFFSET * scene.diagonal();
    let name = plan.shadow_method.to_string();
    let npix = pixels.len();
    let mut classes: Vec<Option<ShadowClass>> = buffers::filled(npix, None);
    let mut per_light = Vec::new();
    let mut maps: Vec<LightMaps> = Vec::new();
    let mut total = SoftShadowCounters::default();
    for (li, light) in scene.lights.iter().enumerate() {
        let Some(light) = light.as_area() else {
            continue;
        };
        let tl = Instant::now();
        let mut c = SoftShadowCounters::default();
        // The queries of the samples facing the light, and where their answers go.
        let mut slots = Vec::new();
        let mut pixel_of = Vec::new();
        let mut queries = Vec::new();
        for p in 0..npix {
            for (si, s) in pixels.pixel(p).iter().enumerate() {
                let Some(hit) = s.hit else { continue };
                if light.patch.is_behind(hit.point, hit.facing_normal()) {
                    continue;
                }
                slots.push(pixels.range(p).start + si);
                pixel_of.push(p);
                queries.push(ShadowQuery {
                    origin: hit.shadow_origin(offset),
                    normal: hit.facing_normal(),
                    light: light.patch,
                    seed: stochastic::seed(window.global(p) as u64, si as u32, li as u32),
                });
            }
        }
        progress.begin(&format!("soft-shadows light {li}"), queries.len() as u64);
        // Asked tile by tile, answered in the samples' order.
        let order = tile_order(&pixel_of, window);
        let queries: Vec<ShadowQuery> = order.iter().map(|&k| queries[k]).collect();
        let mut answers: Vec<LightVisibility> = Vec::with_capacity(queries.len());
        let mut exact_times = ExactTimes::default();
        for chunk in queries.chunks(BATCH) {
            let a = q.soft_shadows(&plan.shadow_method, chunk)?;
            c.queries += a.work.queries;
            c.initial_beams += a.work.initial_beams;
            c.initial_beams_occluded += a.work.initial_occluded;
            c.umbra_proofs += a.work.umbra_proofs;
            c.sub_beams += a.work.sub_beams;
            c.rays += a.work.rays;
            c.cache_hits += a.work.cache_hits;
            c.shaft_triangles += a.work.shaft_triangles;
            c.shaft_faces += a.work.shaft_faces;
            c.bsp_nodes += a.work.bsp.inner_nodes;
            c.bsp_peak_nodes = c.bsp_peak_nodes.max(a.work.bsp.peak_nodes);
            c.bsp_fragments += a.work.bsp.fragments;
            exact_times.add(&a.work.exact_times);
            c.search.add(&a.work.root);
            answers.extend(a.visibility);
            progress.advance(chunk.len() as u64);
        }
        progress.end();
        let answers = in_sample_order(&order, answers);
        // Per pixel: the fraction and its bounds averaged over its shaded samples, and
        // its class.
        let mut answer = slots.iter().zip(&answers).peekable();
        let mut light_maps = LightMaps::with_capacity(npix);
        for (p, pixel_class) in classes.iter_mut().enumerate() {
            let mut class: Option<ShadowClass> = None;
            let mut shadowed = false;
            let mut mean = PixelMean::default();
            for j in pixels.range(p) {
                let s = &pixels.samples[j];
                if s.hit.is_none() {
                    continue;
                }
                let (lv, sample_class) = match answer.peek() {
                    Some(&(&slot, lv)) if slot == j => {
                        answer.next();
                        (*lv, lv.class())
                    }
                    _ => {
                        // No direct light from it: the fraction the shading uses is 0.
                        c.back_facing += 1;
                        (LightVisibility::UMBRA, ShadowClass::BackFacing)
                    }
                };
                vis[j * nl + li] = lv.fraction;
                mean.add(s.weight, &lv);
                shadowed |= lv.fraction < 1.0;
                class = Some(ShadowClass::merge(class, sample_class));
            }
            c.pixels_in_shadow += u64::from(shadowed);
            match class {
                Some(ShadowClass::Lit) => c.lit_pixels += 1,
                Some(ShadowClass::Umbra) => c.umbra_pixels += 1,
                Some(ShadowClass::Penumbra) => c.penumbra_pixels += 1,
                Some(ShadowClass::BackFacing) | None => {}
            }
            if let Some(cl) = class {
                *pixel_class = Some(ShadowClass::merge(*pixel_class, cl));
            }
            light_maps.push(mean.value());
        }
        total.add(&c);
        maps.push(light_maps);
        per_light.push(
            PassStats::new(
                &format!("light {li} ({name})"),
                tl.elapsed(),
                &crate::stats::Counters::list(&c),
            )
            .with_phases(&exact_times.phases()),
        );
    }
    let (mut fractions, mut lower, mut upper) = (Vec::new(), Vec::new(), Vec::new());
    for m in maps {
        fractions.push(m.fraction);
        lower.push(m.lower);
        upper.push(m.upper);
    }
    Ok(SoftShadows {
        pass: PassStats::of(Pass::SoftShadows, t0.elapsed(), &total),
        lights: per_light,
        classes,
        fractions,
        lower,
        upper,
    })
}

/// One light's per-pixel maps: the fraction and its proven bounds (NaN where no sample is
/// shaded).
struct LightMaps {
    fraction: Vec<f32>,
    lower: Vec<f32>,
    upper: Vec<f32>,
}

impl LightMaps {
    fn with_capacity(n: usize) -> Self {
        Self {
            fraction: Vec::with_capacity(n),
            lower: Vec::with_capacity(n),
            upper: Vec::with_capacity(n),
        }
    }

    fn push(&mut self, lv: Option<LightVisibility>) {
        let lv = lv.unwrap_or(LightVisibility {
            fraction: f32::NAN,
            lower: f32::NAN,
            upper: f32::NAN,
        });
        self.fraction.push(lv.fraction);
        self.lower.push(lv.lower);
        self.upper.push(lv.upper);
    }
}

/// The weighted mean of a pixel's samples' visibility: the estimate in `f32` as the shading
/// weighs it, the bounds in outward-rounded interval arithmetic, so that the pixel's true
/// mean fraction lies in the mean bound.
struct PixelMean {
    sum: f32,
    weight: f32,
    lower: Interval<f64>,
    upper: Interval<f64>,
    weights: Interval<f64>,
}

impl Default for PixelMean {
    fn default() -> Self {
        Self {
            sum: 0.0,
            weight: 0.0,
            lower: ipoint(0.0),
            upper: ipoint(0.0),
            weights: ipoint(0.0),
        }
    }
}

impl PixelMean {
    fn add(&mut self, weight: f32, lv: &LightVisibility) {
        let w = ipoint(f64::from(weight));
        self.sum += weight * lv.fraction;
        self.weight += weight;
        self.lower = self.lower + w * ipoint(f64::from(lv.lower));
        self.upper = self.upper + w * ipoint(f64::from(lv.upper));
        self.weights = self.weights + w;
    }

    /// The mean, `None` without a weighed sample.
    fn value(&self) -> Option<LightVisibility> {
        if self.weight <= 0.0 {
            return None;
        }
        let lower = (self.lower / self.weights)
            .cast::<f32>()
            .inf()
            .clamp(0.0, 1.0);
        let upper = (self.upper / self.weights)
            .cast::<f32>()
            .sup()
            .clamp(0.0, 1.0);
        Some(LightVisibility {
            fraction: self.sum / self.weight,
            lower,
            upper,
        })
    }
}

/// Queries per batch.
const BATCH: usize = 1 << 14;

/// The side, in pixels, of the square tiles of the image whose samples' queries go to the
/// backend one tile after another: a run of neighbouring queries, which a method may answer
/// together (the exact method's groups share one tree), then holds points close on the
/// screen both ways, not a strip of one row. A tile's pixels are
/// [`ShadowSpec::MAX_EXACT_GROUP`](crate::shadow::ShadowSpec::MAX_EXACT_GROUP).
const QUERY_TILE: u32 = 8;

/// The order in which to ask the queries of samples of the window's pixels `pixel_of`
/// (ascending): by the image's tiles of [`QUERY_TILE`] pixels, row by row, and in
/// the samples' order inside a tile (the tiles are the whole image's).
fn tile_order(pixel_of: &[usize], window: &Window) -> Vec<usize> {
    let mut order: Vec<usize> = (0..pixel_of.len()).collect();
    order.sort_by_key(|&k| {
        let (x, y) = window.pixel(pixel_of[k]);
        (y / QUERY_TILE, x / QUERY_TILE)
    });
    order
}

/// The answers `answers` to the queries asked in the order `order` ([`tile_order`]), put
/// back in the samples' order.
fn in_sample_order(order: &[usize], answers: Vec<LightVisibility>) -> Vec<LightVisibility> {
    let mut out = vec![LightVisibility::LIT; answers.len()];
    for (&k, a) in order.iter().zip(answers) {
        out[k] = a;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{QUERY_TILE, in_sample_order, tile_order};
    use crate::shadow::LightVisibility;
    use crate::window::Window;

    /// Every query is asked once, tile after tile of the image, and every answer goes back
    /// to its query.
    #[test]
    fn queries_go_tile_by_tile_and_answers_come_back_in_order() {
        let window = Window::full(20, 11);
        // Pixel 3 has no query, pixel 4 two (two samples).
        let mut pixel_of: Vec<usize> = (0..220).filter(|&p| p != 3).collect();
        pixel_of.insert(3, 4);
        let order = tile_order(&pixel_of, &window);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..pixel_of.len()).collect::<Vec<_>>());
        let tile = |k: usize| {
            let (x, y) = window.pixel(pixel_of[k]);
            (y / QUERY_TILE, x / QUERY_TILE)
        };
        assert!(order.windows(2).all(|w| tile(w[0]) <= tile(w[1])));
        // The first tile holds the 8 × 8 pixels at the image's corner, 64 queries less the
        // pixel without one plus the second sample: its first row then the next.
        assert_eq!(order.iter().take_while(|&&k| tile(k) == (0, 0)).count(), 64);
        assert_eq!(pixel_of[order[7]], 7);
        assert_eq!(pixel_of[order[8]], 20);
        let answers: Vec<LightVisibility> = order
            .iter()
            .map(|&k| LightVisibility {
                fraction: k as f32,
                lower: 0.0,
                upper: 1.0,
            })
            .collect();
        let back = in_sample_order(&order, answers);
        assert!(back.iter().enumerate().all(|(k, a)| a.fraction == k as f32));
    }
}
