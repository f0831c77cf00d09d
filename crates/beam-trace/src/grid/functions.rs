//! The functions the cells of a grid are searched with: each non-empty cell's reduced
//! function, pruned by the `min`/`max` choices of its interval evaluation over the cell's
//! classification box, compiled for rays on first use.
//!
//! # Pruning
//!
//! The CSG reduction drops whole objects and leaves; inside one leaf (a formula or a `.vm`
//! model of hundreds of operations) it keeps every operation. An interval evaluation of the
//! reduced function over the cell's classification box records which argument each `min`
//! and `max` took ([`Evaluator::eval_traced`]); where the box decides it (`a ≤ b` proven
//! everywhere in it), [`Tape::simplify`] keeps that argument only. The pruned function is
//! *equal* to the reduced one at every point of the box (and its interval evaluation over
//! any sub-box is the reduced function's, bound for bound), so it is sign-equivalent to the
//! scene function there, as the reduced one is. Where some operation may be undefined in the
//! box nothing is pruned, so definedness proofs are exactly as strong as before.
//!
//! A pruned formula is used only where it is at most half as long as the reduced one: its
//! derivative is the pruned formula's own (tighter where a `min`/`max` was decided, but on
//! the box faces of a clipped surface wider than the whole formula's), which changes the
//! path of the root searches; a slightly shorter tape does not pay for that.
//!
//! Cells that prune to the same formula share one function: the cache is keyed by the pruned
//! tape's content. A function is compiled for rays ([`RayFunction`]: `g` and `g'` by
//! symbolic differentiation) when a ray or beam first needs it, so cells that no search
//! reaches cost one interval evaluation each.

use rustc_hash::FxHashMap;
use std::sync::OnceLock;

use implicit_expr::{RayFunction, Tape};
use rayon::prelude::*;

use crate::ibox::{IBox, hull};

use super::box_eval::{BoxEval, with_thread_eval};
use super::cells::{EMPTY, cell as cell_of, index};

/// Side of the blocks of cells whose tapes are pruned first, for their cells to prune
/// (see [`CellFunctions::build`]); the grid is pruned in slabs of this many layers of cells,
/// which bounds the memory of tapes not yet deduplicated.
const BLOCK: u32 = 4;

/// A cell's pruned function is used when it is at most `1 / PAYS` as long as the cell's
/// reduced function.
const PAYS: usize = 2;

/// Side, in blocks, of the super-blocks whose tapes the blocks of a long reduced function
/// prune from (see [`CellFunctions::build`]).
const SUPER: u32 = 4;

/// Reduced functions longer than this are pruned to the super-blocks first.
const SUPER_MIN_LEN: usize = 256;

/// One function of the grid: its formula in `x y z` and, once needed, its ray form.
#[derive(Clone, Debug)]
struct CellFunction {
    tape: Tape,
    ray: OnceLock<RayFunction>,
}

/// The distinct functions of a grid's cells and the full scene function.
#[derive(Clone, Debug)]
pub(super) struct CellFunctions {
    functions: Vec<CellFunction>,
    /// The ray form of the full scene function, what a function that cannot be compiled
    /// falls back to.
    fallback: RayFunction,
    /// Sum over the non-empty cells of their functions' instruction counts.
    pub(super) cell_instrs: u64,
    /// Distinct functions used by cells.
    pub(super) used: u32,
    /// Index of the full scene function.
    pub(super) full: u32,
}

impl CellFunctions {
    /// No function but the full scene function's ray form (a grid being built).
    pub(super) fn empty(full_ray: &RayFunction) -> Self {
        Self {
            functions: Vec::new(),
            fallback: full_ray.clone(),
            cell_instrs: 0,
            used: 0,
            full: 0,
        }
    }

