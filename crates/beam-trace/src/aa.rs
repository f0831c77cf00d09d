//! Interval anti-aliasing, IAA (thesis 5.5.2): the estimators that decide whether a proven
//! hit region is shaded once. The pass itself is the pixel-beams pass of the renderer.
//!
//! Each pixel starts as its beam from the screen box structure. A rejected beam is
//! background; a beam that the inclusion test proves to hit everywhere is shaded once if
//! its shading varies little across it, judged by [`shading_variation`] (the thesis's
//! normal-variation estimator of eq. 5.10, [`normal_variation`], judges the surface's
//! curvature instead, which splits curved surfaces whose colour hardly changes). Any other
//! beam is split in four, down to a depth limit; the pixel's colour is the area-weighted
//! sum of its parts.
//!
//! At the depth limit, an undecided part is shaded with the first surface its beam may
//! meet: its central ray's hit if it has one, else the point of the central ray in the
//! first parameter range the beam could not reject. So a feature thinner than a pixel
//! that touches any part of the pixel's beam is never lost: the beam cannot be rejected
//! there, and the part is shaded with the feature's surface.

use interval_core::Interval;

use crate::ibox::{IBox, ipoint};
use crate::scene::Material;

/// The normal-variation estimator of eq. 5.10: the width of the interval dot product
/// `N · (P − c)` of the normals' enclosure `N` over the hit region with the viewing
/// directions, scaled by the largest lengths of both, so that it reads as the spread of the
/// cosine between normal and view over the region (0 for a flat region seen head-on, at
/// most 2). A sub-pixel whose spread is at most the threshold is shaded once.
pub fn normal_variation(normal: [Interval<f64>; 3], view: [Interval<f64>; 3]) -> f64 {
    let d = normal[0] * view[0] + normal[1] * view[1] + normal[2] * view[2];
    let length = |v: &[Interval<f64>; 3]| v.iter().map(|c| c.mag() * c.mag()).sum::<f64>().sqrt();
    let scale = length(&normal) * length(&view);
    if d.is_empty() || !scale.is_finite() || scale <= 0.0 {
        return f64::INFINITY;
    }
    d.wid() / scale
}

/// A light as the shading variation sees it: where its direction is taken from, and its
/// colour times intensity.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct LightSource {
    /// The point shading takes the light's direction from.
    pub position: [f64; 3],
    /// Colour times intensity.
    pub color: [f32; 3],
}

/// The spread of the Phong colour ([`phong`](crate::shading::phong)) over a proven hit
/// region: the largest width, over the colour channels, of the colour computed with
/// interval arithmetic from the region's enclosures: `gradient` of the scene function,
/// `region` of the hit points, `eye` of the viewpoints, for every material in `materials`
/// (the leaves that may shade the region). Shadows are not part of it: a region shaded once
/// takes its one sample's shadow query.
///
/// Infinite where the region may hold a silhouette (the normal may face both towards and
/// away from the eye), the gradient may vanish, or the enclosures are unbounded. It is an
/// estimate for deciding splits, not a proven bound: the highlight's power is taken at
/// the ends of its base rounded to nearest.
pub fn shading_variation(
    gradient: IBox,
    region: IBox,
    eye: IBox,
    materials: &[Material],
    ambient: f32,
    lights: &[LightSource],
) -> f64 {
    if materials.is_empty() {
        return f64::INFINITY;
    }
    let unit = |v: IBox| -> Option<IBox> {
        let len = (v[0].sqr() + v[1].sqr() + v[2].sqr()).sqrt();
        (len.inf() > 0.0 && len.sup().is_finite()).then(|| v.map(|c| c / len))
    };
    let dot = |a: &IBox, b: &IBox| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (Some(n), Some(e)) = (
        unit(gradient),
        unit(std::array::from_fn(|i| eye[i] - region[i])),
    ) else {
        return f64::INFINITY;
    };
    // The normal turned towards the eye: one orientation over the whole region.
    let ne = dot(&n, &e);
    let n = if ne.inf() > 0.0 {
        n
    } else if ne.sup() < 0.0 {
        n.map(|c| -c)
    } else {
        return f64::INFINITY;
    };
    let zero = ipoint(0.0);
    let mut diffuse = [ipoint(f64::from(ambient)); 3];
    let mut highlight: Vec<([Interval<f64>; 3], Interval<f64>)> = Vec::new();
    for light in lights {
        let Some(l) = unit(std::array::from_fn(|i| {
            ipoint(light.position[i]) - region[i]
        })) else {
            return f64::INFINITY;
        };
        let nl = dot(&n, &l).max(zero);
        // r = 2 (n·l) n − l, and the highlight's base max(0, e·r).
        let r: IBox = std::array::from_fn(|i| ipoint(2.0) * nl * n[i] - l[i]);
        let er = dot(&e, &r).max(zero);
        let c = light.color.map(|c| ipoint(f64::from(c)));
        for k in 0..3 {
            diffuse[k] = diffuse[k] + c[k] * nl;
        }
        highlight.push((c, er));
    }
    let mut spread: f64 = 0.0;
    for m in materials {
        let p = f64::from(m.shininess);
        let power = |b: Interval<f64>| {
            Interval::new_unchecked(b.inf().min(1.0).powf(p), b.sup().min(1.0).powf(p))
        };
        for k in 0..3 {
            let mut colour = ipoint(f64::from(m.color[k])) * diffuse[k];
            for (c, er) in &highlight {
                colour = colour + ipoint(f64::from(m.specular)) * c[k] * power(*er);
            }
            spread = spread.max(colour.wid());
        }
    }
    if spread.is_nan() {
        f64::INFINITY
    } else {
        spread
    }
}
