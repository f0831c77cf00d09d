//! Penumbra detection with Minkowski operators, carried to implicit surfaces with
//! intervals.
//!
//! The Minkowski-operator method shrinks the light `L` to its centre `c` and grows each
//! occluder `Q` by the light: if the segment from the point `p` to `c` misses the grown
//! occluder `Q ⊖ s · (L ⊖ {c})`, `p` sees the whole light. The smallest sound growth
//! shrinks along the segment (the paper's `t_max` taken point by point): at parameter
//! `t` of the segment the occluder is grown by `t · (L ⊖ {c})`. The points tested are then
//! `p + t (c − p) + t (l − c) = p + t (l − p)`, `l ∈ L`, `t ∈ [0, 1]`: the visibility cone,
//! the shadow beam over the whole light. With intervals the test is an evaluation of `f`
//! over those points; it is done in the beam's form `p + T · (L − p)`, the tightest of the
//! interval forms (`T · (c − p) + T · (L − c)` encloses the same set more loosely, by
//! subdistributivity).
//!
//! * **Lit**: the grown-occluder test rejects: every point of the light is visible, proven.
//! * **Umbra** (the paper's negative offsets): the inclusion test proves that every ray of
//!   the beam meets a surface: no point of the light is visible, proven.
//! * **Penumbra**: neither; only these points get the fine method, stochastic samples or
//!   `n × n` sub-beams.

use super::beam::{cleared, sub_beams};
use super::method::{BeamStart, LightVisibility, Occluders, ShadowMethod, ShadowQuery, ShadowWork};
use super::spec::{Fine, ShadowSpec};
use super::stochastic;
use crate::beam::BoxClass;

/// The Minkowski method with its fine step.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Minkowski {
    /// What runs in the penumbra.
    pub fine: Fine,
}

impl ShadowMethod for Minkowski {
    fn name(&self) -> String {
        ShadowSpec::Minkowski { fine: self.fine }.to_string()
    }

    fn visibility(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        work: &mut ShadowWork,
    ) -> LightVisibility {
        work.queries += 1;
        work.initial_beams += 1;
        let class = occluders.beam(q.origin, &q.light, BeamStart::At(0.0), true, &mut work.root);
        let start = cleared(&class);
        match class {
            BoxClass::Miss => LightVisibility::LIT,
            BoxClass::Hit { .. } => {
                work.initial_occluded += 1;
                work.umbra_proofs += 1;
                LightVisibility::UMBRA
            }
            BoxClass::Undecided { .. } => {
                work.initial_occluded += 1;
                match self.fine {
                    Fine::Stochastic { samples } => {
                        stochastic::estimate(occluders, q, start, samples, false, work)
                    }
                    Fine::Beams { n } => sub_beams(occluders, q, start, n, work),
                }
            }
        }
    }
}
