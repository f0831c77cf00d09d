//! The screen box structure (thesis 5.4.3-5.4.5, 5.5.1): the image is subdivided into
//! boxes that beams classify as Miss, Hit or Undecided.
//!
//! A Miss box is background without a ray. A Hit box needs one ray per pixel, searched only
//! in the box's `T_final`; a Hit box whose `T_final` is wide (the surface's depth varies a lot
//! across it: an aliasing region, thesis 5.5.1) is split further. Undecided boxes are split
//! down to single pixels, which then get several rays.

use crate::beam::BoxClass;

/// Side of the tiles the screen box structure starts from.
pub const SCREEN_TILE: u32 = 32;

/// Side of the tiles the frustum octree starts from (fidget's first 3D tile).
pub const OCTREE_TILE: u32 = 64;

/// A rectangle of pixels `[x0, x1) × [y0, y1)`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct PixelRect {
    /// Left column.
    pub x0: u32,
    /// Top row.
    pub y0: u32,
    /// One past the right column.
    pub x1: u32,
    /// One past the bottom row.
    pub y1: u32,
}

impl PixelRect {
    /// Number of pixels.
    pub fn area(&self) -> u64 {
        u64::from(self.x1 - self.x0) * u64::from(self.y1 - self.y0)
    }

    /// The longer of its width and height, in pixels.
    pub fn side(&self) -> u32 {
        (self.x1 - self.x0).max(self.y1 - self.y0)
    }

    /// Whether the rectangle is one pixel.
    pub fn is_pixel(&self) -> bool {
        self.x1 - self.x0 == 1 && self.y1 - self.y0 == 1
    }

    /// The (up to) four quadrants.
    pub fn split(&self) -> Vec<PixelRect> {
        self.quadrants().collect()
    }

    /// The (up to) four quadrants, top left, top right, bottom left, bottom right (the
    /// empty ones of a rectangle one pixel wide or high left out), without allocating.
    pub fn quadrants(&self) -> impl Iterator<Item = PixelRect> + use<> {
        self.numbered_quadrants().map(|(_, q)| q)
    }

    /// The quadrants of [`PixelRect::quadrants`], each with its position among the four
    /// (0 top left to 3 bottom right), also where an empty one was left out before it.
    pub fn numbered_quadrants(&self) -> impl Iterator<Item = (usize, PixelRect)> + use<> {
        let xm = self.x0 + (self.x1 - self.x0).div_ceil(2);
        let ym = self.y0 + (self.y1 - self.y0).div_ceil(2);
        let xs = [(self.x0, xm), (xm, self.x1)];
        let ys = [(self.y0, ym), (ym, self.y1)];
        (0..4)
            .map(move |k| {
                let ((x0, x1), (y0, y1)) = (xs[k % 2], ys[k / 2]);
                (k, PixelRect { x0, y0, x1, y1 })
            })
            .filter(|(_, q)| q.x1 > q.x0 && q.y1 > q.y0)
    }

    /// The pixels, row by row.
    pub fn pixels(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        (self.y0..self.y1).flat_map(move |y| (self.x0..self.x1).map(move |x| (x, y)))
    }
}

/// The `k × k` stratified positions inside a pixel for `n` rays per pixel (`k` the nearest
/// whole square root of `n`, at least 1): `((a + 0.5) / k, (b + 0.5) / k)`, `a` across
/// fastest, then `b` down. One ray is the pixel's centre.
pub fn stratified_offsets(n: u32) -> Vec<(f64, f64)> {
    let k = stratified_side(n);
    (0..k * k)
        .map(|i| {
            (
                (f64::from(i % k) + 0.5) / f64::from(k),
                (f64::from(i / k) + 0.5) / f64::from(k),
            )
        })
        .collect()
}

/// `k` of [`stratified_offsets`]: the nearest whole square root of `n`, at least 1.
pub fn stratified_side(n: u32) -> u32 {
    (f64::from(n)).sqrt().round().max(1.0) as u32
}

/// A classified box of the structure.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ScreenBox {
    /// Its pixels.
    pub rect: PixelRect,
    /// What its beam proved.
    pub class: BoxClass,
}

/// Whether a box of class `class` is split further: Hit boxes with `T_final` wider than
/// `t_final_width` (an aliasing region, thesis 5.5.1) and Undecided boxes are split until
/// they are single pixels; Miss boxes never.
pub fn needs_split(rect: &PixelRect, class: &BoxClass, t_final_width: f64) -> bool {
    !rect.is_pixel()
        && match class {
            BoxClass::Miss => false,
            BoxClass::Hit { t_final } => t_final.wid() > t_final_width,
            BoxClass::Undecided { .. } => true,
        }
}

/// The tiles of side `size` (or less at the right and bottom edges) covering a `w × h`
/// image, row by row: where the structure starts.
pub fn tiles(w: u32, h: u32, size: u32) -> Vec<PixelRect> {
    tiles_in(
        PixelRect {
            x0: 0,
            y0: 0,
            x1: w,
            y1: h,
        },
        size,
    )
}

/// The tiles of side `size` (or less at the right and bottom edges) covering `area`, from
/// its top left corner, row by row.
pub fn tiles_in(area: PixelRect, size: u32) -> Vec<PixelRect> {
    let mut out = Vec::new();
    for y0 in (area.y0..area.y1).step_by(size as usize) {
        for x0 in (area.x0..area.x1).step_by(size as usize) {
            out.push(PixelRect {
                x0,
                y0,
                x1: (x0 + size).min(area.x1),
                y1: (y0 + size).min(area.y1),
            });
        }
    }
    out
}
