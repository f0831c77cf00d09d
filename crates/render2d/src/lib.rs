//! # render2d
//!
//! Reliable rendering of a planar implicit region `f(x, y) < 0` into a pixel grid by
//! interval subdivision with tape pruning. The `render2d` example program is a command line
//! over this crate, and the benchmarks time it against other 2D renderers.
//!
//! ```
//! use implicit_expr::{Context, Tape, parse::parse};
//! use render2d::{Settings, render, render_points, count_differences};
//!
//! // The unit disc, on a 64 x 64 image of [-1, 1]².
//! let mut ctx = Context::new();
//! let f = parse(&mut ctx, "x^2 + y^2 - 1", &[])?;
//! let tape = Tape::new(&ctx, &[f])?;
//! let settings = Settings::square(64);
//! let (image, stats) = render::<f64>(&tape, &settings)?;
//!
//! // Most pixels are decided by whole tiles; the image equals per-pixel evaluation.
//! assert!(stats.point_pixels < 64 * 64 / 2);
//! let reference = render_points::<f64>(&tape, &settings)?;
//! assert_eq!(count_differences(&image, &reference), 0);
//! # Ok::<(), implicit_expr::Error>(())
//! ```
//!
//! # How
//!
//! The image is cut into square top-level tiles (rayon schedules them), and each tile into
//! smaller tiles, level by level ([`Settings::tiles`], e.g. 64, 16, 4 pixels). For every
//! tile the tape is evaluated once in interval arithmetic over the box that the tile's
//! pixels span: an upper bound below zero proves every pixel inside, a lower bound at or
//! above zero proves every pixel outside. Otherwise the `min`/`max` choices of that
//! evaluation prune the tape ([`Tape::simplify`]), and the shorter tape is passed down to
//! the sub-tiles, which are evaluated together in one pass over it
//! ([`SliceEvaluator::eval_traced`], one choice trace per sub-tile); below the last level
//! the pixels are classified by point evaluation of their centres with a
//! [`SliceEvaluator`].
//!
//! # Why the image equals plain per-pixel evaluation
//!
//! A pixel is inside when the point value `f(c)` at its centre `c`, computed in the chosen
//! precision `T`, is `< 0` (`NaN` counts as outside). [`render`] and [`render_points`] agree
//! pixel for pixel, for three reasons:
//!
//! 1. *The tile boxes hold the pixel centres.* Centre coordinates and tile bounds come from
//!    the same rounded formula `x0 + t·w` (`y1 - t·h` for rows) at `t = i + 1/2` and at the
//!    tile's edge indices; rounding is monotone, so a tile's bounds bracket the centres of
//!    its pixels.
//! 2. *Point values lie inside interval values.* Each point operation rounds to nearest the
//!    real operation (elementary functions correctly rounded), each interval operation
//!    encloses the real range with float bounds, and a constant's point value lies inside
//!    its interval; by induction over the tape every intermediate point value lies inside
//!    the interval value of any box holding the point. So a tile whose interval is `< 0`
//!    has only inside pixels, and one whose interval is `>= 0` only outside ones. An empty
//!    interval (undefined on the whole box) decides nothing: the tile is subdivided.
//! 3. *Pruning is exact inside the region.* A `min(a, b)` is replaced by `a` only when the
//!    interval evaluation proved `sup A <= inf B` on the tile, so at every point of the tile
//!    `a <= b` and `min(a, b) = a` (likewise for `max`); the pruned tape computes the same
//!    point values as the full one on the tile and all its sub-tiles.
//!
//! Points 2 and 3 assume that the operations are applied inside their domains at the pixel
//! centres: interval arithmetic (IEEE 1788) drops the points where an operation such as
//! `sqrt`, `ln` or `/` is undefined, while the point evaluation gives `NaN` (or a signed
//! infinity for `1/0`) there. Tapes of total operations (`+ - * min max neg abs square exp
//! sin cos ...`, the usual CSG and signed-distance expressions) satisfy it everywhere;
//! otherwise [`render_points`] is the reference, and [`count_differences`] (the `--check`
//! option of the `render2d` example) counts any differing pixel.
//!
//! Results do not depend on the number of threads: each top-level tile is a pure function
//! of the tape, the settings and its position.

use std::time::{Duration, Instant};

use implicit_expr::{Choice, Error, Evaluator, Number, SliceEvaluator, Tape};
use interval_core::{Float, Interval};
use rayon::prelude::*;

