//! What the pipeline finds in one window of the image (a [`Piece`]), and the whole render
//! put together from pieces that cover the image.

use std::time::Instant;

use super::box_map::BoxMap;
use super::buffers;
use super::images::shadow_class_image;
use super::output::{RenderOutput, ShadowMaps};
use super::pixel_box::PixelBox;
use crate::error::Error;
use crate::image::Image;
use crate::plan::{Pass, Plan};
use crate::sample::Coverage;
use crate::shadow::ShadowClass;
use crate::stats::{PassStats, RenderStats};
use crate::window::Window;

/// The names of the soft-shadow counters that are not sums over the pixels: computed from
/// the assembled bounds ([`BoundWidths`]).
const WIDTH_COUNTERS: [&str; 3] = [
    "certified_pixels",
    "bound_width_mean_ppm",
    "bound_width_max_ppm",
];

/// What every pass found for the pixels of one window, numbered row-major inside it.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// The window.
    pub window: Window,
    /// Each pixel's colour.
    pub colors: Vec<[f32; 3]>,
    /// Each pixel's screen box class and whether it lies on its box's top or left edge
    /// (`None` where no screen box classified it).
    pub classes: BoxMap,
    /// Each pixel's proven coverage bounds.
    pub coverage: Vec<Coverage>,
    /// Each pixel's cost of primary visibility (the backend's unit: time on the CPU).
    pub cost: Vec<f32>,
    /// The soft-shadow pass's per-pixel maps, when it ran.
    pub shadows: Option<PieceShadows>,
    /// Every pass's time and counters after the set-up, in the order they ran; the
    /// soft-shadow bound widths (`certified_pixels`, `bound_width_mean_ppm`,
    /// `bound_width_max_ppm`) are left to the assembly, which computes them over the image.
    pub passes: Vec<PassStats>,
    /// Per area light, the soft-shadow counters.
    pub lights: Vec<PassStats>,
}

/// The soft-shadow maps of a piece's pixels (see [`ShadowMaps`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PieceShadows {
    /// The class over every area light.
    pub classes: Vec<Option<ShadowClass>>,
    /// Per area light, the mean visible fraction.
    pub fractions: Vec<Vec<f32>>,
    /// Per area light, its proven lower bound.
    pub lower: Vec<Vec<f32>>,
    /// Per area light, its proven upper bound.
    pub upper: Vec<Vec<f32>>,
}

impl Piece {
    /// Checks that every per-pixel vector holds one value per pixel of the window.
    fn check(&self, lights: usize) -> Result<(), Error> {
        let n = self.window.len();
        let mut sizes = vec![
            self.colors.len(),
            self.classes.len(),
            self.coverage.len(),
            self.cost.len(),
        ];
        if let Some(s) = &self.shadows {
            sizes.push(s.classes.len());
            if [&s.fractions, &s.lower, &s.upper]
                .iter()
                .any(|m| m.len() != lights)
            {
                return Err(self.malformed(&format!("shadow maps of {lights} area lights")));
            }
            for m in [&s.fractions, &s.lower, &s.upper] {
                sizes.extend(m.iter().map(Vec::len));
            }
        }
        if sizes.iter().any(|&s| s != n) {
            return Err(self.malformed(&format!("{n} values per map")));
        }
        Ok(())
    }

    fn malformed(&self, expected: &str) -> Error {
        let r = self.window.rect();
        Error::Data(format!(
            "piece [{}, {}) x [{}, {}): expected {expected}",
            r.x0, r.x1, r.y0, r.y1
        ))
    }
}

