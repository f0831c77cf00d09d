//! The batches of image rows the passes hand the backend, and what a primary pass returns.

use super::pixels::Pixels;
use crate::stats::PassStats;

/// Rows of pixels the pixel-beams pass hands the backend per batch: batches big enough to
/// keep every core (or the GPU) busy, small enough to show progress and bound memory.
pub(super) const ROWS_PER_BATCH: u32 = 256;

/// Pixels the primary-rays pass hands the backend per batch (whole rows, at least one).
/// Its records of a batch (a ray's query, its root, its hit point: a few hundred bytes
/// a ray) are made afresh for every batch; in batches of this size the allocator hands
/// the same memory out again instead of mapping fresh pages for each (csg3d-660 at 512 ×
/// 512 on two threads: a quarter fewer page faults and 10 % less processor time than
/// batches of 256 rows; batches of 16 Ki pixels do no better, and a GPU answers fewer,
/// larger batches more cheaply).
pub(super) const RAY_BATCH_PIXELS: u32 = 64 * 1024;

/// A batch of whole image rows: the pixels `first..first + n` (row-major).
pub(super) struct RowBatch {
    /// Rows in the batch.
    pub(super) rows: u32,
    /// Its first pixel.
    pub(super) first: usize,
    /// Its number of pixels.
    pub(super) n: usize,
}

/// The batches of `per_batch` rows (at least one) that cover a `w × h` image, top to
/// bottom.
pub(super) fn row_batches(w: u32, h: u32, per_batch: u32) -> impl Iterator<Item = RowBatch> {
    let per_batch = per_batch.max(1);
    (0..h).step_by(per_batch as usize).map(move |y0| {
        let rows = per_batch.min(h - y0);
        RowBatch {
            rows,
            first: (y0 * w) as usize,
            n: (rows * w) as usize,
        }
    })
}

/// The samples of every pixel from a primary pass, the cost of each pixel, and the pass's
/// statistics.
pub(super) type PixelSamples = (Pixels, Vec<f32>, PassStats);