/// The rectangle of the plane shown by the image.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Region {
    /// Left edge.
    pub x0: f64,
    /// Right edge.
    pub x1: f64,
    /// Bottom edge.
    pub y0: f64,
    /// Top edge.
    pub y1: f64,
}

impl Default for Region {
    /// `[-1, 1]²`.
    fn default() -> Self {
        Self {
            x0: -1.0,
            x1: 1.0,
            y0: -1.0,
            y1: 1.0,
        }
    }
}

/// What to render and how.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Image width in pixels.
    pub width: usize,
    /// Image height in pixels.
    pub height: usize,
    /// The region shown; pixel `(i, j)` (column `i`, row `j` from the top) covers
    /// `[x0 + i·w, x0 + (i+1)·w] × [y1 - (j+1)·h, y1 - j·h]`, `w = (x1 - x0)/width`,
    /// `h = (y1 - y0)/height`, and its sample is its centre.
    pub region: Region,
    /// The value of `z` for expressions that use it.
    pub z: f64,
    /// Tile sizes in pixels, largest first, each a multiple of the next (e.g. `[64, 16, 4]`):
    /// the first is the top-level tile, the last the tile whose pixels are evaluated as
    /// points.
    pub tiles: Vec<usize>,
    /// Prune the tape per tile (the point of the exercise; off to measure what it gives).
    pub prune: bool,
    /// Measure the time spent per stage (interval evaluation, pruning, point evaluation).
    pub timing: bool,
}

impl Settings {
    /// A square image of `size` pixels over `[-1, 1]²`, tiles `[64, 16, 4]`, pruning on.
    pub fn square(size: usize) -> Self {
        Self {
            width: size,
            height: size,
            region: Region::default(),
            z: 0.0,
            tiles: vec![64, 16, 4],
            prune: true,
            timing: false,
        }
    }

    /// Checks the settings.
    ///
    /// Returns an error naming the first problem.
    pub fn validate(&self) -> Result<(), Error> {
        let bad = |m: String| Err(Error::Unsupported(m));
        if self.width == 0 || self.height == 0 {
            return bad(format!(
                "image size {}x{} is empty",
                self.width, self.height
            ));
        }
        if self.width > 1 << 14 || self.height > 1 << 14 {
            return bad(format!(
                "image size {}x{} exceeds 16384 pixels a side",
                self.width, self.height
            ));
        }
        let r = &self.region;
        let finite = [r.x0, r.x1, r.y0, r.y1, self.z]
            .iter()
            .all(|v| v.is_finite());
        if !finite || r.x0 >= r.x1 || r.y0 >= r.y1 {
            return bad(format!(
                "region [{}, {}] x [{}, {}] must have finite bounds with xmin < xmax and ymin < ymax",
                r.x0, r.x1, r.y0, r.y1
            ));
        }
        if self.tiles.is_empty() || self.tiles.contains(&0) {
            return bad("tile sizes must be a non-empty list of positive sizes".into());
        }
        for w in self.tiles.windows(2) {
            if w[1] >= w[0] || w[0] % w[1] != 0 {
                return bad(format!(
                    "tile size {} must be smaller than {} and divide it",
                    w[1], w[0]
                ));
            }
        }
        Ok(())
    }
}

/// How a pixel was classified.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Pixel {
    /// Outside, proven for its whole tile by interval evaluation.
    ProvenOutside = 0,
    /// Inside, proven for its whole tile by interval evaluation.
    ProvenInside = 1,
    /// Outside by point evaluation of its centre.
    Outside = 2,
    /// Inside by point evaluation of its centre.
    Inside = 3,
}

impl Pixel {
    /// Whether the pixel is inside (`f < 0` at its centre).
    pub fn is_inside(self) -> bool {
        matches!(self, Pixel::ProvenInside | Pixel::Inside)
    }

    /// Whether the pixel was decided by interval evaluation of a tile.
    pub fn is_proven(self) -> bool {
        matches!(self, Pixel::ProvenInside | Pixel::ProvenOutside)
    }
}

/// A rendered image: one [`Pixel`] per pixel, row by row from the top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// The pixels, `pixels[j * width + i]` for column `i` and row `j`.
    pub pixels: Vec<Pixel>,
}

/// What happened at one level of tiles.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LevelStats {
    /// Tile size of the level in pixels.
    pub size: usize,
    /// Tiles evaluated in interval arithmetic.
    pub tiles: u64,
    /// Tiles proven inside.
    pub inside: u64,
    /// Tiles proven outside.
    pub outside: u64,
    /// Sum of the lengths of the tapes evaluated at this level.
    pub tape_len_sum: u64,
    /// Shortest tape evaluated at this level.
    pub tape_len_min: usize,
    /// Longest tape evaluated at this level.
    pub tape_len_max: usize,
}

