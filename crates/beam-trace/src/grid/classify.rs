//! The leaves' sign classes over every cell, from coarser blocks of cells.
//!
//! A cell's classes are what the grid's CSG reduction starts from (see [`super::reduce`]):
//! per used leaf, proven positive, negative, undefined, or unknown over the cell's
//! classification box. Evaluating every leaf on every cell (the flat classification)
//! repeats most of the work on a fine grid, and costs the number of leaves times the number
//! of cells. Here the grid is classified as an octree of blocks of cells: the whole grid
//! first, then each block's halves along every axis of more than one cell, down to single
//! cells. A block inherits every class its parent proved (a proof over a box is one over
//! any part of it) and evaluates only the leaves still unknown, each with its tape pruned to
//! the parent (equal to the leaf there, with the same enclosure over any part of it). A
//! block where every leaf is decided is final for all its cells, so a leaf costs about the
//! blocks near its surface rather than every cell. The classes are those of the flat
//! classification wherever interval evaluation is inclusion-monotone (it is, for every
//! operation here); either way each one is proven over its cell.

use implicit_expr::{Evaluator, Tape};
use interval_core::Interval;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::box_eval::{BoxEval, with_thread_eval};
use super::cells::{cell as cell_of, index};
use super::reduce::{C_NEG, C_POS, C_UNKNOWN, C_UNKNOWN_DEFINED, classify};
use crate::ibox::IBox;

/// A class vector stored sparsely: the used leaves (by column) whose class is not
/// [`C_POS`], in increasing column order, with their classes; every other leaf is proven
/// positive. Far from a leaf's surface it is positive (an object is outside), so a cell's
/// row holds the few objects near it, whatever the number of objects in the scene.
pub(super) type Row = Vec<(u32, u8)>;

/// Where column `k` is in `row` (`Err`: where it would go, its class positive).
fn find(row: &[(u32, u8)], k: usize) -> Result<usize, usize> {
    row.binary_search_by_key(&(k as u32), |&(col, _)| col)
}

/// The class of column `k` in `row`.
pub(super) fn class_in(row: &[(u32, u8)], k: usize) -> u8 {
    find(row, k).map_or(C_POS, |i| row[i].1)
}

/// Sets the class of column `k` in `row` to `c`.
fn set_class(row: &mut Row, k: usize, c: u8) {
    match find(row, k) {
        Ok(i) if c == C_POS => {
            row.remove(i);
        }
        Ok(i) => row[i].1 = c,
        Err(_) if c == C_POS => {}
        Err(i) => row.insert(i, (k as u32, c)),
    }
}

/// A dense class vector as a [`Row`].
fn sparse(dense: &[u8]) -> Row {
    dense
        .iter()
        .enumerate()
        .filter(|&(_, &c)| c != C_POS)
        .map(|(k, &c)| (k as u32, c))
        .collect()
}

/// The distinct class vectors of a classification, each stored once.
#[derive(Default)]
struct Rows {
    rows: Vec<Row>,
    index: FxHashMap<Row, u32>,
}

impl Rows {
    /// The index of `row`, added if new.
    fn intern(&mut self, row: Row) -> u32 {
        let next = self.rows.len() as u32;
        *self.index.entry(row).or_insert_with_key(|r| {
            self.rows.push(r.clone());
            next
        })
    }
}

/// The classes of every cell: the distinct class vectors (`rows`, in the order first met),
/// each cell's (`row_of`, in cell order), per cell the smallest mignitude over the cell of
/// its leaves of proven sign (a lower bound), and the number of leaf evaluations spent.
pub(super) struct Classes {
    pub(super) rows: Vec<Row>,
    pub(super) row_of: Vec<u32>,
    pub(super) bound: Vec<f64>,
    pub(super) leaf_evals: u64,
}

