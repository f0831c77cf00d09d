//! The rendered image: how each pixel was classified, and comparison with the reference.

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

/// Number of pixels where `image` and the reference `inside` disagree.
pub fn count_differences(image: &Image, inside: &[bool]) -> usize {
    image
        .pixels
        .iter()
        .zip(inside)
        .filter(|(p, i)| p.is_inside() != **i)
        .count()
}
