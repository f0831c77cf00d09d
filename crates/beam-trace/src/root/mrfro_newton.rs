//! MRFro with interval Newton steps (thesis 4.3.4, Table 4.1 "MRFro+Newt.").
//!
//! The search is [`Mrfro`](super::mrf::Mrfro)'s (end-value conditions made sound, see
//! [`mrf`](super::mrf)), and on every piece `X` that survives them `G'(X)` is evaluated:
//! where `0 ∉ G'(X)` and `g` is proven continuous, an interval Newton step
//! `N = (m − G([m]) / G'(X)) ∩ X` replaces the bisection. An empty `N` rejects `X`; a piece
//! where a root is proven (end values of opposite signs) with `0 ∉ G'(X)`, or with
//! `N ⊂ interior(X)`, holds exactly one root, is searched on by Newton steps alone and
//! returned as [`Proof::Unique`](super::Proof::Unique). Where `0 ∈ G'(X)` the piece is
//! bisected as in MRFro.

use interval_core::Interval;

use super::finder::{RootCounters, RootFinder, RootResult, RootSettings};
use super::mrf::mrfro_search;
use crate::ray::RayFn;

/// MRFro conditions plus interval Newton steps where `0 ∉ G'(X)`.
#[derive(Copy, Clone, Debug, Default)]
pub struct MrfroNewton;

impl RootFinder for MrfroNewton {
    fn name(&self) -> &'static str {
        "mrfro-newton"
    }

    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        mrfro_search(g, t, settings, counters, true)
    }
}
