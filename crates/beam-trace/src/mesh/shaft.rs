//! A shaft: the segments from the points of one box to the points of another (a group of
//! shaded points and a light), and the proofs that a box or a triangle lies outside it.

use interval_core::Interval;

use super::triangle::Triangle;
use crate::ibox::{IBox, disjoint, hull};
use crate::ray::Beam;

/// The parameters `[0, 1]` of a segment's points.
const UNIT: Interval<f64> = Interval::new_unchecked(0.0, 1.0);

/// The segments from the points of a box `from` to the points of a box `to`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Shaft {
    /// The box of both boxes, which holds every segment.
    hull: IBox,
    /// The segments as a beam: origins `from`, directions `to − from`, parameters
    /// [`UNIT`].
    beam: Beam,
}

impl Shaft {
    /// The segments from the points of `from` to those of `to`.
    pub fn new(from: &IBox, to: &IBox) -> Self {
        Shaft {
            hull: hull(from, to),
            beam: Beam {
                origin: *from,
                dir: std::array::from_fn(|k| to[k] - from[k]),
            },
        }
    }

    /// Whether some segment may reach the box `b`: `false` is a proof that none does (the
    /// boxes are disjoint, or the beam's parameter range inside `b` is empty).
    pub fn may_reach(&self, b: &IBox) -> bool {
        !disjoint(b, &self.hull) && self.beam.t_range_within(b, UNIT).is_some()
    }

    /// Whether some segment may meet the triangle: it may reach its box, and the lines of
    /// the beam are not proven to pass outside it ([`Triangle::beam_misses`]). `false` is a
    /// proof.
    pub fn may_meet(&self, t: &Triangle) -> bool {
        self.may_reach(&t.bounds()) && !t.beam_misses(&self.beam)
    }
}
