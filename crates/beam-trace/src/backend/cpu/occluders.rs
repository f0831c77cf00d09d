//! The scene's occluders as the CPU answers the shadow methods' questions: segments and
//! shadow beams searched through the grid, single objects for the last-occluder cache.

use glam::DVec3;
use interval_core::Interval;

use super::queries::{CpuQueries, Evals};
use crate::aa::{facing, shadow_origins};
use crate::beam::{
    BeamSettings, BoxClass, Extent, evaluate_box, evaluate_box_near, rejection_search,
};
use crate::ibox::{IBox, ipoint};
use crate::mesh::Shaft;
use crate::ray::{Beam, Ray, point_box};
use crate::root::{Proof, RootCounters, RootFinder, RootResult};
use crate::sample::SHADOW_OFFSET;
use crate::shadow::beam::{inner_beam_settings, shadow_beam_settings};
use crate::shadow::hard::segment_visibility;
use crate::shadow::{BeamStart, Occluders, Occlusion, Patch, ShaftTriangle};

/// Pieces of a shadow beam asked to prove both ways (free or blocked) try the mean-value
/// form where their natural enclosure holds 0 ([`crate::ray::BeamEval::set_centred_fallback`])
/// up to `1/CENTRED_PIECES` of the scene's diagonal wide. Counted on
/// `scenes/soft-shadows.toml` with `certified:0.5`: of the pieces tried between 1/100 and
/// 1/50 of the diagonal a third were decided by the form, between 1/50 and 1/25 1.5 %,
/// wider ones none (120 k tries, a fifth of all, for nothing).
const CENTRED_PIECES: f64 = 64.0;

/// Shadow beams narrower than this (the largest width of their directions over the length
/// of the longest, about radians) try the mean-value form only while it decides enough of
/// their pieces ([`ThinForms`]): over a thin beam the natural enclosure is often tight
/// (a sphere, a rod), and the form's gradient is then paid for nothing. Measured on
/// `scenes/soft-shadows.toml` at 128 × 96, the soft-shadow pass of `certified:0.5`,
/// `certified:0.25` and `certified:0.1` took 1.8, 4.1 and 9.2 s with this limit and no
/// thin beam trying, 1.7, 4.7 and 12.3 s with every beam trying, 1.9, 5.8 and 8.2 s with
/// 0.03, and 7.4, 9.0 and 11.9 s with no mean-value form at all (before the finer pieces
/// of the certified parts).
const CENTRED_MIN_SPREAD: f64 = 0.01;

/// Whether `beam` is no thinner than [`CENTRED_MIN_SPREAD`] (NaN, a beam without length,
/// counts as thin).
fn is_wide(beam: &Beam) -> bool {
    beam.angular_spread() >= CENTRED_MIN_SPREAD
}

/// Thin shadow beams (see [`CENTRED_MIN_SPREAD`]) of one query try the mean-value form for
/// their first `THIN_TRIAL` tries, and after that while it decides at least one in
/// [`THIN_SHARE`] of them.
/// On `scenes/soft-shadows.toml` (`certified:0.05`, `0.1`, `0.25`, `0.5`) a trial of 4 to
/// 32 tries gives the same beams and bounds as trying always.
const THIN_TRIAL: u64 = 8;

/// See [`THIN_TRIAL`].
const THIN_SHARE: u64 = 20;

/// What the mean-value form did for the thin shadow beams of one query (one point's beams
/// over the light: the record starts afresh at each point, so a point's answer does not
/// depend on the points asked before it, nor on how the render is cut into windows).
/// On `scenes/soft-shadows.toml` it decides 29 % of the pieces of the torus penumbra it
/// is tried on, and proves the parts grazing it that the natural enclosure leaves
/// undecided at any depth; on `scenes/thin-occluder.toml` (rods and a floor, whose natural
/// enclosures are tight) none of 630 k tries, which doubled the pass.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct ThinForms {
    /// The point whose beams the record is of.
    from: Option<DVec3>,
    tries: u64,
    decided: u64,
}

impl ThinForms {
    /// Starts the record afresh where `from` is not the point of the beams before.
    fn of_point(&mut self, from: DVec3) {
        if self.from != Some(from) {
            *self = ThinForms {
                from: Some(from),
                ..ThinForms::default()
            };
        }
    }

