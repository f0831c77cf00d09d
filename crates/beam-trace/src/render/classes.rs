//! What the first primary pass proves of each pixel: its screen box's (or first cell's)
//! class, kept in the form the render's output holds, the kind of each class in a byte,
//! and the pixels whose shading was judged smooth.

use rayon::prelude::*;

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

/// The kind of a pixel's class, which decides how many rays it takes and what its samples
/// prove. The values index tables by kind (`kind as usize`).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum Kind {
    /// No box classified the pixel.
    Unclassified = 0,
    /// Its box is a Miss.
    Miss = 1,
    /// Its box is a Hit.
    Hit = 2,
    /// Its box is Undecided.
    Undecided = 3,
}

impl Kind {
    /// The kind of the class `class` (`None`: no box classified the pixel).
    pub(super) fn of(class: Option<&BoxClass>) -> Kind {
        match class {
            None => Kind::Unclassified,
            Some(BoxClass::Miss) => Kind::Miss,
            Some(BoxClass::Hit { .. }) => Kind::Hit,
            Some(BoxClass::Undecided { .. }) => Kind::Undecided,
        }
    }
}

/// What the first primary pass proved of each pixel of a window.
///
/// The classes are kept as the output holds them, so that a render hands them on without
/// a pass over them, and each class's kind again in a byte: the passes that only ask how
/// many rays a pixel takes read a byte a pixel instead of a class's 32 (csg3d-2k at
/// 1024 × 1024: 1 MB instead of 32 per pass over the image). The smooth pixels, which
/// only the screen boxes of a plan that judges shading have, are kept apart.
#[derive(Clone, Debug)]
pub(super) struct PixelClasses {
    boxes: Vec<BoxOf>,
    kinds: Vec<Kind>,
    /// Per pixel, whether it is judged smooth; empty while none is.
    smooth: Vec<bool>,
}

/// A band of a [`PixelClasses`]' pixels, written by one thread ([`PixelClasses::bands_mut`]).
pub(super) struct BandMut<'a> {
    boxes: &'a mut [BoxOf],
    kinds: &'a mut [Kind],
}

impl BandMut<'_> {
    /// The band's pixel `i` in a box of class `class`, on its top or left edge where
    /// `edge`.
    pub(super) fn set(&mut self, i: usize, class: BoxClass, edge: bool) {
        self.boxes[i] = Some((class, edge));
        self.kinds[i] = Kind::of(Some(&class));
    }
}

impl PixelClasses {
    /// `n` pixels, each with `class` (none judged smooth).
    pub(super) fn filled(n: usize, class: BoxOf) -> Self {
        Self {
            boxes: buffers::filled(n, class),
            kinds: buffers::filled(n, Kind::of(class.as_ref().map(|(c, _)| c))),
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

    /// The kind of pixel `p`'s class.
    #[inline]
    pub(super) fn kind(&self, p: usize) -> Kind {
        self.kinds[p]
    }

    /// Pixel `p` in a box of class `class`, on its top or left edge where `edge`.
    pub(super) fn set(&mut self, p: usize, class: BoxClass, edge: bool) {
        BandMut {
            boxes: &mut self.boxes,
            kinds: &mut self.kinds,
        }
        .set(p, class, edge);
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

    /// The pixels in bands of `band` (the last one shorter), to write in parallel (a
    /// pixel's smoothness is left as it is).
    pub(super) fn bands_mut(
        &mut self,
        band: usize,
    ) -> impl IndexedParallelIterator<Item = BandMut<'_>> {
        self.boxes
            .par_chunks_mut(band)
            .zip(self.kinds.par_chunks_mut(band))
            .map(|(boxes, kinds)| BandMut { boxes, kinds })
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
        let kinds: Vec<Kind> = (0..4).map(|p| c.kind(p)).collect();
        assert_eq!(
            kinds,
            [
                Kind::Unclassified,
                Kind::Hit,
                Kind::Miss,
                Kind::Unclassified
            ]
        );
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

    /// Pixels written band by band read back as when set one by one.
    #[test]
    fn bands_write_classes_and_kinds() {
        let undecided = BoxClass::Undecided {
            t: Interval::new(0.5, 1.0).unwrap(),
        };
        let mut c = PixelClasses::filled(10, Some((BoxClass::Miss, false)));
        c.bands_mut(4).enumerate().for_each(|(b, mut band)| {
            if b == 1 {
                band.set(2, undecided, true);
            }
        });
        assert_eq!(c.kind(6), Kind::Undecided);
        assert!((0..10).filter(|&p| p != 6).all(|p| c.kind(p) == Kind::Miss));
        assert_eq!(c.into_boxes()[6], Some((undecided, true)));
    }
}
