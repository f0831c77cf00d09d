//! The samples of every pixel, stored flat: one vector of samples, pixel after pixel, and
//! where each pixel's samples start. A pixel without samples is background, proven missed
//! (its [`Coverage`](crate::sample::Coverage) is `[0, 0]`).

use std::ops::Range;

use rayon::prelude::*;

use super::buffers;
use crate::sample::Sample;

/// The samples of every pixel, in pixel order.
#[derive(Clone, Debug, Default)]
pub(super) struct Pixels {
    /// Every pixel's samples, pixel after pixel.
    pub(super) samples: Vec<Sample>,
    /// Pixel `p`'s samples are `samples[first[p]..first[p + 1]]`.
    first: Vec<usize>,
}

impl Pixels {
    /// No pixel yet.
    pub(super) fn new() -> Self {
        Pixels {
            samples: Vec::new(),
            first: vec![0],
        }
    }

    /// No pixel yet, with room for `pixels` pixels of `samples` samples in all.
    pub(super) fn with_capacity(pixels: usize, samples: usize) -> Self {
        let mut first = buffers::with_room(pixels + 1);
        first.push(0);
        Pixels {
            samples: buffers::with_room(samples),
            first,
        }
    }

    /// Pixels whose samples are `samples`, pixel `p`'s at `first[p]..first[p + 1]` (see
    /// [`offsets`]).
    pub(super) fn from_offsets(samples: Vec<Sample>, first: Vec<usize>) -> Self {
        debug_assert_eq!(first[first.len() - 1], samples.len());
        Pixels { samples, first }
    }

    /// The number of pixels.
    pub(super) fn len(&self) -> usize {
        self.first.len() - 1
    }

    /// Where pixel `p`'s samples lie in [`Pixels::samples`].
    pub(super) fn range(&self, p: usize) -> Range<usize> {
        self.first[p]..self.first[p + 1]
    }

    /// Pixel `p`'s samples.
    pub(super) fn pixel(&self, p: usize) -> &[Sample] {
        &self.samples[self.range(p)]
    }

    /// Appends pixels whose samples are `samples`, pixel `p`'s at `first[p]..first[p + 1]`
    /// of them (see [`offsets`]), written in place in parallel.
    pub(super) fn par_extend(
        &mut self,
        samples: impl IndexedParallelIterator<Item = Sample>,
        first: &[usize],
    ) {
        let base = self.samples.len();
        self.samples.par_extend(samples);
        debug_assert_eq!(self.samples.len() - base, first[first.len() - 1]);
        self.first.extend(first[1..].iter().map(|&f| base + f));
    }

    /// Appends the pixels of `more`.
    pub(super) fn append(&mut self, more: Pixels) {
        if self.len() == 0 && self.samples.capacity() == 0 {
            *self = more;
            return;
        }
        let base = self.samples.len();
        self.samples.extend(more.samples);
        self.first.extend(more.first[1..].iter().map(|&f| base + f));
    }
}

/// Where the items of each owner start in a flat list where owner `k` has `counts[k]` items
/// in turn, followed by the total: owner `k` owns `first[k]..first[k + 1]`.
pub(super) fn offsets(counts: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut first = Vec::with_capacity(counts.size_hint().0 + 1);
    let mut sum = 0;
    first.push(sum);
    for n in counts {
        sum += n;
        first.push(sum);
    }
    first
}

/// The owner of each item of a flat list where owner `k` owns `first[k]..first[k + 1]`.
pub(super) fn owners(first: &[usize]) -> Vec<u32> {
    let mut out = Vec::with_capacity(first[first.len() - 1]);
    for k in 0..first.len() - 1 {
        out.extend(std::iter::repeat_n(k as u32, first[k + 1] - first[k]));
    }
    out
}
