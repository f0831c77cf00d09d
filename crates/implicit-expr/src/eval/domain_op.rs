//! `domain(d, f)` over a region, written once for the interval types: `f` where the test
//! `d ≤ 0` holds on the whole region, the absent object (`+inf`) where it fails on the whole
//! region, and `f` joined with `+inf` where it takes both answers (or nothing is known of it).

use interval_core::Decoration;

/// How the domain test `d ≤ 0` answers over a region.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Side {
    /// Holds everywhere: the formula's value.
    Inside,
    /// Fails everywhere: the absent object.
    Outside,
    /// Both answers (or an empty test): the jump may lie in the region.
    Both,
}

/// An interval type with what `domain` needs of it.
pub(super) trait Region: Copy {
    /// The answer of the test `d ≤ 0` over the region.
    fn side(d: Self) -> Side;
    /// The absent object, `+inf`, as `[MAX, +inf]`.
    fn absent() -> Self;
    /// `f` joined with `+inf`: `[inf f, +inf]`, or the absent object when `f` is empty.
    fn with_absent(f: Self) -> Self;
    /// Whether the set is empty.
    fn is_empty_set(self) -> bool;
}

/// `domain(d, f)` over the region.
#[inline]
pub(super) fn value<R: Region>(d: R, f: R) -> R {
    match R::side(d) {
        Side::Inside => f,
        Side::Outside => R::absent(),
        Side::Both => R::with_absent(f),
    }
}

/// `domain(d, f)` with an undecided test resolved to one side (`Number::domain_side`):
/// the value, and whether the test was undecided.
#[inline]
pub(super) fn resolved<R: Region>(d: R, f: R, inside: bool) -> (R, bool) {
    match R::side(d) {
        Side::Both if inside && !f.is_empty_set() => (f, true),
        Side::Both => (R::absent(), true),
        _ => (value(d, f), false),
    }
}

/// The decoration of `domain(d, f)` over the region: `Com` where the test has one answer,
/// `Def` where it takes both (the object jumps to absent inside the region), `Trv` where an
/// argument is empty (undefined upstream).
#[inline]
pub(super) fn decoration<R: Region>(d: R, f: R) -> Decoration {
    if d.is_empty_set() || f.is_empty_set() {
        Decoration::Trv
    } else if R::side(d) == Side::Both {
        Decoration::Def
    } else {
        Decoration::Com
    }
}
