//! The soft-shadow pass: the visible fraction of each area light from each shaded sample,
//! by the scene's [`ShadowMethod`], with per-light counters and the proven shadow class of
//! every pixel.

use std::time::Instant;

use glam::DVec3;
use interval_core::Interval;
use rayon::prelude::*;

use super::{Evals, SHADOW_OFFSET, Sample, Tracer};
use crate::beam::{BeamSettings, BoxClass, Extent, evaluate_box, rejection_search};
use crate::image::Image;
use crate::ray::{Beam, Ray, point_box};
use crate::render::Progress;
use crate::root::{RootCounters, RootResult};
use crate::scene::AreaLight;
use crate::shadow::hard::segment_visibility;
use crate::shadow::{
    LightVisibility, Occluders, Occlusion, Patch, ShadowClass, ShadowMethod, ShadowQuery,
    ShadowWork, stochastic,
};
use crate::stats::PassStats;

/// The scene's occluders as the shadow methods see them: the tracer and one thread's
/// evaluators.
pub(crate) struct SceneOccluders<'t, 'e> {
    pub(crate) tracer: &'t Tracer<'t>,
    pub(crate) ev: &'e mut Evals,
}

impl Occluders for SceneOccluders<'_, '_> {
    fn segment(&mut self, from: DVec3, to: DVec3, start: f64, c: &mut RootCounters) -> Occlusion {
        let ray = Ray {
            origin: from,
            dir: to - from,
        };
        let r = self
            .tracer
            .cast(self.ev, &ray, Interval::new_unchecked(start, 1.0), c);
        let at = match r {
            RootResult::Root { t, .. } | RootResult::Undecided { t } if t.mid().is_finite() => {
                Some(t.mid())
            }
            _ => None,
        };
        Occlusion {
            visibility: segment_visibility(r, self.tracer.finder.is_reliable()),
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
            &self.tracer.scene.geometry.bounds(),
            Interval::new_unchecked(0.0, 1.0),
        ) else {
            return false;
        };
        let Some(eval) = self.ev.geo.objects.get_mut(object as usize) else {
            return false;
        };
        eval.set_ray(&ray);
        matches!(
            self.tracer.finder.first_root(eval, t, &self.tracer.plan.root, c),
            RootResult::Root { proof, .. } if proof != crate::root::Proof::Possible
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
            .tracer
            .beam_ranges(&beam, Interval::new_unchecked(start, 1.0));
        if ranges.is_empty() {
            return BoxClass::Miss;
        }
        let settings = self.tracer.shadow_beam_settings(from, light);
        self.ev.geo.beam.set_beam(&beam);
        if !inclusion {
            return rejection_search(&mut self.ev.geo.beam, &ranges, &settings, c);
        }
        let bounds = self.tracer.scene.geometry.bounds();
        let extent = Extent {
            beam: &beam,
            bounds: &bounds,
        };
        evaluate_box(&mut self.ev.geo.beam, &ranges, Some(&extent), &settings, c)
    }
}

impl Tracer<'_> {
    /// The beam tolerances of a shadow beam from `from` over `light` (`t ∈ [0, 1]`): pieces
    /// down to a tenth of the shadow offset in length, so that the first piece can be
    /// cleared of the surface the beam leaves; no `T_final` refinement.
    fn shadow_beam_settings(&self, from: DVec3, light: &Patch) -> BeamSettings {
        let reach = light
            .corners()
            .iter()
            .map(|c| c.distance(from))
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        let offset = SHADOW_OFFSET * self.scene.geometry.diagonal();
        BeamSettings {
            epsilon: 0.1 * offset / reach,
            rel_epsilon: SHADOW_REL_EPSILON,
            refine_steps: 0,
            ..self.plan.beam
        }
    }
}

/// Width of a shadow beam's final pieces relative to their parameter (see
/// [`BeamSettings::rel_epsilon`]).
const SHADOW_REL_EPSILON: f64 = 1.0 / 16.0;

