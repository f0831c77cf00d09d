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

/// Owners per piece of work of [`par_offsets`] and [`owners`].
const OWNERS_PER_PIECE: usize = 4096;

/// [`offsets`] of `n` owners where owner `k` has `count(k)` items, counted in parallel
/// (each piece of owners summed, then each written from where the pieces before end).
pub(super) fn par_offsets(n: usize, count: impl Fn(usize) -> usize + Sync) -> Vec<usize> {
    let totals: Vec<usize> = (0..n.div_ceil(OWNERS_PER_PIECE))
        .into_par_iter()
        .map(|piece| {
            let start = piece * OWNERS_PER_PIECE;
            (start..(start + OWNERS_PER_PIECE).min(n)).map(&count).sum()
        })
        .collect();
    let mut first = vec![0; n + 1];
    let mut pieces = Vec::with_capacity(totals.len());
    let (mut before, mut rest) = (0, &mut first[1..]);
    for (piece, total) in totals.iter().enumerate() {
        let (mine, more) = rest.split_at_mut(OWNERS_PER_PIECE.min(rest.len()));
        pieces.push((piece * OWNERS_PER_PIECE, before, mine));
        before += total;
        rest = more;
    }
    pieces.into_par_iter().for_each(|(start, mut sum, mine)| {
        for (k, f) in mine.iter_mut().enumerate() {
            sum += count(start + k);
            *f = sum;
        }
    });
    first
}

/// The owner of each item of a flat list where owner `k` owns `first[k]..first[k + 1]`,
/// written in parallel.
pub(super) fn owners(first: &[usize]) -> Vec<u32> {
    let n = first.len() - 1;
    let mut out = vec![0; first[n]];
    let mut pieces = Vec::with_capacity(n.div_ceil(OWNERS_PER_PIECE));
    let mut rest = &mut out[..];
    for start in (0..n).step_by(OWNERS_PER_PIECE) {
        let end = (start + OWNERS_PER_PIECE).min(n);
        let (mine, more) = rest.split_at_mut(first[end] - first[start]);
        pieces.push((start..end, mine));
        rest = more;
    }
    pieces.into_par_iter().for_each(|(owned, mine)| {
        let base = first[owned.start];
        for k in owned {
            mine[first[k] - base..first[k + 1] - base].fill(k as u32);
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parallel offsets and owners are those of a plain count, for owners with no
    /// items, one or many, across pieces of work.
    #[test]
    fn offsets_and_owners_follow_the_counts() {
        for n in [0, 1, 5, OWNERS_PER_PIECE, 3 * OWNERS_PER_PIECE + 17] {
            let count = |k: usize| (k * 7 + k / 3) % 4;
            let first = par_offsets(n, count);
            assert_eq!(first, offsets((0..n).map(count)));
            let own = owners(&first);
            assert_eq!(own.len(), first[n]);
            for k in 0..n {
                assert!(own[first[k]..first[k + 1]].iter().all(|&o| o as usize == k));
            }
        }
    }
}
