//! Render backends: what answers the pipeline's queries.
//!
//! The render pipeline ([`render`](mod@crate::render)) is written once. Each pass turns its
//! work into batches of plain-data queries (classify these beams, find the first root on
//! these rays, place the shading points of these hits, test these shadow segments, the
//! visible fraction of a light from these points, shade these samples) and asks a
//! [`Queries`] object for the answers. A [`Backend`] prepares that object for one scene and
//! plan, and says which query kinds it can answer ([`Backend::support`]).
//!
//! * [`cpu::Cpu`]: rayon over the batch, through the regular grid, with the plan's root
//!   finder; it answers every kind.
//! * The GPU backend (crate `gpu-backend`) answers the beam, ray, segment, shadow and
//!   shading kinds with compute kernels.
//!
//! Where the chosen backend cannot answer a kind, the [`Routing`] sends that kind to the
//! CPU backend and says so when it is printed: there is no silent fallback.
//!
//! A backend answers a batch however it is fastest (the CPU in parallel, the GPU in one
//! dispatch), but every answer depends on its query alone, so results do not depend on how
//! a pass cuts its work into batches, nor on the thread count.

pub mod cpu;
mod routing;

pub use routing::Routing;

use std::fmt;

use glam::DVec3;
use interval_core::Interval;

use crate::beam::BoxClass;
use crate::error::Error;
use crate::plan::Plan;
use crate::ray::{Beam, Ray};
use crate::root::{RootCounters, RootResult};
use crate::sample::Hit;
use crate::scene::{Material, Scene};
use crate::shadow::hard::Visibility;
use crate::shadow::{LightVisibility, ShadowQuery, ShadowSpec, ShadowWork};
use crate::stats::PassStats;

/// The kinds of query a pass asks.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum QueryKind {
    /// Classify primary beams (rejection and inclusion tests): [`Queries::beams`].
    Beams,
    /// First roots on rays inside windows: [`Queries::roots`].
    Roots,
    /// Shading points of hits: [`Queries::hit_points`].
    HitPoints,
    /// The normal-variation estimator over a hit region: [`Queries::normal_variation`].
    NormalVariation,
    /// Unit normals at points: [`Queries::normals`].
    Normals,
    /// Hard-shadow segments: [`Queries::segments`].
    Segments,
    /// The visible fraction of an area light by the plan's method:
    /// [`Queries::soft_shadows`].
    SoftShadows,
    /// Phong shading of samples: [`Queries::shade`].
    Shade,
}

impl QueryKind {
    /// Every kind.
    pub const ALL: [QueryKind; 8] = [
        QueryKind::Beams,
        QueryKind::Roots,
        QueryKind::HitPoints,
        QueryKind::NormalVariation,
        QueryKind::Normals,
        QueryKind::Segments,
        QueryKind::SoftShadows,
        QueryKind::Shade,
    ];

    /// The kind's name in routing tables.
    pub fn name(self) -> &'static str {
        match self {
            QueryKind::Beams => "beams",
            QueryKind::Roots => "roots",
            QueryKind::HitPoints => "hit-points",
            QueryKind::NormalVariation => "normal-variation",
            QueryKind::Normals => "normals",
            QueryKind::Segments => "segments",
            QueryKind::SoftShadows => "soft-shadows",
            QueryKind::Shade => "shade",
        }
    }
}

impl fmt::Display for QueryKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Whether a backend answers a kind of query under a plan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Support {
    /// It does.
    Yes,
    /// It does not, and why.
    No(String),
}

/// A beam to classify: every ray of `beam`, searched where its `parent` beam (the beam it
/// was split from, if any) left the rays open (see [`cpu::child_window`]).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct BeamQuery {
    /// The beam.
    pub beam: Beam,
    /// The class of the beam it lies in.
    pub parent: Option<BoxClass>,
}

/// A ray whose first root is wanted for parameters in `window` (clipped to `t ≥ 0`).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct RayQuery {
    /// The ray.
    pub ray: Ray,
    /// The parameter window.
    pub window: Interval<f64>,
}

/// A hit whose shading point is wanted: the ray and the enclosure `t` of its first root.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct HitQuery {
    /// The ray.
    pub ray: Ray,
    /// The root enclosure.
    pub t: Interval<f64>,
}

/// A hit region whose normal variation (thesis eq. 5.10) is wanted: the beam and its proven
/// section `T_final`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct VariationQuery {
    /// The beam.
    pub beam: Beam,
    /// Its proven section.
    pub t_final: Interval<f64>,
}

/// A hard-shadow segment from a point (already off its surface) to a point light.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct SegmentQuery {
    /// Start.
    pub from: DVec3,
    /// End (the light).
    pub to: DVec3,
}

/// A light as shading sees it: where it is (an area light's centre) and its colour.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ShadeLight {
    /// Position.
    pub position: DVec3,
    /// Colour times intensity.
    pub color: [f32; 3],
}

