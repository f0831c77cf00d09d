//! What a soft-shadow method is: the [`ShadowMethod`] trait, the [`Occluders`] it asks, the
//! [`ShadowQuery`] it answers with a [`LightVisibility`] of some [`ShadowClass`], and the
//! [`ShadowWork`] it counts.

use glam::DVec3;
use interval_core::Interval;

use super::exact_work::{BspWork, ExactTimes};
use super::hard::Visibility;
use super::patch::Patch;
use crate::beam::BoxClass;
use crate::ibox::IBox;
use crate::mesh::Triangle;
use crate::root::RootCounters;

/// The proven class of a point's view of a light.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum ShadowClass {
    /// Proven: every point of the light is visible.
    Lit,
    /// Proven: no point of the light is visible.
    Umbra,
    /// Neither was proven; the visible fraction is an estimate.
    Penumbra,
    /// The whole light is behind the surface's tangent plane: the point gets no direct
    /// light from it whatever the occluders (no shadow test runs, and nothing is claimed
    /// about occlusion).
    BackFacing,
}

/// The visible fraction of a light from a point, with proven bounds.
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub struct LightVisibility {
    /// The estimate that shades the point.
    pub fraction: f32,
    /// Proven lower bound of the visible fraction.
    pub lower: f32,
    /// Proven upper bound of the visible fraction.
    pub upper: f32,
}

impl ShadowClass {
    /// The class of a pixel holding a part of class `a` (if any) and one of class `b`: the
    /// common class, or penumbra where they differ.
    pub fn merge(a: Option<ShadowClass>, b: ShadowClass) -> ShadowClass {
        match a {
            Some(a) if a != b => ShadowClass::Penumbra,
            _ => b,
        }
    }
}

impl LightVisibility {
    /// Proven fully lit.
    pub const LIT: LightVisibility = LightVisibility {
        fraction: 1.0,
        lower: 1.0,
        upper: 1.0,
    };
    /// Proven in the umbra.
    pub const UMBRA: LightVisibility = LightVisibility {
        fraction: 0.0,
        lower: 0.0,
        upper: 0.0,
    };

    /// An estimate with no proven bounds.
    pub fn estimate(fraction: f32) -> LightVisibility {
        LightVisibility {
            fraction,
            lower: 0.0,
            upper: 1.0,
        }
    }

    /// What the bounds prove.
    pub fn class(&self) -> ShadowClass {
        if self.lower >= 1.0 {
            ShadowClass::Lit
        } else if self.upper <= 0.0 {
            ShadowClass::Umbra
        } else {
            ShadowClass::Penumbra
        }
    }
}

/// One shadow query: the visible fraction of `light` from `origin`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ShadowQuery {
    /// The shaded point, already moved off its surface.
    pub origin: DVec3,
    /// The receiving surface's unit normal there, on the side `origin` was moved to
    /// (zero where the query has no surface): methods may group queries whose points
    /// share a tangent plane.
    pub normal: DVec3,
    /// The light.
    pub light: Patch,
    /// Seed of the query's random numbers (the same seed gives the same samples).
    pub seed: u64,
}

/// The answer of an occluder segment query.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Occlusion {
    /// Whether the segment is free.
    pub visibility: Visibility,
    /// The segment parameter of the surface the search met, when it met one.
    pub at: Option<f64>,
}

/// Where a shadow beam's search starts.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum BeamStart {
    /// At this parameter: the caller knows every ray free before it.
    At(f64),
    /// Inside a beam over a larger part of the light, from the same point, whose search
    /// ended undecided on these parameters (or proved them to hold every ray's first
    /// root): every ray is free before them, and the search starts there with pieces
    /// graded from their width, at the scale where the other stopped
    /// ([`crate::beam::evaluate_box_near`]).
    Near(Interval<f64>),
    /// As [`BeamStart::Near`], for a part meant to be decided whole however small it is
    /// (a subdivision of the light towards a tolerance): its final pieces are also at most
    /// a quarter of the part's angular size long, and its inclusion test looks further
    /// ahead ([`crate::shadow::beam::inner_beam_settings`]).
    Finer(Interval<f64>),
}

