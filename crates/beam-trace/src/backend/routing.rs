//! Which backend answers which queries of a render: the chosen one where it can, the CPU
//! where it cannot, printed with the reason.

use std::fmt;

use glam::DVec3;

use super::cpu::Cpu;
use super::query::{
    Answers, BeamQuery, CellQuery, Classified, DirectHits, HitQuery, QueryKind, RayQuery,
    SegmentQuery, ShadeBatch, SoftAnswers, Support, VariationQuery,
};
use super::traits::{Backend, Prepared, Queries};
use crate::error::Error;
use crate::frustum::TileCells;
use crate::plan::{Pass, PixelBeams, Plan, Primary};
use crate::progress::Progress;
use crate::root::RootResult;
use crate::sample::Hit;
use crate::scene::Scene;
use crate::shadow::hard::Visibility;
use crate::shadow::{ShadowQuery, ShadowSpec};
use crate::stats::PassStats;

/// The query kinds a pass asks under a plan (none when it does not run).
pub fn pass_queries(pass: Pass, plan: &Plan) -> &'static [QueryKind] {
    if !plan.runs(pass) {
        return &[];
    }
    match pass {
        Pass::Grid => &[],
        Pass::ScreenBoxes => match plan.primary {
            Primary::Octree { .. } => &[QueryKind::Cells],
            // With anti-aliasing the Hit boxes' shading is judged there too.
            Primary::Iaa { .. } => &[QueryKind::Beams, QueryKind::ShadingVariation],
            _ => &[QueryKind::Beams],
        },
        Pass::PrimaryRays => &[QueryKind::Roots, QueryKind::HitPoints],
        // Hit regions are judged by their shading only with anti-aliasing.
        Pass::PixelBeams => match plan.primary.pixel_beams() {
            Some(PixelBeams {
                threshold: Some(_), ..
            }) => &[
                QueryKind::Beams,
                QueryKind::ShadingVariation,
                QueryKind::Roots,
                QueryKind::HitPoints,
            ],
            _ => &[QueryKind::Beams, QueryKind::Roots, QueryKind::HitPoints],
        },
        Pass::Normals => &[QueryKind::Normals],
        Pass::HardShadows => &[QueryKind::Segments],
        Pass::SoftShadows => &[QueryKind::SoftShadows],
        Pass::Shading => &[QueryKind::Shade],
    }
}

/// Who answers a kind of query.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Route {
    /// The chosen backend.
    Main,
    /// The CPU backend, because the chosen one cannot (the reason).
    Cpu(String),
}

