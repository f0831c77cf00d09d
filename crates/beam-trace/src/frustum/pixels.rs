//! Which pixels of a tile the octree has settled: the bitmaps of pixels done and pending,
//! with per-node counts, and the pending pixels' rays.
//!
//! The search asks these of every cell it visits: each is marked `#[inline]` so that it is
//! inlined into the search across the module's boundary (without, the molecule's octree
//! pass took 6 % longer).

use crate::ray::Beam;
use crate::screen::PixelRect;

/// Which pixels of a tile have their first cell and which of those still have rays
/// searched by the octree ([`Pending`]): two bits per pixel (rows of 64-bit words), and
/// per node of the tile's quadtree the number of its pixels *done* (a first cell, no ray
/// of theirs searched on) and *touched* (a first cell, rays searched on or not) through it
/// or a node inside it. A pixel that is neither is *open*.
#[derive(Default)]
pub(super) struct Filled {
    tile: PixelRect,
    words: usize,
    done: Vec<u64>,
    pending: Vec<u64>,
    done_counts: Vec<u32>,
    touched_counts: Vec<u32>,
}

impl Filled {
    /// Every pixel of `tile` open, with counts for `nodes` nodes of its quadtree (0: none
    /// kept, as for a tile too deep to keep a table per node).
    #[inline]
    pub(super) fn reset(&mut self, tile: PixelRect, nodes: usize) {
        self.tile = tile;
        self.words = ((tile.x1 - tile.x0) as usize).div_ceil(64);
        let len = self.words * (tile.y1 - tile.y0) as usize;
        for bits in [&mut self.done, &mut self.pending] {
            bits.clear();
            bits.resize(len, 0);
        }
        for counts in [&mut self.done_counts, &mut self.touched_counts] {
            counts.clear();
            counts.resize(nodes, 0);
        }
    }

    /// Adds `n` to the counts `counts` of node `node` and of every node holding it.
    #[inline]
    fn count(counts: &mut [u32], node: usize, n: u32) {
        if counts.is_empty() || n == 0 {
            return;
        }
        let mut k = node;
        loop {
            counts[k] += n;
            if k == 0 {
                break;
            }
            k = (k - 1) / 4;
        }
    }

    /// Marks every pixel of `r`, node `node` of the quadtree, that is not done yet as done,
    /// calling `each` with it and whether it had rays pending (else it was open).
    #[inline]
    pub(super) fn fill(&mut self, r: PixelRect, node: usize, mut each: impl FnMut(u32, u32, bool)) {
        let (mut opened, mut settled) = (0, 0);
        for (x, y) in r.pixels() {
            let (word, bit) = self.at(x, y);
            if self.done[word] & bit != 0 {
                continue;
            }
            let pending = self.pending[word] & bit != 0;
            self.done[word] |= bit;
            self.pending[word] &= !bit;
            each(x, y, pending);
            if pending {
                settled += 1;
            } else {
                opened += 1;
            }
        }
        Self::count(&mut self.done_counts, node, opened + settled);
        Self::count(&mut self.touched_counts, node, opened);
    }

    /// Marks the open pixel `(x, y)`, node `node` of the quadtree, as having its first
    /// cell with rays pending.
    #[inline]
    pub(super) fn pend(&mut self, x: u32, y: u32, node: usize) {
        let (word, bit) = self.at(x, y);
        self.pending[word] |= bit;
        Self::count(&mut self.touched_counts, node, 1);
    }

    /// Marks the pixel `(x, y)` with rays pending, node `node` of the quadtree, as done.
    #[inline]
    pub(super) fn settle(&mut self, x: u32, y: u32, node: usize) {
        let (word, bit) = self.at(x, y);
        self.pending[word] &= !bit;
        self.done[word] |= bit;
        Self::count(&mut self.done_counts, node, 1);
    }

    /// Whether every pixel of `r`, node `node` of the quadtree, is done: by the node's
    /// count. A node is only asked about while no node holding it was filled whole (a
    /// filled node is not searched again, nor anything inside it), so the count of its
    /// own fills and those inside it is all of its pixels done.
    #[inline]
    pub(super) fn complete(&self, r: PixelRect, node: usize) -> bool {
        match self.done_counts.get(node) {
            Some(&n) => u64::from(n) == r.area(),
            None => self.all(r),
        }
    }

