//! The GPU as a backend of beam-trace's render pipeline: the beam, ray, segment and
//! shadow queries answered by the [`BeamKernel`], shading by the [`ShadingKernel`]. The
//! pipeline is beam-trace's; nothing here decides what a pass does.
//!
//! Triangle meshes are searched on the host, through beam-trace's hierarchy and tests, and
//! each beam's, ray's or segment's answer combined with the kernel's answer for the
//! implicit surfaces by the rules the CPU backend uses (`MeshIndex::primary_beam`,
//! `shadow_beam`, `first_root`): each is a proof about the same rays and parameters.
//!
//! What the GPU does not answer (placing shading points and normals, which need point and
//! gradient evaluations; the shading-variation estimator of IAA; the stochastic method's
//! last-occluder cache, which searches single objects; the exact method's trees; shading
//! beyond [`MAX_LIGHTS`] lights) it says in [`Backend::support`], and the routing sends to
//! the CPU.

use std::time::Instant;

use beam_trace::backend::{
    Answers, Backend, BeamQuery, CellQuery, Classified, HitQuery, Prepared, Queries, QueryKind,
    RayQuery, SegmentQuery, ShadeBatch, SoftAnswers, Support, VariationQuery,
};
use beam_trace::beam::BoxClass;
use beam_trace::beam::{child_window, forward};
use beam_trace::frustum::TileCells;
use beam_trace::mesh::MeshIndex;
use beam_trace::ray::{Beam, IBox, Ray, point_box};
use beam_trace::root::{Proof, RootCounters, RootResult};
use beam_trace::sample::{Hit, SHADOW_OFFSET};
use beam_trace::shadow::beam::shadow_beam_settings;
use beam_trace::shadow::hard::{Visibility, segment_visibility};
use beam_trace::shadow::rounds::{Answer, Question, RoundsError, visibility_in_rounds};
use beam_trace::shadow::{Occlusion, ShadowQuery, ShadowSpec};
use beam_trace::stats::PassStats;
use beam_trace::{Error, Plan, Progress, Scene};
use glam::DVec3;
use interval_core::Interval;

use crate::beams::{self, BeamKernel, GpuBeam, GpuClass, KernelSettings};
use crate::device::Gpu;
use crate::error::GpuError;
use crate::escalation::{OpenBeam, escalate_open, escalate_open_beams};
use crate::shading::{MAX_LIGHTS, ShadingInput, ShadingKernel};

/// The GPU backend: a device whose kernels answer the pipeline's queries.
pub struct GpuBackend {
    gpu: Gpu,
}

impl GpuBackend {
    /// The backend on `gpu`.
    pub fn new(gpu: Gpu) -> Self {
        Self { gpu }
    }

    /// The device.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }
}

impl Backend for GpuBackend {
    fn name(&self) -> String {
        "gpu".into()
    }

    fn support(&self, kind: QueryKind, scene: &Scene, plan: &Plan) -> Support {
        let no = |why: &str| Support::No(why.to_string());
        let searches = matches!(
            kind,
            QueryKind::Beams | QueryKind::Roots | QueryKind::Segments | QueryKind::SoftShadows
        );
        if searches && scene.geometry.tape().has_domain() {
            // A kernel would leave every piece across a domain boundary open (a possible
            // root where the CPU proves none): those queries go back to the CPU backend.
            return no("the kernels have no two-sided test of domain boundaries");
        }
        match kind {
            QueryKind::Beams | QueryKind::Roots | QueryKind::Segments => Support::Yes,
            QueryKind::HitPoints => no(
                "shading points are placed by regula falsi on point values of g, not in a kernel",
            ),
            QueryKind::Normals => no("the kernels evaluate no gradients"),
            QueryKind::Cells => no("the frustum octree searches depth first, tile by tile"),
            QueryKind::ShadingVariation => no("the kernels evaluate no gradient enclosures"),
            QueryKind::SoftShadows => match plan.shadow_method {
                ShadowSpec::Stochastic { cache: true, .. } => {
                    no("the last-occluder cache searches single objects")
                }
                ShadowSpec::Exact { .. } => {
                    no("the exact method grows a BSP of the triangles' edges per point")
                }
                _ => Support::Yes,
            },
            QueryKind::Shade if scene.lights.len() > MAX_LIGHTS => Support::No(format!(
                "{} lights; the shading kernel takes at most {MAX_LIGHTS}",
                scene.lights.len()
            )),
            QueryKind::Shade => Support::Yes,
        }
    }

