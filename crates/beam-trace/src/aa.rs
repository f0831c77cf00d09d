//! Interval anti-aliasing, IAA (thesis 5.5.2): the normal-variation estimator. The pass
//! itself is [`render::iaa`](crate::render::iaa).
//!
//! Each pixel starts as one beam over its whole area. A rejected beam is background; a
//! beam that the inclusion test proves to hit everywhere is shaded once if the surface
//! varies little across it, judged by the normal-variation estimator of eq. 5.10 (the
//! interval dot product of the normals' enclosure over the hit region with the viewing
//! directions). Any other beam is split in four, down to a depth limit; the pixel's colour
//! is the area-weighted sum of its parts.
//!
//! At the depth limit, an undecided part is shaded with the first surface its beam may
//! meet: its central ray's hit if it has one, else the point of the central ray in the
//! first parameter range the beam could not reject. So a feature thinner than a pixel
//! that touches any part of the pixel's beam is never lost: the beam cannot be rejected
//! there, and the part is shaded with the feature's surface.

use interval_core::Interval;

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
