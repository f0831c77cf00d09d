//! Interval anti-aliasing, IAA (thesis 5.5.2).
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

use crate::beam::BoxClass;
use crate::render::{Evals, Hit, Sample, Tracer, Work, forward};
use crate::root::RootResult;

/// Names of the IAA pass counters (in `Work::items` order).
pub const COUNTERS: [&str; 7] = [
    "beams",
    "rejected",
    "shaded_once",
    "splits_undecided",
    "depth_limit",
    "rays",
    "splits_variation",
];

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

/// The samples of pixel `(x, y)` under IAA.
pub(crate) fn iaa_pixel(
    tracer: &Tracer<'_>,
    ev: &mut Evals,
    x: u32,
    y: u32,
    max_depth: u32,
    threshold: f64,
    work: &mut Work,
) -> Vec<Sample> {
    let cam = &tracer.scene.camera;
    let mut out = Vec::new();
    let (fx, fy) = (f64::from(x), f64::from(y));
    let mut stack: Vec<Part> = vec![(fx, fy, 1.0f64, 0u32, None)];
    while let Some((x0, y0, size, depth, parent)) = stack.pop() {
        let weight = (size * size) as f32;
        let beam = cam.beam(x0, y0, x0 + size, y0 + size);
        work.items[0] += 1;
        let class = tracer.classify(ev, &beam, parent.as_ref(), &mut work.root);
        let centre = cam.ray(x0 + 0.5 * size, y0 + 0.5 * size);
        let at_limit = depth >= max_depth;
        match class {
            BoxClass::Miss => {
                work.items[1] += 1;
                out.push(Sample { weight, hit: None });
            }
            BoxClass::Hit { t_final } => {
                let region = beam.points(t_final);
                let (_, grad) = ev.geo.gradient_box(&region);
                let eye = beam.origin;
                let view: [Interval<f64>; 3] = std::array::from_fn(|i| region[i] - eye[i]);
                if at_limit || normal_variation(grad, view) <= threshold {
                    work.items[2] += 1;
                    work.items[5] += 1;
                    let hit = match tracer.cast(ev, &centre, t_final, &mut work.root) {
                        RootResult::Root { t, .. } | RootResult::Undecided { t } => t,
                        RootResult::NoRoot => t_final,
                    };
                    out.push(Sample {
                        weight,
                        hit: Some(tracer.hit(ev, &centre, hit, &mut work.root)),
                    });
                } else {
                    work.items[6] += 1;
                    push_quadrants(&mut stack, x0, y0, size, depth, class);
                }
            }
            BoxClass::Undecided { t } => {
                if at_limit {
                    work.items[4] += 1;
                    work.items[5] += 1;
                    let hit: Option<Hit> = match tracer.cast(ev, &centre, forward(), &mut work.root)
                    {
                        RootResult::Root { t, .. } | RootResult::Undecided { t } => {
                            Some(tracer.hit(ev, &centre, t, &mut work.root))
                        }
                        // The central ray misses, but some ray of the beam may meet the
                        // surface in `t`: keep the feature.
                        RootResult::NoRoot => Some(tracer.hit(ev, &centre, t, &mut work.root)),
                    };
                    out.push(Sample { weight, hit });
                } else {
                    work.items[3] += 1;
                    push_quadrants(&mut stack, x0, y0, size, depth, class);
                }
            }
        }
    }
    out
}

/// A sub-pixel waiting for its beam: corner, size, depth, and the class of the beam it was
/// split from.
type Part = (f64, f64, f64, u32, Option<BoxClass>);

fn push_quadrants(
    stack: &mut Vec<Part>,
    x0: f64,
    y0: f64,
    size: f64,
    depth: u32,
    parent: BoxClass,
) {
    let h = 0.5 * size;
    for (dx, dy) in [(h, h), (0.0, h), (h, 0.0), (0.0, 0.0)] {
        stack.push((x0 + dx, y0 + dy, h, depth + 1, Some(parent)));
    }
}
