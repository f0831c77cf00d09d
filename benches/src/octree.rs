//! A proven first-hit bound for the orthographic view of `[-1, 1]³` that fidget's voxel
//! renderer draws, computed the way fidget computes its depth image (an octree of 3D tiles,
//! front to back, each tile's tape pruned for the tiles inside it, tiles behind filled
//! pixels skipped), but with outward-rounded interval arithmetic throughout.
//!
//! Pixel `(i, j)` is the column `x ∈ [-1 + i·h, -1 + (i + 1)·h]`, `y ∈ [1 − (j + 1)·h, 1 − j·h]`
//! (`h = 2 / size`) of `size` voxels in `z`. A tile whose enclosure of `f` holds no zero is
//! skipped; one whose enclosure is negative, or a voxel whose enclosure holds zero, fills
//! the pixels of its footprint not filled yet with its front face. What is proven for a
//! filled pixel: `f` has no zero in its column in front of that voxel (every tile in front
//! was skipped), and it may have one there (or the solid starts there). For an empty pixel:
//! no zero in its whole column. fidget's image, which fills a voxel whose centre has
//! `f < 0`, can only fill pixels this one fills too (a negative value at a centre keeps
//! every tile holding it from being skipped); [`render3d_compare`] counts pixels where that
//! fails (none must) and pixels this bound fills and fidget does not (the voxels whose
//! enclosure holds zero while fidget's centre samples are positive: the conservative rim).
//!
//! This is primary visibility without the root proofs of the renderer (its screen boxes'
//! inclusion tests and `T_final`, and each pixel's proven first root): the same subdivision
//! would start the renderer's rays inside the voxel where the surface begins.
//!
//! [`render3d_compare`]: ../../render3d_compare/index.html

use implicit_expr::{Choice, Evaluator, Tape};
use interval_core::Interval;
use rayon::prelude::*;

/// Side of the top-level tiles, in voxels (fidget's first tile size).
pub const TILE: usize = 64;

/// Tapes this short are not pruned further (a pruning costs about two evaluations).
const PRUNE_MIN_LEN: usize = 16;

/// The first-hit bound of a model: per pixel (row by row from the top) the index of the
/// first voxel from the front (`z = +1`) that may hold the surface, and the work done.
#[derive(Clone, Debug, PartialEq)]
pub struct FirstHits {
    /// Image side in pixels.
    pub size: usize,
    /// Per pixel, the voxel (0 at `z = +1`) where the surface may begin; `None`: none in
    /// the column.
    pub voxel: Vec<Option<u32>>,
    /// Interval evaluations of the model.
    pub evals: u64,
    /// Tapes pruned.
    pub prunes: u64,
}

impl FirstHits {
    /// Whether each pixel's column may hold the surface.
    pub fn covered(&self) -> Vec<bool> {
        self.voxel.iter().map(Option::is_some).collect()
    }
}

/// The per-tile state of the subdivision.
struct Worker {
    eval: Evaluator<Interval<f64>>,
    trace: Vec<Choice>,
    evals: u64,
    prunes: u64,
    /// The first voxel of each pixel of the tile's footprint (`TILE × TILE`, row `y`
    /// counted from `y = -1`).
    first: Vec<Option<u32>>,
}

/// Where a cell lies: its corner in voxels and its side.
#[derive(Copy, Clone)]
struct Cell {
    x: usize,
    y: usize,
    z: usize,
    n: usize,
}

/// The first-hit bound of the model `tape` (in `x y z`) at `size × size` pixels (a
/// multiple of [`TILE`]), on the current rayon pool.
///
/// # Errors
///
/// When `size` is not a positive multiple of [`TILE`], or the tape has variables beyond
/// `x y z`.
pub fn first_hits(tape: &Tape, size: usize) -> Result<FirstHits, String> {
    if size == 0 || !size.is_multiple_of(TILE) {
        return Err(format!(
            "the octree needs an image side that is a multiple of {TILE}, not {size}"
        ));
    }
    if tape.var_count() > 3 {
        return Err(format!(
            "the model has {} variables; the octree evaluates x, y, z only",
            tape.var_count()
        ));
    }
    let tiles = size / TILE;
    let h = 2.0 / size as f64;
    let columns: Vec<(usize, usize)> = (0..tiles)
        .flat_map(|ty| (0..tiles).map(move |tx| (tx * TILE, ty * TILE)))
        .collect();
    let done: Vec<(usize, usize, Worker)> = columns
        .par_iter()
        .map(|&(x, y)| {
            let mut w = Worker {
                eval: Evaluator::new(tape),
                trace: Vec::new(),
                evals: 0,
                prunes: 0,
                first: vec![None; TILE * TILE],
            };
            // Front to back: the tile nearest z = +1 first.
            for z in (0..tiles).rev() {
                let cell = Cell {
                    x,
                    y,
                    z: z * TILE,
                    n: TILE,
                };
                w.subdivide(tape, cell, (x, y), size, h);
            }
            (x, y, w)
        })
        .collect();
    let mut out = FirstHits {
        size,
        voxel: vec![None; size * size],
        evals: 0,
        prunes: 0,
    };
    for (x0, y0, w) in done {
        out.evals += w.evals;
        out.prunes += w.prunes;
        for (k, v) in w.first.iter().enumerate() {
            let (x, y) = (x0 + k % TILE, y0 + k / TILE);
            // Image rows from the top (y = +1).
            out.voxel[(size - 1 - y) * size + x] = *v;
        }
    }
    Ok(out)
}

