//! Exact soft shadows of polygonal occluders by lazy visibility in Plücker space (the
//! method of seed 003, with the corrections of its analysis).
//!
//! The lines from a point `x` to the points of an area light are split by the hyperplanes of
//! the occluders' edge lines in Plücker space: in each cell of that arrangement, every line
//! stabs the same occluders. A BSP of those hyperplanes, built lazily by the queries of a
//! group of points (expanded only where a query reaches a cell whose occluders are not yet
//! sorted), answers a query by pushing the light, as convex fragments of its parameter
//! square, down the tree: at each node the plane through `x` and the node's edge splits a
//! fragment, and the fragments that reach visible leaves are the visible part of the light.
//! Their area is the visible fraction, exact up to the rounding of the fragments' vertices,
//! and Lambert's formula over them the irradiance ([`form_factor`],
//! [`ExactShadows::visible_irradiance`]).
//!
//! What makes it correct here, beyond the paper:
//!
//! * **Lines against segments.** An occluder blocks `x` only if it meets the segment from
//!   the light to `x`, not the line beyond. Occluders are clipped to the slab between the
//!   light's plane and the receiver's plane (where every query point lies), so inside the
//!   slab a line is its segment.
//! * **An occluder the light straddles** (its plane crosses the light) is crossed both ways
//!   and gets two blocked cells.
//! * **Insertion signs are exact** (Shewchuk's adaptive `orient3d` on the scene's doubles, the
//!   unclipped polygons: a superset of the clipped one, so Theorem 1 still holds); a sign the
//!   other way would lose occlusion.
//! * **Determinism.** The random choices are seeded per group, so results and counters do not
//!   depend on the thread count.
//!
//! * **Proven areas.** The fragments are split in floating point. Each cut's plane comes
//!   with a bound on its error, and the query sums, over the fragments and nodes it
//!   visits, the area inside each cut's band of uncertain sign: the visible fraction lies
//!   within that sum of the fragments' area ([`ExactShadows::visible_bounds`]), wherever
//!   no occluder is cut by the slab's planes and the point lies between the occluders in
//!   front of its receiver plane and those behind it.
//!
//! The receivers are planar groups (a mesh triangle, a floor); the public queries refuse
//! points off the receiver plane.

mod bsp;
mod fragment;
mod group;
mod irradiance;
mod method;
mod orient;

pub use super::exact_work::{BspWork, ExactTimes};
pub use bsp::NODE_BYTES;
pub use group::{ExactError, ExactShadows, FractionBounds, Irradiance, Plane};
pub use irradiance::form_factor;
pub use method::Exact;

#[cfg(test)]
mod tests;
