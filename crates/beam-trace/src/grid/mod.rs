//! The regular grid (thesis 6.2–6.3): cells classified by interval evaluation, the CSG
//! tree reduced per cell, ray and beam traversal, and the first root of a ray through the
//! grid.
//!
//! # Building
//!
//! [`Grid::build`] divides the scene bounds into cells (`resolution` cells along the
//! longest side, proportionally fewer along the others, at least one) and evaluates every
//! leaf surface with intervals over every cell, in parallel. The box a cell is classified on
//! is the cell enlarged by a small margin (relative `1e-9` of the cell size plus a few
//! ulps of the coordinates), so that the traversal below may round outward and still stay
//! inside it. A leaf is, on a cell:
//!
//! * *outside* when it is proven defined at every point of the box and `F > 0`,
//! * *inside* when it is proven defined everywhere and `F < 0`,
//! * *undefined* when `F` is empty (the leaf is defined nowhere in the box),
//! * *unknown* otherwise (`0 ∈ F`, or a sign that is not proven to hold everywhere because
//!   the leaf may be undefined somewhere in the box: `sqrt` of a negative number, a
//!   division by zero, ...).
//!
//! Definedness is proven by the decoration of the leaf's evaluation over the cell
//! ([`Evaluator::eval_decorated`](implicit_expr::Evaluator::eval_decorated), at least `def`); a leaf built only from
//! operations defined on the whole line (`+ − ×`, non-negative integer powers, `min`,
//! `max`, `sin`, `exp`, ...) needs no check.
//!
//! # CSG reduction (thesis 6.3)
//!
//! The scene function is `f = min(objects)`, each object a tree of `min` (union), `max`
//! (intersection) and `max(a, −b)` (difference). Per cell the tree is reduced, bottom up:
//!
//! * a child that is undefined makes its parent undefined (`min` and `max` of an undefined
//!   value are undefined), and so the whole function, which then has no zero in the cell;
//! * in a union (`min`) an outside child is dropped, an inside child makes the node inside
//!   when every remaining child is proven defined;
//! * in an intersection (`max`) an inside child is dropped, an outside child makes the node
//!   outside when every remaining child is proven defined;
//! * a difference `a − b` is the intersection of `a` and `−b`, where `−b` swaps inside and
//!   outside (`b` inside: the node is outside; `b` outside: the node is `a`).
//!
//! The reduced function `r` is *sign-equivalent* to `f` at every point `p` of the
//! (enlarged) cell: `r(p)` is undefined exactly where `f(p)` is, and otherwise has the same
//! sign (`<0`, `=0`, `>0`); in particular `r` and `f` have the same zero set there. Proof
//! for one `min` step, by cases on a point `p`, with `b` proven defined and `b > 0`
//! everywhere: if `a(p)` is undefined so is `min(a, b)(p)`; if `a(p) > 0` both are `> 0`;
//! if `a(p) ≤ 0` then `min(a, b)(p) = a(p)`. With `b < 0` everywhere and every other child
//! defined, `min(…)(p) ≤ b(p) < 0` at every `p`. The `max` case is the mirror image,
//! negation flips signs and keeps definedness, and sign-equivalence composes through
//! `min`, `max` and negation (their signs depend only on the signs of their arguments),
//! so the reduction of every node is sign-equivalent to the node. A node that would become
//! constant while some other child may be undefined is kept as a tree: dropping it would
//! make the reduced function defined where `f` is not. A cell whose top node is inside,
//! outside or undefined holds no point of the surface and is *empty*.
//!
//! Each distinct reduced tree is compiled once ([`RayFunction`]); equal trees are one
//! node of the hash-consed expression graph, so the cache is keyed by node id.
//!
//! # Traversal
//!
//! Cells are closed boxes between shared floating-point boundaries, so they tile the grid.
//! For a ray or a beam the grid is walked slab by slab along its dominant axis (the
//! largest `|direction|` component, thesis 6.2.2): the slab test ([`Beam::slab_t`]) gives
//! the parameters `T_i` in slab `i`, the beam's points over `T_i` give the cells covered on
//! the two other axes, and the parameters of a cell are the intersection of its three
//! slab tests, all rounded outward. A cell whose intersection is empty is proven missed.
//! This is the 3D DDA of Amanatides and Woo made sound: stepping by comparing rounded
//! crossing parameters can decide a near tie wrongly and skip a cell, while the slab walk
//! keeps every cell whose enclosure does not exclude it.
//!
//! The cells of a ray come in order of increasing `t_c.inf()` (a small buffer merges the
//! cells of consecutive slabs: the slab lower bounds increase along the walk). That order,
//! with `t_c.inf()` at or below the exact entry parameter of each cell, is what
//! [`Grid::first_root`] needs: if cell `X` reports the root `r` and the ray met the
//! surface at `t < r.inf()` in a non-empty cell `Y`, then `t ∈ t_Y`; `Y` visited before
//! `X` would have found it, and `Y` visited after `X` has
//! `t_X.inf() ≤ t_Y.inf() ≤ t < r.inf() ≤ t_X.sup()`, so `t ∈ t_X`, where the ray is
//! inside `X`'s classification box and `X`'s function has `f`'s zeros: `X` would have
//! reported it. A cell's reduced function is used for a ray only when the points of the
//! whole `t_c` are proven inside its classification box (always, unless the coordinates
//! are so large that the margin drowns in rounding); otherwise the full scene function is
//! searched there.
//!
//! # Beams
//!
//! [`Grid::beam_cells`] gives, per covered non-empty cell, `T_c`: every parameter at which
//! some ray of the beam is in the cell. A *rejection* (`0 ∉ G_c(T_c)`, a miss proof) with
//! the cell's reduced function is sound: a point of a ray in the cell is a point where
//! the reduced function has `f`'s sign. An *inclusion* proof (every ray of the beam has a
//! root) is not: along one ray the reduced function may change sign at a point outside
//! the cell, where it is not `f`. Beams are therefore evaluated with the whole scene
//! function, over the merged parameter ranges of [`Grid::beam_t_ranges`] only: outside
//! them every ray of the beam is in empty cells or outside the scene bounds.