impl BeamStart {
    /// The search of a beam inside a beam over a larger part that ended as `outer`.
    pub fn inside(outer: &BoxClass) -> BeamStart {
        match *outer {
            BoxClass::Undecided { t } | BoxClass::Hit { t_final: t } => BeamStart::Near(t),
            BoxClass::Miss => BeamStart::At(0.0),
        }
    }

    /// [`BeamStart::inside`], with [`BeamStart::Finer`] pieces.
    pub fn finer_inside(outer: &BoxClass) -> BeamStart {
        match BeamStart::inside(outer) {
            BeamStart::Near(t) => BeamStart::Finer(t),
            other => other,
        }
    }

    /// The parameter before which every ray is known free.
    pub fn at(self) -> f64 {
        match self {
            BeamStart::At(t) => t,
            BeamStart::Near(near) | BeamStart::Finer(near) => near.inf().max(0.0),
        }
    }
}

/// The queries a shadow method asks of the scene's occluders.
pub trait Occluders {
    /// The segment from `from` to `to` for `t ∈ [start, 1]` (the caller knows it free
    /// before `start`), searched by the renderer's root finder: [`Visibility::Lit`] is a
    /// proof with a reliable finder.
    fn segment(&mut self, from: DVec3, to: DVec3, start: f64, c: &mut RootCounters) -> Occlusion;

    /// The top-level object whose surface passes nearest `p`.
    fn object_at(&mut self, p: DVec3) -> u32;

    /// Whether the segment from `from` to `to` proven meets the top-level object `object`
    /// alone (a proven root of that object's function): then it meets the scene's solid,
    /// so the segment is occluded. `false` says nothing.
    fn segment_meets_object(
        &mut self,
        object: u32,
        from: DVec3,
        to: DVec3,
        c: &mut RootCounters,
    ) -> bool;

    /// The shadow beam from `from` over every point of `light`, for `t ∈ [start, 1]` (the
    /// caller knows every ray free before `start`, see [`BeamStart`]): [`BoxClass::Miss`]
    /// proves that no ray of it meets a surface (the light is fully visible); with `inclusion`,
    /// [`BoxClass::Hit`] proves that every ray of it meets one (the light is fully hidden).
    /// Anything else is [`BoxClass::Undecided`] with the first range not cleared: every ray
    /// is free before it, which sub-beams and segments of the same light may start from.
    fn beam(
        &mut self,
        from: DVec3,
        light: &Patch,
        start: BeamStart,
        inclusion: bool,
        c: &mut RootCounters,
    ) -> BoxClass;

    /// The triangles of the scene's meshes that may block a segment from a point of the
    /// box `from` to a point of `light` (none where the scene has no meshes).
    fn triangles(&mut self, from: &IBox, light: &Patch) -> Vec<ShaftTriangle> {
        let _ = (from, light);
        Vec::new()
    }

    /// The occluders that stand for the `triangles` of [`Occluders::triangles`] that are not
    /// redundant: convex polygons, each exactly a union of the scene's triangles, holding
    /// every one of them (the faces of [`crate::mesh::MeshIndex::face`]: coplanar
    /// neighbours merged), each once, in the order of their first triangle. A segment meets
    /// one of them exactly where it meets one of those triangles or another triangle of
    /// their faces. By default each triangle alone.
    fn faces(&mut self, triangles: &[ShaftTriangle]) -> Vec<Vec<DVec3>> {
        triangle_occluders(triangles)
    }

    /// Convex polygons inside closed meshes that some segment from `from` to `light` may
    /// reach, each blocking only segments that a triangle of [`Occluders::triangles`]
    /// blocks as well (the index finds them only inside closed meshes proven embedded,
    /// [`crate::mesh::MeshIndex::inner_in`]): occluders a method may put first to close an
    /// umbra in fewer steps, which change no fraction (none where the scene has no closed
    /// meshes).
    fn inner_occluders(&mut self, from: &IBox, light: &Patch) -> Vec<Vec<DVec3>> {
        let _ = (from, light);
        Vec::new()
    }