    /// Prunes the reduced function of every non-empty cell over its classification box.
    ///
    /// `reduced[idx]` is cell `idx`'s index into `tapes` (the reduced functions in `x y z`),
    /// [`EMPTY`] for an empty cell, in a grid of `n` cells per axis; `class_box(idx)` its
    /// classification box. `full` is the full scene function's tape and `full_ray` its ray
    /// form. Returns the functions and each cell's function index. Deterministic: indices
    /// follow the cells' order.
    ///
    /// Each block of [`BLOCK`]³ cells first prunes each reduced function its cells use over
    /// the hull of their boxes, and each cell prunes the block's tape: a `min`/`max` decided
    /// over the block is decided the same way over the cell, and the argument it forwards
    /// has exactly the operation's enclosure there, so the cell's tape is the one pruning the
    /// reduced function over the cell gives, for the cost of evaluating a shorter one. A
    /// reduced function longer than [`SUPER_MIN_LEN`] is first pruned to super-blocks of
    /// [`SUPER`]³ blocks, which its blocks prune from ([`super_tapes`]): the same tapes, the
    /// long function evaluated once per super-block.
    pub(super) fn build(
        tapes: &[Tape],
        (reduced, n): (&[u32], [u32; 3]),
        class_box: impl Fn(usize) -> IBox + Sync,
        full: Tape,
        full_ray: &RayFunction,
    ) -> (Self, Vec<u32>) {
        let mut by_tape: FxHashMap<Tape, u32> = FxHashMap::default();
        let mut functions: Vec<CellFunction> = Vec::new();
        let mut cells = vec![EMPTY; reduced.len()];
        let mut cell_instrs = 0_u64;
        let layer = n[0] as usize * n[1] as usize;
        let (supers, span) = super_tapes(tapes, (reduced, n), &class_box);
        let m = n.map(|k| k.div_ceil(span));
        // Slabs of `BLOCK` layers of cells (contiguous indices), their blocks in parallel.
        for z0 in (0..n[2]).step_by(BLOCK as usize) {
            let z1 = (z0 + BLOCK).min(n[2]);
            let base = z0 as usize * layer;
            let blocks: Vec<[u32; 2]> = (0..n[1])
                .step_by(BLOCK as usize)
                .flat_map(|y| (0..n[0]).step_by(BLOCK as usize).map(move |x| [x, y]))
                .collect();
            let pruned: Vec<Vec<(usize, Tape)>> = blocks
                .par_iter()
                .map_init(BoxEval::default, |eval, &[x0, y0]| {
                    let (x1, y1) = ((x0 + BLOCK).min(n[0]), (y0 + BLOCK).min(n[1]));
                    let members: Vec<usize> = (z0..z1)
                        .flat_map(|z| (y0..y1).flat_map(move |y| (x0..x1).map(move |x| [x, y, z])))
                        .map(|c| index(c, n))
                        .filter(|&idx| reduced[idx] != EMPTY)
                        .collect();
                    let mut out = Vec::with_capacity(members.len());
                    let mut rs: Vec<u32> = members.iter().map(|&idx| reduced[idx]).collect();
                    rs.sort_unstable();
                    rs.dedup();
                    for r in rs {
                        let tape = &tapes[r as usize];
                        let mine = members.iter().copied().filter(|&idx| reduced[idx] == r);
                        let boxes: Vec<(usize, IBox)> =
                            mine.map(|idx| (idx, class_box(idx))).collect();
                        let block = boxes.iter().map(|(_, b)| *b).reduce(|a, b| hull(&a, &b));
                        // A long function starts from its super-block's tape.
                        let start = supers
                            .get(&(index([x0, y0, z0].map(|k| k / span), m), r))
                            .unwrap_or(tape);
                        let from = match block {
                            Some(b) if boxes.len() > 1 => eval.pruned(start, &b),
                            _ => start.clone(),
                        };
                        for (idx, b) in boxes {
                            let pruned = eval.pruned(&from, &b);
                            // A pruned formula has its own derivative, often tighter,
                            // sometimes wider (a clipped surface's box faces); only a much
                            // shorter tape pays for the change of the root searches' path.
                            out.push((
                                idx,
                                if pruned.len() * PAYS <= tape.len() {
                                    pruned
                                } else {
                                    tape.clone()
                                },
                            ));
                        }
                    }
                    out
                })
                .collect();
            let mut slab: Vec<Option<Tape>> = vec![None; (z1 - z0) as usize * layer];
            for (idx, tape) in pruned.into_iter().flatten() {
                slab[idx - base] = Some(tape);
            }
            for (k, tape) in slab.into_iter().enumerate() {
                let Some(tape) = tape else { continue };
                cell_instrs += tape.len() as u64;
                let next = functions.len() as u32;
                let index = *by_tape.entry(tape.clone()).or_insert_with(|| {
                    functions.push(CellFunction {
                        tape,
                        ray: OnceLock::new(),
                    });
                    next
                });
                cells[base + k] = index;
            }
        }
        let used = functions.len() as u32;
        let full_index = match by_tape.get(&full) {
            Some(&i) => i,
            None => {
                functions.push(CellFunction {
                    tape: full,
                    ray: OnceLock::new(),
                });
                (functions.len() - 1) as u32
            }
        };
        let _ = functions[full_index as usize].ray.set(full_ray.clone());
        (
            Self {
                functions,
                fallback: full_ray.clone(),
                cell_instrs,
                used,
                full: full_index,
            },
            cells,
        )
    }

    /// Number of functions (the cells' and the full one).
    pub(super) fn len(&self) -> usize {
        self.functions.len()
    }

    /// The formula of function `index` in `x y z`.
    pub(super) fn tape(&self, index: u32) -> &Tape {
        &self.functions[index as usize].tape
    }

    /// The ray form of function `index`, compiled on first use (by any thread; the others
    /// wait for it). A formula that cannot be compiled is searched with the full scene
    /// function, which is valid everywhere.
    pub(super) fn ray(&self, index: u32) -> &RayFunction {
        let f = &self.functions[index as usize];
        f.ray.get_or_init(|| {
            f.tape
                .to_context(&["x", "y", "z"])
                .and_then(|(ctx, roots)| RayFunction::new(&ctx, roots[0]))
                .unwrap_or_else(|_| self.fallback.clone())
        })
    }
}