impl Worker {
    /// Searches `cell` (inside the tile at `origin`) with `tape`, pruned for a cell that
    /// holds it.
    fn subdivide(&mut self, tape: &Tape, cell: Cell, origin: (usize, usize), size: usize, h: f64) {
        let Cell { x, y, z, n } = cell;
        let index = |px: usize, py: usize| (py - origin.1) * TILE + (px - origin.0);
        let filled = (y..y + n).all(|py| (x..x + n).all(|px| self.first[index(px, py)].is_some()));
        if filled {
            return;
        }
        let side =
            |i: usize| Interval::new_unchecked(-1.0 + i as f64 * h, -1.0 + (i + n) as f64 * h);
        let region = [side(x), side(y), side(z)];
        self.eval.set_tape(tape);
        let Ok(f) = self.eval.eval_traced(&region, &mut self.trace) else {
            return;
        };
        self.evals += 1;
        if f.is_empty() || f.inf() > 0.0 {
            // No zero in the cell (undefined everywhere in it, or positive).
            return;
        }
        if f.sup() < 0.0 || n == 1 {
            // The voxel index counts from the front face z = +1.
            let front = (size - (z + n)) as u32;
            for py in y..y + n {
                for px in x..x + n {
                    let v = &mut self.first[index(px, py)];
                    if v.is_none() {
                        *v = Some(front);
                    }
                }
            }
            return;
        }
        let pruned;
        let inner = if tape.len() > PRUNE_MIN_LEN {
            pruned = tape.simplify(&self.trace).unwrap_or_else(|_| tape.clone());
            self.prunes += 1;
            &pruned
        } else {
            tape
        };
        let m = n / 2;
        for dz in [1, 0] {
            for dy in [0, 1] {
                for dx in [0, 1] {
                    let child = Cell {
                        x: x + dx * m,
                        y: y + dy * m,
                        z: z + dz * m,
                        n: m,
                    };
                    self.subdivide(inner, child, origin, size, h);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use implicit_expr::Context;
    use implicit_expr::vm::import_vm;

    use super::*;

    fn tape(vm: &str) -> Tape {
        let mut ctx = Context::new();
        let root = import_vm(&mut ctx, vm).expect("valid model");
        Tape::new(&ctx, &[root]).expect("compiles")
    }

    /// A ball of radius 0.7 centred at `(0.1, -0.2, 0.05)`: every pixel whose column's
    /// centre line meets the ball is covered, at or in front of the voxel of its first
    /// intersection, and no pixel whose whole column misses the ball is.
    #[test]
    fn ball_columns() {
        let vm = "x var-x\ny var-y\nz var-z\ncx const 0.1\ncy const -0.2\ncz const 0.05\n\
                  dx sub x cx\ndy sub y cy\ndz sub z cz\nxx square dx\nyy square dy\n\
                  zz square dz\ns add xx yy\nt add s zz\nr2 const 0.49\nf sub t r2\n";
        let size = 128;
        let hits = first_hits(&tape(vm), size).expect("a multiple of the tile");
        let h = 2.0 / size as f64;
        let (cx, cy, cz, r) = (0.1, -0.2, 0.05, 0.7);
        for j in 0..size {
            for i in 0..size {
                let (x0, x1) = (-1.0 + i as f64 * h, -1.0 + (i + 1) as f64 * h);
                let (y0, y1) = (1.0 - (j + 1) as f64 * h, 1.0 - j as f64 * h);
                let v = hits.voxel[j * size + i];
                // The centre line.
                let (x, y) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
                let d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
                if d2 < r * r {
                    let z_first = cz + (r * r - d2).sqrt();
                    let voxel = ((1.0 - z_first) / h).floor() as u32;
                    let v = v.unwrap_or_else(|| panic!("pixel ({i}, {j}) meets the ball"));
                    assert!(v <= voxel, "pixel ({i}, {j}): voxel {v} after {voxel}");
                }
                // The column's nearest point to the centre.
                let nx = cx.clamp(x0, x1) - cx;
                let ny = cy.clamp(y0, y1) - cy;
                if nx * nx + ny * ny > r * r * (1.0 + 1e-9) {
                    assert_eq!(v, None, "pixel ({i}, {j}) misses the ball");
                }
            }
        }
        assert!(
            hits.evals > 0 && hits.prunes == 0,
            "a 15-instruction tape is not pruned"
        );
    }

    #[test]
    fn sizes_that_are_not_multiples_of_the_tile_are_refused() {
        let t = tape("x var-x\ny var-y\nf add x y\n");
        assert!(first_hits(&t, 100).unwrap_err().contains("multiple of 64"));
        assert!(first_hits(&t, 0).is_err());
    }
}
