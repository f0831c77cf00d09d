//! Interval root finders for the ray equation `g(t) = 0` (thesis 4.3, Table 4.1).
//!
//! Every method sees only `g` and `g'` through the [`RayFn`] trait, searches a parameter
//! interval `T` for the **first** root and answers with a [`RootResult`], counting its work
//! in [`RootCounters`]. One file per method:
//!
//! | method | file | reliable | uses `g'` |
//! |---|---|---|---|
//! | classic interval bisection | `bisection.rs` | yes | no |
//! | Mitchell | `mitchell.rs` | yes | yes |
//! | interval Newton | `newton.rs` | yes | yes |
//! | Newton + Alefeld-Hansen | `alefeld_hansen.rs` | yes | yes |
//! | Newton + HC4-revise contraction | `newton_hc4.rs` | yes | yes |
//! | MRF and MRFro (San Juan-Estrada) | `mrf.rs` | yes | no |
//! | MRFro + Newton | `mrfro_newton.rs` | yes | yes |
//! | counter-based bisection (ns, cs) | `counter_bisection.rs` | yes | no |
//! | point-sampling bisection (baseline) | `point_sampling.rs` | **no** | no |
//! | sphere tracing (baseline) | `sphere_tracing.rs` | **no** | no |
//!
//! The two baselines are for comparison only: they can miss roots and say nothing for
//! sure. [`RootFinder::is_reliable`] tells them apart.

use std::fmt;
use std::str::FromStr;

pub use crate::ray::RayFn;
pub use escalation::{Escalating, rounding_dominates};
pub use finder::{Proof, RootCounters, RootFinder, RootResult, RootSettings};

/// The root finders by name.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RootMethod {
    /// Classic interval bisection.
    Bisection,
    /// Mitchell: interval rejection, derivative uniqueness test, point refinement.
    Mitchell,
    /// Interval Newton.
    Newton,
    /// Interval Newton with the Alefeld-Hansen extended-division operator.
    NewtonAlefeldHansen,
    /// Interval Newton on pieces contracted by HC4-revise first.
    NewtonHc4,
    /// San Juan-Estrada's MRF.
    Mrf,
    /// San Juan-Estrada's MRFro.
    Mrfro,
    /// MRFro with Newton steps.
    MrfroNewton,
    /// The non-recursive bisection with counters (ns, cs) of the GPU kernels.
    CounterBisection,
    /// Unreliable baseline: point sampling with a fixed step, then bisection.
    PointSampling,
    /// Unreliable baseline: sphere tracing with a Lipschitz bound.
    SphereTracing,
}

impl RootMethod {
    /// Every method, reliable ones first.
    pub const ALL: [RootMethod; 11] = [
        RootMethod::Bisection,
        RootMethod::Mitchell,
        RootMethod::Newton,
        RootMethod::NewtonAlefeldHansen,
        RootMethod::NewtonHc4,
        RootMethod::Mrf,
        RootMethod::Mrfro,
        RootMethod::MrfroNewton,
        RootMethod::CounterBisection,
        RootMethod::PointSampling,
        RootMethod::SphereTracing,
    ];

    /// The method's name (kebab case, as in scene files and on the command line).
    pub fn name(self) -> &'static str {
        match self {
            RootMethod::Bisection => "bisection",
            RootMethod::Mitchell => "mitchell",
            RootMethod::Newton => "newton",
            RootMethod::NewtonAlefeldHansen => "newton-alefeld-hansen",
            RootMethod::NewtonHc4 => "newton-hc4",
            RootMethod::Mrf => "mrf",
            RootMethod::Mrfro => "mrfro",
            RootMethod::MrfroNewton => "mrfro-newton",
            RootMethod::CounterBisection => "counter-bisection",
            RootMethod::PointSampling => "point-sampling",
            RootMethod::SphereTracing => "sphere-tracing",
        }
    }

    /// The implementation.
    pub fn finder(self) -> &'static dyn RootFinder {
        match self {
            RootMethod::Bisection => &bisection::Bisection,
            RootMethod::Mitchell => &mitchell::Mitchell,
            RootMethod::Newton => &newton::Newton,
            RootMethod::NewtonAlefeldHansen => &alefeld_hansen::NewtonAlefeldHansen,
            RootMethod::NewtonHc4 => &newton_hc4::NewtonHc4,
            RootMethod::Mrf => &mrf::Mrf,
            RootMethod::Mrfro => &mrf::Mrfro,
            RootMethod::MrfroNewton => &mrfro_newton::MrfroNewton,
            RootMethod::CounterBisection => &counter_bisection::CounterBisection,
            RootMethod::PointSampling => &point_sampling::PointSampling,
            RootMethod::SphereTracing => &sphere_tracing::SphereTracing,
        }
    }
}

impl fmt::Display for RootMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for RootMethod {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        RootMethod::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = RootMethod::ALL.iter().map(|m| m.name()).collect();
                let hint = implicit_expr::parse::suggest::did_you_mean(s, names.iter().copied())
                    .map(|h| format!("; {h}"))
                    .unwrap_or_default();
                format!(
                    "unknown root finder '{s}'{hint} (one of: {})",
                    names.join(", ")
                )
            })
    }
}

pub mod alefeld_hansen;
pub mod bisection;
pub mod counter_bisection;
mod escalation;
mod finder;
pub mod mitchell;
pub mod mrf;
pub mod mrfro_newton;
pub mod newton;
pub mod newton_hc4;
pub mod point_sampling;
pub(crate) mod search;
pub mod sphere_tracing;