impl LevelStats {
    /// Mean length of the tapes evaluated at this level.
    pub fn tape_len_mean(&self) -> f64 {
        if self.tiles == 0 {
            0.0
        } else {
            self.tape_len_sum as f64 / self.tiles as f64
        }
    }

    fn add_tape(&mut self, len: usize) {
        if self.tiles == 0 || len < self.tape_len_min {
            self.tape_len_min = len;
        }
        self.tape_len_max = self.tape_len_max.max(len);
        self.tape_len_sum += len as u64;
        self.tiles += 1;
    }

    fn merge(&mut self, o: &LevelStats) {
        if o.tiles > 0 {
            if self.tiles == 0 || o.tape_len_min < self.tape_len_min {
                self.tape_len_min = o.tape_len_min;
            }
            self.tape_len_max = self.tape_len_max.max(o.tape_len_max);
        }
        self.tiles += o.tiles;
        self.inside += o.inside;
        self.outside += o.outside;
        self.tape_len_sum += o.tape_len_sum;
    }
}

/// Counters and times of a [`render`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    /// One entry per tile level, largest tiles first.
    pub levels: Vec<LevelStats>,
    /// Pixels classified by point evaluation.
    pub point_pixels: u64,
    /// Point batches evaluated (one per undecided smallest tile).
    pub point_batches: u64,
    /// Sum over point batches of the length of the tape they used.
    pub point_tape_len_sum: u64,
    /// Tapes pruned (`simplify` calls that returned a shorter tape).
    pub pruned_tapes: u64,
    /// Time in interval evaluation, summed over threads (with [`Settings::timing`]).
    pub interval_time: Duration,
    /// Time in tape pruning, summed over threads (with [`Settings::timing`]).
    pub prune_time: Duration,
    /// Time in point evaluation, summed over threads (with [`Settings::timing`]).
    pub point_time: Duration,
}

impl Stats {
    fn new(tiles: &[usize]) -> Self {
        Self {
            levels: tiles
                .iter()
                .map(|&size| LevelStats {
                    size,
                    ..LevelStats::default()
                })
                .collect(),
            ..Self::default()
        }
    }

    fn merge(&mut self, o: &Stats) {
        for (a, b) in self.levels.iter_mut().zip(&o.levels) {
            a.merge(b);
        }
        self.point_pixels += o.point_pixels;
        self.point_batches += o.point_batches;
        self.point_tape_len_sum += o.point_tape_len_sum;
        self.pruned_tapes += o.pruned_tapes;
        self.interval_time += o.interval_time;
        self.prune_time += o.prune_time;
        self.point_time += o.point_time;
    }

    /// Mean length of the tapes used by the point batches.
    pub fn point_tape_len_mean(&self) -> f64 {
        if self.point_batches == 0 {
            0.0
        } else {
            self.point_tape_len_sum as f64 / self.point_batches as f64
        }
    }
}

/// Pixel coordinates in the working precision: the one formula used for pixel centres and
/// tile bounds alike (see the module documentation, point 1).
#[derive(Copy, Clone, Debug)]
struct Grid<T> {
    x0: T,
    w: T,
    y1: T,
    h: T,
    z: T,
}

impl<T: Float> Grid<T> {
    fn new(s: &Settings) -> Self {
        let r = &s.region;
        Self {
            x0: T::from_f64_rn(r.x0),
            w: T::from_f64_rn((r.x1 - r.x0) / s.width as f64),
            y1: T::from_f64_rn(r.y1),
            h: T::from_f64_rn((r.y1 - r.y0) / s.height as f64),
            z: T::from_f64_rn(s.z),
        }
    }

    /// `x` at column coordinate `t` (`i + 1/2` for the centre of column `i`).
    #[inline]
    fn x(&self, t: f64) -> T {
        self.x0 + T::from_f64_rn(t) * self.w
    }

    /// `y` at row coordinate `t` (rows go down from the top edge).
    #[inline]
    fn y(&self, t: f64) -> T {
        self.y1 - T::from_f64_rn(t) * self.h
    }
}

/// A block of pixels `[i0, i1) × [j0, j1)`.
#[derive(Copy, Clone, Debug)]
struct Tile {
    i0: usize,
    j0: usize,
    i1: usize,
    j1: usize,
}

