//! The images a render produces besides the picture: the screen box classification, the
//! cost map and the shadow classes.

use rayon::prelude::*;

use super::box_map::BoxMap;
use crate::beam::BoxClass;
use crate::image::Image;
use crate::shadow::ShadowClass;

/// The colour of a beam class in classification images: proven miss blue, proven hit red,
/// undecided yellow.
pub fn box_class_color(class: &BoxClass) -> [f32; 3] {
    match class {
        BoxClass::Miss => [0.1, 0.25, 0.8],
        BoxClass::Hit { .. } => [0.85, 0.15, 0.1],
        BoxClass::Undecided { .. } => [0.95, 0.85, 0.1],
    }
}

/// The screen box classification image (thesis fig. 5.13): each pixel's box class, box
/// outlines darker; grey where no beam classified the pixel.
pub fn classification_image(w: u32, h: u32, classes: &BoxMap) -> Image {
    let pixels = classes
        .par_iter()
        .map(|c| match c.get() {
            None => [0.5, 0.5, 0.5],
            Some((class, edge)) => {
                let base = box_class_color(&class);
                if edge { base.map(|v| v * 0.6) } else { base }
            }
        })
        .collect();
    Image {
        width: w,
        height: h,
        pixels,
    }
}

/// A heat map of per-pixel costs (logarithmic, blue cheap to red expensive; black where the
/// cost is zero).
pub fn cost_image(w: u32, h: u32, cost: &[f32]) -> Image {
    let max = cost.par_iter().copied().reduce(|| 0f32, f32::max).max(1e-9);
    let min = cost
        .par_iter()
        .copied()
        .filter(|&c| c > 0.0)
        .reduce(|| f32::INFINITY, f32::min)
        .min(max);
    let (lmin, lmax) = (min.ln(), max.ln());
    let pixels = cost
        .par_iter()
        .map(|&c| {
            let s = if c <= 0.0 || lmax <= lmin {
                0.0
            } else {
                ((c.ln() - lmin) / (lmax - lmin)).clamp(0.0, 1.0)
            };
            heat(s)
        })
        .collect();
    Image {
        width: w,
        height: h,
        pixels,
    }
}

/// A blue → green → yellow → red colour ramp.
fn heat(s: f32) -> [f32; 3] {
    let stops = [
        [0.0, 0.0, 0.3],
        [0.0, 0.4, 1.0],
        [0.0, 0.9, 0.3],
        [1.0, 0.9, 0.0],
        [1.0, 0.1, 0.0],
    ];
    let x = s * (stops.len() - 1) as f32;
    let i = (x.floor() as usize).min(stops.len() - 2);
    let f = x - i as f32;
    std::array::from_fn(|k| stops[i][k] * (1.0 - f) + stops[i + 1][k] * f)
}

/// The shadow classification image (the soft-shadow paper's Fig. 7): proven lit (green),
/// proven umbra (blue), penumbra (orange), facing away from the light (dark blue-grey), no
/// shaded surface (dark grey).
pub fn shadow_class_image(w: u32, h: u32, classes: &[Option<ShadowClass>]) -> Image {
    let pixels = classes
        .par_iter()
        .map(|c| match c {
            None => [0.15, 0.15, 0.15],
            Some(ShadowClass::Lit) => [0.35, 0.8, 0.3],
            Some(ShadowClass::Umbra) => [0.15, 0.25, 0.75],
            Some(ShadowClass::Penumbra) => [0.95, 0.55, 0.1],
            Some(ShadowClass::BackFacing) => [0.25, 0.27, 0.35],
        })
        .collect();
    Image {
        width: w,
        height: h,
        pixels,
    }
}