/// What the soft-shadow pass produces.
pub(crate) struct SoftShadows {
    /// The pass's summed statistics.
    pub(crate) pass: PassStats,
    /// Per area light: its statistics.
    pub(crate) lights: Vec<PassStats>,
    /// Per pixel, the proven class over every area light (`None`: no shaded sample).
    pub(crate) classes: Vec<Option<ShadowClass>>,
    /// Per area light, per pixel: the visible fraction averaged over the pixel's shaded
    /// samples (NaN where there is none).
    pub(crate) fractions: Vec<Vec<f32>>,
}

/// Counters of one light, in the order they are reported.
const LABELS: [&str; 12] = [
    "pixels_in_shadow",
    "lit_pixels",
    "umbra_pixels",
    "penumbra_pixels",
    "queries",
    "back_facing",
    "initial_beams",
    "initial_beams_occluded",
    "umbra_proofs",
    "sub_beams",
    "rays",
    "cache_hits",
];

/// The soft-shadow pass: for each area light in turn (so that each has its own time), the
/// visible fraction from every hit sample, written to `vis` at the light's index `li` of
/// the `nl` lights (sample-major, light-minor per pixel).
pub(crate) fn soft_shadow_pass(
    tracer: &Tracer<'_>,
    samples: &[Vec<Sample>],
    lights: &[(usize, AreaLight)],
    nl: usize,
    vis: &mut [Vec<f32>],
    progress: &dyn Progress,
) -> SoftShadows {
    let w = tracer.scene.camera.width() as usize;
    let t0 = Instant::now();
    let method = tracer.plan.shadow_method.method();
    let mut classes: Vec<Option<ShadowClass>> = vec![None; samples.len()];
    let mut per_light = Vec::with_capacity(lights.len());
    let mut fractions = Vec::with_capacity(lights.len());
    let mut total = [0u64; LABELS.len()];
    let mut total_root = RootCounters::default();
    for &(li, light) in lights {
        let tl = Instant::now();
        progress.begin(
            &format!("soft-shadows light {li}"),
            (samples.len() / w.max(1)) as u64,
        );
        type Row = (
            [u64; LABELS.len()],
            ShadowWork,
            Vec<Option<ShadowClass>>,
            Vec<f32>,
        );
        let rows: Vec<Row> = samples
            .par_chunks(w)
            .zip(vis.par_chunks_mut(w))
            .enumerate()
            .map_init(
                || tracer.evals(),
                |ev, (y, (srow, vrow))| {
                    let mut items = [0u64; LABELS.len()];
                    let mut work = ShadowWork::default();
                    let mut row_classes = Vec::with_capacity(srow.len());
                    let mut row_fractions = Vec::with_capacity(srow.len());
                    for (x, (px, v)) in srow.iter().zip(vrow.iter_mut()).enumerate() {
                        let pixel = (y * w + x) as u64;
                        let mut class: Option<ShadowClass> = None;
                        let mut shadowed = false;
                        let (mut sum, mut weight) = (0f32, 0f32);
                        for (si, s) in px.iter().enumerate() {
                            let Some(hit) = s.hit else { continue };
                            let seed = stochastic::seed(pixel, si as u32, li as u32);
                            let (lv, sample_class) = sample_visibility(
                                tracer, ev, &*method, &hit, &light, seed, &mut items, &mut work,
                            );
                            v[si * nl + li] = lv.fraction;
                            sum += s.weight * lv.fraction;
                            weight += s.weight;
                            shadowed |= lv.fraction < 1.0;
                            class = Some(ShadowClass::merge(class, sample_class));
                        }
                        items[0] += u64::from(shadowed);
                        match class {
                            Some(ShadowClass::Lit) => items[1] += 1,
                            Some(ShadowClass::Umbra) => items[2] += 1,
                            Some(ShadowClass::Penumbra) => items[3] += 1,
                            Some(ShadowClass::BackFacing) | None => {}
                        }
                        row_classes.push(class);
                        row_fractions.push(if weight > 0.0 { sum / weight } else { f32::NAN });
                    }
                    progress.advance(1);
                    (items, work, row_classes, row_fractions)
                },
            )
            .collect();
        progress.end();
        let mut items = [0u64; LABELS.len()];
        let mut work = ShadowWork::default();
        let mut light_fractions = Vec::with_capacity(samples.len());
        for (i, (it, wk, row_classes, row_fractions)) in rows.into_iter().enumerate() {
            light_fractions.extend(row_fractions);
            for (a, b) in items.iter_mut().zip(it) {
                *a += b;
            }
            work.add(&wk);
            for (k, c) in row_classes.into_iter().enumerate() {
                let slot = &mut classes[i * w + k];
                if let Some(c) = c {
                    *slot = Some(ShadowClass::merge(*slot, c));
                }
            }
        }
        items[4] = work.queries;
        items[6] = work.initial_beams;
        items[7] = work.initial_occluded;
        items[8] = work.umbra_proofs;
        items[9] = work.sub_beams;
        items[10] = work.rays;
        items[11] = work.cache_hits;
        for (a, b) in total.iter_mut().zip(items) {
            *a += b;
        }
        total_root.add(&work.root);
        fractions.push(light_fractions);
        per_light.push(stats(
            &format!("light {li} ({})", method.name()),
            tl.elapsed(),
            &items,
            &work.root,
        ));
    }
    SoftShadows {
        pass: stats("soft-shadows", t0.elapsed(), &total, &total_root),
        lights: per_light,
        classes,
        fractions,
    }
}