/// Which backend answers each query kind a plan asks.
#[derive(Clone, Debug)]
pub struct Routing {
    main: String,
    routes: Vec<(QueryKind, Route)>,
    passes: Vec<(Pass, &'static [QueryKind])>,
}

impl Routing {
    /// The routing of the queries of `scene` under `plan` on `backend`.
    pub fn new(backend: &dyn Backend, scene: &Scene, plan: &Plan) -> Routing {
        let passes: Vec<(Pass, &'static [QueryKind])> = Pass::ALL
            .iter()
            .map(|&p| (p, pass_queries(p, plan)))
            .filter(|(_, k)| !k.is_empty())
            .collect();
        let mut routes: Vec<(QueryKind, Route)> = Vec::new();
        for &(_, kinds) in &passes {
            for &kind in kinds {
                if routes.iter().any(|(k, _)| *k == kind) {
                    continue;
                }
                let route = match backend.support(kind, scene, plan) {
                    Support::Yes => Route::Main,
                    Support::No(why) => Route::Cpu(why),
                };
                routes.push((kind, route));
            }
        }
        Routing {
            main: backend.name(),
            routes,
            passes,
        }
    }

    /// The kinds the chosen backend answers.
    pub fn main_kinds(&self) -> Vec<QueryKind> {
        self.kinds(|r| *r == Route::Main)
    }

    /// The kinds the CPU backend answers in its place.
    pub fn cpu_kinds(&self) -> Vec<QueryKind> {
        self.kinds(|r| matches!(r, Route::Cpu(_)))
    }

    fn kinds(&self, f: impl Fn(&Route) -> bool) -> Vec<QueryKind> {
        self.routes
            .iter()
            .filter(|(_, r)| f(r))
            .map(|(k, _)| *k)
            .collect()
    }

    fn to_main(&self, kind: QueryKind) -> bool {
        self.routes
            .iter()
            .find(|(k, _)| *k == kind)
            .is_none_or(|(_, r)| *r == Route::Main)
    }

    /// Prepares the backends for `scene`: the chosen one, and the CPU for the kinds it
    /// answers in its place.
    ///
    /// # Errors
    ///
    /// The error of a backend's preparation.
    pub fn prepare<'a>(
        &self,
        backend: &'a dyn Backend,
        scene: &'a Scene,
        plan: &'a Plan,
    ) -> Result<(Routed<'a>, Vec<PassStats>), Error> {
        let Prepared {
            queries: main,
            mut passes,
        } = backend.prepare(scene, plan, &self.main_kinds())?;
        let cpu_kinds = self.cpu_kinds();
        let cpu = if cpu_kinds.is_empty() {
            None
        } else {
            let p = Cpu.prepare(scene, plan, &cpu_kinds)?;
            passes.extend(p.passes);
            Some(p.queries)
        };
        Ok((
            Routed {
                routing: self.clone(),
                main,
                cpu,
            },
            passes,
        ))
    }
}

impl fmt::Display for Routing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "backend {}:", self.main)?;
        for (pass, kinds) in &self.passes {
            let parts: Vec<String> = kinds
                .iter()
                .map(|k| match self.routes.iter().find(|(kk, _)| kk == k) {
                    Some((_, Route::Cpu(why))) => format!("{k} on the cpu ({why})"),
                    _ => format!("{k} on {}", self.main),
                })
                .collect();
            writeln!(f, "  {:<13} {}", pass.name(), parts.join("; "))?;
        }
        Ok(())
    }
}

/// The queries of a render, each kind sent where its [`Routing`] says.
pub struct Routed<'a> {
    routing: Routing,
    main: Box<dyn Queries + 'a>,
    cpu: Option<Box<dyn Queries + 'a>>,
}

impl Routed<'_> {
    fn to(&self, kind: QueryKind) -> &dyn Queries {
        match &self.cpu {
            Some(cpu) if !self.routing.to_main(kind) => cpu.as_ref(),
            _ => self.main.as_ref(),
        }
    }
}

impl Queries for Routed<'_> {
    fn beams(&self, q: &[BeamQuery]) -> Result<Answers<Classified>, Error> {
        self.to(QueryKind::Beams).beams(q)
    }
    fn first_cells(
        &self,
        q: &[CellQuery],
        progress: &dyn Progress,
    ) -> Result<Answers<TileCells>, Error> {
        self.to(QueryKind::Cells).first_cells(q, progress)
    }
    fn roots(&self, q: &[RayQuery]) -> Result<Answers<RootResult>, Error> {
        self.to(QueryKind::Roots).roots(q)
    }
    fn hit_points(&self, q: &[HitQuery]) -> Result<Answers<Hit>, Error> {
        self.to(QueryKind::HitPoints).hit_points(q)
    }
    fn direct_hits(&self) -> Option<DirectHits> {
        self.to(QueryKind::HitPoints).direct_hits()
    }
    fn shading_variation(&self, q: &[VariationQuery]) -> Result<Answers<f64>, Error> {
        self.to(QueryKind::ShadingVariation).shading_variation(q)
    }
    fn normals(&self, p: &[DVec3]) -> Result<Answers<Option<DVec3>>, Error> {
        self.to(QueryKind::Normals).normals(p)
    }
    fn segments(&self, q: &[SegmentQuery]) -> Result<Answers<Visibility>, Error> {
        self.to(QueryKind::Segments).segments(q)
    }
    fn soft_shadows(&self, m: &ShadowSpec, q: &[ShadowQuery]) -> Result<SoftAnswers, Error> {
        self.to(QueryKind::SoftShadows).soft_shadows(m, q)
    }
    fn shade(&self, b: &ShadeBatch<'_>) -> Result<Answers<[f32; 3]>, Error> {
        self.to(QueryKind::Shade).shade(b)
    }
}
