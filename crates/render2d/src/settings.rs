//! What to render and how: image size, region, tile sizes and switches.

use implicit_expr::Error;

use crate::region::Region;

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
    /// A square image of `size` pixels over `[-1, 1]²`, tiles `[128, 32, 8]` (the fastest
    /// of those measured on the benchmark expressions, see `docs/expr-benchmarks.md`),
    /// pruning on.
    pub fn square(size: usize) -> Self {
        Self {
            width: size,
            height: size,
            region: Region::default(),
            z: 0.0,
            tiles: vec![128, 32, 8],
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
