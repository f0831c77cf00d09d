//! The leaves' sign classes over every cell, flat or from coarser cells.
//!
//! A cell's classes are what the grid's CSG reduction starts from (see [`super::reduce`]):
//! per used leaf, proven positive, negative, undefined, or unknown over the cell's
//! classification box. The flat classification evaluates every leaf on every cell. On a
//! fine grid most of that work is repeated: the two-level classification first classifies
//! blocks of up to `BLOCK³` cells (on the hull of their classification boxes), and a cell then
//! inherits every class its block proved, a proof over the block being one over any part of
//! it, and evaluates only the leaves still unknown, each with its tape pruned to the block
//! (equal to the leaf on the block, with the same enclosure over any part of it). Cells of
//! blocks where every leaf is decided cost nothing. The classes are those of the flat
//! classification wherever interval evaluation is inclusion-monotone (it is, for every
//! operation here); either way each one is proven over its cell.

use implicit_expr::{Evaluator, Tape};
use interval_core::Interval;
use rayon::prelude::*;

use super::box_eval::BoxEval;
use super::cells::{cell as cell_of, index};
use super::reduce::{C_NEG, C_POS, C_UNKNOWN, C_UNKNOWN_DEFINED, classify};
use crate::ibox::IBox;

/// Cells per block side in the two-level classification, on axes of at least
/// [`TWO_LEVEL_MIN`] cells (one cell on the others).
const BLOCK: u32 = 4;

/// Axes with at least this many cells are divided into blocks.
const TWO_LEVEL_MIN: u32 = 2 * BLOCK;

/// Blocks smaller than this many cells do not pay for their own classification.
const BLOCK_MIN_CELLS: u32 = 16;

/// The classes of every cell (`nused` per cell, in cell order), per cell the smallest
/// mignitude over the cell of its leaves of proven sign (a lower bound), and the number of
/// leaf evaluations spent.
pub(super) struct Classes {
    pub(super) classes: Vec<u8>,
    pub(super) bound: Vec<f64>,
    pub(super) leaf_evals: u64,
}

/// The leaves to classify: one tape with every used leaf as an output, and each leaf's own
/// tape (which proves definedness where the leaf is not total).
pub(super) struct LeafTapes {
    pub(super) all: Tape,
    pub(super) each: Vec<Tape>,
    pub(super) total: Vec<bool>,
}

/// Per-thread evaluators of the flat classification.
struct Flat {
    all: Evaluator<Interval<f64>>,
    one: BoxEval,
    values: Vec<Interval<f64>>,
}

impl Flat {
    fn new(t: &LeafTapes) -> Self {
        Self {
            all: Evaluator::new(&t.all),
            one: BoxEval::default(),
            values: vec![Interval::EMPTY; t.each.len()],
        }
    }

    /// The classes of every leaf over `b` into `out`, and the bound of the signed ones.
    fn classify(&mut self, t: &LeafTapes, b: &IBox, out: &mut [u8], bound: &mut f64) {
        self.all
            .eval_outputs(b, &mut self.values)
            .expect("tape in x y z");
        for (k, o) in out.iter_mut().enumerate() {
            let (f, defined) = if t.total[k] {
                (self.values[k], true)
            } else {
                self.one
                    .on(&t.each[k])
                    .eval_defined(b)
                    .expect("tape in x y z")
            };
            *o = classify(f, defined);
            if matches!(*o, C_POS | C_NEG) {
                *bound = bound.min(f.mig());
            }
        }
    }
}

/// Classifies `ncells` cells (`cell_box(idx)` the classification box of cell `idx`) with
/// every leaf.
fn flat(t: &LeafTapes, ncells: usize, cell_box: &(dyn Fn(usize) -> IBox + Sync)) -> Classes {
    let nused = t.each.len();
    let mut classes = vec![0_u8; ncells * nused];
    let mut bound = vec![f64::INFINITY; ncells];
    if nused > 0 {
        classes
            .par_chunks_mut(nused)
            .zip(bound.par_iter_mut())
            .enumerate()
            .for_each_init(
                || Flat::new(t),
                |st, (idx, (out, bound))| st.classify(t, &cell_box(idx), out, bound),
            );
    }
    Classes {
        classes,
        bound,
        leaf_evals: (ncells * nused) as u64,
    }
}