impl Classes {
    /// The class vector of cell `idx`.
    #[cfg(test)]
    fn row(&self, idx: usize) -> &[(u32, u8)] {
        &self.rows[self.row_of[idx] as usize]
    }
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
                self.one.defined_on(&t.each[k], b)
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
    let (cells, bound): (Vec<Row>, Vec<f64>) = (0..ncells)
        .into_par_iter()
        .map_init(
            || (Flat::new(t), vec![0_u8; nused]),
            |(st, dense), idx| {
                let mut bound = f64::INFINITY;
                if nused > 0 {
                    st.classify(t, &cell_box(idx), dense, &mut bound);
                }
                (sparse(dense), bound)
            },
        )
        .unzip();
    let mut rows = Rows::default();
    let row_of = cells.into_iter().map(|r| rows.intern(r)).collect();
    Classes {
        rows: rows.rows,
        row_of,
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
    // The hull of the classification boxes of cells `lo..hi` (per axis, `hi` excluded).
    let box_of = |lo: [u32; 3], hi: [u32; 3]| -> IBox {
        std::array::from_fn(|a| {
            Interval::new_unchecked(
                boundary(a, lo[a]) - margin[a],
                boundary(a, hi[a]) + margin[a],
            )
        })
    };
    let ncells = n.iter().map(|&k| k as usize).product::<usize>();
    let nused = t.each.len();
    if nused == 0 || ncells <= 1 {
        return flat(t, ncells, &|idx| {
            let c = cell_of(idx, n);
            box_of(c, c.map(|i| i + 1))
        });
    }
    // The root: every leaf over the whole grid.
    let root = flat(t, 1, &|_| box_of([0; 3], n));
    let mut leaf_evals = root.leaf_evals;
    let row = root.rows[root.row_of[0] as usize].clone();
    let unknown = undecided(&row)
        .map(|k| {
            (
                k,
                with_thread_eval(|e| e.pruned(&t.each[k], &box_of([0; 3], n))),
            )
        })
        .collect();
    let mut level = vec![Node {
        lo: [0; 3],
        hi: n,
        row,
        bound: root.bound[0],
        unknown,
    }];
    let mut rows = Rows::default();
    let mut row_of = vec![0_u32; ncells];
    let mut bound = vec![f64::INFINITY; ncells];
    // Level by level: each node's children, with the leaves still unknown evaluated over
    // each child; a child without unknown leaves, or of one cell, is final.
    while !level.is_empty() {
        let children: Vec<(Node, u64)> = level
            .par_iter()
            .flat_map_iter(|node| node.split())
            .map_init(BoxEval::default, |eval, (parent, lo, hi)| {
                let b = box_of(lo, hi);
                let one_cell = (0..3).all(|a| hi[a] - lo[a] == 1);
                let mut row = parent.row.clone();
                let mut bound = parent.bound;
                let mut unknown = Vec::new();
                for (k, tape) in &parent.unknown {
                    let (f, defined) = eval.defined_on(tape, &b);
                    let c = classify(f, defined);
                    set_class(&mut row, *k, c);
                    if matches!(c, C_POS | C_NEG) {
                        bound = bound.min(f.mig());
                    } else if !one_cell {
                        unknown.push((*k, eval.pruned(tape, &b)));
                    }
                }
                let evals = parent.unknown.len() as u64;
                let node = Node {
                    lo,
                    hi,
                    row,
                    bound,
                    unknown,
                };
                (node, evals)
            })
            .collect();
        level = Vec::new();
        for (node, evals) in children {
            leaf_evals += evals;
            if node.unknown.is_empty() {
                let r = rows.intern(node.row.clone());
                for c in node.cells() {
                    let idx = index(c, n);
                    row_of[idx] = r;
                    bound[idx] = node.bound;
                }
            } else {
                level.push(node);
            }
        }
    }
    Classes {
        rows: rows.rows,
        row_of,
        bound,
        leaf_evals,
    }
}

/// The leaves whose class in `row` is unknown (defined or not).
fn undecided(row: &[(u32, u8)]) -> impl Iterator<Item = usize> + '_ {
    row.iter()
        .filter(|(_, c)| matches!(*c, C_UNKNOWN | C_UNKNOWN_DEFINED))
        .map(|&(k, _)| k as usize)
}

