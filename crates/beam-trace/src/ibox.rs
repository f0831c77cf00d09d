//! Interval boxes: [`IBox`], one interval per axis, and the small constructors of
//! intervals and boxes that rays, beams, root finders and shadows share.

use glam::DVec3;
use interval_core::Interval;

/// A box in space: one interval per axis.
pub type IBox = [Interval<f64>; 3];

/// The degenerate interval `[x, x]` (`x` finite).
#[inline]
pub fn ipoint(x: f64) -> Interval<f64> {
    Interval::new_unchecked(x, x)
}

/// `[lo, hi]` (the caller guarantees `lo <= hi`, both not NaN).
#[inline]
pub fn ival(lo: f64, hi: f64) -> Interval<f64> {
    debug_assert!(lo <= hi, "[{lo}, {hi}]");
    Interval::new_unchecked(lo, hi)
}

/// A box of one point.
pub fn point_box(p: DVec3) -> IBox {
    [ipoint(p.x), ipoint(p.y), ipoint(p.z)]
}

/// Whether the boxes `a` and `b` share no point (on some axis their intervals are
/// disjoint).
pub fn disjoint(a: &IBox, b: &IBox) -> bool {
    (0..3).any(|k| a[k].disjoint(b[k]))
}

/// The length of the box's diagonal.
pub fn diagonal(b: &IBox) -> f64 {
    b.iter().map(|i| i.wid() * i.wid()).sum::<f64>().sqrt()
}

/// The smallest box holding `a` and `b`.
pub fn hull(a: &IBox, b: &IBox) -> IBox {
    std::array::from_fn(|k| a[k].convex_hull(b[k]))
}
