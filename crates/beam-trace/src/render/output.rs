//! What a render produces: the image, the per-pixel maps and the statistics.

use rayon::prelude::*;

use super::box_map::BoxMap;
use super::images::{classification_image, cost_image};
use crate::beam::BoxClass;
use crate::float_map::FloatMap;
use crate::image::Image;
use crate::plan::Plan;
use crate::sample::Coverage;
use crate::shadow::ShadowClass;
use crate::stats::RenderStats;

/// What a render produces.
#[derive(Clone, Debug)]
pub struct RenderOutput {
    /// The image.
    pub image: Image,
    /// Per-pass time and counters.
    pub stats: RenderStats,
    /// The cost of primary visibility per pixel, row-major, in the backend's unit of cost
    /// (time on the CPU); [`RenderOutput::cost_map`] draws it.
    pub cost: Vec<f32>,
    /// Each pixel's screen box class and whether it lies on its box's top or left edge
    /// (`None` where no screen box pass ran).
    pub(super) boxes: BoxMap,
    /// Each pixel's proven bounds on the share of its area whose rays meet a surface.
    pub coverage: Vec<Coverage>,
    /// Soft shadows per pixel; `None` without a soft-shadow pass.
    pub shadows: Option<ShadowMaps>,
    /// The plan that ran.
    pub plan: Plan,
}

impl RenderOutput {
    /// Each pixel's screen box class, row-major (`None` where no screen box pass ran).
    pub fn box_classes(&self) -> Vec<Option<BoxClass>> {
        self.boxes.par_iter().map(|b| b.class()).collect()
    }

    /// Proven-miss (blue), proven-hit (red) and undecided (yellow) screen boxes, with box
    /// outlines (thesis fig. 5.13); grey where no beam classified the pixel.
    pub fn classification(&self) -> Image {
        classification_image(self.image.width, self.image.height, &self.boxes)
    }

    /// The cost of primary visibility per pixel as a heat map (thesis fig. 5.8).
    pub fn cost_map(&self) -> Image {
        cost_image(self.image.width, self.image.height, &self.cost)
    }
}

/// What the soft-shadow pass found, per pixel (row-major).
#[derive(Clone, Debug)]
pub struct ShadowMaps {
    /// The class over every area light: `Lit` or `Umbra` when every shaded sample of the
    /// pixel is proven so for every area light, `BackFacing` when every one faces away from
    /// every area light, else `Penumbra`; `None` where no sample is shaded.
    pub classes: Vec<Option<ShadowClass>>,
    /// Per area light (in the scene's order of area lights), the visible fraction averaged
    /// over the pixel's shaded samples; NaN where none is shaded.
    pub fractions: Vec<Vec<f32>>,
    /// Per area light, the proven lower bound of each pixel's mean visible fraction (the
    /// fraction the shading uses: 0 for samples facing away from the light); NaN where no
    /// sample is shaded.
    pub lower: Vec<Vec<f32>>,
    /// Per area light, the proven upper bound, likewise.
    pub upper: Vec<Vec<f32>>,
    /// Width of the maps in pixels.
    pub width: u32,
    /// Height of the maps in pixels.
    pub height: u32,
    /// The classes as an image (the soft-shadow paper's Fig. 7): proven lit green, proven
    /// umbra blue, penumbra orange, facing away from every area light blue-grey, no shaded
    /// surface dark grey.
    pub image: Image,
}

impl ShadowMaps {
    /// Area light `light`'s fraction, lower and upper bound maps, `None` past the last area
    /// light.
    pub fn light_maps(&self, light: usize) -> Option<[FloatMap; 3]> {
        let map = |v: &Vec<Vec<f32>>| FloatMap {
            width: self.width,
            height: self.height,
            values: v[light].clone(),
        };
        (light < self.fractions.len())
            .then(|| [map(&self.fractions), map(&self.lower), map(&self.upper)])
    }

    /// Area light `light`'s bound widths as an image: black where the fraction is proven
    /// exactly, brighter with the width (`sqrt(width)`, white for the unknown `[0, 1]`),
    /// dark red where no sample is shaded; `None` past the last area light.
    pub fn bound_width_image(&self, light: usize) -> Option<Image> {
        let (lower, upper) = (self.lower.get(light)?, self.upper.get(light)?);
        let pixels = lower
            .iter()
            .zip(upper)
            .map(|(&lo, &hi)| {
                let w = hi - lo;
                if w.is_finite() {
                    [w.max(0.0).sqrt(); 3]
                } else {
                    [0.25, 0.0, 0.0]
                }
            })
            .collect();
        Some(Image {
            width: self.width,
            height: self.height,
            pixels,
        })
    }
}
