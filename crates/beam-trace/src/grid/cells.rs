//! How the grid numbers its cells: the index of a cell in its tables (`x` fastest, then `y`,
//! then `z`) and back, and the mark of an empty cell. Shared by the grid and by the
//! classification of blocks of cells, which number blocks the same way.

/// The function index of an empty cell (no point of the surface in it).
pub const EMPTY: u32 = u32::MAX;

/// The index of cell `c` in a grid of `n` cells per axis.
#[inline]
pub(super) fn index(c: [u32; 3], n: [u32; 3]) -> usize {
    c[0] as usize + n[0] as usize * (c[1] as usize + n[1] as usize * c[2] as usize)
}

/// The cell of index `idx` in a grid of `n` cells per axis.
#[inline]
pub(super) fn cell(idx: usize, n: [u32; 3]) -> [u32; 3] {
    let (n0, n1) = (n[0] as usize, n[1] as usize);
    [
        (idx % n0) as u32,
        ((idx / n0) % n1) as u32,
        (idx / (n0 * n1)) as u32,
    ]
}