/// The tapes of the reduced functions longer than [`SUPER_MIN_LEN`] pruned to each
/// super-block of `SUPER`³ blocks whose non-empty cells use them, keyed by the super-block's
/// index and the function's; and the super-blocks' side in cells. Each is equal to its
/// function on the super-block's box, with the same enclosure over every part of it, so
/// the blocks inside prune from it to the tapes they would prune from the whole function,
/// evaluating the long function once per super-block instead of once per block.
fn super_tapes(
    tapes: &[Tape],
    (reduced, n): (&[u32], [u32; 3]),
    class_box: &(impl Fn(usize) -> IBox + Sync),
) -> (FxHashMap<(usize, u32), Tape>, u32) {
    let span = BLOCK * SUPER;
    let m = n.map(|k| k.div_ceil(span));
    if tapes.iter().all(|t| t.len() <= SUPER_MIN_LEN) {
        return (FxHashMap::default(), span);
    }
    let count = m.iter().map(|&k| k as usize).product::<usize>();
    let pruned: Vec<Vec<((usize, u32), Tape)>> = (0..count)
        .into_par_iter()
        .map_init(BoxEval::default, |eval, s| {
            let sc = cell_of(s, m);
            let lo = sc.map(|k| k * span);
            let hi: [u32; 3] = std::array::from_fn(|a| ((sc[a] + 1) * span).min(n[a]));
            let mut rs: Vec<u32> = (lo[2]..hi[2])
                .flat_map(|z| {
                    (lo[1]..hi[1]).flat_map(move |y| (lo[0]..hi[0]).map(move |x| [x, y, z]))
                })
                .map(|c| reduced[index(c, n)])
                .filter(|&r| r != EMPTY && tapes[r as usize].len() > SUPER_MIN_LEN)
                .collect();
            rs.sort_unstable();
            rs.dedup();
            if rs.is_empty() {
                return Vec::new();
            }
            let b = hull(
                &class_box(index(lo, n)),
                &class_box(index(hi.map(|k| k - 1), n)),
            );
            rs.into_iter()
                .map(|r| ((s, r), eval.pruned(&tapes[r as usize], &b)))
                .collect()
        })
        .collect();
    (pruned.into_iter().flatten().collect(), span)
}

/// The scene function pruned to each cell, built when a cell is first asked for (normals
/// at hit points): an interval evaluation over the cell's classification box records the
/// `min`/`max` choices, [`Tape::simplify`] keeps the taken arguments. Equal to the scene
/// function at every point of the box, with the same gradient wherever the evaluators'
/// `min`/`max` pick a side (they pick the side the interval evaluation proved).
///
/// A cell's tape is pruned from its block's (the scene function pruned to the hull of
/// [`SCENE_BLOCK`]³ cells, built the same way), so that the whole function is evaluated
/// once per block rather than once per cell. The result is the tape pruning the whole
/// function to the cell would give: a `min`/`max` decided over the block is decided the
/// same way over the cell (the cell's enclosures lie inside the block's), and the argument
/// it forwards has exactly the enclosure the operation had.
#[derive(Clone, Debug)]
pub(super) struct SceneTapes {
    full: Tape,
    /// Cells per axis, and blocks per axis.
    n: [u32; 3],
    m: [u32; 3],
    blocks: Vec<OnceLock<Tape>>,
    cells: Vec<OnceLock<Tape>>,
}

/// Cells per block side of [`SceneTapes`].
const SCENE_BLOCK: u32 = 4;

impl SceneTapes {
    /// Nothing built yet for a grid of `n` cells per axis with the scene function `full`.
    pub(super) fn new(full: Tape, n: [u32; 3]) -> Self {
        let count = |k: [u32; 3]| k.iter().map(|&k| k as usize).product::<usize>();
        let m = n.map(|k| k.div_ceil(SCENE_BLOCK));
        Self {
            full,
            n,
            m,
            blocks: (0..count(m)).map(|_| OnceLock::new()).collect(),
            cells: (0..count(n)).map(|_| OnceLock::new()).collect(),
        }
    }

    /// The scene function pruned to cell `idx`; `class_box` gives the classification box of
    /// a cell.
    pub(super) fn get(&self, idx: usize, class_box: impl Fn([u32; 3]) -> IBox) -> &Tape {
        self.cells[idx].get_or_init(|| {
            let cell = cell_of(idx, self.n);
            let b = cell.map(|i| i / SCENE_BLOCK);
            let block = self.blocks[index(b, self.m)].get_or_init(|| {
                let lo = b.map(|i| i * SCENE_BLOCK);
                let hi: [u32; 3] =
                    std::array::from_fn(|a| ((b[a] + 1) * SCENE_BLOCK).min(self.n[a]) - 1);
                let (l, h) = (class_box(lo), class_box(hi));
                with_thread_eval(|e| e.pruned(&self.full, &hull(&l, &h)))
            });
            with_thread_eval(|e| e.pruned(block, &class_box(cell)))
        })
    }
}
