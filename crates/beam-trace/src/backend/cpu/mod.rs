//! The CPU backend: every query answered in parallel with rayon, through the regular grid
//! when the plan builds one, with the plan's root finder and beam tests.

mod occluders;
mod queries;
mod scoped;

pub use queries::CpuQueries;
use scoped::ScopedFunctions;

use std::sync::{Mutex, OnceLock};
use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;

use super::query::{
    Answers, BeamQuery, CellQuery, Classified, DirectHits, HitQuery, QueryKind, RayQuery,
    SegmentQuery, ShadeBatch, SoftAnswers, Support, VariationQuery,
};
use super::traits::{Backend, Prepared, Queries};
use crate::aa::{LightSource, shading_variation};
use crate::error::Error;
use crate::frustum::TileCells;
use crate::grid::Grid;
use crate::ibox::point_box;
use crate::mesh::MeshIndex;
use crate::plan::{Pass, Plan};
use crate::progress::Progress;
use crate::root::{Escalating, RootFinder, RootResult};
use crate::sample::Hit;
use crate::scene::{Material, Scene};
use crate::shading::{Incoming, phong};
use crate::shadow::hard::{Visibility, segment_visibility};
use crate::shadow::{ShadowQuery, ShadowSpec, ShadowWork};
use crate::stats::PassStats;
use crate::stats::counters::GridCounters;
use occluders::{SceneOccluders, ThinForms};

/// Soft-shadow queries per run handed to a method together
/// ([`ShadowMethod::visibility_run`](crate::shadow::ShadowMethod::visibility_run)): as many
/// as the exact method's largest group.
const SHADOW_RUN: usize = crate::shadow::ShadowSpec::MAX_EXACT_GROUP as usize;

/// The CPU backend.
#[derive(Copy, Clone, Debug, Default)]
pub struct Cpu;

impl Backend for Cpu {
    fn name(&self) -> String {
        "cpu".into()
    }

    fn support(&self, _kind: QueryKind, _scene: &Scene, _plan: &Plan) -> Support {
        Support::Yes
    }

    fn prepare<'a>(
        &'a self,
        scene: &'a Scene,
        plan: &'a Plan,
        kinds: &[QueryKind],
    ) -> Result<Prepared<'a>, Error> {
        // Only searches go through the grid.
        let searches = kinds.iter().any(|k| {
            matches!(
                k,
                QueryKind::Beams | QueryKind::Roots | QueryKind::Segments | QueryKind::SoftShadows
            )
        });
        let (grid, stats) = match plan.grid {
            Some(res) if searches => {
                let t0 = Instant::now();
                let g = Grid::build(&scene.geometry, res);
                let s = g.stats();
                let counters = GridCounters {
                    cells: s.cells,
                    non_empty: s.non_empty,
                    functions: s.functions,
                    reduced: s.reduced,
                    cell_instrs: s.cell_instrs,
                    full_instrs: s.full_instrs,
                    leaf_evals: s.leaf_evals,
                };
                (Some(g), PassStats::of(Pass::Grid, t0.elapsed(), &counters))
            }
            _ => (None, PassStats::skipped(Pass::Grid.name())),
        };
        let scoped = ScopedFunctions::new(grid.as_ref());
        Ok(Prepared {
            queries: Box::new(CpuQueries {
                scene,
                plan,
                grid,
                finder: Escalating::new(plan.root_finder.finder()),
                scoped,
                meshes: (!scene.meshes.is_empty())
                    .then(|| MeshIndex::new(scene.meshes.iter().map(|m| m.triangles.as_slice()))),
                diagonal: scene.diagonal(),
                pool: Mutex::new(Vec::new()),
                edge_beams: OnceLock::new(),
            }),
            passes: vec![stats],
        })
    }
}