    fn prepare<'a>(
        &'a self,
        scene: &'a Scene,
        plan: &'a Plan,
        kinds: &[QueryKind],
    ) -> Result<Prepared<'a>, Error> {
        let t = Instant::now();
        let geometry = &scene.geometry;
        let kernel =
            BeamKernel::new(&self.gpu, geometry.tape(), geometry.bounds()).map_err(backend)?;
        let shader = if kinds.contains(&QueryKind::Shade) {
            Some(ShadingKernel::new(&self.gpu).map_err(backend)?)
        } else {
            None
        };
        let stats = PassStats::new(
            "gpu-compile",
            t.elapsed(),
            &[
                ("instructions", geometry.tape().len() as u64),
                ("proves_hits", u64::from(kernel.proves_hits())),
            ],
        );
        let diag = geometry.diagonal();
        let offset = SHADOW_OFFSET * scene.diagonal();
        // The kernels search the implicit surfaces; the triangles are searched here, through
        // the same hierarchy and tests as on the CPU, and the two answers combined by the
        // same rules (`beam_trace::mesh::combine`).
        let meshes = (!scene.meshes.is_empty())
            .then(|| MeshIndex::new(scene.meshes.iter().map(|m| m.triangles.as_slice())));
        Ok(Prepared {
            queries: Box::new(GpuQueries {
                gpu: &self.gpu,
                scene,
                plan,
                kernel,
                shader,
                meshes,
                bounds: geometry.bounds(),
                primary: KernelSettings {
                    epsilon: plan.beam.epsilon as f32,
                    ..KernelSettings::default()
                },
                // A ray's first root is located, not only proven: narrow sections.
                ray: KernelSettings {
                    epsilon: (1e-6 * diag) as f32,
                    rel_epsilon: 1e-6,
                    narrow_hits: true,
                    ..KernelSettings::default()
                },
                // A segment is a single ray: its sections shrink to the root-finder scale.
                segment: KernelSettings {
                    epsilon: (1e-3 * offset) as f32,
                    rel_epsilon: 1e-6,
                    ..KernelSettings::default()
                },
                // Shadow beams stop where a section is small against their cross-section.
                shadow: KernelSettings {
                    epsilon: (1e-3 * offset) as f32,
                    rel_epsilon: 1.0 / 16.0,
                    ..KernelSettings::default()
                },
            }),
            passes: vec![stats],
        })
    }
}

/// The GPU's queries for one scene.
struct GpuQueries<'g> {
    gpu: &'g Gpu,
    scene: &'g Scene,
    plan: &'g Plan,
    kernel: BeamKernel,
    shader: Option<ShadingKernel>,
    /// The scene's triangles, searched on the host beside the kernels' implicit answers.
    meshes: Option<MeshIndex>,
    bounds: IBox,
    primary: KernelSettings,
    ray: KernelSettings,
    segment: KernelSettings,
    shadow: KernelSettings,
}

fn backend(e: GpuError) -> Error {
    Error::Backend {
        backend: "gpu".into(),
        message: e.to_string(),
    }
}

fn unsupported<T>(what: &str) -> Result<T, Error> {
    Err(Error::Backend {
        backend: "gpu".into(),
        message: format!("{what} queries are not answered on the GPU"),
    })
}

/// `[0, f64::MAX]`: the kernel searches bounded ranges from the origin on.
fn ahead() -> Interval<f64> {
    Interval::new_unchecked(0.0, f64::MAX)
}

