//! Primary visibility by an octree over the view frustum: each pixel's first cell where the
//! surface may be, the way a voxel renderer finds its depth image (fidget's 3D tiles), with
//! every cell a beam over a parameter range.
//!
//! A cell is a rectangle of pixels `R` and a range `T` of the ray parameter; its enclosure is
//! `g` over every ray of `R`'s beam for `t ∈ T`. Cells are searched depth first, the nearer
//! half of `T` first, so that along every pixel's column of cells they come in increasing
//! `t`; a cell whose pixels all have their first cell already is skipped. A cell is
//!
//! * **rejected** where its enclosure is positive (or empty: `g` undefined there): no ray
//!   of `R` meets the surface in `T`;
//! * **first** for the pixels of `R` that have no first cell yet where its enclosure is
//!   negative (every ray is inside: the surface lies at its near face, which only a jump or
//!   a hole in `g`'s domain allows after positive cells), or where it may vanish and it is a
//!   leaf: one pixel wide, and `T` no longer than the pixel's cross-section at `T`'s far
//!   end (nor `epsilon`);
//! * else split: `T` in two where it is longer than the cross-section of `R`'s beam, else
//!   `R` in four and `T` in two.
//!
//! What a pixel's first cell proves: every earlier cell of its column was rejected, so no
//! ray of the pixel meets the surface before `T`: the pixel is
//! [`BoxClass::Undecided`] with `T`, and its rays search
//! from there. Where the first cell is a leaf that passes the inclusion test
//! ([`inclusion_test`]: `g` continuous over the pixel's beam and `T`, with opposite signs at
//! `T`'s ends for every ray, both ends inside the scene bounds) on `T`, or on `[inf T, p]`
//! for a probe `p` up to 16 lengths of `T` further, every ray of the pixel has its first
//! root in that range: the pixel is a [`BoxClass::Hit`] with it
//! as `T_final`. A pixel without a first cell is a
//! [`BoxClass::Miss`].
//! Each cell that is split prunes `g` to its beam over `T` ([`RayFn::restrict`]) for the
//! cells inside it, so the deep cells evaluate a few instructions of a long formula; the
//! restrictions of the cells holding a leaf are kept, and a probe past the region of the
//! leaf's own is evaluated with the next one out.
//!
//! Against the screen box structure ([`crate::beam::evaluate_box_within`]), a cell costs one
//! evaluation (a leaf that may hold the surface a few more for its inclusion test; no
//! bisection of a wide beam along `T`, no `T_final` refinement), and space and screen are
//! subdivided together.

use interval_core::Interval;

use crate::beam::{BeamScope, BoxClass, Extent, inclusion_test};
use crate::camera::{Camera, EdgeBeams};
use crate::ibox::IBox;
use crate::ray::{Beam, BeamEval, RayFn};
use crate::root::RootCounters;
use crate::root::search::{Eval, sign, sign_change};
use crate::screen::PixelRect;

/// How far [`Search::included`] looks past a leaf: up to `2^LOOK_AHEAD` of its lengths.
const LOOK_AHEAD: u32 = 4;

/// Tapes this short are not pruned for the cells inside a cell (a pruning costs about two
/// evaluations of the tape it prunes).
const PRUNE_MIN_LEN: usize = 16;

/// Where a pixel's surface may begin: the range `t` of its first cell (no ray of the pixel
/// meets the surface before it), whether every ray of the pixel meets it there, and the
/// scene function pruned to a region holding the cell.
#[derive(Clone, Debug, PartialEq)]
pub struct FirstCell {
    /// The parameter range of the cell.
    pub t: Interval<f64>,
    /// Every ray of the pixel has its first root in `t` (the inclusion test passed).
    pub hit: bool,
    /// `g` pruned for a cell holding this one, for the pixel's rays over the scope's own
    /// parameters: `t` for a Hit, the whole region of the restriction (which holds `t`)
    /// otherwise.
    pub scope: Option<BeamScope>,
}

impl FirstCell {
    /// The pixel's class: a Hit with `T_final = t` where every ray meets the surface in
    /// `t`, else Undecided in `t`.
    pub fn class(&self) -> BoxClass {
        if self.hit {
            BoxClass::Hit { t_final: self.t }
        } else {
            BoxClass::Undecided { t: self.t }
        }
    }
}

/// The first cell of each pixel of `tile` (row by row), searched in the parameter range
/// `range` (where the tile's beam lies in the scene bounds `bounds`), with `g` the scene
/// function of the camera's beams; leaves are no longer than `epsilon` or the pixel's
/// cross-section. Counts each cell's evaluation (and the inclusion tests') in
/// `counters.g_evals`.
pub fn first_cells(
    g: &mut BeamEval,
    (cam, bounds): (&Camera, &IBox),
    tile: PixelRect,
    range: Interval<f64>,
    epsilon: f64,
    counters: &mut RootCounters,
) -> Vec<Option<FirstCell>> {
    let mut search = Search {
        g,
        beams: cam.edge_beams(tile),
        bounds,
        range,
        tile,
        epsilon,
        first: vec![None; tile.area() as usize],
        filled: Filled::new(tile),
        counters,
        chain: Vec::new(),
    };
    if !range.is_empty() {
        let column = Column::of(&search.beams, tile);
        search.visit(&column, range);
    }
    search.first
}