/// A sample to shade.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ShadeSample {
    /// The surface point.
    pub point: DVec3,
    /// Its unit normal.
    pub normal: DVec3,
    /// Unit vector to the eye.
    pub to_eye: DVec3,
    /// Its material.
    pub material: Material,
}

/// A batch of samples to shade under the same lights.
#[derive(Copy, Clone, Debug)]
pub struct ShadeBatch<'a> {
    /// The lights.
    pub lights: &'a [ShadeLight],
    /// The ambient term.
    pub ambient: f32,
    /// The samples.
    pub samples: &'a [ShadeSample],
    /// The visible fraction of each light from each sample (sample-major, light-minor).
    pub fractions: &'a [f32],
}

/// The answers to a batch, in the order of the queries, with what they cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Answers<T> {
    /// One answer per query.
    pub values: Vec<T>,
    /// The cost of each answer in the backend's unit (seconds on the CPU, sections
    /// evaluated on the GPU): the cost map shows it.
    pub cost: Vec<f32>,
    /// The search counters of the whole batch.
    pub search: RootCounters,
}

impl<T> Answers<T> {
    /// Answers that cost nothing to report.
    pub fn free(values: Vec<T>) -> Self {
        Self {
            cost: vec![0.0; values.len()],
            values,
            search: RootCounters::default(),
        }
    }
}

/// The answers to a batch of soft-shadow queries.
#[derive(Clone, Debug, PartialEq)]
pub struct SoftAnswers {
    /// The visible fraction of the light from each query's point, with proven bounds.
    pub visibility: Vec<LightVisibility>,
    /// The work of the whole batch (its search counters included).
    pub work: ShadowWork,
}

/// Answers the queries of the passes for one scene and plan.
///
/// Every method answers a batch (any size, empty included) in the order of the queries, or
/// fails with an [`Error`] naming the backend; a backend is asked only the kinds it
/// supports.
pub trait Queries: Sync {
    /// Classifies each beam: [`BoxClass::Miss`] proves that no ray of it meets a surface
    /// where its parent left it open; [`BoxClass::Hit`] that every ray has its first root in
    /// `T_final`; else [`BoxClass::Undecided`] with the first range not rejected.
    fn beams(&self, queries: &[BeamQuery]) -> Result<Answers<BoxClass>, Error>;

    /// The first root of each ray in its window.
    fn roots(&self, queries: &[RayQuery]) -> Result<Answers<RootResult>, Error>;

    /// The hit record of each ray and root enclosure: the shading point inside the
    /// enclosure, the leaf surface that shades it, the direction to the eye.
    fn hit_points(&self, queries: &[HitQuery]) -> Result<Answers<Hit>, Error>;

    /// The normal-variation estimator of each hit region (see
    /// [`aa::normal_variation`](crate::aa::normal_variation)).
    fn normal_variation(&self, queries: &[VariationQuery]) -> Result<Answers<f64>, Error>;

    /// The unit normal at each point (`None` where the gradient vanishes).
    fn normals(&self, points: &[DVec3]) -> Result<Answers<Option<DVec3>>, Error>;

    /// Whether each segment is free: [`Visibility::Lit`] is a proof with a reliable
    /// search.
    fn segments(&self, queries: &[SegmentQuery]) -> Result<Answers<Visibility>, Error>;

    /// The visible fraction of each query's light from its point by the method `method`.
    fn soft_shadows(
        &self,
        method: &ShadowSpec,
        queries: &[ShadowQuery],
    ) -> Result<SoftAnswers, Error>;

    /// The Phong colour of each sample.
    fn shade(&self, batch: &ShadeBatch<'_>) -> Result<Answers<[f32; 3]>, Error>;
}

/// A backend prepared for one scene: its queries and the passes its set-up ran.
pub struct Prepared<'a> {
    /// The queries.
    pub queries: Box<dyn Queries + 'a>,
    /// Statistics of the set-up (the grid on the CPU, compiling kernels on the GPU).
    pub passes: Vec<PassStats>,
}

/// Something that answers the pipeline's queries: the CPU, a GPU.
pub trait Backend: Sync {
    /// The backend's name in plans and errors (`cpu`, `gpu (llvmpipe)`).
    fn name(&self) -> String;

    /// Whether it answers queries of `kind` for `scene` under `plan`.
    fn support(&self, kind: QueryKind, scene: &Scene, plan: &Plan) -> Support;

    /// Prepares the queries of `scene` under `plan`, for the query kinds `kinds` (those
    /// the routing sends to it).
    ///
    /// # Errors
    ///
    /// [`Error::Backend`] when the scene cannot run on the backend.
    fn prepare<'a>(
        &'a self,
        scene: &'a Scene,
        plan: &'a Plan,
        kinds: &[QueryKind],
    ) -> Result<Prepared<'a>, Error>;
}