impl GpuQueries<'_> {
    /// The kernel query of `beam` for parameters in `window`, inside the scene bounds.
    fn query(&self, beam: Beam, window: Interval<f64>) -> beams::BeamQuery {
        let t = beam.t_range(&self.bounds).map_or(Interval::EMPTY, |t| {
            t.intersection(window).intersection(ahead())
        });
        beams::BeamQuery { beam, t }
    }

    /// Classifies kernel queries, with each answer's cost (sections evaluated) and the
    /// batch's counters (every section an interval evaluation of `g`).
    fn classify(
        &self,
        queries: &[beams::BeamQuery],
        settings: &KernelSettings,
    ) -> Result<Answers<GpuClass>, Error> {
        let out: Vec<GpuBeam> = self
            .kernel
            .classify(self.gpu, queries, settings)
            .map_err(backend)?;
        let search = RootCounters {
            g_evals: out.iter().map(|b| u64::from(b.steps)).sum(),
            ..RootCounters::default()
        };
        Ok(Answers {
            cost: out.iter().map(|b| b.steps as f32).collect(),
            values: out.into_iter().map(|b| b.class).collect(),
            search,
        })
    }

    /// The segment `from → to` as a ray (`t = 1` at `to`).
    fn segment_ray(from: DVec3, to: DVec3) -> Ray {
        Ray {
            origin: from,
            dir: to - from,
        }
    }

    fn segment_beam(from: DVec3, to: DVec3) -> Beam {
        Self::segment_ray(from, to).beam()
    }

    /// The first root of the segment `from → to` (`t = 1` at `to`) for `t ∈ [start, 1]`
    /// from the kernel's class of its implicit part and, where the scene has meshes, the
    /// first crossing of a triangle.
    fn segment_root(&self, class: GpuClass, from: DVec3, to: DVec3, start: f64) -> RootResult {
        let implicit = root_result(class);
        match &self.meshes {
            Some(m) => m.first_root(
                implicit,
                &Self::segment_ray(from, to),
                Interval::new_unchecked(start.clamp(0.0, 1.0), 1.0),
            ),
            None => implicit,
        }
    }

    /// Answers a shadow method's questions: segments, beams with and without the
    /// inclusion test, one dispatch each.
    fn questions(&self, questions: &[Question]) -> Result<Vec<(Answer, RootCounters)>, Error> {
        let mut out = vec![None; questions.len()];
        for group in 0..3 {
            let picked: Vec<usize> = (0..questions.len())
                .filter(|&i| {
                    group
                        == match questions[i] {
                            Question::Segment { .. } => 0,
                            Question::Beam {
                                inclusion: false, ..
                            } => 1,
                            Question::Beam {
                                inclusion: true, ..
                            } => 2,
                        }
                })
                .collect();
            if picked.is_empty() {
                continue;
            }
            let queries: Vec<beams::BeamQuery> = picked
                .iter()
                .map(|&i| match questions[i] {
                    Question::Segment { from, to, start } => beams::BeamQuery {
                        beam: Self::segment_beam(from, to),
                        t: Interval::new_unchecked(start.clamp(0.0, 1.0), 1.0),
                    },
                    Question::Beam {
                        from, light, start, ..
                    } => beams::BeamQuery {
                        beam: Beam {
                            origin: point_box(from),
                            dir: light.directions_from(from),
                        },
                        t: Interval::new_unchecked(start.clamp(0.0, 1.0), 1.0),
                    },
                })
                .collect();
            let settings = match group {
                0 => self.segment,
                1 => KernelSettings {
                    inclusion: false,
                    ..self.shadow
                },
                _ => self.shadow,
            };
            let answers = self
                .kernel
                .classify(self.gpu, &queries, &settings)
                .map_err(backend)?;
            for (&i, b) in picked.iter().zip(&answers) {
                let c = RootCounters {
                    g_evals: u64::from(b.steps),
                    ..RootCounters::default()
                };
                let a = if let Question::Segment { from, to, start } = questions[i] {
                    Answer::Segment(occlusion(self.segment_root(b.class, from, to, start)))
                } else {
                    Answer::Beam(box_class(b.class))
                };
                out[i] = Some((a, c));
            }
            // Undecided shadow beams where a higher precision may decide them: on the CPU.
            let (at, open): (Vec<usize>, Vec<OpenBeam>) = picked
                .iter()
                .zip(&queries)
                .zip(&answers)
                .enumerate()
                .filter_map(|(k, ((&i, q), b))| match (b.class, questions[i]) {
                    (
                        GpuClass::Undecided { t },
                        Question::Beam {
                            from,
                            light,
                            inclusion,
                            ..
                        },
                    ) => Some((
                        k,
                        OpenBeam {
                            beam: q.beam,
                            searched: q.t,
                            piece: t,
                            settings: shadow_beam_settings(
                                &self.plan.beam,
                                self.scene.geometry.diagonal(),
                                from,
                                &light,
                            ),
                            inclusion,
                        },
                    )),
                    _ => None,
                })
                .unzip();
            for (k, (class, extra)) in at
                .into_iter()
                .zip(escalate_open_beams(self.scene, self.plan, &open))
            {
                if let Some((answer, c)) = out[picked[k]].as_mut() {
                    c.add(&extra);
                    if let Some(class) = class {
                        *answer = Answer::Beam(class);
                    }
                }
            }
            // The triangles' part of each shadow beam, over the same parameters.
            if let Some(m) = &self.meshes {
                for (&i, q) in picked.iter().zip(&queries) {
                    if let (Question::Beam { inclusion, .. }, Some((Answer::Beam(class), _))) =
                        (questions[i], out[i].as_mut())
                    {
                        *class = m.shadow_beam(*class, &q.beam, q.t, inclusion);
                    }
                }
            }
        }
        Ok(out.into_iter().flatten().collect())
    }
}

