//! What the first primary pass proves of each pixel: its screen box's (or first cell's)
//! class, kept in the form the render's output holds, and the pixels whose shading was
//! judged smooth.

use super::buffers;
use crate::beam::BoxClass;

/// What the first primary pass proved of a pixel.
#[derive(Copy, Clone, Debug)]
pub(super) struct BoxPixel {
    /// Its box's class.
    pub(super) class: BoxClass,
    /// Whether its box is a Hit whose shading was judged to vary by at most the
    /// anti-aliasing threshold, hard shadows included ([`shading_variation`]: a bound up to
    /// the rounding of its cone angles): the pixel is shaded once, in the box's `T_final`,
    /// with no beam of its own.
    ///
    /// [`shading_variation`]: crate::aa::shading_variation
    pub(super) smooth: bool,
}

/// A pixel's box class and whether it lies on its box's top or left edge (the
/// classification image's outlines), as the render's output keeps them (`None`: no box
/// classified the pixel).
pub(super) type BoxOf = Option<(BoxClass, bool)>;

/// What the first primary pass proved of each pixel of a window.
///
/// The classes are kept as the output holds them, so that a render hands them on without
/// a pass over them; the smooth pixels, which only the screen boxes of a plan that judges
/// shading have, are kept apart.
#[derive(Clone, Debug)]
pub(super) struct PixelClasses {
    boxes: Vec<BoxOf>,
    /// Per pixel, whether it is judged smooth; empty while none is.
    smooth: Vec<bool>,
}

impl PixelClasses {
    /// `n` pixels, each with `class` (none judged smooth).
    pub(super) fn filled(n: usize, class: BoxOf) -> Self {
        Self {
            boxes: buffers::filled(n, class),
            smooth: Vec::new(),
        }
    }

    /// The number of pixels.
    pub(super) fn len(&self) -> usize {
        self.boxes.len()
    }

    /// What is proven of pixel `p` (`None`: no box classified it).
    #[inline]
    pub(super) fn get(&self, p: usize) -> Option<BoxPixel> {
        self.boxes[p].map(|(class, _)| BoxPixel {
            class,
            smooth: self.smooth.get(p).copied().unwrap_or(false),
        })
    }

    /// Pixel `p` in a box of class `class`, on its top or left edge where `edge`.
    pub(super) fn set(&mut self, p: usize, class: BoxClass, edge: bool) {
        self.boxes[p] = Some((class, edge));
    }

    /// Marks pixel `p` smooth, where a box classified it.
    pub(super) fn mark_smooth(&mut self, p: usize) {
        if self.boxes[p].is_none() {
            return;
        }
        if self.smooth.is_empty() {
            self.smooth = vec![false; self.boxes.len()];
        }
        self.smooth[p] = true;
    }

    /// The classes, to write in place (a pixel's smoothness is left as it is).
    pub(super) fn boxes_mut(&mut self) -> &mut [BoxOf] {
        &mut self.boxes
    }

    /// The classes as the render's output keeps them.
    pub(super) fn into_boxes(self) -> Vec<BoxOf> {
        self.boxes
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use interval_core::Interval;

    /// A pixel reads back the class it was given (and the output its edge), and is smooth only once marked;
    /// a pixel no box classified cannot be marked.
    #[test]
    fn pixels_keep_their_class_edge_and_smoothness() {
        let hit = BoxClass::Hit {
            t_final: Interval::new(1.0, 2.0).unwrap(),
        };
        let mut c = PixelClasses::filled(4, None);
        c.set(1, hit, true);
        c.set(2, BoxClass::Miss, false);
        assert!(c.get(0).is_none());
        let p = c.get(1).unwrap();
        assert!(!p.smooth && p.class == hit);
        c.mark_smooth(1);
        c.mark_smooth(0);
        assert!(c.get(1).unwrap().smooth);
        assert!(!c.get(2).unwrap().smooth);
        assert!(c.get(0).is_none());
        assert_eq!(c.len(), 4);
        assert_eq!(c.into_boxes()[1], Some((hit, true)));
    }
}