    /// Whether every pixel of `r`, node `node` of the quadtree, is open: by the node's
    /// count where it is kept (asked, as [`complete`](Self::complete), only of a node that
    /// no node holding it was filled whole).
    #[inline]
    pub(super) fn untouched(&self, r: PixelRect, node: usize) -> bool {
        match self.touched_counts.get(node) {
            Some(&n) => n == 0,
            None => (r.y0..r.y1).all(|y| {
                self.row_words(r, y)
                    .all(|(_, done, pending, mask)| (done | pending) & mask == 0)
            }),
        }
    }

    /// The smallest rectangle holding every open pixel of `r` (inside the tile, not every
    /// one open); `None` where none is.
    #[inline]
    pub(super) fn open(&self, r: PixelRect) -> Option<PixelRect> {
        let (mut lo, mut hi) = (usize::MAX, 0);
        let (mut top, mut bottom) = (u32::MAX, 0);
        for y in r.y0..r.y1 {
            for (word, done, pending, mask) in self.row_words(r, y) {
                let open = !(done | pending) & mask;
                if open != 0 {
                    let base = word * 64;
                    lo = lo.min(base + open.trailing_zeros() as usize);
                    hi = hi.max(base + 63 - open.leading_zeros() as usize);
                    top = top.min(y);
                    bottom = bottom.max(y);
                }
            }
        }
        (top != u32::MAX).then(|| PixelRect {
            x0: self.tile.x0 + lo as u32,
            y0: top,
            x1: self.tile.x0 + hi as u32 + 1,
            y1: bottom + 1,
        })
    }

    /// The pixels of `r`, node `node` of the quadtree, with rays pending, row by row: `each`
    /// is called with each of them. Where the node's counts are kept none is looked for
    /// when they say there is none: every pixel touched is done or pending, so the node's
    /// pending pixels are its touched less its done (a cell away from every undecided pixel
    /// has none).
    #[inline]
    pub(super) fn pending_in(&self, r: PixelRect, node: usize, mut each: impl FnMut(u32, u32)) {
        if let (Some(touched), Some(done)) =
            (self.touched_counts.get(node), self.done_counts.get(node))
            && touched == done
        {
            return;
        }
        for y in r.y0..r.y1 {
            for (word, _, pending, mask) in self.row_words(r, y) {
                let mut bits = pending & mask;
                while bits != 0 {
                    let b = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    each(self.tile.x0 + (word * 64 + b) as u32, y);
                }
            }
        }
    }

    /// The word of pixel `(x, y)` in the bitmaps, and its bit there.
    #[inline]
    fn at(&self, x: u32, y: u32) -> (usize, u64) {
        let (row, col) = ((y - self.tile.y0) as usize, (x - self.tile.x0) as usize);
        (row * self.words + col / 64, 1 << (col % 64))
    }

    /// Whether pixel `(x, y)` is done.
    #[inline]
    fn is_done(&self, x: u32, y: u32) -> bool {
        let (word, bit) = self.at(x, y);
        self.done[word] & bit != 0
    }

    /// Whether pixel `(x, y)` has rays pending.
    #[inline]
    pub(super) fn is_pending(&self, x: u32, y: u32) -> bool {
        let (word, bit) = self.at(x, y);
        self.pending[word] & bit != 0
    }

    /// Whether every pixel of `r` (inside the tile) is done.
    #[inline]
    fn all(&self, r: PixelRect) -> bool {
        if r.is_pixel() {
            return self.is_done(r.x0, r.y0);
        }
        (r.y0..r.y1).all(|y| {
            self.row_words(r, y)
                .all(|(_, done, _, mask)| done & mask == mask)
        })
    }

