//! Roots and beams the kernels leave open where `f32` rounding dominates, searched again on
//! the CPU: in `f64`, and in double-double beyond where `f64` rounding dominates too
//! ([`Escalating`] for rays, [`BeamSettings::escalate`] for beams). This is how the GPU
//! backend escalates precision: only the rays and beams whose open answer the rounding test
//! picks pay for it, and the answers count as `escalated` (`escalated_resolved` where the
//! CPU proves a root, no root, or the beam's class).

use beam_trace::backend::RayQuery;
use beam_trace::beam::{BeamSettings, BoxClass, Extent, evaluate_box, rejection_search};
use beam_trace::ray::{Beam, BeamEval, Precision, RayFn};
use beam_trace::root::{Escalating, RootCounters, RootFinder, RootResult, rounding_dominates};
use beam_trace::{Plan, Scene};
use interval_core::Interval;
use rayon::prelude::*;

/// Re-searches on the CPU the open `answers` of `queries` where `f32` rounding dominates
/// (the test of [`rounding_dominates`], in `f32` as the kernels evaluate), replacing them;
/// returns the counters of that work. Nothing when the plan does not escalate.
pub(crate) fn escalate_open(
    scene: &Scene,
    plan: &Plan,
    queries: &[RayQuery],
    answers: &mut [RootResult],
) -> RootCounters {
    let mut total = RootCounters::default();
    if !plan.root.escalate {
        return total;
    }
    let open: Vec<(usize, Interval<f64>)> = answers
        .iter()
        .enumerate()
        .filter_map(|(i, r)| r.open().map(|t| (i, t)))
        .collect();
    if open.is_empty() {
        return total;
    }
    let f = scene.geometry.ray_function();
    let bounds = scene.geometry.bounds();
    let finder = Escalating::new(plan.root_finder.finder());
    let redone: Vec<(usize, Option<RootResult>, RootCounters)> = open
        .par_iter()
        .map_init(
            || BeamEval::new(f),
            |ev, &(i, piece)| {
                let mut c = RootCounters::default();
                let q = &queries[i];
                // Everything before the open piece is proven free of roots.
                let rest = Interval::new_unchecked(piece.inf(), q.window.sup().max(piece.inf()));
                let Some(t) = q.ray.beam().t_range_within(&bounds, rest) else {
                    return (i, None, c);
                };
                ev.set_ray(&q.ray);
                ev.set_precision(Precision::F32);
                let dominated = rounding_dominates(ev, t.inf(), t.sup(), plan.root.epsilon, &mut c);
                ev.set_precision(Precision::F64);
                if !dominated {
                    return (i, None, c);
                }
                c.escalated += 1;
                let r = finder.first_root(ev, t, &plan.root, &mut c);
                if r.open().is_none() {
                    c.escalated_resolved += 1;
                }
                (i, Some(r), c)
            },
        )
        .collect();
    for (i, r, c) in redone {
        if let Some(r) = r {
            answers[i] = r;
        }
        total.add(&c);
    }
    total
}

/// A beam a kernel left undecided: what the CPU needs to search it again.
pub(crate) struct OpenBeam {
    /// The beam.
    pub beam: Beam,
    /// The parameters its kernel searched.
    pub searched: Interval<f64>,
    /// Its kernel's undecided piece (everything before it is proven free of roots).
    pub piece: Interval<f64>,
    /// The tolerances of its search.
    pub settings: BeamSettings,
    /// Whether the inclusion test runs (EvaluateBox), or the rejection test alone.
    pub inclusion: bool,
}

/// Classifies again on the CPU the undecided beams `open` where a higher precision may
/// decide them ([`RayFn::escalation_helps`], in `f32` as the kernels evaluate): EvaluateBox
/// (or the rejection test) in `f64` from the start of the undecided piece, escalating to
/// double-double where `f64` does not decide them either. Returns, per beam, its new class
/// (`None`: left as the kernel answered) and the counters of that work. Nothing when the
/// plan does not escalate.
pub(crate) fn escalate_open_beams(
    scene: &Scene,
    plan: &Plan,
    open: &[OpenBeam],
) -> Vec<(Option<BoxClass>, RootCounters)> {
    if !plan.beam.escalate || open.is_empty() {
        return vec![(None, RootCounters::default()); open.len()];
    }
    let f = scene.geometry.ray_function();
    let bounds = scene.geometry.bounds();
    open.par_iter()
        .map_init(
            || BeamEval::new(f),
            |ev, o| {
                let mut c = RootCounters::default();
                if o.piece.is_empty() {
                    return (None, c);
                }
                // Everything before the undecided piece is proven free of roots; the search
                // stays inside the scene bounds, as on the CPU.
                let rest =
                    Interval::new_unchecked(o.piece.inf(), o.searched.sup().max(o.piece.inf()));
                let Some(rest) = o.beam.t_range_within(&bounds, rest) else {
                    return (None, c);
                };
                ev.set_precision(Precision::F32);
                ev.set_beam(&o.beam);
                let now = ev.g(o.piece);
                c.g_evals += 1;
                let helps =
                    ev.escalation_helps(o.piece, now, rest.sup(), o.settings.epsilon, &mut c);
                ev.set_precision(Precision::F64);
                if !helps {
                    return (None, c);
                }
                c.escalated += 1;
                ev.set_beam(&o.beam);
                let class = if o.inclusion {
                    let extent = Extent {
                        beam: &o.beam,
                        bounds: &bounds,
                    };
                    evaluate_box(ev, &[rest], Some(&extent), &o.settings, &mut c)
                } else {
                    rejection_search(ev, &[rest], &o.settings, &mut c)
                };
                if !matches!(class, BoxClass::Undecided { .. }) {
                    c.escalated_resolved += 1;
                }
                (Some(class), c)
            },
        )
        .collect()
}