/// A rectangle of pixels with its beam and the beam's largest spread of directions (its
/// cross-section at `t` is the spread times `t`: the origin is the eye).
struct Column {
    r: PixelRect,
    beam: Beam,
    spread: f64,
}

impl Column {
    /// The column of `r`, whose beam `beams` gives.
    fn of(beams: &EdgeBeams, r: PixelRect) -> Self {
        let beam = beams.beam(r);
        let spread = beam.dir.iter().map(|d| d.wid()).fold(0.0, f64::max);
        Self { r, beam, spread }
    }
}

/// Which pixels of a tile have their first cell: a bit per pixel, rows of 64-bit words.
struct Filled {
    tile: PixelRect,
    words: usize,
    bits: Vec<u64>,
}

impl Filled {
    /// No pixel of `tile` filled.
    fn new(tile: PixelRect) -> Self {
        let words = ((tile.x1 - tile.x0) as usize).div_ceil(64);
        Self {
            tile,
            words,
            bits: vec![0; words * (tile.y1 - tile.y0) as usize],
        }
    }

    /// Marks pixel `(x, y)`.
    fn set(&mut self, x: u32, y: u32) {
        let (row, col) = ((y - self.tile.y0) as usize, (x - self.tile.x0) as usize);
        self.bits[row * self.words + col / 64] |= 1 << (col % 64);
    }

    /// Whether every pixel of `r` (inside the tile) is marked.
    fn all(&self, r: PixelRect) -> bool {
        let (c0, c1) = (
            (r.x0 - self.tile.x0) as usize,
            (r.x1 - self.tile.x0) as usize,
        );
        (r.y0..r.y1).all(|y| {
            let row = &self.bits[(y - self.tile.y0) as usize * self.words..][..self.words];
            let mut c = c0;
            while c < c1 {
                let (word, bit) = (c / 64, c % 64);
                let n = (c1 - c).min(64 - bit);
                let mask = if n == 64 {
                    u64::MAX
                } else {
                    ((1u64 << n) - 1) << bit
                };
                if row[word] & mask != mask {
                    return false;
                }
                c += n;
            }
            true
        })
    }
}

/// One tile's search.
struct Search<'a> {
    g: &'a mut BeamEval,
    beams: EdgeBeams,
    bounds: &'a IBox,
    range: Interval<f64>,
    tile: PixelRect,
    epsilon: f64,
    first: Vec<Option<FirstCell>>,
    /// The pixels of `first` that are set.
    filled: Filled,
    counters: &'a mut RootCounters,
    /// The restrictions of `g` of the cells holding the one searched, outermost first
    /// (each over its own cell, a part of the one before); empty: the whole `g`.
    chain: Vec<BeamScope>,
}

