//! Hard shadows from point lights: the interval shadow segment test.
//!
//! The segment from a surface point to the light is searched with the renderer's root
//! finder, through the regular grid when there is one (segments through empty cells cost
//! nothing). With a reliable finder, "no root" is a proof that the segment is free: the
//! point is lit. A root means the light is blocked; a search that hits its limits is
//! counted apart and treated as blocked.

use crate::root::RootResult;

/// Whether a segment reaches the light.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Visibility {
    /// Proven: nothing lies on the segment.
    Lit,
    /// A surface lies on the segment (a root was found), or an unreliable finder said so.
    Occluded,
    /// The search hit its limits; treated as occluded.
    Undecided,
}

/// The visibility of a segment from the root search over it (`t ∈ [0, 1]`), by a finder
/// that is `reliable` or not.
pub fn segment_visibility(search: RootResult, reliable: bool) -> Visibility {
    match search {
        RootResult::NoRoot if reliable => Visibility::Lit,
        RootResult::NoRoot | RootResult::Root { .. } => Visibility::Occluded,
        RootResult::Undecided { .. } => Visibility::Undecided,
    }
}
