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
mod query;
mod routing;
mod traits;

pub use query::{
    Answers, BeamQuery, CellQuery, Classified, DirectHits, HitQuery, QueryKind, RayQuery,
    SegmentQuery, ShadeBatch, ShadeLight, ShadeSample, SoftAnswers, Support, VariationQuery,
};
pub(crate) use routing::Routed;
pub use routing::Routing;
pub use traits::{Backend, Prepared, Queries};