/// The pipeline's class of a kernel class.
fn box_class(c: GpuClass) -> BoxClass {
    match c {
        GpuClass::Miss => BoxClass::Miss,
        GpuClass::Hit { t } => BoxClass::Hit { t_final: t },
        GpuClass::Undecided { t } => BoxClass::Undecided { t },
    }
}

/// A single ray's first root from its kernel class: a proven section of a single ray holds
/// a root (a sign change of a continuous `g`); rejected is a proof that there is none.
fn root_result(c: GpuClass) -> RootResult {
    match c {
        GpuClass::Miss => RootResult::NoRoot,
        GpuClass::Hit { t } => RootResult::Root {
            t,
            proof: Proof::Exists,
        },
        GpuClass::Undecided { t } => RootResult::Undecided { t },
    }
}

/// A shadow segment's answer from its first root: free where none is proven, and where it
/// may be blocked, about where.
fn occlusion(r: RootResult) -> Occlusion {
    Occlusion {
        visibility: segment_visibility(r, true),
        at: match r {
            RootResult::Root { t, .. } | RootResult::Undecided { t } => Some(t.mid()),
            RootResult::NoRoot => None,
        },
    }
}

fn map<T, U>(a: Answers<T>, f: impl Fn(T) -> U) -> Answers<U> {
    Answers {
        values: a.values.into_iter().map(f).collect(),
        cost: a.cost,
        search: a.search,
    }
}