mod box_eval;
mod cells;
mod classify;
mod functions;
mod leaves;
mod reduce;

use std::collections::HashMap;
use std::ops::ControlFlow;

use glam::DVec3;
use implicit_expr::{NodeId, RayFunction, Tape};
use interval_core::Interval;

use crate::ibox::IBox;
use crate::ray::{Beam, BeamEval, Precision, Ray, RayFn};
use crate::root::{RootCounters, RootFinder, RootResult, RootSettings};
use crate::scene::Geometry;
use classify::{Classes, LeafTapes, class_in, classify_cells};
use functions::{CellFunctions, SceneTapes};
use leaves::CellLeaves;
pub use leaves::LeafCandidates;
use rayon::prelude::*;
use reduce::{C_POS, Reduced, Sign, combine, reduce};

pub use cells::EMPTY;

/// Margin of a cell's classification box, relative to the largest cell side.
const MARGIN: f64 = 1e-9;

/// Statistics of a grid.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct GridStats {
    /// Number of cells.
    pub cells: u64,
    /// Cells the surface may cross (not empty).
    pub non_empty: u64,
    /// Distinct functions used by the cells (CSG-reduced, then pruned per cell).
    pub functions: u64,
    /// Distinct CSG reductions of the objects' trees used by the cells.
    pub reduced: u64,
    /// Mean number of instructions of the non-empty cells' functions (rounded).
    pub cell_instrs: u64,
    /// Instructions of the full scene function.
    pub full_instrs: u64,
    /// Interval evaluations of leaf surfaces over cells.
    pub leaf_evals: u64,
}

/// A non-empty cell met by a ray or a beam.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct CellHit {
    /// The cell's indices along `x`, `y`, `z`.
    pub cell: [u32; 3],
    /// An enclosure, rounded outward and clipped to the searched range, of the parameters
    /// at which the ray (some ray of the beam) is in the cell.
    pub t: Interval<f64>,
    /// The index in the grid's functions ([`Grid::function`]) of the function to search in the cell. For a ray:
    /// the cell's reduced function, or the full scene function where the ray's points
    /// over `t` could not be proven inside the cell's classification box. For a beam:
    /// the cell's reduced function (valid for miss proofs only, see the
    /// [module documentation](self)).
    pub function: u32,
}

/// A non-empty cell covered by a beam ([`Grid::beam_cells`]).
pub type BeamCell = CellHit;

/// A regular grid over the scene bounds. See the [module documentation](self).
#[derive(Clone, Debug)]
pub struct Grid {
    lo: [f64; 3],
    hi: [f64; 3],
    step: [f64; 3],
    n: [u32; 3],
    margin: [f64; 3],
    cells: Vec<u32>,
    /// Per axis `c`: whether the line of cells along `c` at each pair of indices on the
    /// two other axes (`others(c)`, the first one varying fastest) holds a non-empty cell.
    lines: [Vec<bool>; 3],
    /// Per axis: whether each slab of cells across that axis holds a non-empty cell.
    planes: [Vec<bool>; 3],
    functions: CellFunctions,
    scene: SceneTapes,
    leaves: CellLeaves,
    stats: GridStats,
}

