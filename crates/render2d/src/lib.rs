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

mod grid;
mod image;
mod region;
mod settings;
mod stats;
mod worker;

use implicit_expr::{Error, Number, SliceEvaluator, Tape};
use interval_core::{Float, Interval};
use rayon::prelude::*;

use crate::grid::{Grid, top_tiles};
use crate::worker::Worker;

pub use crate::image::{Image, Pixel, count_differences};
pub use crate::region::Region;
pub use crate::settings::Settings;
pub use crate::stats::{LevelStats, Stats};

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
