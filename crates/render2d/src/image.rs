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

    /// The pixel's colour as RGB: inside dark blue, outside off-white; with `show_points`,
    /// the pixels decided by point evaluation are lighter (inside) or tinted (outside).
    pub fn color(self, show_points: bool) -> [u8; 3] {
        const INSIDE: [u8; 3] = [0x1d, 0x35, 0x57];
        const OUTSIDE: [u8; 3] = [0xf4, 0xf1, 0xe8];
        match (self, show_points) {
            (Pixel::Inside, true) => [0x45, 0x7b, 0x9d],
            (Pixel::Outside, true) => [0xe6, 0xa5, 0x7e],
            (p, _) if p.is_inside() => INSIDE,
            _ => OUTSIDE,
        }
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

impl Image {
    /// The image as 8-bit RGB bytes, three per pixel in the order of [`Image::pixels`],
    /// coloured by [`Pixel::color`].
    pub fn to_rgb8(&self, show_points: bool) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|&p| p.color(show_points))
            .collect()
    }
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

    #[test]
    fn colours_tell_inside_from_outside_and_points_when_asked() {
        let all = [
            Pixel::ProvenOutside,
            Pixel::ProvenInside,
            Pixel::Outside,
            Pixel::Inside,
        ];
        for p in all {
            assert_eq!(p.color(false), p.color(p.is_proven()));
        }
        assert_eq!(Pixel::Inside.color(false), Pixel::ProvenInside.color(false));
        assert_ne!(Pixel::Inside.color(true), Pixel::ProvenInside.color(true));
        assert_ne!(Pixel::Outside.color(true), Pixel::ProvenOutside.color(true));
        assert_ne!(Pixel::Inside.color(false), Pixel::Outside.color(false));
        let image = Image {
            width: 2,
            height: 2,
            pixels: all.to_vec(),
        };
        let rgb = image.to_rgb8(true);
        assert_eq!(rgb.len(), 12);
        assert_eq!(rgb[9..], Pixel::Inside.color(true));
        assert_eq!(count_differences(&image, &[false, true, true, true]), 1);
    }
}