    /// Whether the next thin beam tries the form.
    fn worth_trying(&self) -> bool {
        self.tries < THIN_TRIAL || self.decided * THIN_SHARE >= self.tries
    }

    /// Adds what a thin beam's search did: the evaluator's
    /// [`centred_record`](crate::ray::BeamEval::centred_record) before and after it.
    fn add(&mut self, before: (u64, u64), after: (u64, u64)) {
        self.tries += after.0 - before.0;
        self.decided += after.1 - before.1;
    }
}

/// The scene's occluders as the shadow methods see them: the CPU queries and one thread's
/// evaluators.
pub(super) struct SceneOccluders<'q, 'a, 'e> {
    pub(super) queries: &'q CpuQueries<'a>,
    pub(super) ev: &'e mut Evals,
    /// What the mean-value form did for thin beams in this run.
    pub(super) thin_forms: ThinForms,
}

impl Occluders for SceneOccluders<'_, '_, '_> {
    fn segment(&mut self, from: DVec3, to: DVec3, start: f64, c: &mut RootCounters) -> Occlusion {
        let r = self.queries.segment_search(self.ev, (from, to), start, c);
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
        start: BeamStart,
        inclusion: bool,
        c: &mut RootCounters,
    ) -> BoxClass {
        let (beam, settings) = self.light_beam(from, light, start);
        self.with_thin_forms(from, &beam, |q, ev, forms| {
            q.shadow_beam(ev, &beam, (start, inclusion, forms), &settings, c)
        })
    }

    fn triangles(&mut self, from: &IBox, light: &Patch) -> Vec<ShaftTriangle> {
        let Some(m) = &self.queries.meshes else {
            return Vec::new();
        };
        let corners = light.corners();
        // The box of the shaft, then the triangles that some line of the shadow beam from
        // the points `from` over the whole light may meet (the others are proven outside
        // the shaft).
        let light_box = light.bounding_box();
        m.bvh()
            .in_shaft(&Shaft::new(from, &light_box))
            .into_iter()
            .map(|i| ShaftTriangle {
                triangle: *m.bvh().triangle(i),
                redundant: m.turned_away(i, &light_box, &corners),
                face: m.face_of(i),
            })
            .collect()
    }

    fn faces(&mut self, triangles: &[ShaftTriangle]) -> Vec<Vec<DVec3>> {
        let Some(m) = &self.queries.meshes else {
            return Vec::new();
        };
        // A face's triangles are of one mesh, one plane and one facing: redundant alike.
        let mut seen = std::collections::HashSet::new();
        triangles
            .iter()
            .filter(|t| !t.redundant && seen.insert(t.face))
            .map(|t| m.face(t.face).to_vec())
            .collect()
    }

    fn inner_occluders(&mut self, from: &IBox, light: &Patch) -> Vec<Vec<DVec3>> {
        let Some(m) = &self.queries.meshes else {
            return Vec::new();
        };
        let light_box = light.bounding_box();
        let middle = DVec3::from_array(std::array::from_fn(|k| from[k].mid()));
        m.inner_in(
            &Shaft::new(from, &light_box),
            &light_box,
            light.center() - middle,
        )
    }

    fn implicit_beam(
        &mut self,
        from: DVec3,
        light: &Patch,
        start: BeamStart,
        inclusion: bool,
        c: &mut RootCounters,
    ) -> BoxClass {
        let (beam, settings) = self.light_beam(from, light, start);
        self.with_thin_forms(from, &beam, |q, ev, forms| {
            q.shadow_beam_implicit(ev, &beam, (start, inclusion, forms), &settings, c)
        })
    }
}