/// A block of cells `lo..hi` of the classification: the classes proven over its box (every
/// used leaf), the smallest mignitude of the signed ones, and the leaves still unknown with
/// their tapes pruned to the box.
struct Node {
    lo: [u32; 3],
    hi: [u32; 3],
    row: Row,
    bound: f64,
    unknown: Vec<(usize, Tape)>,
}

impl Node {
    /// The node's children with their cell ranges: each axis of more than one cell halved.
    fn split(&self) -> impl Iterator<Item = (&Node, [u32; 3], [u32; 3])> + '_ {
        let halves = |a: usize| -> Vec<(u32, u32)> {
            let (lo, hi) = (self.lo[a], self.hi[a]);
            if hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                vec![(lo, mid), (mid, hi)]
            } else {
                vec![(lo, hi)]
            }
        };
        let (x, y, z) = (halves(0), halves(1), halves(2));
        let mut out = Vec::with_capacity(8);
        for &(z0, z1) in &z {
            for &(y0, y1) in &y {
                for &(x0, x1) in &x {
                    out.push((self, [x0, y0, z0], [x1, y1, z1]));
                }
            }
        }
        out.into_iter()
    }

    /// The cells of the node.
    fn cells(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        (self.lo[2]..self.hi[2]).flat_map(move |z| {
            (self.lo[1]..self.hi[1])
                .flat_map(move |y| (self.lo[0]..self.hi[0]).map(move |x| [x, y, z]))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use implicit_expr::Context;

    /// Leaves of several kinds (total, with `min`/`max` to prune, partly undefined) and the
    /// grid's boundaries over `[-2, 2]³`.
    fn leaves() -> LeafTapes {
        let formulas = [
            "x^2 + y^2 + z^2 - 1",
            "(x - 0.7)^2 + (y + 0.4)^2 + z^2 - 0.09",
            "max(abs(x) - 1.5, min(abs(y) - 0.2, abs(z + 0.5) - 0.3))",
            "sqrt(x + 1) - y - 1",
            "min(x - 1.9, 1.9 - x) + 0.05",
        ];
        let mut ctx = Context::new();
        let nodes: Vec<_> = formulas
            .iter()
            .map(|f| implicit_expr::parse::parse(&mut ctx, f, &[]).unwrap())
            .collect();
        LeafTapes {
            all: Tape::new(&ctx, &nodes).unwrap(),
            each: nodes
                .iter()
                .map(|&n| Tape::new(&ctx, &[n]).unwrap())
                .collect(),
            total: nodes.iter().map(|&n| ctx.is_total(n)).collect(),
        }
    }

    #[test]
    fn octree_classes_equal_the_flat_ones() {
        let t = leaves();
        for n in [[1, 1, 1], [7, 1, 3], [16, 16, 16], [13, 9, 20]] {
            let step: [f64; 3] = std::array::from_fn(|a| 4.0 / f64::from(n[a]));
            let boundary = |a: usize, i: u32| {
                if i >= n[a] {
                    2.0
                } else {
                    -2.0 + f64::from(i) * step[a]
                }
            };
            let margin = [1e-9; 3];
            let tree = classify_cells(&t, n, &boundary, margin);
            let ncells = n.iter().map(|&k| k as usize).product::<usize>();
            let flat = flat(&t, ncells, &|idx| {
                let c = cell_of(idx, n);
                std::array::from_fn(|a| {
                    Interval::new_unchecked(
                        boundary(a, c[a]) - margin[a],
                        boundary(a, c[a] + 1) + margin[a],
                    )
                })
            });
            for idx in 0..ncells {
                assert_eq!(tree.row(idx), flat.row(idx), "{n:?}, cell {idx}");
            }
            // The bound is a smallest mignitude over the cell's signed leaves: the octree's
            // comes from the box where each was proven, at most the cell's own.
            for (a, b) in tree.bound.iter().zip(&flat.bound) {
                assert!(a <= b, "{n:?}: {a} > {b}");
            }
            if ncells >= 4096 {
                assert!(tree.leaf_evals < flat.leaf_evals / 2, "{}", tree.leaf_evals);
            }
        }
    }
}
