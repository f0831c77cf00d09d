//! What the first primary pass proves of each pixel: its screen box's (or first cell's)
//! class and scope, kept once per box ([`BoxMap`]: the form the render's output holds),
//! and the pixels whose shading was judged smooth.

use interval_core::Interval;
use rayon::prelude::*;

pub(super) use super::box_map::BandMut;
use super::box_map::{BoxId, BoxMap};
use super::pixel_box::Kind;
use super::pixel_box::PixelBox;
use crate::beam::{BeamScope, BoxClass};
use crate::error::Error;

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

/// What the first primary pass proved of each pixel of a window: the pixel's box (its
/// class and edge, in the [`BoxMap`] the output keeps), the backend's scope of the box,
/// and whether the pixel was judged smooth.
///
/// Class and scope are kept once per box (a first cell of the octree, a screen box), and a
/// pixel holds only its box's index: 4 bytes a pixel where its class, its kind and its
/// scope's index took 29.
#[derive(Clone, Debug)]
pub(super) struct PixelClasses {
    map: BoxMap,
    /// Box `b`'s scope is `scopes[scope_of[b]]`, none where that is [`NO_SCOPE`].
    scope_of: Vec<u32>,
    /// The scopes of the boxes.
    scopes: Vec<BeamScope>,
    /// Per pixel, whether it is judged smooth; empty while none is.
    smooth: Vec<bool>,
}

/// The index of a box's scope where it has none.
const NO_SCOPE: u32 = u32::MAX;

impl PixelClasses {
    /// `n` pixels, each in one box of class `class` without a scope (none judged smooth).
    pub(super) fn filled(n: usize, class: Option<BoxClass>) -> Self {
        Self {
            map: BoxMap::filled(n, PixelBox::from(class.map(|c| (c, false)))),
            scope_of: vec![NO_SCOPE],
            scopes: Vec::new(),
            smooth: Vec::new(),
        }
    }

    /// The number of pixels.
    pub(super) fn len(&self) -> usize {
        self.map.len()
    }

    /// Keeps a box of class `class` with the backend's scope `scope` and returns its index
    /// (for [`PixelClasses::assign`] and [`BandMut::assign`]).
    ///
    /// # Errors
    ///
    /// [`Error::Setting`] where the window has more boxes than a map keeps
    /// ([`MAX_BOXES`](super::box_map::MAX_BOXES), 2³¹).
    pub(super) fn add_box(
        &mut self,
        class: BoxClass,
        scope: Option<BeamScope>,
    ) -> Result<BoxId, Error> {
        let id = self
            .map
            .add(PixelBox::new(class, false))
            .ok_or_else(|| Error::Setting {
                name: "camera".into(),
                message: "more than 2^31 boxes in one window: render the image in smaller \
                          windows"
                    .into(),
            })?;
        self.scope_of.push(match scope {
            Some(s) => {
                self.scopes.push(s);
                // Fewer scopes than boxes.
                (self.scopes.len() - 1) as u32
            }
            None => NO_SCOPE,
        });
        Ok(id)
    }

    /// Puts pixel `p` in box `id`, on its top or left edge where `edge`.
    pub(super) fn assign(&mut self, p: usize, id: BoxId, edge: bool) {
        self.map.assign(p, id, edge);
    }

    /// What is proven of pixel `p` (`None`: no box classified it).
    #[inline]
    pub(super) fn get(&self, p: usize) -> Option<BoxPixel> {
        self.map.box_of(p).class().map(|class| BoxPixel {
            class,
            smooth: self.smooth.get(p).copied().unwrap_or(false),
        })
    }

    /// The kind of pixel `p`'s class.
    #[inline]
    pub(super) fn kind(&self, p: usize) -> Kind {
        self.map.box_of(p).kind
    }

    /// The kind of pixel `p`'s class and its range (`T_final` of a Hit, `t` of an
    /// Undecided box, zero otherwise), from one look-up of its box.
    #[inline]
    pub(super) fn kind_and_range(&self, p: usize) -> (Kind, Interval<f64>) {
        let b = self.map.box_of(p);
        (b.kind, b.t)
    }

