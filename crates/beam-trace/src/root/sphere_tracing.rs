//! Sphere tracing (Hart; thesis 4.3.5): the unreliable baseline with a Lipschitz bound.
//!
//! From `t = T.inf()` the march steps `t += |g(t)| / L` with `L =`
//! [`RootSettings::lipschitz`]: if `L` bounds `|g'|` on `T` no step passes a root. It stops
//! with a root where `|g(t)| < ε · L` (the root is then within `ε` of `t`, reported as
//! `[t − ε, t + ε] ∩ T` with [`Proof::Possible`]), with `NoRoot`
//! past `T.sup()`, and `Undecided` after `max_steps` steps (a ray grazing the surface
//! creeps). Nothing is proven: `L` is a guess that the renderer cannot check, so a too
//! small `L` steps over thin parts, and point values are rounded to nearest. A `g` that
//! is undefined (NaN) at `t` is stepped over by `ε`.

use interval_core::Interval;

use super::finder::{Proof, RootCounters, RootFinder, RootResult, RootSettings};
use super::search::begin;
use crate::ibox::ival;
use crate::ray::RayFn;

/// Sphere tracing with the Lipschitz bound of the settings.
#[derive(Copy, Clone, Debug, Default)]
pub struct SphereTracing;

impl RootFinder for SphereTracing {
    fn name(&self) -> &'static str {
        "sphere-tracing"
    }

    fn is_reliable(&self) -> bool {
        false
    }

    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        let Some((mut ev, mut budget)) = begin(g, t, settings, counters) else {
            return RootResult::NoRoot;
        };
        let (lo, hi) = (t.inf(), t.sup());
        let eps = settings.epsilon;
        let lip = settings.lipschitz;
        let mut s = lo;
        while s <= hi {
            let v = ev.point(s);
            if v.abs() < eps * lip {
                let a = (s - eps).max(lo);
                let b = (s + eps).min(hi);
                return RootResult::Root {
                    t: ival(a, b),
                    proof: Proof::Possible,
                };
            }
            if let Some(undecided) = budget.step(s) {
                return undecided;
            }
            let step = if v.is_nan() { eps } else { v.abs() / lip };
            // At least one ulp, so that the march always moves.
            s = (s + step).max(s.next_up());
        }
        RootResult::NoRoot
    }
}
