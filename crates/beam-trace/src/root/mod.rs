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

use interval_core::Interval;

/// `g` and `g'` of one ray or beam, as inclusion functions of the ray parameter.
///
/// The renderer implements it over implicit-expr's ray evaluators; tests implement it with
/// closures. Implementations must be sound: for every `t` in `T` (and every ray of the
/// beam), `g(t) ∈ g(T)` and `g'(t) ∈ g'(T)` wherever `g` is defined.
pub trait RayFn {
    /// An enclosure of `g` over `t` (every ray of the beam).
    fn g(&mut self, t: Interval<f64>) -> Interval<f64>;

    /// Enclosures of `g` and `g'` over `t`. A derivative that is undefined somewhere in
    /// the region is the whole line, never empty.
    fn g_dg(&mut self, t: Interval<f64>) -> (Interval<f64>, Interval<f64>);

    /// `g` over `t` and whether `g` is proven continuous there (every operation defined on
    /// all of its arguments, no step function). A sign change proves a root only then.
    fn g_checked(&mut self, t: Interval<f64>) -> (Interval<f64>, bool);

    /// The floating-point value of `g` at the point `t` for the central ray, rounded to
    /// nearest: for the unreliable baselines only.
    fn g_point(&mut self, t: f64) -> f64;
}

/// Limits and tolerances of a root search.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct RootSettings {
    /// Width below which a parameter interval where a root may lie is reported as the root
    /// enclosure (thesis: `ε_T`).
    pub epsilon: f64,
    /// Largest number of interval subdivisions (bisections and Newton steps) before the
    /// search gives up with [`RootResult::Undecided`].
    pub max_steps: u64,
    /// Step of the point-sampling baseline, as a fraction of the width of `T`.
    pub sampling_step: f64,
    /// Lipschitz bound of `g` per unit of `t` for the sphere-tracing baseline.
    pub lipschitz: f64,
}

impl Default for RootSettings {
    fn default() -> Self {
        Self {
            epsilon: 1e-6,
            max_steps: 100_000,
            sampling_step: 1e-3,
            lipschitz: 10.0,
        }
    }
}

/// What a derivative or sign test proved about a root enclosure.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Proof {
    /// Exactly one root lies in the enclosure (`0 ∉ g'(T)` and a sign change, or a Newton
    /// contraction).
    Unique,
    /// At least one root lies in the enclosure (a sign change of a continuous `g`).
    Exists,
    /// The enclosure is narrower than epsilon and `0 ∈ g(T)`: a root is possible there
    /// and none is possible before it, but none is proven (a tangent ray, a double root).
    Possible,
}

/// The answer of a root search over `T`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum RootResult {
    /// The first root: `g` has no root in `T` before `t.inf()`, and `t` holds the first
    /// root (if `proof` is [`Proof::Possible`]: the first possible root).
    Root {
        /// The enclosure of the first root.
        t: Interval<f64>,
        /// What is proven about it.
        proof: Proof,
    },
    /// Proven: `g` has no root in `T` (for a reliable method; a baseline only guesses).
    NoRoot,
    /// A limit was hit: no root before `t.inf()`, nothing decided in `t`.
    Undecided {
        /// The part of `T` left undecided.
        t: Interval<f64>,
    },
}

impl RootResult {
    /// The root enclosure, if any.
    pub fn root(&self) -> Option<Interval<f64>> {
        match *self {
            RootResult::Root { t, .. } => Some(t),
            _ => None,
        }
    }
}

/// Work done by root searches; sums over many searches with [`RootCounters::add`].
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct RootCounters {
    /// Interval evaluations of `g`.
    pub g_evals: u64,
    /// Interval evaluations of `g'` (each also evaluates `g`).
    pub dg_evals: u64,
    /// Point evaluations of `g` (baselines and point refinement).
    pub point_evals: u64,
    /// Interval bisections.
    pub bisections: u64,
}

impl RootCounters {
    /// Adds `other` to `self`.
    pub fn add(&mut self, other: &RootCounters) {
        self.g_evals += other.g_evals;
        self.dg_evals += other.dg_evals;
        self.point_evals += other.point_evals;
        self.bisections += other.bisections;
    }
}

/// A method that finds the first root of `g` in a parameter interval.
pub trait RootFinder: Send + Sync + fmt::Debug {
    /// The method's name, as accepted by [`RootMethod::from_str`].
    fn name(&self) -> &'static str;

    /// Whether "no root" and root enclosures are proofs: `true` unless the method says
    /// otherwise (the baselines do).
    fn is_reliable(&self) -> bool {
        true
    }

    /// The first root of `g` in `t`, counting work in `counters`.
    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult;
}

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
    pub const ALL: [RootMethod; 10] = [
        RootMethod::Bisection,
        RootMethod::Mitchell,
        RootMethod::Newton,
        RootMethod::NewtonAlefeldHansen,
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
pub mod mitchell;
pub mod mrf;
pub mod mrfro_newton;
pub mod newton;
pub mod point_sampling;
pub(crate) mod search;
pub mod sphere_tracing;
