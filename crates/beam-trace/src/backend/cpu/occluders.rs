//! The scene's occluders as the CPU answers the shadow methods' questions: segments and
//! shadow beams searched through the grid, single objects for the last-occluder cache.

use glam::DVec3;
use interval_core::Interval;

use super::queries::{CpuQueries, Evals};
use crate::beam::{BoxClass, Extent, evaluate_box, rejection_search};
use crate::ray::{Beam, Ray, point_box};
use crate::root::{Proof, RootCounters, RootFinder, RootResult};
use crate::shadow::beam::shadow_beam_settings;
use crate::shadow::hard::segment_visibility;
use crate::shadow::{Occluders, Occlusion, Patch};

/// The scene's occluders as the shadow methods see them: the CPU queries and one thread's
/// evaluators.
pub(super) struct SceneOccluders<'q, 'a, 'e> {
    pub(super) queries: &'q CpuQueries<'a>,
    pub(super) ev: &'e mut Evals,
}

impl Occluders for SceneOccluders<'_, '_, '_> {
    fn segment(&mut self, from: DVec3, to: DVec3, start: f64, c: &mut RootCounters) -> Occlusion {
        let ray = Ray {
            origin: from,
            dir: to - from,
        };
        let r = self
            .queries
            .cast(self.ev, &ray, Interval::new_unchecked(start, 1.0), None, c);
        let at = match r {
            RootResult::Root { t, .. } | RootResult::Undecided { t } if t.mid().is_finite() => {
                Some(t.mid())
            }
            _ => None,
        };
        Occlusion {
            visibility: segment_visibility(r, self.queries.finder.is_reliable()),
            at,
        }
    }

    fn object_at(&mut self, p: DVec3) -> u32 {
        self.ev.geo.object_at(p) as u32
    }

    fn segment_meets_object(
        &mut self,
        object: u32,
        from: DVec3,
        to: DVec3,
        c: &mut RootCounters,
    ) -> bool {
        let ray = Ray {
            origin: from,
            dir: to - from,
        };
        let Some(t) = ray.beam().t_range_within(
            &self.queries.scene.geometry.bounds(),
            Interval::new_unchecked(0.0, 1.0),
        ) else {
            return false;
        };
        let Some(eval) = self.ev.geo.objects.get_mut(object as usize) else {
            return false;
        };
        eval.set_ray(&ray);
        matches!(
            self.queries.finder.first_root(eval, t, &self.queries.plan.root, c),
            RootResult::Root { proof, .. } if proof != Proof::Possible
        )
    }

    fn beam(
        &mut self,
        from: DVec3,
        light: &Patch,
        start: f64,
        inclusion: bool,
        c: &mut RootCounters,
    ) -> BoxClass {
        let beam = Beam {
            origin: point_box(from),
            dir: light.directions_from(from),
        };
        let ranges = self
            .queries
            .beam_ranges(&beam, Interval::new_unchecked(start, 1.0));
        if ranges.is_empty() {
            return BoxClass::Miss;
        }
        let settings = shadow_beam_settings(
            &self.queries.plan.beam,
            self.queries.scene.geometry.diagonal(),
            from,
            light,
        );
        self.ev.geo.beam.set_beam(&beam);
        if !inclusion {
            return rejection_search(&mut self.ev.geo.beam, &ranges, &settings, c);
        }
        let bounds = self.queries.scene.geometry.bounds();
        let extent = Extent {
            beam: &beam,
            bounds: &bounds,
        };
        evaluate_box(&mut self.ev.geo.beam, &ranges, Some(&extent), &settings, c)
    }
}