/// The render of a `width × height` image from `pieces` covering it, each pixel once, with
/// the set-up's passes `setup` first (see [`Pipeline::assemble`](super::Pipeline)).
pub(super) fn assemble(
    (width, height): (u32, u32),
    plan: &Plan,
    (setup, pieces): (&[PassStats], Vec<Piece>),
    started: Instant,
) -> Result<RenderOutput, Error> {
    let tolerance = plan.shadow_method.method().tolerance();
    let soft = plan.runs(Pass::SoftShadows);
    let (maps, mut passes, mut lights) = gather((width, height), plan, pieces)?;
    let (lower, upper) = (maps.lower, maps.upper);
    let shadows = soft.then(|| {
        // The bound widths, pixel by pixel in image order, per light and over all.
        let mut all = BoundWidths::default();
        for (li, stats) in lights.iter_mut().enumerate() {
            let widths = BoundWidths::of(&lower[li], &upper[li], tolerance);
            widths.write(stats);
            all.merge(&widths);
        }
        if let Some(stats) = passes
            .iter_mut()
            .find(|p| p.name == Pass::SoftShadows.name())
        {
            all.write(stats);
        }
        ShadowMaps {
            image: shadow_class_image(width, height, &maps.shadow_classes),
            classes: maps.shadow_classes,
            fractions: maps.fractions,
            lower,
            upper,
            width,
            height,
        }
    });
    let mut all_passes = setup.to_vec();
    all_passes.extend(passes);
    Ok(RenderOutput {
        boxes: maps.classes,
        coverage: maps.coverage,
        cost: maps.cost,
        shadows,
        image: Image {
            width,
            height,
            pixels: maps.colors,
        },
        stats: RenderStats {
            passes: all_passes,
            lights,
            total: started.elapsed(),
        },
        plan: plan.clone(),
    })
}

/// Every pixel's values of the image, in image order.
struct ImageMaps {
    colors: Vec<[f32; 3]>,
    classes: BoxMap,
    coverage: Vec<Coverage>,
    cost: Vec<f32>,
    shadow_classes: Vec<Option<ShadowClass>>,
    fractions: Vec<Vec<f32>>,
    lower: Vec<Vec<f32>>,
    upper: Vec<Vec<f32>>,
}

/// Whether `piece` belongs to a `width × height` image rendered with soft shadows where
/// `soft` (of `lights` area lights), with one value per pixel of its window in every map.
fn check_piece(
    piece: &Piece,
    (width, height): (u32, u32),
    soft: bool,
    lights: usize,
) -> Result<(), Error> {
    if piece.window.image_size() != (width, height) {
        return Err(piece.malformed(&format!("a window of a {width} x {height} image")));
    }
    if piece.shadows.is_some() != soft {
        return Err(piece.malformed("the plan's soft-shadow maps"));
    }
    piece.check(lights)
}

/// The maps of the `width × height` image from `pieces` covering it, each pixel once, and
/// their passes' and lights' statistics summed. A single piece over the whole image hands
/// its maps on as they are.
fn gather(
    (width, height): (u32, u32),
    plan: &Plan,
    pieces: Vec<Piece>,
) -> Result<(ImageMaps, Vec<PassStats>, Vec<PassStats>), Error> {
    let npix = width as usize * height as usize;
    let soft = plan.runs(Pass::SoftShadows);
    let nl = plan.soft_shadow_lights;
    let mut pieces = pieces;
    if pieces.len() == 1
        && pieces[0].window.rect() == Window::full(width, height).rect()
        && let Some(piece) = pieces.pop()
    {
        check_piece(&piece, (width, height), soft, nl)?;
        let shadows = piece.shadows.unwrap_or_else(|| PieceShadows {
            classes: buffers::filled(npix, None),
            fractions: Vec::new(),
            lower: Vec::new(),
            upper: Vec::new(),
        });
        return Ok((
            ImageMaps {
                colors: piece.colors,
                classes: piece.classes,
                coverage: piece.coverage,
                cost: piece.cost,
                shadow_classes: shadows.classes,
                fractions: shadows.fractions,
                lower: shadows.lower,
                upper: shadows.upper,
            },
            piece.passes,
            piece.lights,
        ));
    }
    let mut seen = vec![false; npix];
    let mut colors = vec![[0f32; 3]; npix];
    let mut classes = BoxMap::filled(npix, PixelBox::NONE);
    let no_coverage = Coverage {
        proven: 0.0,
        possible: 0.0,
    };
    let mut coverage = vec![no_coverage; npix];
    let mut cost = vec![0f32; npix];
    let mut shadow_classes: Vec<Option<ShadowClass>> = vec![None; npix];
    let maps = || vec![vec![f32::NAN; npix]; if soft { nl } else { 0 }];
    let (mut fractions, mut lower, mut upper) = (maps(), maps(), maps());
    let mut passes: Vec<PassStats> = Vec::new();
    let mut lights: Vec<PassStats> = Vec::new();
    for piece in pieces {
        check_piece(&piece, (width, height), soft, nl)?;
        let base = classes
            .add_all(&piece.classes)
            .ok_or_else(|| piece.malformed("pieces of at most 2^31 screen boxes in all"))?;
        for k in 0..piece.window.len() {
            let g = piece.window.global(k);
            if std::mem::replace(&mut seen[g], true) {
                let (x, y) = piece.window.pixel(k);
                return Err(Error::Data(format!(
                    "pixel ({x}, {y}) is in two pieces of the render"
                )));
            }
            colors[g] = piece.colors[k];
            classes.copy_pixel(g, &piece.classes, k, base);
            coverage[g] = piece.coverage[k];
            cost[g] = piece.cost[k];
            if let Some(s) = &piece.shadows {
                shadow_classes[g] = s.classes[k];
                for li in 0..nl {
                    fractions[li][g] = s.fractions[li][k];
                    lower[li][g] = s.lower[li][k];
                    upper[li][g] = s.upper[li][k];
                }
            }
        }
        merge_stats(&mut passes, piece.passes)?;
        merge_stats(&mut lights, piece.lights)?;
    }
    if let Some(g) = seen.iter().position(|&s| !s) {
        let (x, y) = (g as u32 % width, g as u32 / width);
        return Err(Error::Data(format!(
            "pixel ({x}, {y}) is in no piece of the render"
        )));
    }
    Ok((
        ImageMaps {
            colors,
            classes,
            coverage,
            cost,
            shadow_classes,
            fractions,
            lower,
            upper,
        },
        passes,
        lights,
    ))
}

