//! Precision escalation: a search that ends open (a possible root, or undecided) because
//! rounding, not the width of its pieces, keeps `g`'s enclosures wide is run again in the
//! next precision (`f32 → f64 → dd`). Only those searches pay for it.
//!
//! **When rounding dominates.** At the start `a` of the open piece, the enclosure of `g` at
//! the single parameter `a` has a width `w` that is rounding alone (a point has no width of
//! its own). The root's position is then uncertain by about `w / |g'|`; when that is at
//! least a quarter of the root-finder tolerance `ε` (with `|g'|` bounded by the magnitude of
//! `G'` over `[a, a + ε]`), no subdivision in this precision can localise the root to `ε`:
//! the search escalates. Large terms that cancel (`(x + 1e6)² − 2e6·x − 1e12`) give
//! `w ≈ 1e-4` against `ε·|g'| ≈ 1e-6`; a tangent ray or a double root gives `w ≈ 1e-16`,
//! and is left as it is (more precision would not decide it).

use interval_core::Interval;

use super::finder::{RootCounters, RootFinder, RootResult, RootSettings};
use crate::ibox::{ipoint, ival};
use crate::ray::RayFn;

/// A root finder that runs `inner` and, when [`RootSettings::escalate`] is set, runs an open
/// answer again in the next precision ([`RayFn::escalate`]) where rounding dominates: the
/// enclosure of `g` at the start `a` of the open piece is at least `ε·|G'([a, a + ε])| / 4`
/// wide, so no subdivision in this precision can place the root to `ε`. The search then
/// goes on from `a` (everything before it is proven free of roots).
#[derive(Debug)]
pub struct Escalating {
    inner: &'static dyn RootFinder,
}

impl Escalating {
    /// `inner`, escalating.
    pub fn new(inner: &'static dyn RootFinder) -> Self {
        Self { inner }
    }
}

/// Whether rounding alone keeps the open piece starting at `a` (and ending at most at `end`)
/// from being decided to `epsilon` in `g`'s current precision: the enclosure of `g` at `a`
/// is at least `epsilon·|G'([a, a + epsilon])| / 4` wide. Two evaluations, counted.
pub fn rounding_dominates(
    g: &mut dyn RayFn,
    a: f64,
    end: f64,
    epsilon: f64,
    counters: &mut RootCounters,
) -> bool {
    let w = g.g(ipoint(a)).wid();
    let (_, dg) = g.g_dg(ival(a, (a + epsilon).min(end).max(a)));
    counters.g_evals += 1;
    counters.dg_evals += 1;
    let slope = dg.mag();
    w > 0.0 && w.is_finite() && slope.is_finite() && w >= 0.25 * epsilon * slope
}

impl RootFinder for Escalating {
    fn name(&self) -> &'static str {
        self.inner.name()
    }

    fn is_reliable(&self) -> bool {
        self.inner.is_reliable()
    }

    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        let r = self.inner.first_root(g, t, settings, counters);
        let Some(open) = r.open() else {
            return r;
        };
        if !settings.escalate
            || !self.inner.is_reliable()
            || !rounding_dominates(g, open.inf(), t.sup(), settings.epsilon, counters)
        {
            return r;
        }
        let Some(previous) = g.escalate() else {
            return r;
        };
        counters.escalated += 1;
        // Everything before the open piece is proven free of roots: search from there.
        let rest = ival(open.inf(), t.sup());
        let again = self.inner.first_root(g, rest, settings, counters);
        g.restore(previous);
        if again.open().is_none() {
            counters.escalated_resolved += 1;
        }
        again
    }
}
