//! Pixel coordinates: the pixel-centre grid and blocks of pixels (tiles).

use interval_core::Float;

use crate::settings::Settings;

/// Pixel coordinates in the working precision: the one formula used for pixel centres and
/// tile bounds alike (see the crate documentation, point 1).
#[derive(Copy, Clone, Debug)]
pub(crate) struct Grid<T> {
    x0: T,
    w: T,
    y1: T,
    h: T,
    /// The value of `z` (the same at every pixel).
    pub(crate) z: T,
}

impl<T: Float> Grid<T> {
    /// The grid of `s`, its coordinates rounded to `T`.
    pub(crate) fn new(s: &Settings) -> Self {
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
    pub(crate) fn x(&self, t: f64) -> T {
        self.x0 + T::from_f64_rn(t) * self.w
    }

    /// `y` at row coordinate `t` (rows go down from the top edge).
    #[inline]
    pub(crate) fn y(&self, t: f64) -> T {
        self.y1 - T::from_f64_rn(t) * self.h
    }
}

/// A block of pixels `[i0, i1) × [j0, j1)`.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Tile {
    /// First column.
    pub(crate) i0: usize,
    /// First row.
    pub(crate) j0: usize,
    /// Column past the last.
    pub(crate) i1: usize,
    /// Row past the last.
    pub(crate) j1: usize,
}

/// The top-level tiles, row by row.
pub(crate) fn top_tiles(s: &Settings) -> Vec<Tile> {
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