impl Search<'_> {
    fn index(&self, x: u32, y: u32) -> usize {
        let width = (self.tile.x1 - self.tile.x0) as usize;
        (y - self.tile.y0) as usize * width + (x - self.tile.x0) as usize
    }

    /// Where every ray of the leaf's beam (set on `g` with the innermost restriction) has
    /// its first root, given none before `t`, and the restriction that holds there: `t`
    /// itself when the inclusion test passes, else `[inf t, p]` for the first
    /// `p = sup t + w·2^k` (`k ≤` [`LOOK_AHEAD`]) where the sign has changed for every ray,
    /// with `g` continuous up to it and both ends inside the scene bounds. Each probe is
    /// made with the innermost restriction whose region holds it (the whole `g` only
    /// without any), so the probes reach as far as the leaf's depth needs, each made once.
    fn included(
        &mut self,
        beam: &Beam,
        t: Interval<f64>,
        extent: &Extent<'_>,
    ) -> Option<(Interval<f64>, Option<BeamScope>)> {
        if extent.holds(t.sup()) && inclusion_test(&mut *self.g, t, self.counters) {
            return Some((t, self.chain.last().cloned()));
        }
        let start = Eval::new(&mut *self.g, self.counters).at(t.inf());
        let (a, b, w) = (t.inf(), t.sup(), t.wid());
        if w.is_nan() || w <= 0.0 || sign(start) == 0 {
            return None;
        }
        // Level `k` is the restriction `chain[k - 1]`, level 0 the whole `g` (only tried
        // without any restriction); the leaf's beam is set with the innermost.
        let outermost = usize::from(!self.chain.is_empty());
        let limit = |chain: &[BeamScope], k: usize| match k {
            0 => self.range.sup(),
            k => chain[k - 1].t.sup(),
        };
        let mut level = self.chain.len();
        let mut step = w;
        for _ in 0..=LOOK_AHEAD {
            let p = b + step;
            if level > outermost && limit(&self.chain, level) < p {
                while level > outermost && limit(&self.chain, level) < p {
                    level -= 1;
                }
                let scope = level.checked_sub(1).map(|i| &self.chain[i].tape);
                self.g.set_interval_beam(beam, scope);
            }
            if limit(&self.chain, level) < p {
                // Past the region of every restriction.
                return None;
            }
            let mut ev = Eval::new(&mut *self.g, self.counters);
            if sign_change(start, ev.at(p)) {
                if !extent.holds(p) {
                    return None;
                }
                let h = Interval::new_unchecked(a, p);
                let (_, continuous) = ev.checked(h);
                let scope = level.checked_sub(1).map(|i| self.chain[i].clone());
                return continuous.then_some((h, scope));
            }
            step *= 2.0;
        }
        None
    }

    /// Searches the cell `column × t` with the innermost restriction of the chain.
    fn visit(&mut self, column: &Column, t: Interval<f64>) {
        let Column {
            r,
            ref beam,
            spread,
        } = *column;
        if self.filled.all(r) {
            return;
        }
        self.g
            .set_interval_beam(beam, self.chain.last().map(|s| &s.tape));
        let gt = self.g.g(t);
        self.counters.g_evals += 1;
        if gt.is_empty() || gt.inf() > 0.0 {
            return;
        }
        let across = spread * t.sup().abs();
        let shallow = t.wid() <= self.epsilon.max(across);
        let leaf = r.is_pixel() && shallow;
        if gt.sup() < 0.0 || leaf {
            let extent = Extent {
                beam,
                bounds: self.bounds,
            };
            let included = if leaf && gt.inf() < 0.0 && extent.holds(t.inf()) {
                self.included(beam, t, &extent)
            } else {
                None
            };
            // A Hit's scope is asked about its range only; an undecided cell's keeps the
            // whole region it holds for, where the pixel's rays search on from the cell.
            let first = match included {
                Some((range, holds)) => FirstCell {
                    t: range,
                    hit: true,
                    scope: holds.map(|s| BeamScope { t: range, ..s }),
                },
                None => FirstCell {
                    t,
                    hit: false,
                    scope: self.chain.last().cloned(),
                },
            };
            for (x, y) in r.pixels() {
                let i = self.index(x, y);
                if self.first[i].is_none() {
                    self.first[i] = Some(first.clone());
                    self.filled.set(x, y);
                }
            }
            return;
        }
        // The cells inside this one search with `g` pruned to it; where pruning decides
        // nothing, the tape keeps the wider region it holds for.
        let mut pushed = false;
        if let Some(tape) = self.g.scope()
            && tape.len() > PRUNE_MIN_LEN
        {
            self.g.restrict(t);
            if let Some(pruned) = self.g.scope().filter(|p| !p.ptr_eq(&tape)) {
                self.chain.push(BeamScope {
                    tape: pruned,
                    t,
                    escalated: false,
                });
                pushed = true;
            }
        }
        // Each pixel's cells come in increasing `t` either way: a quadrant's halves one
        // after the other.
        let (near, far) = t.bisect();
        if shallow {
            for q in r.split() {
                let quadrant = Column::of(&self.beams, q);
                self.visit(&quadrant, near);
                self.visit(&quadrant, far);
            }
        } else {
            self.visit(column, near);
            self.visit(column, far);
        }
        if pushed {
            self.chain.pop();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bitmap agrees with a plain set of pixels on every rectangle of a tile wider than
    /// one word, after marking a scattered set.
    #[test]
    fn filled_pixels_agree_with_a_plain_set() {
        let tile = PixelRect {
            x0: 3,
            y0: 5,
            x1: 3 + 70,
            y1: 5 + 4,
        };
        let mut filled = Filled::new(tile);
        let mut plain = std::collections::HashSet::new();
        for (k, (x, y)) in tile.pixels().enumerate() {
            if k % 7 != 3 {
                filled.set(x, y);
                plain.insert((x, y));
            }
        }
        // Then every pixel of the second row but one.
        for x in tile.x0..tile.x1 {
            if x != 40 {
                filled.set(x, 6);
                plain.insert((x, 6));
            }
        }
        for y0 in tile.y0..tile.y1 {
            for y1 in y0 + 1..=tile.y1 {
                for x0 in tile.x0..tile.x1 {
                    for x1 in x0 + 1..=tile.x1 {
                        let r = PixelRect { x0, y0, x1, y1 };
                        let expected = r.pixels().all(|p| plain.contains(&p));
                        assert_eq!(filled.all(r), expected, "{r:?}");
                    }
                }
            }
        }
    }
}