impl SceneOccluders<'_, '_, '_> {
    /// `search` (a shadow beam's, told whether the beam may try the mean-value form) for
    /// `beam` from the point `from`: a wide beam may, a thin one as the point's
    /// [`ThinForms`] say, and what the form did for it is added there.
    fn with_thin_forms(
        &mut self,
        from: DVec3,
        beam: &Beam,
        search: impl FnOnce(&CpuQueries<'_>, &mut Evals, bool) -> BoxClass,
    ) -> BoxClass {
        if is_wide(beam) {
            return search(self.queries, self.ev, true);
        }
        self.thin_forms.of_point(from);
        let before = self.ev.geo.beam.centred_record();
        let class = search(self.queries, self.ev, self.thin_forms.worth_trying());
        self.thin_forms
            .add(before, self.ev.geo.beam.centred_record());
        class
    }

    /// The shadow beam from `from` over `light`, and its search settings (finer for
    /// [`BeamStart::Finer`], [`inner_beam_settings`]).
    fn light_beam(&self, from: DVec3, light: &Patch, start: BeamStart) -> (Beam, BeamSettings) {
        let beam = Beam {
            origin: point_box(from),
            dir: light.directions_from(from),
        };
        let settings = shadow_beam_settings(
            &self.queries.plan.beam,
            self.queries.scene.geometry.diagonal(),
            from,
            light,
        );
        let settings = match start {
            BeamStart::Finer(_) => inner_beam_settings(&settings, from, light),
            BeamStart::At(_) | BeamStart::Near(_) => settings,
        };
        (beam, settings)
    }
}