/// Adds the passes `more` into `into` (empty: taken as they are): the counters summed by
/// name (a counter only some pieces report is added at the end), the times summed.
fn merge_stats(into: &mut Vec<PassStats>, more: Vec<PassStats>) -> Result<(), Error> {
    if into.is_empty() {
        *into = more;
        return Ok(());
    }
    if into.len() != more.len() {
        return Err(Error::Data(format!(
            "pieces of the render with {} and {} passes",
            into.len(),
            more.len()
        )));
    }
    for (a, b) in into.iter_mut().zip(more) {
        if a.name != b.name {
            return Err(Error::Data(format!(
                "pieces of the render with passes {} and {} in one place",
                a.name, b.name
            )));
        }
        a.ran |= b.ran;
        a.time += b.time;
        for (name, t) in b.phases {
            match a.phases.iter_mut().find(|(n, _)| *n == name) {
                Some((_, sum)) => *sum += t,
                None => a.phases.push((name, t)),
            }
        }
        for (name, v) in b.counters {
            match a.counters.iter_mut().find(|(n, _)| *n == name) {
                Some((_, sum)) => *sum += v,
                None => a.counters.push((name, v)),
            }
        }
    }
    Ok(())
}

/// The widths of the pixels' proven bounds on a light's visible fraction.
#[derive(Default)]
struct BoundWidths {
    pixels: u64,
    certified: u64,
    sum: f64,
    max: f32,
}

impl BoundWidths {
    /// The widths `upper - lower` of the pixels that have bounds (not NaN), in order.
    fn of(lower: &[f32], upper: &[f32], tolerance: f32) -> Self {
        /// How far the outward rounding of a pixel's mean bound may widen it: a few ulps
        /// of 1.
        const MEAN_ROUNDING: f32 = 4.0 * f32::EPSILON;
        let mut w = Self::default();
        for (&lo, &hi) in lower.iter().zip(upper) {
            if lo.is_nan() {
                continue;
            }
            let width = hi - lo;
            w.pixels += 1;
            // A pixel's bound is the mean of its samples' rounded outward to `f32`: where
            // every sample's is within the tolerance, the mean's may exceed it by rounding.
            w.certified += u64::from(width <= tolerance + MEAN_ROUNDING);
            w.sum += f64::from(width);
            w.max = w.max.max(width);
        }
        w
    }

    fn merge(&mut self, o: &BoundWidths) {
        self.pixels += o.pixels;
        self.certified += o.certified;
        self.sum += o.sum;
        self.max = self.max.max(o.max);
    }

    /// Writes the figures into the counters of `stats` ([`WIDTH_COUNTERS`]).
    fn write(&self, stats: &mut PassStats) {
        let ppm = |x: f64| (x * 1e6).round() as u64;
        let values = [
            self.certified,
            ppm(self.sum / self.pixels.max(1) as f64),
            ppm(f64::from(self.max)),
        ];
        for (name, v) in WIDTH_COUNTERS.iter().zip(values) {
            if let Some((_, c)) = stats.counters.iter_mut().find(|(n, _)| n == name) {
                *c = v;
            }
        }
    }
}