/// The visible fraction of `light` from one hit and its class: with the whole light behind
/// the tangent plane the point gets no direct light (fraction 0, class
/// [`ShadowClass::BackFacing`], no test); otherwise the method answers from the point moved
/// off the surface.
#[allow(clippy::too_many_arguments)]
fn sample_visibility(
    tracer: &Tracer<'_>,
    ev: &mut Evals,
    method: &dyn ShadowMethod,
    hit: &super::Hit,
    light: &AreaLight,
    seed: u64,
    items: &mut [u64; LABELS.len()],
    work: &mut ShadowWork,
) -> (LightVisibility, ShadowClass) {
    if light.patch.is_behind(hit.point, hit.facing_normal()) {
        items[5] += 1;
        return (LightVisibility::estimate(0.0), ShadowClass::BackFacing);
    }
    let origin = hit.shadow_origin(SHADOW_OFFSET * tracer.scene.geometry.diagonal());
    let q = ShadowQuery {
        origin,
        light: light.patch,
        seed,
    };
    let mut occluders = SceneOccluders { tracer, ev };
    let lv = method.visibility(&mut occluders, &q, work);
    (lv, lv.class())
}

fn stats(
    name: &str,
    time: std::time::Duration,
    items: &[u64; LABELS.len()],
    root: &RootCounters,
) -> PassStats {
    PassStats::with_search(name, time, &LABELS, items, root)
}

/// The shadow classification image (the soft-shadow paper's Fig. 7): proven lit (green),
/// proven umbra (blue), penumbra (orange), facing away from the light (dark blue-grey), no
/// shaded surface (dark grey).
pub fn shadow_class_image(w: u32, h: u32, classes: &[Option<ShadowClass>]) -> Image {
    let pixels = classes
        .iter()
        .map(|c| match c {
            None => [0.15, 0.15, 0.15],
            Some(ShadowClass::Lit) => [0.35, 0.8, 0.3],
            Some(ShadowClass::Umbra) => [0.15, 0.25, 0.75],
            Some(ShadowClass::Penumbra) => [0.95, 0.55, 0.1],
            Some(ShadowClass::BackFacing) => [0.25, 0.27, 0.35],
        })
        .collect();
    Image {
        width: w,
        height: h,
        pixels,
    }
}