impl CpuQueries<'_> {
    /// Whether the shadow of every point light at `lights` is judged the same over a hit
    /// region (`gradient`, the points `region`, seen from `eye`), so that one sample's
    /// shadow query may stand for all of them: the shadow beam of the region's samples'
    /// own shadow rays to the light is proven free or proven blocked, or the light is
    /// behind the surface at every point (no sample asks). The region's box holds points on
    /// both sides of the surface (its rays over the whole section `T_final`), and rays from
    /// those inside the solid would be blocked by the surface itself; so the beam is
    /// searched from where every ray has left the region's slab ([`shadow_origins`],
    /// [`ShadowStarts::clear_from`](crate::aa::ShadowStarts::clear_from)). An estimate for
    /// deciding splits: an occluder inside that slab is not seen (each sample's own segment
    /// still decides its shade). `false` where the origins cannot be bounded (the normal
    /// may turn either way over the region) or some ray may not leave the slab.
    pub(super) fn hard_shadows_uniform(
        &self,
        ev: &mut Evals,
        (gradient, region, eye): (&IBox, &IBox, &IBox),
        lights: &[DVec3],
        c: &mut RootCounters,
    ) -> bool {
        if lights.is_empty() {
            return true;
        }
        let diagonal = self.scene.geometry.diagonal();
        let offset = SHADOW_OFFSET * self.diagonal;
        let Some(starts) = shadow_origins(gradient, region, eye, offset) else {
            return false;
        };
        let origins = starts.origins;
        let centre = DVec3::from_array(std::array::from_fn(|i| origins[i].mid()));
        lights.iter().all(|&light| {
            let to = point_box(light);
            // The facing normal's product with the direction to the light, over the region:
            // at most zero everywhere, and no sample casts a segment.
            if (ipoint(starts.side) * facing(gradient, region, &to)).sup() <= 0.0 {
                return true;
            }
            let beam = Beam {
                origin: origins,
                dir: std::array::from_fn(|i| to[i] - origins[i]),
            };
            // The samples' own shadow rays, searched past the region's slab; where they may
            // not leave it (a grazing light), the shadow is not judged uniform.
            let Some(start) = starts.clear_from(&beam.dir) else {
                return false;
            };
            let patch = Patch {
                corner: light,
                edge_u: DVec3::ZERO,
                edge_v: DVec3::ZERO,
            };
            let settings = shadow_beam_settings(&self.plan.beam, diagonal, centre, &patch);
            !matches!(
                self.shadow_beam(
                    ev,
                    &beam,
                    (BeamStart::At(start), true, is_wide(&beam)),
                    &settings,
                    c
                ),
                BoxClass::Undecided { .. }
            )
        })
    }

    /// The search of the shadow segment `from → to` (`t = 1` at `to`) for `t ∈ [start, 1]`.
    /// Blocked or not is what a segment asks (and, for the occluder cache, a point near an
    /// occluder): a root proven to exist is not narrowed ([`RootSettings::existence`](crate::root::RootSettings::existence)).
    pub(super) fn segment_search(
        &self,
        ev: &mut Evals,
        (from, to): (DVec3, DVec3),
        start: f64,
        c: &mut RootCounters,
    ) -> RootResult {
        let ray = Ray {
            origin: from,
            dir: to - from,
        };
        let root = self.plan.root.existence();
        let t = Interval::new_unchecked(start, 1.0);
        self.cast(ev, &ray, t, (None, &root), c)
    }

    /// A shadow beam (rays `origin + t·dir` to the light at `t = 1`) searched for
    /// `t ∈ [start, 1]` through the grid's non-empty cells with `settings`:
    /// [`BoxClass::Miss`] proves that no ray meets a surface there; with `inclusion`,
    /// [`BoxClass::Hit`] that every ray does; else [`BoxClass::Undecided`]. With `forms`
    /// and `inclusion`, pieces whose natural enclosure is loose try the mean-value form
    /// ([`CENTRED_PIECES`]).
    pub(super) fn shadow_beam(
        &self,
        ev: &mut Evals,
        beam: &Beam,
        (start, inclusion, forms): (BeamStart, bool, bool),
        settings: &BeamSettings,
        c: &mut RootCounters,
    ) -> BoxClass {
        let window = Interval::new_unchecked(start.at(), 1.0);
        let implicit = self.shadow_beam_implicit(ev, beam, (start, inclusion, forms), settings, c);
        match &self.meshes {
            Some(m) => m.shadow_beam(implicit, beam, window, inclusion),
            None => implicit,
        }
    }

    /// [`shadow_beam`](Self::shadow_beam) against the implicit surfaces alone.
    pub(super) fn shadow_beam_implicit(
        &self,
        ev: &mut Evals,
        beam: &Beam,
        (start, inclusion, forms): (BeamStart, bool, bool),
        settings: &BeamSettings,
        c: &mut RootCounters,
    ) -> BoxClass {
        let ranges = self.beam_ranges(beam, Interval::new_unchecked(start.at(), 1.0));
        if ranges.is_empty() {
            return BoxClass::Miss;
        }
        ev.geo.beam.set_beam(beam);
        // A beam asked to prove both ways (free or blocked) is decided by the mean-value
        // form where the natural enclosure is loose ([`CENTRED_PIECES`]).
        let widest = self.scene.geometry.diagonal() / CENTRED_PIECES;
        ev.geo
            .beam
            .set_centred_fallback((inclusion && forms).then_some(widest));
        let bounds = self.scene.geometry.bounds();
        let extent = Extent {
            beam,
            bounds: &bounds,
        };
        let g = &mut ev.geo.beam;
        let class = match (start, inclusion) {
            (BeamStart::Near(near) | BeamStart::Finer(near), _) => {
                let extent = (inclusion.then_some(&extent), inclusion);
                evaluate_box_near(g, &ranges, extent, near, settings, c)
            }
            (BeamStart::At(_), true) => evaluate_box(g, &ranges, Some(&extent), settings, c),
            (BeamStart::At(_), false) => rejection_search(g, &ranges, settings, c),
        };
        ev.geo.beam.set_centred_fallback(None);
        class
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thin_beams_stop_trying_a_form_that_decides_nothing() {
        let mut record = ThinForms::default();
        record.of_point(DVec3::ONE);
        assert!(record.worth_trying());
        // The trial: tried whatever it decides.
        record.add((0, 0), (THIN_TRIAL - 1, 0));
        assert!(record.worth_trying());
        record.add((0, 0), (1, 0));
        assert!(!record.worth_trying());
        // Deciding one in `THIN_SHARE` of the tries keeps it tried.
        let mut record = ThinForms::default();
        record.of_point(DVec3::ZERO);
        record.add((5, 2), (5 + THIN_SHARE * THIN_TRIAL, 2 + THIN_TRIAL));
        assert!(record.worth_trying());
        record.add((0, 0), (1, 0));
        assert!(!record.worth_trying());
        // Another point starts afresh; the same point keeps its record.
        record.of_point(DVec3::ZERO);
        assert!(!record.worth_trying());
        record.of_point(DVec3::X);
        assert!(record.worth_trying());
    }
}
