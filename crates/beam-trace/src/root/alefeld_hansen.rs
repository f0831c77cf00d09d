//! Interval Newton with the Alefeld–Hansen operator (Capriani et al.; thesis 4.3.3,
//! eq. 4.2 and Fig. 4.8).
//!
//! The search is [`Newton`](super::newton::Newton)'s, with one more case: where
//! `0 ∈ G'(X)` but `0 ∉ G([m])`, the extended division
//! `Q = {q : g'·q = g(m), g' ∈ G'(X), g(m) ∈ G([m])}` (IEEE 1788 `mulRevToPair`) has one or
//! two pieces, and every root of `X` lies in `(m − Q) ∩ X`: zero, one or two intervals,
//! searched left first. Nothing left proves that `X` holds no root. A piece that is not at
//! most half as wide as `X` is bisected before it is searched, so the search always
//! progresses. Where `0 ∈ G([m])` or continuity is not proven, `X` is bisected.

use interval_core::Interval;

use super::finder::{RootCounters, RootFinder, RootResult, RootSettings};
use super::newton::{Variant, newton_search};
use crate::ray::RayFn;

/// Interval Newton plus the Alefeld–Hansen extended-division step.
#[derive(Copy, Clone, Debug, Default)]
pub struct NewtonAlefeldHansen;

impl RootFinder for NewtonAlefeldHansen {
    fn name(&self) -> &'static str {
        "newton-alefeld-hansen"
    }

    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        let variant = Variant {
            extended: true,
            contract: false,
        };
        newton_search(g, t, settings, counters, variant)
    }
}