/// Per-thread state: the evaluators (reused across tapes) and scratch space.
struct Worker<'a, T: Float + Number>
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
    stats: Stats,
}

impl<'a, T: Float + Number> Worker<'a, T>
where
    Interval<T>: Number,
{
    fn new(tape: &Tape, settings: &'a Settings) -> Self {
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
            stats: Stats::new(&settings.tiles),
        }
    }

    fn clock(&self) -> Option<Instant> {
        self.settings.timing.then(Instant::now)
    }

    /// Renders the top-level tile `t` into `out` (its pixels, row by row).
    fn top(&mut self, tape: &Tape, t: Tile, out: &mut [Pixel]) -> Result<(), Error> {
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
        let mut children = Vec::new();
        for j0 in (t.j0..t.j1).step_by(size) {
            for i0 in (t.i0..t.i1).step_by(size) {
                children.push(Tile {
                    i0,
                    j0,
                    i1: (i0 + size).min(t.i1),
                    j1: (j0 + size).min(t.j1),
                });
            }
        }
        if !self.settings.prune {
            for child in children {
                self.tile(&sub, level + 1, child, top, out)?;
            }
            return Ok(());
        }
        // All children in one pass over the pruned tape, each with its own choice trace.
        let mut cols: [Vec<Interval<T>>; 3] = Default::default();
        for &child in &children {
            for (col, b) in cols.iter_mut().zip(self.bounds(child)?) {
                col.push(b);
            }
        }
        let mut values = vec![Interval::ENTIRE; children.len()];
        let mut traces = vec![Vec::new(); children.len()];
        let clock = self.clock();
        self.boxes.set_tape(&sub);
        self.boxes.eval_traced(
            &[&cols[0][..], &cols[1][..], &cols[2][..]],
            &mut values,
            &mut traces,
        )?;
        if let Some(c) = clock {
            self.stats.interval_time += c.elapsed();
        }
        for ((child, v), trace) in children.into_iter().zip(values).zip(&traces) {
            self.evaluated(&sub, level + 1, child, v, trace, top, out)?;
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

/// Checks that `tape` is a function of `x`, `y`, `z` only.
fn check_tape(tape: &Tape) -> Result<(), Error> {
    if tape.var_count() > 3 {
        return Err(Error::Unsupported(format!(
            "the expression has {} variable slots; a 2D render gives values to x, y and z only",
            tape.var_count()
        )));
    }
    Ok(())
}

/// The top-level tiles, row by row.
fn top_tiles(s: &Settings) -> Vec<Tile> {
    let size = s.tiles[0];
    let mut tiles = Vec::new();
    for j0 in (0..s.height).step_by(size) {
        for i0 in (0..s.width).step_by(size) {
            tiles.push(Tile {
                i0,
                j0,
                i1: (i0 + size).min(s.width),
                j1: (j0 + size).min(s.height),
            });
        }
    }
    tiles
}

/// Renders `tape` (its first output is `f`) by interval subdivision with pruning, in
/// precision `T` (`f32` or `f64`), on rayon's current thread pool. See the
/// [crate documentation](crate).
///
/// Returns an error for invalid settings or a tape with variables besides `x`, `y`, `z`.
pub fn render<T: Float + Number>(tape: &Tape, settings: &Settings) -> Result<(Image, Stats), Error>
where
    Interval<T>: Number,
{
    settings.validate()?;
    check_tape(tape)?;
    let tiles = top_tiles(settings);
    let results: Vec<Result<(Vec<Pixel>, Stats), Error>> = tiles
        .par_iter()
        .map_init(
            || Worker::<T>::new(tape, settings),
            |w, &t| {
                let mut buf = vec![Pixel::ProvenOutside; (t.i1 - t.i0) * (t.j1 - t.j0)];
                w.stats = Stats::new(&settings.tiles);
                w.top(tape, t, &mut buf)?;
                Ok((buf, std::mem::take(&mut w.stats)))
            },
        )
        .collect();
    let mut image = Image {
        width: settings.width,
        height: settings.height,
        pixels: vec![Pixel::ProvenOutside; settings.width * settings.height],
    };
    let mut stats = Stats::new(&settings.tiles);
    for (t, r) in tiles.iter().zip(results) {
        let (buf, s) = r?;
        stats.merge(&s);
        let stride = t.i1 - t.i0;
        for (row, j) in (t.j0..t.j1).enumerate() {
            let dst = j * settings.width;
            image.pixels[dst + t.i0..dst + t.i1]
                .copy_from_slice(&buf[row * stride..(row + 1) * stride]);
        }
    }
    Ok((image, stats))
}

/// The reference: every pixel classified by point evaluation of its centre with the full
/// tape, in precision `T`, row by row on rayon's current thread pool. `true` is inside.
///
/// Returns an error for invalid settings or a tape with variables besides `x`, `y`, `z`.
pub fn render_points<T: Float + Number>(
    tape: &Tape,
    settings: &Settings,
) -> Result<Vec<bool>, Error> {
    settings.validate()?;
    check_tape(tape)?;
    let g = Grid::<T>::new(settings);
    let w = settings.width;
    let xs: Vec<T> = (0..w).map(|i| g.x(i as f64 + 0.5)).collect();
    let zs = vec![g.z; w];
    let mut inside = vec![false; w * settings.height];
    inside.par_chunks_mut(w).enumerate().try_for_each_init(
        || {
            (
                SliceEvaluator::<T>::new(tape),
                vec![T::ZERO; w],
                vec![T::ZERO; w],
            )
        },
        |(eval, ys, values), (j, row)| -> Result<(), Error> {
            ys.fill(g.y(j as f64 + 0.5));
            eval.eval(&[&xs[..], &ys[..], &zs[..]], values)?;
            for (o, v) in row.iter_mut().zip(values.iter()) {
                *o = *v < T::ZERO;
            }
            Ok(())
        },
    )?;
    Ok(inside)
}

/// Number of pixels where `image` and the reference `inside` disagree.
pub fn count_differences(image: &Image, inside: &[bool]) -> usize {
    image
        .pixels
        .iter()
        .zip(inside)
        .filter(|(p, i)| p.is_inside() != **i)
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use implicit_expr::Context;

    fn tape_of(formula: &str) -> Tape {
        let mut ctx = Context::new();
        let f = implicit_expr::parse::parse(&mut ctx, formula, &[]).unwrap();
        Tape::new(&ctx, &[f]).unwrap()
    }

    fn agree<T: Float + Number>(formula: &str, settings: &Settings) -> Stats
    where
        Interval<T>: Number,
    {
        let tape = tape_of(formula);
        let (image, stats) = render::<T>(&tape, settings).unwrap();
        let reference = render_points::<T>(&tape, settings).unwrap();
        assert_eq!(count_differences(&image, &reference), 0, "{formula}");
        stats
    }

    #[test]
    fn disc_union_matches_point_evaluation() {
        let f = "min(sqrt((x-0.3)^2 + y^2) - 0.5, max(abs(x+0.4) - 0.2, abs(y-0.1) - 0.6))";
        let s = Settings::square(96);
        let stats = agree::<f32>(f, &s);
        agree::<f64>(f, &s);
        // Most of the picture is decided by tiles, and pruning happened.
        assert!(stats.point_pixels < 96 * 96 / 2);
        assert!(stats.pruned_tapes > 0);
    }

    #[test]
    fn odd_sizes_regions_and_tiles() {
        let f = "max(x^2 + y^2 - 0.8, -(x^2 + 4*y^2 - 0.1))";
        let mut s = Settings::square(37);
        s.height = 53;
        s.region = Region {
            x0: -1.3,
            x1: 0.7,
            y0: -0.9,
            y1: 1.1,
        };
        s.tiles = vec![32, 8, 2];
        agree::<f64>(f, &s);
        s.prune = false;
        agree::<f32>(f, &s);
    }

    #[test]
    fn thread_count_does_not_change_the_image() {
        let tape = tape_of("min(sin(5*x) + cos(4*y), 0.3 - x*y)");
        let s = Settings::square(80);
        let run = |n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
                .install(|| render::<f64>(&tape, &s).unwrap())
        };
        let (a, sa) = run(1);
        let (b, sb) = run(3);
        assert_eq!(a, b);
        assert_eq!(sa.levels, sb.levels);
        assert_eq!(sa.point_pixels, sb.point_pixels);
    }

    #[test]
    fn bad_settings_are_errors() {
        let tape = tape_of("x");
        let mut s = Settings::square(16);
        s.tiles = vec![16, 5];
        assert!(render::<f64>(&tape, &s).is_err());
        s.tiles = vec![];
        assert!(render::<f64>(&tape, &s).is_err());
        let mut s = Settings::square(16);
        s.region.x1 = s.region.x0;
        assert!(render_points::<f64>(&tape, &s).is_err());
        s = Settings::square(0);
        assert!(render::<f32>(&tape, &s).is_err());
    }
}
