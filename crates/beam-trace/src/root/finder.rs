//! What a root finder is: the [`RootFinder`] trait, its [`RootSettings`], its answer
//! ([`RootResult`], with the [`Proof`] behind a root) and its work ([`RootCounters`]).

use std::fmt;

use interval_core::Interval;

use crate::ray::RayFn;

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
    /// Whether a search that ends open because rounding dominates its enclosures is run
    /// again in the next higher precision ([`Escalating`](super::Escalating)).
    pub escalate: bool,
    /// Whether a piece proven to hold exactly one root (the first) is narrowed to width
    /// [`epsilon`](Self::epsilon) before it is returned. Where only the root's existence
    /// matters (a shadow segment is blocked or not), `false` ends the search at that piece,
    /// returned as it is ([`Proof::Unique`]); the finders that prove uniqueness (the Newton
    /// searches, Mitchell, MRFro) then skip their narrowing steps. Which searches find a root
    /// does not change, only how narrow the reported enclosure is.
    pub narrow_roots: bool,
}

impl RootSettings {
    /// Whether a piece `x` proven to hold exactly one root is returned as it is: it is
    /// narrower than [`epsilon`](Self::epsilon), or roots are not narrowed.
    pub(crate) fn unique_settled(&self, x: Interval<f64>) -> bool {
        !self.narrow_roots || super::search::is_small(x, self.epsilon)
    }

    /// These settings for a search that asks only whether a root exists
    /// ([`narrow_roots`](Self::narrow_roots) off).
    pub fn existence(self) -> Self {
        Self {
            narrow_roots: false,
            ..self
        }
    }
}

impl Default for RootSettings {
    fn default() -> Self {
        Self {
            epsilon: 1e-6,
            max_steps: 100_000,
            sampling_step: 1e-3,
            lipschitz: 10.0,
            escalate: true,
            narrow_roots: true,
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
    /// The first root proven to lie in `t` by a beam's inclusion test (a sign change of a
    /// continuous `g` for every ray, no root before `t`): [`Proof::Exists`].
    pub fn included(t: Interval<f64>) -> Self {
        RootResult::Root {
            t,
            proof: Proof::Exists,
        }
    }

    /// The first root of the union of two sets searched over the same window, from the
    /// answers `self` and `other` of their searches (the first root along the ray of
    /// either).
    ///
    /// A root proven to end before the other answer begins comes first as it is; where the
    /// two overlap, the first root lies between the earlier start and the earlier end, and
    /// a root is proven there only if the answer that ends first proves one (uniqueness is
    /// not kept). An undecided answer keeps undecided everything from the earlier start on.
    pub fn first_of(self, other: RootResult) -> RootResult {
        use RootResult::{NoRoot, Root, Undecided};
        match (self, other) {
            (NoRoot, x) | (x, NoRoot) => x,
            (Undecided { t: a }, Undecided { t: b }) => Undecided {
                t: a.convex_hull(b),
            },
            (Undecided { t: u }, Root { t, proof }) | (Root { t, proof }, Undecided { t: u }) => {
                if t.sup() < u.inf() {
                    Root { t, proof }
                } else {
                    Undecided {
                        t: Interval::new_unchecked(t.inf().min(u.inf()), u.sup().max(t.sup())),
                    }
                }
            }
            (Root { t: a, proof: pa }, Root { t: b, proof: pb }) => {
                if a.sup() < b.inf() {
                    self
                } else if b.sup() < a.inf() {
                    other
                } else {
                    let ends_first = if a.sup() <= b.sup() { pa } else { pb };
                    Root {
                        t: Interval::new_unchecked(a.inf().min(b.inf()), a.sup().min(b.sup())),
                        proof: match ends_first {
                            Proof::Possible => Proof::Possible,
                            _ => Proof::Exists,
                        },
                    }
                }
            }
        }
    }

    /// The root enclosure, if any.
    pub fn root(&self) -> Option<Interval<f64>> {
        match *self {
            RootResult::Root { t, .. } => Some(t),
            _ => None,
        }
    }

    /// The piece left open, if the answer proves neither a root nor its absence: a
    /// possible root's enclosure, or the undecided part. Nothing before it is a root.
    pub fn open(&self) -> Option<Interval<f64>> {
        match *self {
            RootResult::Root {
                t,
                proof: Proof::Possible,
            }
            | RootResult::Undecided { t } => Some(t),
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
    /// Searches run again in a higher precision ([`Escalating`](super::Escalating)).
    pub escalated: u64,
    /// Escalated searches that ended proven (a root proven or no root).
    pub escalated_resolved: u64,
    /// Rejection tests not evaluated because a block of frames proved them
    /// ([`crate::free_ranges`]).
    pub block_proven: u64,
}

impl RootCounters {
    /// Adds `other` to `self`.
    pub fn add(&mut self, other: &RootCounters) {
        self.g_evals += other.g_evals;
        self.dg_evals += other.dg_evals;
        self.point_evals += other.point_evals;
        self.bisections += other.bisections;
        self.escalated += other.escalated;
        self.escalated_resolved += other.escalated_resolved;
        self.block_proven += other.block_proven;
    }
}

/// A method that finds the first root of `g` in a parameter interval.
pub trait RootFinder: Send + Sync + fmt::Debug {
    /// The method's name, as accepted by [`RootMethod`](super::RootMethod)'s `FromStr`.
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