    /// The words of row `y` that hold `r`'s columns: each word's index in the row, its
    /// bits done and pending, and the mask of `r`'s columns in it.
    #[inline]
    fn row_words(&self, r: PixelRect, y: u32) -> impl Iterator<Item = (usize, u64, u64, u64)> + '_ {
        let (c0, c1) = (
            (r.x0 - self.tile.x0) as usize,
            (r.x1 - self.tile.x0) as usize,
        );
        let row = (y - self.tile.y0) as usize * self.words;
        let (done, pending) = (
            &self.done[row..][..self.words],
            &self.pending[row..][..self.words],
        );
        // No word for an empty rectangle.
        let words = (c0 / 64)..c1.div_ceil(64).max(c0 / 64);
        words.map(move |word| {
            // Columns `from..to` of the word.
            let from = c0.max(word * 64) - word * 64;
            let to = c1.min(word * 64 + 64) - word * 64;
            let mask = if to - from == 64 {
                u64::MAX
            } else {
                ((1u64 << (to - from)) - 1) << from
            };
            (word, done[word], pending[word], mask)
        })
    }
}

/// The rays of a tile's undecided pixels that the octree searches on past their first
/// cells (the pixels [`Filled`] marks pending): each such pixel's node, first cell and
/// rays, each ray's beam and whether it is still searched.
#[derive(Default)]
pub(super) struct Pending {
    /// Per pixel of the tile (row-major), its index in `pixels`, where it has one.
    slot: Vec<u32>,
    /// The pixels with rays pending.
    pixels: Vec<PendingPixel>,
    /// The rays traced per pixel.
    per: usize,
    /// The rays of the pixels, `per` after each other; `None` once settled.
    rays: Vec<Option<PendingRay>>,
}

/// A ray of a [`PendingPixel`]: its beam (of one ray) and the evaluations its own searches
/// may still spend (the search's budget per ray in all; the cells it shares with
/// other rays do not count).
#[derive(Copy, Clone)]
pub(super) struct PendingRay {
    pub(super) beam: Beam,
    pub(super) budget: u64,
}

/// A pixel of [`Pending`].
#[derive(Copy, Clone)]
pub(super) struct PendingPixel {
    /// Its quadtree node.
    pub(super) node: usize,
    /// Its first cell's index among the tile's first cells.
    pub(super) cell: u32,
    /// How many of its rays are still searched.
    left: u32,
}

impl Pending {
    /// No pixel pending, in a tile of `area` pixels, each with `per` rays traced.
    #[inline]
    pub(super) fn reset(&mut self, area: usize, per: usize) {
        self.per = per;
        self.slot.clear();
        self.slot.resize(area, u32::MAX);
        self.pixels.clear();
        self.rays.clear();
    }

    /// Makes the pixel of row-major index `k` pending, node `node` of the quadtree, with its
    /// first cell `cell` and its rays' beams `rays` (as many as the tile traces per pixel),
    /// each with `budget` evaluations to spend.
    #[inline]
    pub(super) fn add(
        &mut self,
        k: usize,
        (node, cell): (usize, u32),
        rays: impl Iterator<Item = Beam>,
        budget: u64,
    ) {
        self.slot[k] = self.pixels.len() as u32;
        self.pixels.push(PendingPixel {
            node,
            cell,
            left: self.per as u32,
        });
        self.rays
            .extend(rays.map(|beam| Some(PendingRay { beam, budget })));
        debug_assert_eq!(self.rays.len(), self.pixels.len() * self.per);
    }

    /// The pending pixel of row-major index `k` in the tile, where it is one.
    #[inline]
    pub(super) fn pixel(&self, k: usize) -> Option<&PendingPixel> {
        self.pixels.get(*self.slot.get(k)? as usize)
    }

    /// The rays of the pixel of row-major index `k`, `None` for those settled (all `None`
    /// where the pixel is not pending).
    #[inline]
    fn rays(&self, k: usize) -> &[Option<PendingRay>] {
        let first = self.slot.get(k).map_or(usize::MAX, |&s| s as usize);
        self.rays
            .get(first.saturating_mul(self.per)..)
            .map_or(&[], |rays| &rays[..self.per])
    }

    /// The rays still searched of the pixel of row-major index `k`.
    #[inline]
    pub(super) fn rays_of(&self, k: usize) -> impl Iterator<Item = &Beam> {
        self.rays(k).iter().flatten().map(|ray| &ray.beam)
    }

    /// Ray `i` of the pixel of row-major index `k`, where it is still searched.
    #[inline]
    pub(super) fn ray(&self, k: usize, i: usize) -> Option<PendingRay> {
        self.rays(k).get(i).copied().flatten()
    }

