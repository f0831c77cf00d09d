//! The queries a pass asks a backend, and the answers it gets back: plain data.

use std::fmt;

use glam::DVec3;
use interval_core::Interval;

use crate::beam::{BeamScope, BoxClass};
use crate::ray::{Beam, Ray};
use crate::root::RootCounters;
use crate::sample::Hit;
use crate::scene::Material;
use crate::screen::PixelRect;
use crate::shadow::{LightVisibility, ShadowWork};

/// The kinds of query a pass asks.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum QueryKind {
    /// Classify primary beams (rejection and inclusion tests):
    /// [`Queries::beams`](super::Queries::beams).
    Beams,
    /// Each pixel's first cell of the frustum octree:
    /// [`Queries::first_cells`](super::Queries::first_cells).
    Cells,
    /// First roots on rays inside windows: [`Queries::roots`](super::Queries::roots).
    Roots,
    /// Shading points of hits: [`Queries::hit_points`](super::Queries::hit_points).
    HitPoints,
    /// The spread of the shaded colour over a hit region:
    /// [`Queries::shading_variation`](super::Queries::shading_variation).
    ShadingVariation,
    /// Unit normals at points: [`Queries::normals`](super::Queries::normals).
    Normals,
    /// Hard-shadow segments: [`Queries::segments`](super::Queries::segments).
    Segments,
    /// The visible fraction of an area light by the plan's method:
    /// [`Queries::soft_shadows`](super::Queries::soft_shadows).
    SoftShadows,
    /// Phong shading of samples: [`Queries::shade`](super::Queries::shade).
    Shade,
}

impl QueryKind {
    /// Every kind.
    pub const ALL: [QueryKind; 9] = [
        QueryKind::Beams,
        QueryKind::Cells,
        QueryKind::Roots,
        QueryKind::HitPoints,
        QueryKind::ShadingVariation,
        QueryKind::Normals,
        QueryKind::Segments,
        QueryKind::SoftShadows,
        QueryKind::Shade,
    ];

    /// The kind's name in routing tables.
    pub fn name(self) -> &'static str {
        match self {
            QueryKind::Beams => "beams",
            QueryKind::Cells => "cells",
            QueryKind::Roots => "roots",
            QueryKind::HitPoints => "hit-points",
            QueryKind::ShadingVariation => "shading-variation",
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
/// was split from, if any) left the rays open (see
/// [`child_window`](crate::beam::child_window)).
#[derive(Clone, Debug, PartialEq)]
pub struct BeamQuery {
    /// The beam.
    pub beam: Beam,
    /// The class of the beam it lies in.
    pub parent: Option<BoxClass>,
    /// What the backend that classified the parent beam handed on with its answer
    /// ([`Classified::scope`]), `None` for a first beam or a backend without one.
    pub scope: Option<BeamScope>,
}

/// The answer to a [`BeamQuery`]: the beam's class and, where the backend has one, a
/// restriction of the scene function to the beam that the beams inside it may start from
/// (the CPU's pruned tape of the range the search ended in; see
/// [`evaluate_box_within`](crate::beam::evaluate_box_within)).
#[derive(Clone, Debug, PartialEq)]
pub struct Classified {
    /// The class.
    pub class: BoxClass,
    /// For the beams inside this one ([`BeamQuery::scope`]).
    pub scope: Option<BeamScope>,
}

impl From<BoxClass> for Classified {
    fn from(class: BoxClass) -> Self {
        Self { class, scope: None }
    }
}

/// A ray whose first root is wanted for parameters in `window` (clipped to `t ≥ 0`).
#[derive(Clone, Debug, PartialEq)]
pub struct RayQuery {
    /// The ray.
    pub ray: Ray,
    /// The parameter window.
    pub window: Interval<f64>,
    /// The scope of a classified beam the ray lies in ([`Classified::scope`]), which the
    /// backend that made it may search the ray with where the window lies inside the
    /// scope's parameters (the CPU: the tape pruned to the beam, with a derivative of its
    /// own, instead of the grid's cells); `None` where there is none.
    pub scope: Option<BeamScope>,
}

/// A hit whose shading point is wanted: the ray and the enclosure `t` of its first root.
#[derive(Clone, Debug, PartialEq)]
pub struct HitQuery {
    /// The ray.
    pub ray: Ray,
    /// The root enclosure.
    pub t: Interval<f64>,
    /// The scope of a classified beam the ray lies in, as [`RayQuery::scope`].
    pub scope: Option<BeamScope>,
}

/// The hit records a backend leaves to the caller: where the scene has one leaf surface
/// and no triangle mesh and the plan does not narrow hits, a ray's hit record follows from
/// its root enclosure alone (the shading point at the enclosure's start, the one leaf),
/// and [`Queries::hit_points`](super::Queries::hit_points) would evaluate nothing for it.
/// A primary pass makes such records where it writes its samples, without a query (on the
/// CSG models at 1024 × 1024, three hundred thousand rays whose queries and answers were
/// most of the pass's memory traffic).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct DirectHits {
    /// The leaf every hit is shaded by.
    pub leaf: u32,
}

impl DirectHits {
    /// The hit record of `ray` with the root enclosure `t`, as
    /// [`Queries::hit_points`](super::Queries::hit_points) makes it; `None` where `t`
    /// has no finite start (the backend searches for a shading point there).
    pub fn hit(&self, ray: &Ray, t: Interval<f64>) -> Option<Hit> {
        Self::applies(t).then(|| Hit::on_ray(ray, t, t.inf(), self.leaf))
    }

    /// Whether [`hit`](Self::hit) makes the record of a root enclosure `t`.
    pub fn applies(t: Interval<f64>) -> bool {
        t.inf().is_finite()
    }
}

/// A tile of the image whose pixels' first cells of the frustum octree are wanted (see
/// [`crate::frustum`]).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct CellQuery {
    /// The tile.
    pub tile: PixelRect,
    /// How many rays of each pixel whose first cell is undecided are searched on from
    /// there ([`FirstCell::traced`](crate::frustum::FirstCell::traced)): 0 for none, else
    /// at the [stratified positions](crate::screen::stratified_offsets) of that many.
    pub traced_rays: u32,
}

/// A hit region whose shading variation is wanted: the beam and its proven section
/// `T_final`, and the variation below which it would be shaded once.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct VariationQuery {
    /// The beam.
    pub beam: Beam,
    /// Its proven section.
    pub t_final: Interval<f64>,
    /// The threshold of the judgement: where the shading's spread is at most this, the
    /// region's hard shadows are judged too. A point light whose shadow could add more to
    /// the spread than the threshold allows (its term in the colour is that large
    /// somewhere in the region) and is not proven the same over the whole region makes the
    /// variation infinite; a wider spread is split anyway, so its shadows are not judged.
    pub threshold: f64,
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
    /// evaluated on the GPU), for the cost map of primary visibility; a backend may report
    /// 0 for the other kinds (the CPU does).
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