    /// [`Occluders::beam`] against the implicit surfaces alone, for a method that treats
    /// the [`triangles`](Occluders::triangles) itself (the same as `beam` where the scene
    /// has no meshes).
    fn implicit_beam(
        &mut self,
        from: DVec3,
        light: &Patch,
        start: BeamStart,
        inclusion: bool,
        c: &mut RootCounters,
    ) -> BoxClass {
        self.beam(from, light, start, inclusion, c)
    }
}

/// A triangle that may block a segment to a light ([`Occluders::triangles`]).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ShaftTriangle {
    /// The triangle.
    pub triangle: Triangle,
    /// Whether every segment to the light that it blocks is blocked by a triangle of the
    /// same mesh that is not redundant (a face of a closed mesh turned away from the whole
    /// light: [`crate::mesh::MeshIndex::turned_away`]). The visible fractions need no
    /// redundant triangle; a proof that no triangle meets a segment needs them all.
    pub redundant: bool,
    /// The face of the scene's meshes that holds it ([`crate::mesh::MeshIndex::face_of`]).
    pub face: u32,
}

/// The `triangles` that are not redundant, each as an occluder of its own.
pub(crate) fn triangle_occluders(triangles: &[ShaftTriangle]) -> Vec<Vec<DVec3>> {
    triangles
        .iter()
        .filter(|t| !t.redundant)
        .map(|t| t.triangle.v.to_vec())
        .collect()
}

/// Work counters of soft shadows (the columns of the soft-shadow paper's Table 1 and more).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct ShadowWork {
    /// Queries (shaded point × light).
    pub queries: u64,
    /// Initial shadow beams over a whole light.
    pub initial_beams: u64,
    /// Initial beams that could not be rejected (possibly occluded).
    pub initial_occluded: u64,
    /// Initial beams proven to be blocked for every ray (umbra).
    pub umbra_proofs: u64,
    /// Sub-beams over parts of a light.
    pub sub_beams: u64,
    /// Shadow segments (stochastic samples).
    pub rays: u64,
    /// Samples decided by the last-occluder cache.
    pub cache_hits: u64,
    /// Triangles kept by the exact method's shaft culling, summed over its queries.
    pub shaft_triangles: u64,
    /// The faces of those triangles ([`Occluders::faces`]): the exact method's occluders.
    pub shaft_faces: u64,
    /// The exact method's BSP work.
    pub bsp: BspWork,
    /// The exact method's thread time per phase (zero for the other methods).
    pub exact_times: ExactTimes,
    /// Root-search counters of every test.
    pub root: RootCounters,
}

impl ShadowWork {
    /// Adds `o` into `self`.
    pub fn add(&mut self, o: &ShadowWork) {
        self.queries += o.queries;
        self.initial_beams += o.initial_beams;
        self.initial_occluded += o.initial_occluded;
        self.umbra_proofs += o.umbra_proofs;
        self.sub_beams += o.sub_beams;
        self.rays += o.rays;
        self.cache_hits += o.cache_hits;
        self.shaft_triangles += o.shaft_triangles;
        self.shaft_faces += o.shaft_faces;
        self.bsp.add(&o.bsp);
        self.exact_times.add(&o.exact_times);
        self.root.add(&o.root);
    }
}

/// A way to compute the visible fraction of an area light.
pub trait ShadowMethod: Send + Sync {
    /// The method and its settings, as the command line writes them (`beam:7`).
    fn name(&self) -> String;

    /// The width of the bound `[lower, upper]` at which the method stops refining (0 for
    /// the methods that refine to a fixed amount of work instead).
    fn tolerance(&self) -> f32 {
        0.0
    }

    /// The visible fraction of `q.light` from `q.origin`.
    fn visibility(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        work: &mut ShadowWork,
    ) -> LightVisibility;

    /// The visible fractions of a run of queries (neighbouring samples of the image, in
    /// their order), which a method may answer together to share work between neighbours;
    /// one at a time by default.
    fn visibility_run(
        &self,
        occluders: &mut dyn Occluders,
        queries: &[ShadowQuery],
        work: &mut ShadowWork,
    ) -> Vec<LightVisibility> {
        queries
            .iter()
            .map(|q| self.visibility(occluders, q, work))
            .collect()
    }
}
