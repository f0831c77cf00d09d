//! The per-tile subdivision worker: interval evaluation, pruning and point evaluation of
//! one top-level tile and its sub-tiles.

use std::time::Instant;

use implicit_expr::{Choice, Error, Evaluator, Number, SliceEvaluator, Tape};
use interval_core::{Float, Interval};

use crate::grid::{Grid, Tile};
use crate::image::Pixel;
use crate::settings::Settings;
use crate::stats::Stats;

/// Per-thread state: the evaluators (reused across tapes) and scratch space.
pub(crate) struct Worker<'a, T: Float + Number>
where
    Interval<T>: Number,
{
    settings: &'a Settings,
    grid: Grid<T>,
    interval: Evaluator<Interval<T>>,
    boxes: SliceEvaluator<Interval<T>>,
    point: SliceEvaluator<T>,
    trace: Vec<Choice>,
    xs: Vec<T>,
    ys: Vec<T>,
    zs: Vec<T>,
    values: Vec<T>,
    /// Per level, the buffers of the children of the tile being split there.
    levels: Vec<Children<T>>,
    /// The counters of the tile being rendered.
    pub(crate) stats: Stats,
}

impl<'a, T: Float + Number> Worker<'a, T>
where
    Interval<T>: Number,
{
    /// A worker for `tape` (and tapes pruned from it) under `settings`.
    pub(crate) fn new(tape: &Tape, settings: &'a Settings) -> Self {
        Self {
            settings,
            grid: Grid::new(settings),
            interval: Evaluator::new(tape),
            boxes: SliceEvaluator::new(tape),
            point: SliceEvaluator::new(tape),
            trace: Vec::new(),
            xs: Vec::new(),
            ys: Vec::new(),
            zs: Vec::new(),
            values: Vec::new(),
            levels: (0..settings.tiles.len())
                .map(|_| Children::default())
                .collect(),
            stats: Stats::new(&settings.tiles),
        }
    }

    fn clock(&self) -> Option<Instant> {
        self.settings.timing.then(Instant::now)
    }

    /// Renders the top-level tile `t` into `out` (its pixels, row by row).
    pub(crate) fn top(&mut self, tape: &Tape, t: Tile, out: &mut [Pixel]) -> Result<(), Error> {
        self.tile(tape, 0, t, t, out)
    }

    /// The box of tile `t`: its edges hold every pixel centre of the tile.
    fn bounds(&self, t: Tile) -> Result<[Interval<T>; 3], Error> {
        let g = self.grid;
        let x = Interval::new(g.x(t.i0 as f64), g.x(t.i1 as f64)).map_err(bad_bounds)?;
        let y = Interval::new(g.y(t.j1 as f64), g.y(t.j0 as f64)).map_err(bad_bounds)?;
        let z = Interval::new(g.z, g.z).map_err(bad_bounds)?;
        Ok([x, y, z])
    }

    /// Renders tile `t` at `level`, evaluating it on its own; `top` is the enclosing
    /// top-level tile (whose pixel buffer `out` is).
    fn tile(
        &mut self,
        tape: &Tape,
        level: usize,
        t: Tile,
        top: Tile,
        out: &mut [Pixel],
    ) -> Result<(), Error> {
        let b = self.bounds(t)?;
        let clock = self.clock();
        self.interval.set_tape(tape);
        let v = if self.settings.prune {
            self.interval.eval_traced(&b, &mut self.trace)?
        } else {
            self.interval.eval(&b)?
        };
        if let Some(c) = clock {
            self.stats.interval_time += c.elapsed();
        }
        let trace = std::mem::take(&mut self.trace);
        let result = self.evaluated(tape, level, t, v, &trace, top, out);
        self.trace = trace;
        result
    }

    /// Continues with tile `t` once its interval value `v` (and, when pruning, the choice
    /// `trace` of that evaluation) is known: fills it when `v` decides it, else prunes the
    /// tape and goes down to the next level (children evaluated together in one slice pass)
    /// or to the pixels.
    #[allow(clippy::too_many_arguments)]
    fn evaluated(
        &mut self,
        tape: &Tape,
        level: usize,
        t: Tile,
        v: Interval<T>,
        trace: &[Choice],
        top: Tile,
        out: &mut [Pixel],
    ) -> Result<(), Error> {
        let stats = &mut self.stats.levels[level];
        stats.add_tape(tape.len());
        let decided = match v.bounds() {
            Some((_, hi)) if hi < T::ZERO => Some(Pixel::ProvenInside),
            Some((lo, _)) if lo >= T::ZERO => Some(Pixel::ProvenOutside),
            _ => None,
        };
        if let Some(p) = decided {
            if p == Pixel::ProvenInside {
                stats.inside += 1;
            } else {
                stats.outside += 1;
            }
            fill(out, top, t, p);
            return Ok(());
        }
        let sub = if self.settings.prune {
            let clock = self.clock();
            let sub = tape.simplify(trace)?;
            if let Some(c) = clock {
                self.stats.prune_time += c.elapsed();
            }
            if !sub.ptr_eq(tape) {
                self.stats.pruned_tapes += 1;
            }
            sub
        } else {
            tape.clone()
        };
        let Some(&size) = self.settings.tiles.get(level + 1) else {
            return self.points(&sub, t, top, out);
        };
        let mut c = std::mem::take(&mut self.levels[level]);
        c.tiles.clear();
        for j0 in (t.j0..t.j1).step_by(size) {
            for i0 in (t.i0..t.i1).step_by(size) {
                c.tiles.push(Tile {
                    i0,
                    j0,
                    i1: (i0 + size).min(t.i1),
                    j1: (j0 + size).min(t.j1),
                });
            }
        }
        let result = self.children(&sub, level, &mut c, top, out);
        self.levels[level] = c;
        result
    }

    /// Evaluates the children `c.tiles` of a tile at `level` on `tape` (the tile's pruned
    /// tape) and goes on with each.
    fn children(
        &mut self,
        tape: &Tape,
        level: usize,
        c: &mut Children<T>,
        top: Tile,
        out: &mut [Pixel],
    ) -> Result<(), Error> {
        if !self.settings.prune {
            for &child in &c.tiles {
                self.tile(tape, level + 1, child, top, out)?;
            }
            return Ok(());
        }
        // All children in one pass over the pruned tape, each with its own choice trace.
        for col in &mut c.cols {
            col.clear();
        }
        for &child in &c.tiles {
            for (col, b) in c.cols.iter_mut().zip(self.bounds(child)?) {
                col.push(b);
            }
        }
        let n = c.tiles.len();
        c.values.clear();
        c.values.resize(n, Interval::ENTIRE);
        c.traces.resize_with(n, Vec::new);
        let clock = self.clock();
        self.boxes.set_tape(tape);
        self.boxes.eval_traced(
            &[&c.cols[0][..], &c.cols[1][..], &c.cols[2][..]],
            &mut c.values,
            &mut c.traces[..n],
        )?;
        if let Some(c) = clock {
            self.stats.interval_time += c.elapsed();
        }
        for k in 0..n {
            let (child, v) = (c.tiles[k], c.values[k]);
            self.evaluated(tape, level + 1, child, v, &c.traces[k], top, out)?;
        }
        Ok(())
    }

    /// Classifies the pixels of tile `t` by their centres.
    fn points(&mut self, tape: &Tape, t: Tile, top: Tile, out: &mut [Pixel]) -> Result<(), Error> {
        let g = self.grid;
        self.xs.clear();
        self.ys.clear();
        for j in t.j0..t.j1 {
            let y = g.y(j as f64 + 0.5);
            for i in t.i0..t.i1 {
                self.xs.push(g.x(i as f64 + 0.5));
                self.ys.push(y);
            }
        }
        let n = self.xs.len();
        self.zs.clear();
        self.zs.resize(n, g.z);
        self.values.resize(n, T::ZERO);
        let clock = self.clock();
        self.point.set_tape(tape);
        self.point.eval(
            &[&self.xs[..], &self.ys[..], &self.zs[..]],
            &mut self.values,
        )?;
        if let Some(c) = clock {
            self.stats.point_time += c.elapsed();
        }
        self.stats.point_pixels += n as u64;
        self.stats.point_batches += 1;
        self.stats.point_tape_len_sum += tape.len() as u64;
        let stride = top.i1 - top.i0;
        let mut k = 0;
        for j in t.j0..t.j1 {
            let row = (j - top.j0) * stride;
            for i in t.i0..t.i1 {
                out[row + i - top.i0] = if self.values[k] < T::ZERO {
                    Pixel::Inside
                } else {
                    Pixel::Outside
                };
                k += 1;
            }
        }
        Ok(())
    }
}

/// The children of a tile being split, their boxes (by variable slot), interval values and
/// choice traces: kept per level and reused from tile to tile.
struct Children<T: Float> {
    tiles: Vec<Tile>,
    cols: [Vec<Interval<T>>; 3],
    values: Vec<Interval<T>>,
    traces: Vec<Vec<Choice>>,
}

impl<T: Float> Default for Children<T> {
    fn default() -> Self {
        Self {
            tiles: Vec::new(),
            cols: Default::default(),
            values: Vec::new(),
            traces: Vec::new(),
        }
    }
}

/// The error of a tile box that is not an interval.
fn bad_bounds(e: interval_core::IntervalError) -> Error {
    Error::Unsupported(format!("tile bounds: {e}"))
}

/// Fills the pixels of tile `t` in the buffer of top-level tile `top`.
fn fill(out: &mut [Pixel], top: Tile, t: Tile, p: Pixel) {
    let stride = top.i1 - top.i0;
    for j in t.j0..t.j1 {
        let row = (j - top.j0) * stride;
        out[row + t.i0 - top.i0..row + t.i1 - top.i0].fill(p);
    }
}
