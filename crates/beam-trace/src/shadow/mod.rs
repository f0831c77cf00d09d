//! Shadows.
//!
//! Point lights cast hard shadows ([`hard`]): a segment from a surface point to the light
//! is proven unoccluded by interval rejection, and otherwise a reliable root search
//! decides.
//!
//! Area lights ([`Patch`]) cast soft shadows: the visible fraction of the light from a
//! point, computed by a [`ShadowMethod`]:
//!
//! * [`stochastic`]: jittered-stratified shadow segments over the light (distributed ray
//!   tracing), the baseline, optionally with a last-occluder cache;
//! * [`beam`]: one interval shadow beam over the whole light proves a point fully lit;
//!   only the points it cannot clear trace `n × n` sub-beams (the reliable soft-shadow
//!   method; also its always-`n²` and quadtree variants);
//! * [`certified`]: the light subdivided as a quadtree until the visible fraction is
//!   proven to lie in a bound no wider than a tolerance, with an estimate inside it;
//! * [`minkowski`]: the penumbra detection of the Minkowski-operator method carried to
//!   implicit surfaces: a lit test on the occluders grown by the light, an umbra test,
//!   and a fine method only in the penumbra left;
//! * [`exact`]: the shadows of the scene's triangles by the lazy BSP in Plücker space
//!   (seed 003), and of its implicit surfaces by shadow beams over the visible fragments.
//!
//! Every method works through the scene's [`Occluders`] (segment and beam queries the
//! renderer answers through its regular grid), returns a [`LightVisibility`] with proven
//! bounds on the visible fraction, and counts its work in [`ShadowWork`].

pub mod beam;
pub mod certified;
pub mod exact;
mod exact_work;
pub mod hard;
mod method;
pub mod minkowski;
mod patch;
pub mod rounds;
mod spec;
pub mod stochastic;

pub use method::{
    BeamStart, LightVisibility, Occluders, Occlusion, ShadowClass, ShadowMethod, ShadowQuery,
    ShadowWork, ShaftTriangle,
};
pub use patch::Patch;
pub use spec::{Fine, ShadowSpec, Strategy, Tolerance};

use beam::BeamShadows;
use certified::Certified;
use minkowski::Minkowski;
use stochastic::Stochastic;

impl ShadowSpec {
    /// The method.
    pub fn method(&self) -> Box<dyn ShadowMethod> {
        match *self {
            ShadowSpec::Stochastic { samples, cache } => Box::new(Stochastic { samples, cache }),
            ShadowSpec::Beam { n, strategy } => Box::new(BeamShadows { n, strategy }),
            ShadowSpec::Minkowski { fine } => Box::new(Minkowski { fine }),
            ShadowSpec::Certified {
                tolerance,
                budget,
                segments,
            } => Box::new(Certified {
                tolerance,
                budget,
                segments,
            }),
            ShadowSpec::Exact {
                depth,
                group,
                faces,
            } => Box::new(exact::Exact {
                depth,
                group,
                faces,
            }),
        }
    }
}