    /// Takes `spent` evaluations from the budget of ray `i` of the pixel of row-major index
    /// `k`.
    #[inline]
    pub(super) fn spend(&mut self, k: usize, i: usize, spent: u64) {
        if let Some(s) = self.slot.get(k)
            && let Some(Some(ray)) = self.rays.get_mut(*s as usize * self.per + i)
        {
            ray.budget = ray.budget.saturating_sub(spent);
        }
    }

    /// Settles ray `i` of the pixel of row-major index `k`; returns whether that was the
    /// pixel's last ray still searched.
    #[inline]
    pub(super) fn settle(&mut self, k: usize, i: usize) -> bool {
        let Some(&s) = self.slot.get(k) else {
            return false;
        };
        let (pixel, ray) = (
            &mut self.pixels[s as usize],
            &mut self.rays[s as usize * self.per + i],
        );
        if ray.take().is_some() {
            pixel.left -= 1;
        }
        pixel.left == 0
    }

    /// Settles every ray still searched of the pixel of row-major index `k`, calling
    /// `each` with the pixel's first cell and the ray's index among the pixel's rays.
    #[inline]
    pub(super) fn settle_all(&mut self, k: usize, mut each: impl FnMut(u32, usize)) {
        let Some(&s) = self.slot.get(k) else {
            return;
        };
        let Some(pixel) = self.pixels.get_mut(s as usize) else {
            return;
        };
        let rays = &mut self.rays[s as usize * self.per..][..self.per];
        for (i, ray) in rays.iter_mut().enumerate() {
            if ray.take().is_some() {
                each(pixel.cell, i);
            }
        }
        pixel.left = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frustum::quadtree_nodes;
    use std::collections::HashSet;

    /// The smallest rectangle holding `pixels` (`None` for none).
    fn bounding(pixels: &[(u32, u32)]) -> Option<PixelRect> {
        Some(PixelRect {
            x0: pixels.iter().map(|p| p.0).min()?,
            y0: pixels.iter().map(|p| p.1).min()?,
            x1: pixels.iter().map(|p| p.0).max()? + 1,
            y1: pixels.iter().map(|p| p.1).max()? + 1,
        })
    }

    /// The one-pixel rectangle of `(x, y)`.
    fn pixel(x: u32, y: u32) -> PixelRect {
        PixelRect {
            x0: x,
            y0: y,
            x1: x + 1,
            y1: y + 1,
        }
    }

    /// What the bitmaps say of `r` against plain sets of the pixels done and pending: done
    /// whole, untouched, the rectangle of the open pixels, the pixels pending.
    fn check_against_sets(
        filled: &Filled,
        (r, node): (PixelRect, usize),
        done: &HashSet<(u32, u32)>,
        pending: &HashSet<(u32, u32)>,
    ) {
        let open: Vec<(u32, u32)> = r
            .pixels()
            .filter(|p| !done.contains(p) && !pending.contains(p))
            .collect();
        assert_eq!(
            filled.complete(r, node),
            r.pixels().all(|p| done.contains(&p)),
            "{r:?}"
        );
        assert_eq!(
            filled.untouched(r, node),
            open.len() as u64 == r.area(),
            "{r:?}"
        );
        assert_eq!(filled.open(r), bounding(&open), "{r:?}");
        let mut listed = Vec::new();
        filled.pending_in(r, node, |x, y| listed.push((x, y)));
        let expected: Vec<(u32, u32)> = r.pixels().filter(|p| pending.contains(p)).collect();
        assert_eq!(listed, expected, "{r:?}");
    }

    /// The bitmaps agree with plain sets of pixels on every rectangle of a tile wider than
    /// one word (done whole, untouched, the rectangle of the open pixels, the pixels
    /// pending), after marking a scattered set done, another pending, and settling some of
    /// those.
    #[test]
    fn filled_pixels_agree_with_plain_sets() {
        let tile = PixelRect {
            x0: 3,
            y0: 5,
            x1: 3 + 70,
            y1: 5 + 4,
        };
        let mut filled = Filled::default();
        filled.reset(tile, 0);
        let (mut done, mut pending) = (HashSet::new(), HashSet::new());
        for (k, (x, y)) in tile.pixels().enumerate() {
            match k % 7 {
                3 => {}
                5 => {
                    filled.pend(x, y, 0);
                    pending.insert((x, y));
                }
                _ => filled.fill(pixel(x, y), 0, |_, _, was| assert!(!was)),
            }
            if k % 7 != 3 && k % 7 != 5 {
                done.insert((x, y));
            }
        }
        // Then every pixel of the second row but one, settling those pending.
        for x in tile.x0..tile.x1 {
            if x != 40 {
                let was = pending.remove(&(x, 6));
                filled.fill(pixel(x, 6), 0, |_, _, p| assert_eq!(p, was));
                done.insert((x, 6));
            }
        }
        // And one pixel of the third row settled by itself.
        let settled = (tile.x0..tile.x1)
            .find(|&x| pending.contains(&(x, 7)))
            .unwrap();
        filled.settle(settled, 7, 0);
        pending.remove(&(settled, 7));
        done.insert((settled, 7));
        for y0 in tile.y0..tile.y1 {
            for y1 in y0 + 1..=tile.y1 {
                for x0 in tile.x0..tile.x1 {
                    for x1 in x0 + 1..=tile.x1 {
                        let r = PixelRect { x0, y0, x1, y1 };
                        check_against_sets(&filled, (r, 0), &done, &pending);
                    }
                }
            }
        }
    }

    /// The per-node counts agree with the bitmaps (done whole, untouched, the rectangle of
    /// the open pixels) on every node that the search may still ask about (no node holding
    /// it filled whole), after fills of nodes, pixels made pending and pixels settled in a
    /// scattered order, on a tile whose sides split unevenly.
    #[test]
    fn node_counts_agree_with_the_bitmaps() {
        let tile = PixelRect {
            x0: 64,
            y0: 128,
            x1: 64 + 45,
            y1: 128 + 23,
        };
        // Every node with its rectangle and the nodes holding it.
        let mut nodes = Vec::new();
        let mut stack = vec![(tile, 0usize, Vec::new())];
        while let Some((r, id, above)) = stack.pop() {
            let mut inner = above.clone();
            inner.push(id);
            for (k, q) in r.numbered_quadrants() {
                if !r.is_pixel() {
                    stack.push((q, 4 * id + 1 + k, inner.clone()));
                }
            }
            nodes.push((r, id, above));
        }
        let mut filled = Filled::default();
        filled.reset(tile, quadtree_nodes(tile).unwrap_or(0));
        let (mut done, mut pending) = (HashSet::new(), HashSet::new());
        let mut whole = HashSet::new();
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let (mut settled, mut with_pending) = (0, 0);
        let mut made_pending: Vec<(u32, u32, usize)> = Vec::new();
        for step in 0..600 {
            // A node that may still be searched: none holding it filled whole.
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let (r, id, above) = &nodes[(state >> 33) as usize % nodes.len()];
            if whole.contains(id) || above.iter().any(|a| whole.contains(a)) {
                continue;
            }
            let (x, y) = (r.x0, r.y0);
            if step % 4 == 1 {
                // A pending pixel settled at its own node (none holding it was filled whole:
                // that would have settled it).
                if let Some(&(x, y, id)) =
                    made_pending.iter().find(|p| pending.contains(&(p.0, p.1)))
                {
                    filled.settle(x, y, id);
                    pending.remove(&(x, y));
                    done.insert((x, y));
                    whole.insert(id);
                    settled += 1;
                }
            } else if r.is_pixel() && step % 3 == 0 && !done.contains(&(x, y)) {
                if pending.insert((x, y)) {
                    // A leaf's pixel made pending.
                    filled.pend(x, y, *id);
                    made_pending.push((x, y, *id));
                }
            } else {
                filled.fill(*r, *id, |x, y, was| {
                    assert_eq!(pending.remove(&(x, y)), was);
                    done.insert((x, y));
                });
                whole.insert(*id);
            }
            with_pending += usize::from(!pending.is_empty());
            for (r, id, above) in &nodes {
                if above.iter().any(|a| whole.contains(a)) {
                    continue;
                }
                check_against_sets(&filled, (*r, *id), &done, &pending);
            }
        }
        assert!(whole.len() > 20, "{} fills", whole.len());
        assert!(
            settled > 0 && with_pending > 20,
            "{settled} settled, {with_pending}"
        );
    }
}
