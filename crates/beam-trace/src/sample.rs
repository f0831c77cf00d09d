//! What a primary sample sees: the surface point it hit (its root enclosure, its shading
//! point, the leaf whose material shades it, its normal), and its weight in its pixel.

use glam::DVec3;
use interval_core::Interval;

use crate::ray::Ray;

/// Distance, as a fraction of the scene diagonal, by which a shadow segment starts off the
/// surface along the normal. It must exceed the width of a root enclosure along the segment
/// (`epsilon` times the segment's length) by a wide margin, or the search finds the surface
/// the segment leaves as a possible root (shadow acne); occluders thinner than it at the
/// very start of a segment are not seen.
pub const SHADOW_OFFSET: f64 = 1e-4;

/// A surface point seen by a primary sample.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Hit {
    /// Enclosure of the ray parameter of the first root.
    pub t: Interval<f64>,
    /// The point (central ray at the middle of `t`).
    pub point: DVec3,
    /// Unit vector from the point to the eye.
    pub to_eye: DVec3,
    /// The leaf surface whose material shades it.
    pub leaf: u32,
    /// Unit normal (set by the normals pass).
    pub normal: DVec3,
}

impl Hit {
    /// The hit of `ray` at the parameter `tm` inside its root enclosure `t`, shaded by
    /// leaf `leaf`, before the normals pass: its normal faces the eye until then.
    pub fn on_ray(ray: &Ray, t: Interval<f64>, tm: f64, leaf: u32) -> Hit {
        let to_eye = (-ray.dir).normalize_or_zero();
        Hit {
            t,
            point: ray.at(tm),
            to_eye,
            leaf,
            normal: to_eye,
        }
    }

    /// The normal turned towards the eye (the side of the surface the sample sees).
    pub fn facing_normal(&self) -> DVec3 {
        if self.normal.dot(self.to_eye) < 0.0 {
            -self.normal
        } else {
            self.normal
        }
    }

    /// Where shadow rays from the hit start: `offset` off the surface along the facing
    /// normal (see [`SHADOW_OFFSET`]).
    pub fn shadow_origin(&self, offset: f64) -> DVec3 {
        self.point + self.facing_normal() * offset
    }
}

/// What the beam of a sample's share of its pixel proved about that share.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Area {
    /// No ray of the share meets a surface (a rejected beam).
    Missed,
    /// Every ray of the share meets a surface (an inclusion).
    Covered,
    /// Nothing proven: some rays of the share may meet a surface (an undecided beam, or a
    /// point sample, which proves nothing about the area around it).
    Unknown,
}

/// One primary sample of a pixel: its weight (area fraction), what it sees, and what is
/// proven about its share of the pixel.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Sample {
    /// Weight of the sample in its pixel (the weights of a pixel sum to 1).
    pub weight: f32,
    /// The surface point, or `None` for background.
    pub hit: Option<Hit>,
    /// What its beam proved about its share of the pixel.
    pub area: Area,
}

/// Proven bounds on the share of a pixel whose rays meet a surface: every ray of a share
/// `proven` of the pixel's area meets one, and the rays of at most a share `possible` do.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Coverage {
    /// The share proven covered (the weights of [`Area::Covered`] samples).
    pub proven: f32,
    /// The share that may be covered (the weights of samples that are not
    /// [`Area::Missed`]).
    pub possible: f32,
}

impl Coverage {
    /// The bounds over a pixel's samples.
    pub fn of(samples: &[Sample]) -> Coverage {
        Coverage::of_shares(samples.iter().map(|s| (s.weight, s.area)))
    }

    /// The bounds over a pixel's shares, each given as its weight and what its beam proved
    /// of it.
    pub fn of_shares(shares: impl Iterator<Item = (f32, Area)> + Clone) -> Coverage {
        let share = |keep: fn(Area) -> bool| {
            shares
                .clone()
                .filter(|&(_, area)| keep(area))
                .map(|(weight, _)| weight)
                .sum::<f32>()
                .min(1.0)
        };
        Coverage {
            proven: share(|a| a == Area::Covered),
            possible: share(|a| a != Area::Missed),
        }
    }
}
