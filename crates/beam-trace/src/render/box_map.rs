//! Each pixel's screen box (or first cell) and its class, kept once per box: a pixel holds
//! the index of its box and whether it lies on the box's top or left edge, in 4 bytes.
//!
//! A render's class of every pixel was 24 bytes a pixel of fresh memory (a [`PixelBox`]
//! each), and the pixels of a box (up to 8 × 8 pixels of a block of the octree, whole
//! tiles of the screen boxes) all held the same one. The memory a render writes afresh is
//! what it pays for in page faults and zeroing before anything is written: on `csg3d-2k`
//! at 1024 × 1024, 24 MiB more of it took 10 % longer (`docs/expr-benchmarks.md`).

use rayon::prelude::*;

use super::pixel_box::PixelBox;

/// Every pixel's [`PixelBox`] of an image or window (row-major), each box's class kept
/// once: pixel `p` holds the index of its box and its edge flag.
#[derive(Clone, Debug, Default)]
pub struct BoxMap {
    /// The boxes' classes (each with `edge` false).
    boxes: Vec<PixelBox>,
    /// Pixel `p`'s box is `boxes[of[p] >> 1]`; it lies on the box's top or left edge where
    /// `of[p] & 1` is 1.
    of: Vec<u32>,
}

/// The index of a box of a [`BoxMap`].
pub(super) type BoxId = u32;

/// The most boxes a map holds: a pixel keeps its box's index and its edge flag in 32 bits.
pub(super) const MAX_BOXES: usize = 1 << 31;

impl BoxMap {
    /// `n` pixels, each in a box of class `class` (its edge flag cleared).
    pub(super) fn filled(n: usize, class: PixelBox) -> Self {
        Self {
            boxes: vec![PixelBox {
                edge: false,
                ..class
            }],
            of: super::buffers::filled(n, 0),
        }
    }

    /// The number of pixels.
    pub fn len(&self) -> usize {
        self.of.len()
    }

    /// Whether the map holds no pixel.
    pub fn is_empty(&self) -> bool {
        self.of.is_empty()
    }

    /// The number of boxes kept (at most one per pixel, often far fewer).
    pub fn box_count(&self) -> usize {
        self.boxes.len()
    }

    /// Pixel `p`'s box and edge flag.
    ///
    /// # Panics
    ///
    /// Where `p` is not a pixel of the map (`p >= len()`), as a slice's index does.
    #[inline]
    pub fn get(&self, p: usize) -> PixelBox {
        let i = self.of[p];
        PixelBox {
            edge: i & 1 != 0,
            ..self.boxes[(i >> 1) as usize]
        }
    }

    /// Pixel `p`'s box, without its edge flag.
    #[inline]
    pub(super) fn box_of(&self, p: usize) -> &PixelBox {
        &self.boxes[(self.of[p] >> 1) as usize]
    }

    /// Pixel `p`'s box index.
    #[inline]
    pub(super) fn id(&self, p: usize) -> BoxId {
        self.of[p] >> 1
    }

    /// Every pixel's box and edge flag, in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = PixelBox> + '_ {
        (0..self.len()).map(|p| self.get(p))
    }

    /// Every pixel's box and edge flag, in order, in parallel.
    pub fn par_iter(&self) -> impl IndexedParallelIterator<Item = PixelBox> + '_ {
        (0..self.len()).into_par_iter().map(|p| self.get(p))
    }

    /// Keeps a box of class `class` (its edge flag ignored) and returns its index, or
    /// `None` where the map holds [`MAX_BOXES`] already.
    pub(super) fn add(&mut self, class: PixelBox) -> Option<BoxId> {
        if self.boxes.len() >= MAX_BOXES {
            return None;
        }
        self.boxes.push(PixelBox {
            edge: false,
            ..class
        });
        Some((self.boxes.len() - 1) as BoxId)
    }

    /// Puts pixel `p` in box `id`, on its top or left edge where `edge`.
    #[inline]
    pub(super) fn assign(&mut self, p: usize, id: BoxId, edge: bool) {
        self.of[p] = pixel_entry(id, edge);
    }

    /// The pixels' entries in bands of `band` (the last one shorter), to write in parallel
    /// with [`BandMut::assign`].
    pub(super) fn bands_mut(
        &mut self,
        band: usize,
    ) -> impl IndexedParallelIterator<Item = BandMut<'_>> {
        self.of.par_chunks_mut(band).map(|of| BandMut { of })
    }

    /// Keeps every box of `other` and returns the index the first takes here: pixel `k` of
    /// `other` is then put here by [`BoxMap::copy_pixel`].
    pub(super) fn add_all(&mut self, other: &BoxMap) -> Option<BoxId> {
        if self.boxes.len() + other.boxes.len() > MAX_BOXES {
            return None;
        }
        let base = self.boxes.len() as BoxId;
        self.boxes.extend_from_slice(&other.boxes);
        Some(base)
    }

    /// Puts pixel `p` in the box that pixel `k` of `other` is in, `other`'s boxes kept from
    /// index `base` on ([`BoxMap::add_all`]), with its edge flag.
    #[inline]
    pub(super) fn copy_pixel(&mut self, p: usize, other: &BoxMap, k: usize, base: BoxId) {
        let i = other.of[k];
        self.of[p] = pixel_entry(base + (i >> 1), i & 1 != 0);
    }
}

/// A pixel's entry: its box's index and its edge flag.
#[inline]
fn pixel_entry(id: BoxId, edge: bool) -> u32 {
    (id << 1) | u32::from(edge)
}