/// The classes of the cells of a grid of `n` cells per axis; `boundary(a, i)` is boundary
/// `i` on axis `a` (non-decreasing) and `margin` the classification margin per axis.
pub(super) fn classify_cells(
    t: &LeafTapes,
    n: [u32; 3],
    boundary: &(dyn Fn(usize, u32) -> f64 + Sync),
    margin: [f64; 3],
) -> Classes {
    let box_of = |lo: [u32; 3], hi: [u32; 3]| -> IBox {
        std::array::from_fn(|a| {
            Interval::new_unchecked(
                boundary(a, lo[a]) - margin[a],
                boundary(a, hi[a]) + margin[a],
            )
        })
    };
    let ncells = n.iter().map(|&k| k as usize).product::<usize>();
    let fine_box = |idx: usize| {
        let c = cell_of(idx, n);
        box_of(c, c.map(|i| i + 1))
    };
    let nused = t.each.len();
    let side: [u32; 3] = n.map(|k| if k >= TWO_LEVEL_MIN { BLOCK } else { 1 });
    if nused == 0 || side.iter().product::<u32>() < BLOCK_MIN_CELLS {
        return flat(t, ncells, &fine_box);
    }

    // The blocks: `side` cells per axis each (fewer at the far ends), classified flat on
    // the hull of their cells' classification boxes.
    let m: [u32; 3] = std::array::from_fn(|a| n[a].div_ceil(side[a]));
    let block_cells = |b: [u32; 3]| -> ([u32; 3], [u32; 3]) {
        let lo: [u32; 3] = std::array::from_fn(|a| b[a] * side[a]);
        let hi: [u32; 3] = std::array::from_fn(|a| ((b[a] + 1) * side[a]).min(n[a]));
        (lo, hi)
    };
    let nblocks = m.iter().map(|&k| k as usize).product::<usize>();
    let block_box = |idx: usize| {
        let (lo, hi) = block_cells(cell_of(idx, m));
        box_of(lo, hi)
    };
    let coarse = flat(t, nblocks, &block_box);

    // Per block, each leaf still unknown with its tape pruned to the block.
    let pruned: Vec<Vec<(usize, Tape)>> = (0..nblocks)
        .into_par_iter()
        .map_init(BoxEval::default, |eval, bi| {
            let b = block_box(bi);
            let row = &coarse.classes[bi * nused..(bi + 1) * nused];
            row.iter()
                .enumerate()
                .filter(|(_, c)| matches!(**c, C_UNKNOWN | C_UNKNOWN_DEFINED))
                .map(|(k, _)| (k, eval.pruned(&t.each[k], &b)))
                .collect()
        })
        .collect();

    // The cells: the block's decided classes, the unknown leaves evaluated.
    let mut classes = vec![0_u8; ncells * nused];
    let mut bound = vec![f64::INFINITY; ncells];
    let block_of = |idx: usize| -> usize {
        let c = cell_of(idx, n);
        index(std::array::from_fn(|a| c[a] / side[a]), m)
    };
    classes
        .par_chunks_mut(nused)
        .zip(bound.par_iter_mut())
        .enumerate()
        .for_each_init(BoxEval::default, |eval, (idx, (out, bound))| {
            let bi = block_of(idx);
            out.copy_from_slice(&coarse.classes[bi * nused..(bi + 1) * nused]);
            *bound = coarse.bound[bi];
            if pruned[bi].is_empty() {
                return;
            }
            let b = fine_box(idx);
            for (k, tape) in &pruned[bi] {
                let (f, defined) = eval.on(tape).eval_defined(&b).expect("tape in x y z");
                out[*k] = classify(f, defined);
                if matches!(out[*k], C_POS | C_NEG) {
                    *bound = bound.min(f.mig());
                }
            }
        });
    let unknown: u64 = (0..ncells)
        .map(|idx| pruned[block_of(idx)].len() as u64)
        .sum();
    Classes {
        classes,
        bound,
        leaf_evals: coarse.leaf_evals + unknown,
    }
}