impl Queries for GpuQueries<'_> {
    fn beams(&self, queries: &[BeamQuery]) -> Result<Answers<Classified>, Error> {
        let q: Vec<beams::BeamQuery> = queries
            .iter()
            .map(|b| self.query(b.beam, child_window(b.parent.as_ref())))
            .collect();
        let mut answers = map(self.classify(&q, &self.primary)?, |c| {
            Classified::from(box_class(c))
        });
        let (at, open): (Vec<usize>, Vec<OpenBeam>) = answers
            .values
            .iter()
            .enumerate()
            .filter_map(|(i, a)| match a.class {
                BoxClass::Undecided { t } => Some((
                    i,
                    OpenBeam {
                        beam: q[i].beam,
                        searched: q[i].t,
                        piece: t,
                        settings: self.plan.beam,
                        inclusion: true,
                    },
                )),
                _ => None,
            })
            .unzip();
        for (i, (class, c)) in at
            .into_iter()
            .zip(escalate_open_beams(self.scene, self.plan, &open))
        {
            if let Some(class) = class {
                answers.values[i] = class.into();
            }
            answers.search.add(&c);
        }
        if let Some(m) = &self.meshes {
            for (a, b) in answers.values.iter_mut().zip(queries) {
                let window = child_window(b.parent.as_ref());
                *a = m.primary_beam(a.class, &b.beam, window).into();
            }
        }
        Ok(answers)
    }

    fn roots(&self, queries: &[RayQuery]) -> Result<Answers<RootResult>, Error> {
        let q: Vec<beams::BeamQuery> = queries
            .iter()
            .map(|r| self.query(r.ray.beam(), r.window))
            .collect();
        let mut answers = map(self.classify(&q, &self.ray)?, root_result);
        let escalated = escalate_open(self.scene, self.plan, queries, &mut answers.values);
        answers.search.add(&escalated);
        if let Some(m) = &self.meshes {
            for (r, q) in answers.values.iter_mut().zip(queries) {
                let window = q.window.intersection(forward());
                if !window.is_empty() {
                    *r = m.first_root(*r, &q.ray, window);
                }
            }
        }
        Ok(answers)
    }

    fn hit_points(&self, _: &[HitQuery]) -> Result<Answers<Hit>, Error> {
        unsupported("hit-point")
    }

    fn shading_variation(&self, _: &[VariationQuery]) -> Result<Answers<f64>, Error> {
        unsupported("shading-variation")
    }

    fn first_cells(&self, _: &[CellQuery], _: &dyn Progress) -> Result<Answers<TileCells>, Error> {
        unsupported("first-cell")
    }

    fn normals(&self, _: &[DVec3]) -> Result<Answers<Option<DVec3>>, Error> {
        unsupported("normal")
    }

    fn segments(&self, queries: &[SegmentQuery]) -> Result<Answers<Visibility>, Error> {
        let q: Vec<beams::BeamQuery> = queries
            .iter()
            .map(|s| beams::BeamQuery {
                beam: Self::segment_beam(s.from, s.to),
                t: Interval::new_unchecked(0.0, 1.0),
            })
            .collect();
        let answers = self.classify(&q, &self.segment)?;
        Ok(Answers {
            values: answers
                .values
                .into_iter()
                .zip(queries)
                .map(|(c, s)| segment_visibility(self.segment_root(c, s.from, s.to, 0.0), true))
                .collect(),
            cost: answers.cost,
            search: answers.search,
        })
    }

    fn soft_shadows(
        &self,
        method: &ShadowSpec,
        queries: &[ShadowQuery],
    ) -> Result<SoftAnswers, Error> {
        let m = method.method();
        match visibility_in_rounds(&*m, queries, |q| self.questions(q)) {
            Ok((visibility, work)) => Ok(SoftAnswers { visibility, work }),
            Err(RoundsError::Answer(e)) => Err(e),
            Err(RoundsError::NeedsObjects) => unsupported("single-object"),
            Err(RoundsError::TooManyRounds) => Err(Error::Backend {
                backend: "gpu".into(),
                message: format!("the {method} shadow method did not settle in rounds"),
            }),
        }
    }

    fn shade(&self, batch: &ShadeBatch<'_>) -> Result<Answers<[f32; 3]>, Error> {
        let Some(shader) = &self.shader else {
            return unsupported("shading");
        };
        let nl = batch.lights.len();
        let inputs: Vec<ShadingInput> = batch
            .samples
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let mut fractions = [0f32; MAX_LIGHTS];
                fractions[..nl].copy_from_slice(&batch.fractions[i * nl..(i + 1) * nl]);
                ShadingInput {
                    point: s.point,
                    normal: s.normal,
                    to_eye: s.to_eye,
                    material: s.material,
                    fractions,
                }
            })
            .collect();
        let colors = shader
            .shade(self.gpu, batch.lights, batch.ambient, &inputs)
            .map_err(backend)?;
        Ok(Answers::free(colors))
    }
}
