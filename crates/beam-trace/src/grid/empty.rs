//! The mark of an empty cell in the grid's tables of cell functions.

/// The function index of an empty cell (no point of the surface in it).
pub const EMPTY: u32 = u32::MAX;