impl Queries for CpuQueries<'_> {
    fn beams(&self, queries: &[BeamQuery]) -> Result<Answers<Classified>, Error> {
        Ok(self.map(queries, true, |ev, q, c| self.classify(ev, q, c)))
    }

    fn first_cells(
        &self,
        queries: &[CellQuery],
        progress: &dyn Progress,
    ) -> Result<Answers<TileCells>, Error> {
        if !self.scene.meshes.is_empty() {
            return Err(Error::Backend {
                backend: "cpu".into(),
                message: "the frustum octree (primary = \"octree\") does not search triangle \
                          meshes; render this scene with primary = \"screen-boxes\", \
                          \"screen-rays\" or \"per-pixel\""
                    .into(),
            });
        }
        // A tile is much work, and neighbouring tiles share prunings and compiled tapes:
        // the tiles are taken in order by whichever thread is free.
        Ok(self.map_pulled(queries, |ev, q, c| {
            let cells = self.cells(ev, q, c);
            progress.advance(q.tile.area());
            cells
        }))
    }

    fn roots(&self, queries: &[RayQuery]) -> Result<Answers<RootResult>, Error> {
        let root = self.plan.ray_root();
        Ok(self.map(queries, true, |ev, q, c| {
            self.cast(ev, &q.ray, q.window, (q.scope.as_ref(), &root), c)
        }))
    }

    fn hit_points(&self, queries: &[HitQuery]) -> Result<Answers<Hit>, Error> {
        // Timed where the plan narrows each hit's root (a search); otherwise a hit point
        // costs about as much as reading the clock (tens of nanoseconds), the same at
        // every pixel, and timing it would only add that to the cost map.
        Ok(self.map(queries, self.plan.narrow_hits, |ev, q, c| {
            self.hit(ev, &q.ray, q.t, q.scope.as_ref(), c)
        }))
    }

    fn direct_hits(&self) -> Option<DirectHits> {
        CpuQueries::direct_hits(self)
    }

    fn shading_variation(&self, queries: &[VariationQuery]) -> Result<Answers<f64>, Error> {
        let lights: Vec<LightSource> = self
            .scene
            .lights
            .iter()
            .map(|l| LightSource {
                position: l.center().to_array(),
                color: l.color(),
            })
            .collect();
        // The point lights (hard shadows) by their index in `lights`.
        let point_lights: Vec<Option<DVec3>> = self
            .scene
            .lights
            .iter()
            .map(|l| l.as_point().map(|p| p.position))
            .collect();
        Ok(self.map(queries, true, |ev, q, c| {
            let region = q.beam.points(q.t_final);
            // A beam proven to hit one triangle ([`Bvh::beam_hit`]) has that triangle's
            // normal and material over its region; inside `T_final` its central ray
            // crosses a triangle only then.
            let on_mesh = self.meshes.as_ref().and_then(|m| {
                let tri = m
                    .bvh()
                    .first_crossing(&q.beam.central_ray(), q.t_final)
                    .triangle?;
                let mesh = &self.scene.meshes[m.owner(tri) as usize];
                Some((point_box(m.normal(tri)), vec![mesh.material]))
            });
            let (grad, materials) = match on_mesh {
                Some(x) => x,
                None => {
                    let (_, grad) = ev.geo.gradient_box(&region);
                    let leaves = self.scene.geometry.leaves();
                    let materials: Vec<Material> = ev
                        .geo
                        .leaves_over(&region)
                        .into_iter()
                        .map(|i| leaves[i].material)
                        .collect();
                    (grad, materials)
                }
            };
            let v = shading_variation(
                grad,
                region,
                q.beam.origin,
                &materials,
                self.scene.ambient,
                &lights,
            );
            if v.spread > q.threshold {
                return v.spread;
            }
            // The point lights whose shadow could change the colour by more than the
            // threshold allows: their shadows must be the same over the whole region.
            let judged: Vec<DVec3> = point_lights
                .iter()
                .zip(&v.light_terms)
                .filter(|&(_, &term)| v.spread + term > q.threshold)
                .filter_map(|(p, _)| *p)
                .collect();
            let region = (&grad, &region, &q.beam.origin);
            if self.hard_shadows_uniform(ev, region, &judged, c) {
                v.spread
            } else {
                f64::INFINITY
            }
        }))
    }

    fn normals(&self, points: &[DVec3]) -> Result<Answers<Option<DVec3>>, Error> {
        Ok(self.map(points, false, |ev, p, _| {
            match self.grid.as_ref().and_then(|g| g.scene_tape_at(*p)) {
                Some(tape) => ev.geo.normal_with(tape, *p),
                None => ev.geo.normal(*p),
            }
        }))
    }

    fn segments(&self, queries: &[SegmentQuery]) -> Result<Answers<Visibility>, Error> {
        Ok(self.map(queries, false, |ev, q, c| {
            let r = self.segment_search(ev, (q.from, q.to), 0.0, c);
            segment_visibility(r, self.finder.is_reliable())
        }))
    }

    fn soft_shadows(
        &self,
        method: &ShadowSpec,
        queries: &[ShadowQuery],
    ) -> Result<SoftAnswers, Error> {
        let method = method.method();
        // Runs of neighbouring samples, which a method may answer together; the runs are
        // cut at fixed places of the batch, so the answers do not depend on the threads.
        let answers: Vec<_> = queries
            .par_chunks(SHADOW_RUN)
            .map_init(
                || self.evals(),
                |ev, run| {
                    let mut work = ShadowWork::default();
                    let mut occluders = SceneOccluders {
                        queries: self,
                        ev,
                        thin_forms: ThinForms::default(),
                    };
                    (method.visibility_run(&mut occluders, run, &mut work), work)
                },
            )
            .collect();
        let mut work = ShadowWork::default();
        let mut visibility = Vec::with_capacity(queries.len());
        for (v, w) in answers {
            work.add(&w);
            visibility.extend(v);
        }
        Ok(SoftAnswers { visibility, work })
    }

    fn shade(&self, batch: &ShadeBatch<'_>) -> Result<Answers<[f32; 3]>, Error> {
        let nl = batch.lights.len();
        let colors = batch
            .samples
            .par_iter()
            .enumerate()
            .map_init(
                || Vec::with_capacity(nl),
                |incoming: &mut Vec<Incoming>, (i, s)| {
                    incoming.clear();
                    incoming.extend(
                        batch
                            .lights
                            .iter()
                            .zip(&batch.fractions[i * nl..(i + 1) * nl])
                            .map(|(l, f)| Incoming {
                                dir: (l.position - s.point).normalize_or_zero(),
                                color: l.color.map(|c| c * f),
                            }),
                    );
                    phong(&s.material, batch.ambient, s.normal, s.to_eye, incoming)
                },
            )
            .collect();
        Ok(Answers::free(colors))
    }
}