    /// The backend's scope of pixel `p`'s box.
    #[inline]
    pub(super) fn scope(&self, p: usize) -> Option<&BeamScope> {
        match self.scope_of[self.map.id(p) as usize] {
            NO_SCOPE => None,
            k => Some(&self.scopes[k as usize]),
        }
    }

    /// Marks pixel `p` smooth, where a box classified it.
    pub(super) fn mark_smooth(&mut self, p: usize) {
        if self.kind(p) == Kind::Unclassified {
            return;
        }
        if self.smooth.is_empty() {
            self.smooth = vec![false; self.len()];
        }
        self.smooth[p] = true;
    }

    /// The pixels in bands of `band` (the last one shorter), to put in their boxes in
    /// parallel (a pixel's smoothness is left as it is).
    pub(super) fn bands_mut(
        &mut self,
        band: usize,
    ) -> impl IndexedParallelIterator<Item = BandMut<'_>> {
        self.map.bands_mut(band)
    }

    /// The classes as the render's output keeps them.
    pub(super) fn into_map(self) -> BoxMap {
        self.map
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use implicit_expr::{Context, Tape};

    fn scope(t: f64) -> BeamScope {
        let mut ctx = Context::new();
        let x = ctx.x();
        BeamScope {
            tape: Tape::new(&ctx, &[x]).unwrap(),
            t: Interval::new(t, t + 1.0).unwrap(),
            escalated: false,
        }
    }

    /// A pixel reads back the class and scope of its box (and the output its edge), and is
    /// smooth only once marked; a pixel no box classified cannot be marked.
    #[test]
    fn pixels_keep_their_box_edge_and_smoothness() {
        let hit = BoxClass::Hit {
            t_final: Interval::new(1.0, 2.0).unwrap(),
        };
        let mut c = PixelClasses::filled(5, None);
        let h = c.add_box(hit, Some(scope(1.0))).unwrap();
        let m = c.add_box(BoxClass::Miss, None).unwrap();
        c.assign(1, h, true);
        c.assign(4, h, false);
        c.assign(2, m, false);
        assert!(c.get(0).is_none());
        let kinds: Vec<Kind> = (0..5).map(|p| c.kind(p)).collect();
        assert_eq!(
            kinds,
            [
                Kind::Unclassified,
                Kind::Hit,
                Kind::Miss,
                Kind::Unclassified,
                Kind::Hit
            ]
        );
        let scopes: Vec<Option<f64>> = (0..5).map(|p| c.scope(p).map(|s| s.t.inf())).collect();
        assert_eq!(scopes, [None, Some(1.0), None, None, Some(1.0)]);
        let p = c.get(1).unwrap();
        assert!(!p.smooth && p.class == hit);
        c.mark_smooth(1);
        c.mark_smooth(0);
        assert!(c.get(1).unwrap().smooth);
        assert!(!c.get(4).unwrap().smooth);
        assert!(!c.get(2).unwrap().smooth);
        assert!(c.get(0).is_none());
        assert_eq!(c.len(), 5);
        let map = c.into_map();
        assert_eq!(map.get(1).get(), Some((hit, true)));
        assert_eq!(map.get(4).get(), Some((hit, false)));
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

    /// Pixels put in their boxes band by band read back as when put one by one.
    #[test]
    fn bands_put_pixels_in_their_boxes() {
        let undecided = BoxClass::Undecided {
            t: Interval::new(0.5, 1.0).unwrap(),
        };
        let mut c = PixelClasses::filled(10, Some(BoxClass::Miss));
        let u = c.add_box(undecided, Some(scope(0.5))).unwrap();
        c.bands_mut(4).enumerate().for_each(|(b, mut band)| {
            if b == 1 {
                band.assign(2, u, true);
            }
        });
        assert_eq!(c.kind(6), Kind::Undecided);
        assert_eq!(c.scope(6).map(|s| s.t.inf()), Some(0.5));
        assert!((0..10).filter(|&p| p != 6).all(|p| c.kind(p) == Kind::Miss));
        assert!((0..10).filter(|&p| p != 6).all(|p| c.scope(p).is_none()));
        assert_eq!(c.into_map().get(6).get(), Some((undecided, true)));
    }
}