/// The two axes other than `a`.
fn others(a: usize) -> (usize, usize) {
    match a {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

/// The axis of the largest `|d|` (the first on ties).
fn dominant(d: [f64; 3]) -> usize {
    let mut a = 0;
    for i in 1..3 {
        if d[i].abs() > d[a].abs() {
            a = i;
        }
    }
    a
}

/// Grids with at most this many functions keep one evaluator per function and thread;
/// beyond, one evaluator is switched between them.
const EVALUATORS_PER_FUNCTION: usize = 256;

/// Per-thread evaluators of a grid's functions: one per function on grids with few
/// functions (created on first use), else one [`BeamEval`] switched to the function of each
/// cell searched (a switch to the function already set costs nothing).
#[derive(Clone, Debug, Default)]
pub struct GridEval {
    each: Vec<Option<BeamEval>>,
    shared: Option<BeamEval>,
    precision: Precision,
}

impl GridEval {
    /// An evaluator whose interval evaluations run in `precision`.
    fn with_precision(precision: Precision) -> Self {
        Self {
            each: Vec::new(),
            shared: None,
            precision,
        }
    }

    /// The evaluator, set to function `index` of `grid`.
    ///
    /// # Panics
    /// If `index` is not a function of `grid`.
    pub fn get(&mut self, grid: &Grid, index: u32) -> &mut BeamEval {
        let f = grid.function(index);
        let precision = self.precision;
        let count = grid.function_count();
        if count <= EVALUATORS_PER_FUNCTION {
            if self.each.len() < count {
                self.each.resize(count, None);
            }
            return self.each[index as usize]
                .get_or_insert_with(|| BeamEval::with_precision(f, precision));
        }
        if let Some(e) = &mut self.shared {
            e.set_function(f);
        }
        self.shared
            .get_or_insert_with(|| BeamEval::with_precision(f, precision))
    }

    /// Sets the precision of the interval evaluations.
    pub fn set_precision(&mut self, precision: Precision) {
        self.precision = precision;
        for e in self.each.iter_mut().flatten().chain(&mut self.shared) {
            e.set_precision(precision);
        }
    }

    /// The precision of the interval evaluations.
    pub fn precision(&self) -> Precision {
        self.precision
    }
}

/// The cells of one axis met by a ray, in travel order, each with an outward enclosure of
/// the parameters at which the ray's coordinate on that axis is in the cell. Boundary
/// crossings are enclosed once each: a cell's exit crossing is the next cell's entry.
struct AxisWalk {
    axis: usize,
    origin: Interval<f64>,
    dir: Interval<f64>,
    /// Travel order is increasing indices.
    up: bool,
    /// The direction component is 0: the window is fixed, every parameter qualifies.
    fixed: bool,
    /// The next cell to generate and how many are left.
    next: u32,
    left: u32,
    /// The crossing of the next cell's entry boundary.
    entry: Interval<f64>,
    /// Generated cells whose range may still meet a later slab's parameters.
    window: std::collections::VecDeque<(u32, Interval<f64>)>,
}

impl AxisWalk {
    /// The walk of `axis` over the cells the ray can reach for `t ∈ tg` (from the ray's
    /// coordinates over `tg`); `None` when there is none.
    fn new(grid: &Grid, beam: &Beam, axis: usize, tg: Interval<f64>) -> Option<AxisWalk> {
        let origin = beam.origin[axis];
        let dir = beam.dir[axis];
        let (lo, hi) = grid.index_range(axis, origin + tg * dir)?;
        let d = dir.inf();
        let mut w = AxisWalk {
            axis,
            origin,
            dir,
            up: d >= 0.0,
            fixed: d == 0.0,
            next: if d >= 0.0 { lo } else { hi },
            left: hi - lo + 1,
            entry: Interval::EMPTY,
            window: std::collections::VecDeque::new(),
        };
        if w.fixed {
            w.window.extend((lo..=hi).map(|j| (j, Interval::ENTIRE)));
            w.left = 0;
        } else {
            let first = if w.up { lo } else { hi + 1 };
            w.entry = w.cross(grid, first);
        }
        Some(w)
    }

    /// The parameters at which the ray crosses boundary `m`.
    fn cross(&self, grid: &Grid, m: u32) -> Interval<f64> {
        let b = grid.boundary(self.axis, m);
        (Interval::new_unchecked(b, b) - self.origin) / self.dir
    }

    /// The next cell in travel order and its parameter range.
    fn generate(&mut self, grid: &Grid) -> Option<(u32, Interval<f64>)> {
        if self.left == 0 {
            return None;
        }
        let j = self.next;
        let exit = self.cross(grid, if self.up { j + 1 } else { j });
        let range = Interval::new_unchecked(self.entry.inf(), exit.sup());
        self.entry = exit;
        self.left -= 1;
        if self.left > 0 {
            self.next = if self.up { j + 1 } else { j - 1 };
        }
        Some((j, range))
    }

    /// Makes the window hold every cell whose range meets `t` (`t.inf()` never decreases
    /// from one call to the next).
    fn update(&mut self, grid: &Grid, t: Interval<f64>) {
        if self.fixed {
            return;
        }
        while self.window.front().is_some_and(|(_, r)| r.sup() < t.inf()) {
            self.window.pop_front();
        }
        while self.window.back().is_none_or(|(_, r)| r.inf() <= t.sup()) {
            let Some((j, r)) = self.generate(grid) else {
                break;
            };
            if r.sup() >= t.inf() {
                self.window.push_back((j, r));
            }
        }
    }
}

impl Grid {
    /// Builds the grid of `geometry` with `resolution` cells along the longest side of
    /// its bounds (at least 1), classifying cells in parallel. The result does not depend
    /// on the number of threads.
    pub fn build(geometry: &Geometry, resolution: u32) -> Grid {
        let res = resolution.max(1);
        let bounds = geometry.bounds();
        let lo: [f64; 3] = std::array::from_fn(|a| bounds[a].inf());
        let hi: [f64; 3] = std::array::from_fn(|a| bounds[a].sup());
        let ext: [f64; 3] = std::array::from_fn(|a| hi[a] - lo[a]);
        let longest = ext
            .iter()
            .copied()
            .filter(|e| e.is_finite())
            .fold(0.0_f64, f64::max);
        let n: [u32; 3] = std::array::from_fn(|a| {
            if !ext[a].is_finite() || longest <= 0.0 {
                1
            } else {
                ((ext[a] / longest * res as f64).round() as u32).clamp(1, res)
            }
        });
        let step: [f64; 3] = std::array::from_fn(|a| {
            if ext[a].is_finite() {
                ext[a] / n[a] as f64
            } else {
                0.0
            }
        });
        let largest_step = step.iter().copied().fold(0.0_f64, f64::max);
        let margin: [f64; 3] = std::array::from_fn(|a| {
            let mag = lo[a].abs().max(hi[a].abs());
            let m = MARGIN * largest_step + 4.0 * f64::EPSILON * mag;
            if m.is_finite() { m } else { 0.0 }
        });
        let mut grid = Grid {
            lo,
            hi,
            step,
            n,
            margin,
            cells: Vec::new(),
            lines: Default::default(),
            planes: Default::default(),
            functions: CellFunctions::empty(geometry.ray_function()),
            scene: SceneTapes::new(geometry.tape().clone(), [0; 3]),
            leaves: CellLeaves::default(),
            stats: GridStats::default(),
        };
        let ncells = n.iter().map(|&k| k as usize).product::<usize>();

        // The leaves the objects use, and where each sits in the class vectors.
        let mut used = Vec::new();
        for o in geometry.objects() {
            o.leaves(&mut used);
        }
        used.sort_unstable();
        used.dedup();
        let leaves = geometry.leaves();
        let ctx = geometry.context();
        let used_nodes: Vec<NodeId> = used.iter().map(|&i| leaves[i].node).collect();
        let tapes = LeafTapes {
            all: Tape::new(ctx, &used_nodes).expect("the geometry's leaf tape builds"),
            each: used_nodes
                .iter()
                .map(|&node| Tape::new(ctx, &[node]).expect("a leaf's tape builds"))
                .collect(),
            total: used_nodes.iter().map(|&node| ctx.is_total(node)).collect(),
        };
        let nused = used.len();

        // Classify every cell (parallel; each cell's classes depend only on the cell).
        let Classes {
            rows,
            row_of,
            bound: signed_bound,
            leaf_evals,
        } = {
            let g = &grid;
            classify_cells(&tapes, n, &|a, i| g.boundary(a, i), margin)
        };

        // Reduce each distinct class vector once, compile each distinct tree once.
        let mut fctx = ctx.clone();
        let leaf_nodes: Vec<NodeId> = leaves.iter().map(|l| l.node).collect();
        let mut by_node: HashMap<NodeId, u32> = HashMap::new();
        let mut reduced_nodes: Vec<NodeId> = Vec::new();
        let mut reduced = vec![EMPTY; ncells];
        let mut non_empty = 0_u64;
        let mut position = vec![usize::MAX; leaves.len()];
        for (k, &i) in used.iter().enumerate() {
            position[i] = k;
        }
        // A row lists the leaves not proven positive; an object whose leaves all are
        // reduces as it does with every leaf positive, which in a union of objects drops it
        // when that is positive. So a row's reduction needs only the objects of its listed
        // leaves (and the objects that are not positive with every leaf positive), in object
        // order: the same tree as reducing every object.
        let objects = geometry.objects();
        let all_positive = |_: usize| C_POS;
        let always: Vec<usize> = (0..objects.len())
            .filter(|&o| reduce(&objects[o], &all_positive).sign != Sign::Pos)
            .collect();
        let mut objects_of: Vec<Vec<usize>> = vec![Vec::new(); nused];
        for (o, object) in objects.iter().enumerate() {
            let mut own = Vec::new();
            object.leaves(&mut own);
            for leaf in own {
                let column = &mut objects_of[position[leaf]];
                if column.last() != Some(&o) {
                    column.push(o);
                }
            }
        }
        // The reductions in parallel (each depends on its class vector only), the trees
        // added to the context in row order.
        let tops: Vec<Option<Reduced>> = rows
            .par_iter()
            .map(|row| {
                let mut near: Vec<usize> = row
                    .iter()
                    .flat_map(|&(k, _)| objects_of[k as usize].iter().copied())
                    .chain(always.iter().copied())
                    .collect();
                near.sort_unstable();
                near.dedup();
                let class = |leaf: usize| class_in(row, position[leaf]);
                let reds: Vec<Reduced> =
                    near.iter().map(|&o| reduce(&objects[o], &class)).collect();
                // No object left: every one is proven positive, the cell is empty.
                (!reds.is_empty()).then(|| combine(reds, true))
            })
            .collect();
        let row_function: Vec<u32> = tops
            .iter()
            .map(|top| {
                let Some(top) = top else {
                    return EMPTY;
                };
                if top.sign != Sign::Unknown {
                    return EMPTY;
                }
                let node = top.expr.build(&mut fctx, &leaf_nodes);
                *by_node.entry(node).or_insert_with(|| {
                    reduced_nodes.push(node);
                    (reduced_nodes.len() - 1) as u32
                })
            })
            .collect();
        for (cell, &row) in reduced.iter_mut().zip(&row_of) {
            *cell = row_function[row as usize];
            non_empty += u64::from(*cell != EMPTY);
        }
        let full_tape = |ctx| Tape::new(ctx, &[geometry.root()]).expect("the scene's tape builds");
        let reduced_tapes: Vec<Tape> = reduced_nodes
            .iter()
            .map(|&node| Tape::new(&fctx, &[node]).unwrap_or_else(|_| full_tape(ctx)))
            .collect();
        let full = full_tape(ctx);
        let full_instrs = full.len() as u64;
        // Prune each cell's reduced function over its classification box.
        let (functions, cells) = {
            let g = &grid;
            CellFunctions::build(
                &reduced_tapes,
                (&reduced, n),
                |idx| g.class_box(g.cell_of_index(idx)),
                full,
                geometry.ray_function(),
            )
        };
        grid.leaves = CellLeaves::build(
            ctx,
            &leaf_nodes,
            &used,
            &rows,
            &row_of,
            signed_bound,
            |idx| cells[idx] != EMPTY,
        )
        .unwrap_or_default();
        grid.cells = cells;
        grid.index_occupancy();
        grid.stats = GridStats {
            cells: ncells as u64,
            non_empty,
            functions: u64::from(functions.used),
            reduced: reduced_nodes.len() as u64,
            cell_instrs: functions.cell_instrs.div_ceil(non_empty.max(1)),
            full_instrs,
            leaf_evals,
        };
        grid.functions = functions;
        grid.scene = SceneTapes::new(geometry.tape().clone(), grid.n);
        grid
    }

    /// Fills the line and plane occupancy tables from the cells.
    fn index_occupancy(&mut self) {
        let n = self.n.map(|k| k as usize);
        self.lines = std::array::from_fn(|c| {
            let (p, q) = others(c);
            vec![false; n[p] * n[q]]
        });
        self.planes = std::array::from_fn(|a| vec![false; n[a]]);
        for idx in 0..self.cells.len() {
            if self.cells[idx] == EMPTY {
                continue;
            }
            let cell = self.cell_of_index(idx);
            for c in 0..3 {
                let (p, q) = others(c);
                self.lines[c][cell[p] as usize + n[p] * cell[q] as usize] = true;
                self.planes[c][cell[c] as usize] = true;
            }
        }
    }

    /// Whether the line along axis `c` through `cell` (its index on `c` ignored) holds a
    /// non-empty cell.
    fn line_occupied(&self, c: usize, cell: [u32; 3]) -> bool {
        let (p, q) = others(c);
        self.lines[c][cell[p] as usize + self.n[p] as usize * cell[q] as usize]
    }

    /// Number of cells along `x`, `y`, `z`.
    pub fn dims(&self) -> [u32; 3] {
        self.n
    }

    /// The box the grid covers (the scene bounds).
    pub fn bounds(&self) -> IBox {
        std::array::from_fn(|a| Interval::new_unchecked(self.lo[a], self.hi[a]))
    }

    /// Statistics.
    pub fn stats(&self) -> GridStats {
        self.stats
    }

    /// Number of functions: the distinct functions of the cells and the full scene
    /// function ([`Grid::full_function`]).
    pub fn function_count(&self) -> usize {
        self.functions.len()
    }

    /// Function `index` restricted to rays ([`RayFunction`]), compiled on first use: a
    /// cell's function (its objects' CSG trees reduced over the cell, then pruned by the
    /// `min`/`max` choices of its interval evaluation over the cell) or the full scene
    /// function.
    ///
    /// # Panics
    /// If `index` is not below [`Grid::function_count`].
    pub fn function(&self, index: u32) -> &RayFunction {
        self.functions.ray(index)
    }

    /// Function `index` as a formula in `x y z` (see [`Grid::function`]).
    ///
    /// # Panics
    /// If `index` is not below [`Grid::function_count`].
    pub fn function_tape(&self, index: u32) -> &Tape {
        self.functions.tape(index)
    }

    /// The scene function pruned to the cell holding `p` (equal to it on the cell's
    /// classification box, see the pruning of [`Grid::function`]), built on first use;
    /// `None` when `p` is outside the grid (or not finite).
    pub fn scene_tape_at(&self, p: DVec3) -> Option<&Tape> {
        let idx = self.cell_at(p)?;
        Some(self.scene.get(idx, |c| self.class_box(c)))
    }

    /// The leaves that may shade a hit at `p` (see [`LeafCandidates`]), from the cell
    /// holding `p`; `None` outside the grid or in a cell without candidates.
    pub fn leaf_candidates_at(&self, p: DVec3) -> Option<LeafCandidates<'_>> {
        self.leaves.get(self.cell_at(p)?)
    }

    /// The index of the cell whose classification box holds `p`, `None` when there is none
    /// (outside the grid, not finite).
    fn cell_at(&self, p: DVec3) -> Option<usize> {
        let v = p.to_array();
        if !(0..3).all(|a| v[a] >= self.lo[a] && v[a] <= self.hi[a]) {
            return None;
        }
        let cell: [u32; 3] = std::array::from_fn(|a| self.guess(a, v[a]));
        let b = self.class_box(cell);
        (0..3)
            .all(|a| b[a].contains(v[a]))
            .then(|| self.index_of(cell))
    }

    /// The index of the full scene function.
    pub fn full_function(&self) -> u32 {
        self.functions.full
    }

    /// The function index of a cell, `None` for an empty cell.
    ///
    /// # Panics
    /// If the cell is outside the grid.
    pub fn cell_function(&self, cell: [u32; 3]) -> Option<u32> {
        let f = self.cells[self.index_of(cell)];
        (f != EMPTY).then_some(f)
    }

    /// The closed box of a cell. Neighbouring cells share their boundary values, so the
    /// cells tile [`Grid::bounds`].
    pub fn cell_box(&self, cell: [u32; 3]) -> IBox {
        std::array::from_fn(|a| self.cell_range(a, cell[a]))
    }

    /// The box a cell was classified on: the cell enlarged by the margin. Its function is
    /// sign-equivalent to the scene function at every point of it.
    pub fn class_box(&self, cell: [u32; 3]) -> IBox {
        std::array::from_fn(|a| {
            let r = self.cell_range(a, cell[a]);
            Interval::new_unchecked(r.inf() - self.margin[a], r.sup() + self.margin[a])
        })
    }

    /// Per-thread evaluators of the grid's functions, in [`Precision::F64`].
    pub fn evaluator(&self) -> GridEval {
        self.evaluator_with(Precision::F64)
    }

    /// Per-thread evaluators of the grid's functions whose interval evaluations run in
    /// `precision`.
    pub fn evaluator_with(&self, precision: Precision) -> GridEval {
        GridEval::with_precision(precision)
    }

    fn index_of(&self, c: [u32; 3]) -> usize {
        assert!(
            (0..3).all(|a| c[a] < self.n[a]),
            "cell {c:?} outside {:?}",
            self.n
        );
        cells::index(c, self.n)
    }

    fn cell_of_index(&self, idx: usize) -> [u32; 3] {
        cells::cell(idx, self.n)
    }

    /// Boundary `i` on axis `a` (`0 ≤ i ≤ n`): non-decreasing in `i`, the bounds at both
    /// ends.
    fn boundary(&self, a: usize, i: u32) -> f64 {
        if i == 0 {
            self.lo[a]
        } else if i >= self.n[a] {
            self.hi[a]
        } else {
            (self.lo[a] + i as f64 * self.step[a]).min(self.hi[a])
        }
    }

    fn cell_range(&self, a: usize, i: u32) -> Interval<f64> {
        Interval::new_unchecked(self.boundary(a, i), self.boundary(a, i + 1))
    }

    fn guess(&self, a: usize, v: f64) -> u32 {
        let g = ((v - self.lo[a]) / self.step[a]).floor();
        if g.is_nan() || self.n[a] == 1 {
            0
        } else {
            g.clamp(0.0, (self.n[a] - 1) as f64) as u32
        }
    }

    /// The cells on axis `a` whose closed range meets `x`: `None` when none does.
    fn index_range(&self, a: usize, x: Interval<f64>) -> Option<(u32, u32)> {
        if x.is_empty() || x.sup() < self.lo[a] || x.inf() > self.hi[a] {
            return None;
        }
        let last = self.n[a] - 1;
        // First cell reaching x.inf(): its lower boundary below x.inf() (or the first cell)
        // and its upper boundary at or above it.
        let mut i0 = self.guess(a, x.inf());
        while i0 > 0 && self.boundary(a, i0) >= x.inf() {
            i0 -= 1;
        }
        while i0 < last && self.boundary(a, i0 + 1) < x.inf() {
            i0 += 1;
        }
        // Last cell reaching x.sup().
        let mut i1 = self.guess(a, x.sup());
        while i1 < last && self.boundary(a, i1 + 1) <= x.sup() {
            i1 += 1;
        }
        while i1 > 0 && self.boundary(a, i1) > x.sup() {
            i1 -= 1;
        }
        (i0 <= i1).then_some((i0, i1))
    }

    /// The non-empty cells of slab `i` on axis `a` met by the beam for `t ∈ ti` (the
    /// slab's parameters), with their parameter enclosures and function indices. Empty
    /// slabs, lines and cells are skipped before any parameter is computed for them.
    fn slab_cells(
        &self,
        beam: &Beam,
        a: usize,
        i: u32,
        ti: Interval<f64>,
        mut out: impl FnMut([u32; 3], Interval<f64>, u32),
    ) {
        if !self.planes[a][i as usize] {
            return;
        }
        let (b, c) = others(a);
        let yb = beam.origin[b] + ti * beam.dir[b];
        let Some((j0, j1)) = self.index_range(b, yb) else {
            return;
        };
        let mut cell = [0; 3];
        cell[a] = i;
        for j in j0..=j1 {
            cell[b] = j;
            if !self.line_occupied(c, cell) {
                continue;
            }
            let tj = beam.slab_t(b, self.cell_range(b, j), ti);
            if tj.is_empty() {
                continue;
            }
            let zc = beam.origin[c] + tj * beam.dir[c];
            let Some((k0, k1)) = self.index_range(c, zc) else {
                continue;
            };
            for k in k0..=k1 {
                cell[c] = k;
                let f = self.cells[self.index_of(cell)];
                if f == EMPTY {
                    continue;
                }
                let tk = beam.slab_t(c, self.cell_range(c, k), tj);
                if !tk.is_empty() {
                    out(cell, tk, f);
                }
            }
        }
    }

    /// The function to search for a ray in a non-empty cell over `t`: the cell's reduced
    /// function when the ray's points over `t` are proven inside its classification box,
    /// else the full function.
    fn ray_function(&self, beam: &Beam, cell: [u32; 3], f: u32, t: Interval<f64>) -> u32 {
        let p = beam.points(t);
        let c = self.class_box(cell);
        if (0..3).all(|a| p[a].subset(c[a])) {
            f
        } else {
            self.functions.full
        }
    }

    /// Visits the non-empty cells the ray passes for `t ∈ t`, in order of non-decreasing
    /// `t_c.inf()`, until `visit` breaks. Sound: every parameter in `t` at which the ray is
    /// in a non-empty (closed) cell lies in the `t_c` of that cell's visit. Handles rays
    /// parallel to axes or grid planes, starting inside or outside the grid, and zero
    /// direction components.
    ///
    /// The walk is incremental, in the manner of a DDA: each cell boundary's crossing
    /// parameter is enclosed once (an interval division), the cells of each axis follow in
    /// travel order with their parameter ranges, and a cell is visited when the ranges of
    /// its three indices meet (the same cells and enclosures as the slab walk of
    /// [`Grid::beam_cells_within`] for the beam of this one ray).
    pub fn for_each_ray_cell<B>(
        &self,
        ray: &Ray,
        t: Interval<f64>,
        mut visit: impl FnMut(CellHit) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        if !ray.origin.is_finite() || !ray.dir.is_finite() {
            return ControlFlow::Continue(());
        }
        let beam = ray.beam();
        if ray.dir == glam::DVec3::ZERO {
            // A point: every cell holding it, for every parameter.
            for hit in self.beam_cells_within(&beam, t) {
                let function = self.ray_function(&beam, hit.cell, hit.function, hit.t);
                visit(CellHit { function, ..hit })?;
            }
            return ControlFlow::Continue(());
        }
        let Some(tg) = beam.t_range_within(&self.bounds(), t) else {
            return ControlFlow::Continue(());
        };
        let a = dominant(ray.dir.to_array());
        let (b, c) = others(a);
        let (Some(mut wa), Some(mut wb), Some(mut wc)) = (
            AxisWalk::new(self, &beam, a, tg),
            AxisWalk::new(self, &beam, b, tg),
            AxisWalk::new(self, &beam, c, tg),
        ) else {
            return ControlFlow::Continue(());
        };
        // Cells found but not yet visited, sorted by t_c.inf() (stable on ties).
        let mut pending: Vec<CellHit> = Vec::new();
        let mut cell = [0; 3];
        let mut current = wa.generate(self);
        while let Some((i, sa)) = current {
            let next = wa.generate(self);
            let ti = sa.intersection(tg);
            if !ti.is_empty() && self.planes[a][i as usize] {
                cell[a] = i;
                wb.update(self, ti);
                wc.update(self, ti);
                for &(j, sb) in &wb.window {
                    cell[b] = j;
                    if !self.line_occupied(c, cell) {
                        continue;
                    }
                    let tj = ti.intersection(sb);
                    if tj.is_empty() {
                        continue;
                    }
                    for &(k, sc) in &wc.window {
                        cell[c] = k;
                        let f = self.cells[self.index_of(cell)];
                        if f == EMPTY {
                            continue;
                        }
                        let tc = tj.intersection(sc);
                        if tc.is_empty() {
                            continue;
                        }
                        let hit = CellHit {
                            cell,
                            t: tc,
                            function: self.ray_function(&beam, cell, f, tc),
                        };
                        let pos = pending.partition_point(|h| h.t.inf() <= tc.inf());
                        pending.insert(pos, hit);
                    }
                }
            }
            // Every cell of a later slab has t_c.inf() at or above the next slab's lower
            // parameter bound: the slabs' bounds increase along the walk (and once a slab
            // misses `tg`, every later one does). The pending cells below it come first.
            let bound = next.map_or(f64::INFINITY, |(_, s)| s.intersection(tg).inf());
            if !pending.is_empty() {
                let ready = pending.partition_point(|h| h.t.inf() <= bound);
                for hit in pending.drain(..ready) {
                    visit(hit)?;
                }
            }
            current = next;
        }
        for hit in pending {
            visit(hit)?;
        }
        ControlFlow::Continue(())
    }

    /// The function that equals the scene function's sign at every point of the ray for
    /// `t ∈ t` (a root enclosure, say), when one cell holds all of them: the first
    /// non-empty cell the ray passes, when its parameter range holds `t` (its function, or
    /// the full one where the ray's points are not proven inside the cell's box). `None`
    /// when `t` spans several cells or meets no non-empty one.
    pub fn function_over(&self, ray: &Ray, t: Interval<f64>) -> Option<u32> {
        match self.for_each_ray_cell(ray, t, ControlFlow::Break) {
            ControlFlow::Break(hit) if t.subset(hit.t) => Some(hit.function),
            _ => None,
        }
    }

    /// The non-empty cells the ray passes for `t ∈ t`, in visiting order (see
    /// [`Grid::for_each_ray_cell`]).
    pub fn ray_cells(&self, ray: &Ray, t: Interval<f64>) -> Vec<CellHit> {
        let mut out = Vec::new();
        let _ = self.for_each_ray_cell::<()>(ray, t, |h| {
            out.push(h);
            ControlFlow::Continue(())
        });
        out
    }

    /// The first root of the scene function along `ray` for `t ≥ 0`, see
    /// [`Grid::first_root_within`].
    pub fn first_root(
        &self,
        evals: &mut GridEval,
        ray: &Ray,
        finder: &dyn RootFinder,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        let forward = Interval::new_unchecked(0.0, f64::INFINITY);
        self.first_root_within(evals, ray, forward, finder, settings, counters)
    }

    /// The first root of the scene function along `ray` for parameters in `t` (clipped to
    /// the grid): the cells are searched in order with `finder`, each with its function
    /// over its `t_c`. Returns the first cell's `Root` or `Undecided` (nothing before it
    /// is a root), `NoRoot` when every cell says so. Sound when `finder` is reliable; see
    /// the [module documentation](self) for why the order makes the first root of a cell
    /// the first root of the ray.
    pub fn first_root_within(
        &self,
        evals: &mut GridEval,
        ray: &Ray,
        t: Interval<f64>,
        finder: &dyn RootFinder,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        // Once a cell's search escalated to a higher precision (rounding kept it open), the
        // ray's later cells start in that precision: they meet the same large terms.
        let mut escalated = false;
        let r = self.for_each_ray_cell(ray, t, |hit| {
            let e = evals.get(self, hit.function);
            e.set_ray(ray);
            let previous = if escalated { e.escalate() } else { None };
            let before = counters.escalated;
            let r = finder.first_root(e, hit.t, settings, counters);
            if let Some(p) = previous {
                e.restore(p);
            }
            escalated |= counters.escalated > before;
            match r {
                RootResult::NoRoot => ControlFlow::Continue(()),
                r => ControlFlow::Break(r),
            }
        });
        match r {
            ControlFlow::Break(r) => r,
            ControlFlow::Continue(()) => RootResult::NoRoot,
        }
    }

    /// The non-empty cells covered by the beam for `t ≥ 0`, see
    /// [`Grid::beam_cells_within`].
    pub fn beam_cells(&self, beam: &Beam) -> Vec<BeamCell> {
        self.beam_cells_within(beam, Interval::new_unchecked(0.0, f64::INFINITY))
    }

    /// The non-empty cells covered by the beam for `t ∈ t` (thesis 6.2.2): the grid is
    /// walked along the axis of the largest `|mid direction|`, each slab's parameters give
    /// the beam's footprint on the two other axes, and each covered cell's `T_c` is the
    /// intersection of its three slab tests. Sorted by `T_c.inf()`. Sound: for every ray
    /// of the beam and `t ∈ t` with the ray's point in a non-empty cell, `t` lies in that
    /// cell's `T_c`. The function index is the cell's reduced function: use it for miss
    /// proofs only (see the [module documentation](self)).
    pub fn beam_cells_within(&self, beam: &Beam, t: Interval<f64>) -> Vec<BeamCell> {
        let mut out = Vec::new();
        let Some(tg) = beam.t_range_within(&self.bounds(), t) else {
            return out;
        };
        let mid: [f64; 3] = std::array::from_fn(|k| beam.dir[k].mid());
        let a = if mid.iter().all(|m| m.is_finite()) {
            dominant(mid)
        } else {
            0
        };
        let xa = beam.origin[a] + tg * beam.dir[a];
        let Some((i0, i1)) = self.index_range(a, xa) else {
            return out;
        };
        for i in i0..=i1 {
            let ti = beam.slab_t(a, self.cell_range(a, i), tg);
            if ti.is_empty() {
                continue;
            }
            self.slab_cells(beam, a, i, ti, |cell, tc, function| {
                out.push(CellHit {
                    cell,
                    t: tc,
                    function,
                });
            });
        }
        out.sort_by(|x, y| {
            x.t.inf()
                .total_cmp(&y.t.inf())
                .then_with(|| self.index_of(x.cell).cmp(&self.index_of(y.cell)))
        });
        out
    }

    /// The parameter ranges (`t ≥ 0`) where some ray of the beam may be in a non-empty
    /// cell, see [`Grid::beam_t_ranges_within`].
    pub fn beam_t_ranges(&self, beam: &Beam) -> Vec<Interval<f64>> {
        self.beam_t_ranges_within(beam, Interval::new_unchecked(0.0, f64::INFINITY))
    }

    /// The `T_c` of the non-empty cells covered by the beam for `t ∈ t`, merged where they
    /// overlap or touch, in increasing order. Outside them every ray of the beam is in
    /// empty cells or outside the scene bounds, so the beam tests (with the full scene
    /// function: a cell's reduced function cannot prove a hit) need only these ranges.
    pub fn beam_t_ranges_within(&self, beam: &Beam, t: Interval<f64>) -> Vec<Interval<f64>> {
        let mut out: Vec<Interval<f64>> = Vec::new();
        for c in self.beam_cells_within(beam, t) {
            match out.last_mut() {
                Some(last) if c.t.inf() <= last.sup() => *last = last.convex_hull(c.t),
                _ => out.push(c.t),
            }
        }
        out
    }
}
