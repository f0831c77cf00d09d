//! The batches of image rows the passes hand the backend, and what a primary pass returns.

use super::pixels::Pixels;
use crate::stats::PassStats;

/// Rows of pixels a pass hands the backend per batch: batches big enough to keep every
/// core (or the GPU) busy, small enough to show progress and bound memory.
pub(super) const ROWS_PER_BATCH: u32 = 256;

/// A batch of whole image rows: the pixels `first..first + n` (row-major).
pub(super) struct RowBatch {
    /// Rows in the batch.
    pub(super) rows: u32,
    /// Its first pixel.
    pub(super) first: usize,
    /// Its number of pixels.
    pub(super) n: usize,
}

/// The batches of [`ROWS_PER_BATCH`] rows that cover a `w × h` image, top to bottom.
pub(super) fn row_batches(w: u32, h: u32) -> impl Iterator<Item = RowBatch> {
    (0..h).step_by(ROWS_PER_BATCH as usize).map(move |y0| {
        let rows = ROWS_PER_BATCH.min(h - y0);
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
