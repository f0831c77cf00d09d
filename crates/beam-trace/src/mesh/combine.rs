//! What a search of the implicit surfaces and one of the meshes' triangles prove together
//! about a beam or a segment: each search is a proof about the same rays over the same
//! parameters, so any backend that answers the implicit part (the CPU's grid, a GPU
//! kernel) gets the scene's answer by the same rules.

use interval_core::Interval;

use super::MeshIndex;
use crate::beam::{BoxClass, forward};
use crate::ray::{Beam, Ray};
use crate::root::RootResult;

/// The class of a beam whose implicit class is `implicit`, where its rays may meet a
/// triangle first in `tm` (and in no range before), and where, if `covered` is given, every
/// ray's first crossing of a triangle is proven to lie in it
/// ([`Bvh::beam_hit`](super::Bvh::beam_hit)). The beam is Hit where the first of the two is
/// proven for every ray; else it is Undecided from the earlier of the two ranges on.
fn with_triangles(
    implicit: BoxClass,
    tm: Interval<f64>,
    covered: Option<Interval<f64>>,
) -> BoxClass {
    let earlier = |t: Interval<f64>| if tm.inf() < t.inf() { tm } else { t };
    match (implicit, covered) {
        (BoxClass::Miss, Some(t)) => BoxClass::Hit { t_final: t },
        (BoxClass::Miss, None) => BoxClass::Undecided { t: tm },
        (BoxClass::Undecided { t }, Some(tc)) if tc.sup() < t.inf() => {
            BoxClass::Hit { t_final: tc }
        }
        (BoxClass::Undecided { t }, _) => BoxClass::Undecided { t: earlier(t) },
        (BoxClass::Hit { t_final }, _) if tm.inf() > t_final.sup() => implicit,
        (BoxClass::Hit { t_final }, Some(tc)) if t_final.sup() < tc.inf() => implicit,
        (BoxClass::Hit { t_final }, Some(tc)) if tc.sup() < t_final.inf() => {
            BoxClass::Hit { t_final: tc }
        }
        (BoxClass::Hit { t_final }, _) => BoxClass::Undecided {
            t: earlier(t_final),
        },
    }
}

impl MeshIndex {
    /// The first parameter range in `window` (clipped to `t ≥ 0`) where a ray of `beam`
    /// may meet a triangle (`None`: proven that none does).
    pub fn beam_first(&self, beam: &Beam, window: Interval<f64>) -> Option<Interval<f64>> {
        let window = window.intersection(forward());
        if window.is_empty() {
            return None;
        }
        self.bvh().beam_first(beam, window)
    }

    /// A primary beam's class over `window` (clipped to `t ≥ 0`) from its class against the
    /// implicit surfaces alone (`implicit`, searched over the same parameters): Hit where
    /// the first of the two, the implicit surfaces or a triangle
    /// ([`Bvh::beam_hit`](super::Bvh::beam_hit)), is proven for every ray; else Undecided
    /// from the earlier of the two ranges where a ray may meet a surface.
    pub fn primary_beam(&self, implicit: BoxClass, beam: &Beam, window: Interval<f64>) -> BoxClass {
        let window = window.intersection(forward());
        let Some(tm) = self.beam_first(beam, window) else {
            return implicit;
        };
        let covered = self.bvh().beam_hit(beam, window).map(|(t, _)| t);
        with_triangles(implicit, tm, covered)
    }

    /// A shadow beam's class over `window` from its class against the implicit surfaces
    /// alone (`implicit`, searched over the same parameters): blocked by the implicit
    /// surfaces is blocked whatever the triangles do; with `inclusion`, a beam whose every
    /// ray crosses one triangle is blocked there ([`Bvh::covering`](super::Bvh::covering));
    /// else Undecided from the earlier of the two ranges where a ray may meet a surface.
    ///
    /// A shadow beam asks only whether its segments are blocked, so its Hit is weaker than
    /// a primary beam's: every ray meets a surface (an implicit one or a triangle) in
    /// `t_final`, but another surface may come first on some rays. What a shadow method
    /// takes from it (blocked; or a sub-beam's search started at `inf t_final`, where each
    /// of its rays still meets the same surface) holds either way.
    pub fn shadow_beam(
        &self,
        implicit: BoxClass,
        beam: &Beam,
        window: Interval<f64>,
        inclusion: bool,
    ) -> BoxClass {
        match (implicit, self.beam_first(beam, window)) {
            (class @ BoxClass::Hit { .. }, _) | (class, None) => class,
            (class, Some(tm)) => {
                let covered = inclusion
                    .then(|| self.bvh().covering(beam, window))
                    .flatten();
                match covered {
                    Some((t_final, _)) => BoxClass::Hit { t_final },
                    None => with_triangles(class, tm, None),
                }
            }
        }
    }

    /// The first root along `ray` for parameters in `window` (already clipped to `t ≥ 0`)
    /// from the first root of the implicit surfaces there (`implicit`) and the first
    /// crossing of a triangle ([`RootResult::first_of`]).
    pub fn first_root(&self, implicit: RootResult, ray: &Ray, window: Interval<f64>) -> RootResult {
        implicit.first_of(self.bvh().first_crossing(ray, window).result)
    }
}
