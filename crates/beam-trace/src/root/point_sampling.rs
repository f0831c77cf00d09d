//! Point-sampling bisection: the unreliable baseline of thesis 4.3.1 (Figs. 4.3–4.5).
//!
//! `g` is sampled in floating point at the fixed step `h = sampling_step · width(T)` from
//! `T.inf()`; the first pair of samples whose signs differ (or a sample that is exactly 0)
//! brackets the root, which point bisection narrows to width `ε`. The answer is a guess:
//! a root between two samples of one sign (a thin part, a tangent ray) is missed, and a
//! sign change of a discontinuous `g` is taken for a root. `NoRoot` means "no sign change
//! seen", and a root is reported as [`Proof::Possible`].
//!
//! Every sample and bisection value counts in `point_evals`, every refinement halving in
//! `bisections`; the halvings count against `max_steps`.

use interval_core::Interval;

use super::finder::{Proof, RootCounters, RootFinder, RootResult, RootSettings};
use super::search::{Budget, Eval, begin};
use crate::ibox::ival;
use crate::ray::RayFn;

/// The most samples one search takes, whatever `sampling_step` says.
const MAX_SAMPLES: u64 = 1 << 24;

/// Fixed-step point sampling, then point bisection of the first sign change.
#[derive(Copy, Clone, Debug, Default)]
pub struct PointSampling;

impl RootFinder for PointSampling {
    fn name(&self) -> &'static str {
        "point-sampling"
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
        let Some((mut ev, budget)) = begin(g, t, settings, counters) else {
            return RootResult::NoRoot;
        };
        if !t.is_common_interval() {
            return RootResult::NoRoot;
        }
        let (lo, hi) = (t.inf(), t.sup());
        let samples = if settings.sampling_step > 0.0 {
            (1.0 / settings.sampling_step)
                .ceil()
                .clamp(1.0, MAX_SAMPLES as f64) as u64
        } else {
            MAX_SAMPLES
        };
        let h = (hi - lo) / samples as f64;
        let sample = |i: u64| if i >= samples { hi } else { lo + i as f64 * h };
        let mut a = lo;
        let mut ga = ev.point(a);
        if ga == 0.0 {
            return RootResult::Root {
                t: ival(a, a),
                proof: Proof::Possible,
            };
        }
        for i in 1..=samples {
            let b = sample(i).max(a);
            let gb = ev.point(b);
            if gb == 0.0 {
                return RootResult::Root {
                    t: ival(b, b),
                    proof: Proof::Possible,
                };
            }
            if (ga < 0.0) != (gb < 0.0) && !ga.is_nan() && !gb.is_nan() {
                return refine(&mut ev, a, b, ga, settings, budget);
            }
            (a, ga) = (b, gb);
        }
        RootResult::NoRoot
    }
}

/// Point bisection of `[a, b]`, where `g(a)` (`ga`) and `g(b)` have opposite signs, within
/// the search's `budget`.
fn refine(
    ev: &mut Eval<'_>,
    mut a: f64,
    mut b: f64,
    ga: f64,
    settings: &RootSettings,
    mut budget: Budget,
) -> RootResult {
    loop {
        let m = 0.5 * (a + b);
        if b - a <= settings.epsilon || !(a < m && m < b) {
            return RootResult::Root {
                t: ival(a, b),
                proof: Proof::Possible,
            };
        }
        if let Some(undecided) = budget.step(a) {
            return undecided;
        }
        ev.counters.bisections += 1;
        let gm = ev.point(m);
        if gm == 0.0 {
            return RootResult::Root {
                t: ival(m, m),
                proof: Proof::Possible,
            };
        }
        if (gm < 0.0) == (ga < 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
}
