//! A pixel's screen box class as a render's output gives it ([`PixelBox`]), and the kinds
//! of class it is kept as ([`Kind`]).

use interval_core::Interval;

use crate::beam::BoxClass;

/// A pixel's screen box class and whether it lies on its box's top or left edge (the
/// classification image's outlines), as a render's output gives them ([`BoxMap::get`](super::box_map::BoxMap::get)):
/// the class's kind, its range and the edge in 24 bytes, where an
/// `Option<(BoxClass, bool)>` takes 32.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct PixelBox {
    /// The class's range (`T_final` of a Hit, `t` of an Undecided box); zero otherwise.
    pub(super) t: Interval<f64>,
    pub(super) kind: Kind,
    pub(super) edge: bool,
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
