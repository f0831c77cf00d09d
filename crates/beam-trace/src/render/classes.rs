//! What the first primary pass proves of each pixel: its screen box's (or first cell's)
//! class, kept in the form the render's output holds, the kind of each class in a byte,
//! and the pixels whose shading was judged smooth.

use interval_core::Interval;
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

/// A pixel's screen box class and whether it lies on its box's top or left edge (the
/// classification image's outlines), as a render's output keeps them: the class's kind, its
/// range and the edge in 24 bytes, where an `Option<(BoxClass, bool)>` takes 32. At
/// 1024 × 1024 that is 24 MiB of fresh memory a render instead of 32, under the 32 MiB
/// above which the C library's allocator maps every allocation afresh.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct PixelBox {
    /// The class's range (`T_final` of a Hit, `t` of an Undecided box); zero otherwise.
    t: Interval<f64>,
    kind: Kind,
    edge: bool,
}

impl PixelBox {
    /// A pixel that no box classified.
    pub const NONE: PixelBox = PixelBox {
        t: Interval::ZERO,
        kind: Kind::Unclassified,
        edge: false,
    };

    /// A pixel in a box of class `class`, on the box's top or left edge where `edge`.
    pub fn new(class: BoxClass, edge: bool) -> PixelBox {
        let (kind, t) = match class {
            BoxClass::Miss => (Kind::Miss, Interval::ZERO),
            BoxClass::Hit { t_final } => (Kind::Hit, t_final),
            BoxClass::Undecided { t } => (Kind::Undecided, t),
        };
        PixelBox { t, kind, edge }
    }

    /// The class and whether the pixel lies on its box's top or left edge (`None`: no box
    /// classified the pixel).
    pub fn get(&self) -> Option<(BoxClass, bool)> {
        let class = match self.kind {
            Kind::Unclassified => return None,
            Kind::Miss => BoxClass::Miss,
            Kind::Hit => BoxClass::Hit { t_final: self.t },
            Kind::Undecided => BoxClass::Undecided { t: self.t },
        };
        Some((class, self.edge))
    }

    /// The class (`None`: no box classified the pixel).
    pub fn class(&self) -> Option<BoxClass> {
        self.get().map(|(class, _)| class)
    }
}

impl From<Option<(BoxClass, bool)>> for PixelBox {
    fn from(class: Option<(BoxClass, bool)>) -> PixelBox {
        class.map_or(PixelBox::NONE, |(class, edge)| PixelBox::new(class, edge))
    }
}

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
    boxes: Vec<PixelBox>,
    kinds: Vec<Kind>,
    /// Per pixel, whether it is judged smooth; empty while none is.
    smooth: Vec<bool>,
}

/// A band of a [`PixelClasses`]' pixels, written by one thread ([`PixelClasses::bands_mut`]).
pub(super) struct BandMut<'a> {
    boxes: &'a mut [PixelBox],
    kinds: &'a mut [Kind],
}

impl BandMut<'_> {
    /// The band's pixel `i` in a box of class `class`, on its top or left edge where
    /// `edge`.
    pub(super) fn set(&mut self, i: usize, class: BoxClass, edge: bool) {
        let b = PixelBox::new(class, edge);
        self.boxes[i] = b;
        self.kinds[i] = b.kind;
    }
}

impl PixelClasses {
    /// `n` pixels, each with `class` (none judged smooth).
    pub(super) fn filled(n: usize, class: Option<(BoxClass, bool)>) -> Self {
        let b = PixelBox::from(class);
        Self {
            boxes: buffers::filled(n, b),
            kinds: buffers::filled(n, b.kind),
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
        self.boxes[p].class().map(|class| BoxPixel {
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
        if self.kinds[p] == Kind::Unclassified {
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
    pub(super) fn into_boxes(self) -> Vec<PixelBox> {
        self.boxes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert_eq!(c.into_boxes()[1].get(), Some((hit, true)));
    }

    /// A pixel's box reads back as it was made, in 24 bytes.
    #[test]
    fn pixel_boxes_keep_class_and_edge() {
        assert_eq!(size_of::<PixelBox>(), 24);
        let t = Interval::new(0.25, 0.5).unwrap();
        for class in [
            None,
            Some((BoxClass::Miss, true)),
            Some((BoxClass::Hit { t_final: t }, false)),
            Some((BoxClass::Undecided { t }, true)),
        ] {
            let b = PixelBox::from(class);
            assert_eq!(b.get(), class);
            assert_eq!(b.class(), class.map(|(c, _)| c));
        }
        assert_eq!(PixelBox::NONE.get(), None);
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
        assert_eq!(c.into_boxes()[6].get(), Some((undecided, true)));
    }
}
