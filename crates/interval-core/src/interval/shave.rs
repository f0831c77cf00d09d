//! Shaving: the ends of a valid enclosure of a preimage `{z ∈ x : f(z) ∈ c}` moved inward,
//! one float at a time, past the gaps between neighbouring floats that the forward function
//! proves to lie outside (`f([z, z⁺]) ∩ c = ∅` for the end `z` and its neighbour `z⁺`: every
//! real number between them, not only the floats, is proven not to belong, so the result
//! stays valid). An end stops at the first gap that may hold a point of the preimage. The
//! forward function runs in double-double ([`DdInterval`], errors near `2^-80`), so a gap
//! is kept only when its image comes within that of `c`: the ends land on the tight ones
//! unless `f` is flat there (an extremum of `sin`), where no fixed number of ulps is
//! promised. The reverse
//! operations whose inverse-function formula is a few ulps loose (`sin_rev`, `cos_rev`,
//! `tan_rev`, `pow_rev1`, `pow_rev2`) finish with it.

use super::Interval;
use crate::dd::{Dd, DdInterval};
use crate::float::Float;

/// At most this many floats are shaved off each end.
const MAX_STEPS: usize = 16;

/// `r` with each finite end moved inward past the gaps `[z, z⁺]` (neighbouring floats) where
/// `outside` proves that no point belongs, at most [`MAX_STEPS`] per end; the empty set when
/// the whole of `r` is proven outside.
pub(super) fn shave<T: Float>(
    r: Interval<T>,
    outside: impl Fn(Interval<T>) -> bool,
) -> Interval<T> {
    let Some((mut lo, mut hi)) = r.bounds() else {
        return r;
    };
    let gap = |a: T, b: T| Interval::new_unchecked(a, b);
    if lo.is_finite() {
        for _ in 0..MAX_STEPS {
            if lo == hi {
                // The last point: removed only if it is proven outside itself.
                return if outside(gap(lo, lo)) {
                    Interval::EMPTY
                } else {
                    gap(lo, hi)
                };
            }
            let next = lo.next_up();
            if !outside(gap(lo, next)) {
                break;
            }
            lo = next;
        }
    }
    if hi.is_finite() {
        for _ in 0..MAX_STEPS {
            if hi == lo {
                return if outside(gap(lo, lo)) {
                    Interval::EMPTY
                } else {
                    gap(lo, hi)
                };
            }
            let prev = hi.next_down();
            if !outside(gap(prev, hi)) {
                break;
            }
            hi = prev;
        }
    }
    gap(lo, hi)
}

/// The gap `[a, b]` of `T`s as a double-double interval (exact).
pub(super) fn dd_of<T: Float>(z: Interval<T>) -> DdInterval {
    DdInterval::from_interval(z.cast::<f64>())
}

/// Whether the double-double enclosure `y` of an image misses `c` (compared exactly).
pub(super) fn misses<T: Float>(y: DdInterval, c: Interval<T>) -> bool {
    match (y.bounds(), c.bounds()) {
        (None, _) | (_, None) => true,
        (Some((lo, hi)), Some((clo, chi))) => {
            hi < Dd::from_f64(clo.to_f64()) || lo > Dd::from_f64(chi.to_f64())
        }
    }
}