/// A band of a [`BoxMap`]'s pixels, written by one thread ([`BoxMap::bands_mut`]).
pub(super) struct BandMut<'a> {
    of: &'a mut [u32],
}

impl BandMut<'_> {
    /// Puts the band's pixel `i` in box `id`, on its top or left edge where `edge`.
    #[inline]
    pub(super) fn assign(&mut self, i: usize, id: BoxId, edge: bool) {
        self.of[i] = pixel_entry(id, edge);
    }
}

/// Pixel by pixel, the same boxes and edge flags (however the boxes are kept).
impl PartialEq for BoxMap {
    fn eq(&self, other: &Self) -> bool {
        self.len() == other.len() && self.iter().eq(other.iter())
    }
}

impl BoxMap {
    /// The map of `pixels` in order, consecutive pixels with the same class in one box;
    /// `None` where that is more than the 2³¹ boxes a map keeps (more than 2³¹ pixels, none
    /// next to one of the same class).
    pub fn try_from_pixels(pixels: impl IntoIterator<Item = PixelBox>) -> Option<Self> {
        let pixels = pixels.into_iter();
        let mut map = BoxMap {
            boxes: Vec::new(),
            of: Vec::with_capacity(pixels.size_hint().0),
        };
        for b in pixels {
            let class = PixelBox { edge: false, ..b };
            let id = match map.boxes.last() {
                Some(last) if *last == class => (map.boxes.len() - 1) as BoxId,
                _ => map.add(class)?,
            };
            map.of.push(pixel_entry(id, b.edge));
        }
        Some(map)
    }
}

/// The pixels in order ([`BoxMap::try_from_pixels`]).
///
/// # Panics
///
/// Where more than the 2³¹ boxes a map keeps would be kept.
impl FromIterator<PixelBox> for BoxMap {
    fn from_iter<I: IntoIterator<Item = PixelBox>>(pixels: I) -> Self {
        Self::try_from_pixels(pixels)
            .expect("more boxes than a map keeps (2^31 pixels of no common class)")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::BoxClass;
    use interval_core::Interval;

    fn hit(a: f64) -> BoxClass {
        BoxClass::Hit {
            t_final: Interval::new(a, a + 1.0).unwrap(),
        }
    }

    /// Pixels read back the class and edge they were given, boxes shared or not.
    #[test]
    fn pixels_read_back_their_box_and_edge() {
        let mut m = BoxMap::filled(6, PixelBox::new(BoxClass::Miss, true));
        assert_eq!(m.get(0), PixelBox::new(BoxClass::Miss, false));
        let a = m.add(PixelBox::new(hit(1.0), true)).unwrap();
        let b = m.add(PixelBox::new(hit(2.0), false)).unwrap();
        m.assign(1, a, true);
        m.assign(2, a, false);
        m.assign(3, b, true);
        m.bands_mut(4).enumerate().for_each(|(k, mut band)| {
            if k == 1 {
                band.assign(1, b, false);
            }
        });
        let got: Vec<PixelBox> = m.iter().collect();
        assert_eq!(
            got,
            [
                PixelBox::new(BoxClass::Miss, false),
                PixelBox::new(hit(1.0), true),
                PixelBox::new(hit(1.0), false),
                PixelBox::new(hit(2.0), true),
                PixelBox::new(BoxClass::Miss, false),
                PixelBox::new(hit(2.0), false),
            ]
        );
        assert_eq!(m.par_iter().collect::<Vec<_>>(), got);
        assert_eq!((m.len(), m.box_count()), (6, 3));
        assert_eq!(m.id(5), b);
        assert_eq!(*m.box_of(3), PixelBox::new(hit(2.0), false));
    }

    /// A map made from its pixels equals the map, with consecutive pixels of one class in
    /// one box; maps of the same pixels are equal however their boxes are kept.
    #[test]
    fn from_pixels_shares_runs_and_compares_by_pixel() {
        let pixels = [
            PixelBox::NONE,
            PixelBox::new(hit(1.0), true),
            PixelBox::new(hit(1.0), false),
            PixelBox::new(BoxClass::Miss, false),
            PixelBox::new(hit(1.0), false),
        ];
        let m: BoxMap = pixels.iter().copied().collect();
        assert_eq!(m.iter().collect::<Vec<_>>(), pixels);
        assert_eq!(m.box_count(), 4);
        let mut n = BoxMap::filled(5, PixelBox::NONE);
        let h = n.add(PixelBox::new(hit(1.0), false)).unwrap();
        let miss = n.add(PixelBox::new(BoxClass::Miss, false)).unwrap();
        for (p, id, edge) in [(1, h, true), (2, h, false), (3, miss, false), (4, h, false)] {
            n.assign(p, id, edge);
        }
        assert_eq!(m, n);
        n.assign(4, miss, false);
        assert_ne!(m, n);
        assert_ne!(m, BoxMap::filled(4, PixelBox::NONE));
    }

    /// Pixels copied from another map keep their boxes and edges.
    #[test]
    fn pixels_copied_from_another_map_keep_their_boxes() {
        let a: BoxMap = [PixelBox::new(hit(3.0), true), PixelBox::NONE]
            .into_iter()
            .collect();
        let mut m = BoxMap::filled(3, PixelBox::new(BoxClass::Miss, false));
        let base = m.add_all(&a).unwrap();
        m.copy_pixel(2, &a, 0, base);
        m.copy_pixel(0, &a, 1, base);
        assert_eq!(
            m.iter().collect::<Vec<_>>(),
            [
                PixelBox::NONE,
                PixelBox::new(BoxClass::Miss, false),
                PixelBox::new(hit(3.0), true)
            ]
        );
    }
}
