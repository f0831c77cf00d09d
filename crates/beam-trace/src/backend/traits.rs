//! What a backend is: [`Backend`] prepares [`Queries`] for one scene and plan.

use glam::DVec3;

use super::query::{
    Answers, BeamQuery, CellQuery, Classified, DirectHits, HitQuery, QueryKind, RayQuery,
    SegmentQuery, ShadeBatch, SoftAnswers, Support, VariationQuery,
};
use crate::error::Error;
use crate::frustum::TileCells;
use crate::plan::Plan;
use crate::progress::Progress;
use crate::root::RootResult;
use crate::sample::Hit;
use crate::scene::Scene;
use crate::shadow::hard::Visibility;
use crate::shadow::{ShadowQuery, ShadowSpec};
use crate::stats::PassStats;

/// Answers the queries of the passes for one scene and plan.
///
/// Every method answers a batch (any size, empty included) in the order of the queries, or
/// fails with an [`Error`] naming the backend; a backend is asked only the kinds it
/// supports.
pub trait Queries: Sync {
    /// Classifies each beam: [`BoxClass::Miss`](crate::beam::BoxClass::Miss) proves that no ray of it meets a surface
    /// where its parent left it open; [`BoxClass::Hit`](crate::beam::BoxClass::Hit) that every ray has its first root in
    /// `T_final`; else [`BoxClass::Undecided`](crate::beam::BoxClass::Undecided) with the first range not rejected.
    fn beams(&self, queries: &[BeamQuery]) -> Result<Answers<Classified>, Error>;

    /// The first cells of the frustum octree of each tile's pixels that have one
    /// ([`TileCells`]): where the pixel's rays may first meet a surface, none before
    /// ([`crate::frustum`]); a pixel without one has no ray that meets a surface. Each
    /// tile's area in pixels is added to `progress` as its answer is made (a batch is
    /// much work: the tiles of a whole image).
    fn first_cells(
        &self,
        queries: &[CellQuery],
        progress: &dyn Progress,
    ) -> Result<Answers<TileCells>, Error>;

    /// The first root of each ray in its window.
    fn roots(&self, queries: &[RayQuery]) -> Result<Answers<RootResult>, Error>;

    /// The hit record of each ray and root enclosure: the shading point inside the
    /// enclosure, the leaf surface that shades it, the direction to the eye.
    fn hit_points(&self, queries: &[HitQuery]) -> Result<Answers<Hit>, Error>;

    /// The hit records that follow from a ray's root enclosure alone, which the caller
    /// may make without asking [`hit_points`](Self::hit_points) (the same records):
    /// `None` (the default) where every record is the backend's to make.
    fn direct_hits(&self) -> Option<DirectHits> {
        None
    }

    /// The spread of the shaded colour over each hit region (see
    /// [`aa::shading_variation`](crate::aa::shading_variation)).
    fn shading_variation(&self, queries: &[VariationQuery]) -> Result<Answers<f64>, Error>;

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
