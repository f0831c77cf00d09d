//! Windows of the image: the rectangle of pixels one run of the render pipeline covers, the
//! whole image or one work unit of a render shared among processes (the thesis's screen
//! boxes handed from workstation to workstation, 7.2).
//!
//! The passes start from tiles of the whole image (the screen box structure's 32 pixels,
//! the frustum octree's 64) and every answer depends on its query alone, so a window whose
//! sides lie on the plan's grid of tiles ([`window_grid`]) or on the image's edge gets,
//! for each of its pixels, bit for bit what a render of the whole image gets: the same
//! tiles, rays, beams and seeds. Pixels are numbered row-major inside the window;
//! [`Window::global`] gives a pixel's number in the whole image (what its stochastic seeds
//! use).

use crate::error::Error;
use crate::plan::{Pass, Plan, Primary};
use crate::screen::{OCTREE_TILE, PixelRect, SCREEN_TILE, tiles_in};

/// The largest grid a window's sides may need: the frustum octree's tiles (64 pixels), a
/// multiple of every plan's [`window_grid`].
pub const WINDOW_ALIGN: u32 = 64;

/// The grid that the sides of a window rendered with `plan` must lie on (away from the
/// image's edges): the first tiles of its first primary pass (the frustum octree's 64
/// pixels, the screen boxes' 32), or single pixels when no pass starts from tiles.
pub fn window_grid(plan: &Plan) -> u32 {
    match plan.primary {
        Primary::Octree { .. } => OCTREE_TILE,
        _ if plan.runs(Pass::ScreenBoxes) => SCREEN_TILE,
        _ => 1,
    }
}

/// A rectangle of an image's pixels that a render covers.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct Window {
    rect: PixelRect,
    image_width: u32,
    image_height: u32,
}

impl Window {
    /// The whole `width × height` image.
    pub fn full(width: u32, height: u32) -> Self {
        Self {
            rect: PixelRect {
                x0: 0,
                y0: 0,
                x1: width,
                y1: height,
            },
            image_width: width,
            image_height: height,
        }
    }

    /// The rectangle `rect` of a `width × height` image.
    ///
    /// # Errors
    ///
    /// [`Error::Setting`] (`window`) when `rect` is empty or leaves the image.
    pub fn new(rect: PixelRect, width: u32, height: u32) -> Result<Self, Error> {
        let PixelRect { x0, y0, x1, y1 } = rect;
        if x0 >= x1 || y0 >= y1 || x1 > width || y1 > height {
            return Err(Error::Setting {
                name: "window".into(),
                message: format!(
                    "[{x0}, {x1}) x [{y0}, {y1}) is empty or leaves the {width} x {height} image"
                ),
            });
        }
        Ok(Self {
            rect,
            image_width: width,
            image_height: height,
        })
    }

    /// Checks that the window's sides lie on the grid of side `grid` or on the image's
    /// edges ([`window_grid`]).
    ///
    /// # Errors
    ///
    /// [`Error::Setting`] (`window`) naming the window and the grid.
    pub fn check_grid(&self, grid: u32) -> Result<(), Error> {
        let PixelRect { x0, y0, x1, y1 } = self.rect;
        let (w, h) = (self.image_width, self.image_height);
        let on = |v: u32, edge: u32| v.is_multiple_of(grid) || v == edge;
        if on(x0, w) && on(y0, h) && on(x1, w) && on(y1, h) {
            Ok(())
        } else {
            Err(Error::Setting {
                name: "window".into(),
                message: format!(
                    "[{x0}, {x1}) x [{y0}, {y1}): its sides must be multiples of {grid} pixels \
                     (the plan's first tiles) or the image's edges"
                ),
            })
        }
    }

    /// The window's pixels in the image.
    pub fn rect(&self) -> PixelRect {
        self.rect
    }

    /// Whether the window is the whole image.
    pub fn is_full(&self) -> bool {
        *self == Self::full(self.image_width, self.image_height)
    }

    /// The image's width and height.
    pub fn image_size(&self) -> (u32, u32) {
        (self.image_width, self.image_height)
    }

    /// The window's width in pixels.
    pub fn width(&self) -> u32 {
        self.rect.x1 - self.rect.x0
    }

    /// The window's height in pixels.
    pub fn height(&self) -> u32 {
        self.rect.y1 - self.rect.y0
    }

    /// The number of pixels.
    pub fn len(&self) -> usize {
        self.width() as usize * self.height() as usize
    }

    /// Whether the window has no pixel (never: [`Window::new`] refuses empty windows).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The image coordinates of the window's pixel `k`.
    pub fn pixel(&self, k: usize) -> (u32, u32) {
        let w = self.width() as usize;
        (self.rect.x0 + (k % w) as u32, self.rect.y0 + (k / w) as u32)
    }

    /// The window's number of the image's pixel `(x, y)`, which must lie inside it.
    pub fn local(&self, x: u32, y: u32) -> usize {
        debug_assert!(x >= self.rect.x0 && x < self.rect.x1);
        debug_assert!(y >= self.rect.y0 && y < self.rect.y1);
        (y - self.rect.y0) as usize * self.width() as usize + (x - self.rect.x0) as usize
    }

    /// The image's number (row-major) of the window's pixel `k`.
    pub fn global(&self, k: usize) -> usize {
        let (x, y) = self.pixel(k);
        y as usize * self.image_width as usize + x as usize
    }

    /// The tiles of side `size` of the whole image that lie in the window (each lies in it
    /// or outside it when the window is on the grid of `size`), row by row.
    pub fn tiles(&self, size: u32) -> Vec<PixelRect> {
        debug_assert!(self.check_grid(size).is_ok());
        tiles_in(self.rect, size)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::screen::tiles;

    #[test]
    fn windows_on_the_grid_or_the_edge_only() {
        let r = |x0, y0, x1, y1| PixelRect { x0, y0, x1, y1 };
        let on = |rect, grid| Window::new(rect, 200, 100).unwrap().check_grid(grid);
        assert!(on(r(64, 0, 128, 100), 64).is_ok());
        assert!(on(r(128, 64, 200, 100), 64).is_ok());
        assert!(on(r(32, 0, 64, 64), 32).is_ok());
        assert!(on(r(3, 5, 4, 6), 1).is_ok());
        for bad in [r(0, 0, 65, 64), r(32, 0, 64, 64), r(0, 0, 64, 96)] {
            let e = on(bad, 64).unwrap_err().to_string();
            assert!(e.contains("multiples of 64"), "{e}");
        }
        for bad in [r(0, 0, 0, 10), r(0, 0, 64, 101)] {
            let e = Window::new(bad, 200, 100).unwrap_err().to_string();
            assert!(e.contains("empty or leaves"), "{e}");
        }
    }

    #[test]
    fn a_window_holds_the_image_tiles_inside_it() {
        let (w, h) = (200, 150);
        let win = Window::new(
            PixelRect {
                x0: 64,
                y0: 64,
                x1: 200,
                y1: 150,
            },
            w,
            h,
        )
        .unwrap();
        for size in [32, 64] {
            let inside: Vec<PixelRect> = tiles(w, h, size)
                .into_iter()
                .filter(|t| t.x0 >= 64 && t.y0 >= 64)
                .collect();
            assert_eq!(win.tiles(size), inside);
        }
        assert_eq!(win.pixel(0), (64, 64));
        assert_eq!(win.local(65, 66), 2 * 136 + 1);
        assert_eq!(win.global(win.local(65, 66)), 66 * 200 + 65);
        assert!(Window::full(w, h).is_full());
        assert!(!win.is_full());
    }
}
