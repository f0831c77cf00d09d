//! Non-recursive interval bisection with two counters, as a GPU kernel runs it (the
//! beam-tracing paper's root search: `ns` subdivision level, `cs` current section).
//!
//! No stack: the state of the search is two integers. At level `ns` the piece
//! `T = [lo, hi]` is cut into `2^ns` sections; section `k` (0-based) is
//! `[end(k, ns), end(k + 1, ns)]` with
//!
//! ```text
//! end(k, ns) = E(k · 2^(60 − ns))
//! E(J)       = hi                                    if J = 2^60
//!            = min(lo + f64(J) · (f64(hi − lo) · 2^−60), hi)   otherwise
//! ```
//!
//! Every end is computed by this one function of the level-60 index `J`, so a section and
//! its two halves share their outer ends exactly, adjacent sections share their common end
//! exactly, the first end is exactly `lo` and the last exactly `hi` (`E` is non-decreasing
//! because each rounding is). The sections of a level therefore cover `T` without gaps, and
//! rejecting a section rejects exactly that part of `T`.
//!
//! The loop, starting at `ns = 0, k = 0` (the section `T` itself):
//!
//! ```text
//! loop:
//!   X = [end(k, ns), end(k + 1, ns)]
//!   if 0 ∈ G(X):
//!     if width(X) ≤ ε, or X cannot be split, or ns = 60:  return X  (a possible root)
//!     ns = ns + 1; k = 2k                          (descend into the left half)
//!   else:                                          (X rejected)
//!     if k is even: k = k + 1                      (go to the right half of the pair)
//!     else:         ns = ns − 1; k = (k + 1) / 2   (both halves rejected: the section
//!                                                   after their parent, one level up)
//!     if k ≥ 2^ns: return no root                  (past the end of T)
//! ```
//!
//! This is the paper's rule with 0-based sections (its `cs = 2·cs − 1` on descent,
//! `cs + 1` after a rejected first section, `cs/2 + 1` one level up after a rejected
//! second one, and the end test `cs > 2^ns`). The paper starts at level 1 because its cell
//! test has already evaluated `T`; starting at level 0 rejects a root-free `T` with one
//! evaluation. Sections are visited left to right, so the first section returned holds the
//! first possible root and everything before it is rejected. The final section then gets
//! the end-value test every finder applies (a sign change proves a root; with both ends of
//! one sign, a look-ahead of a few section widths for a sign change just after it), as a
//! fixed epilogue that a kernel runs as well; otherwise the answer is
//! [`Proof::Possible`](super::Proof::Possible). Descents count
//! against [`RootSettings::max_steps`], and running out gives
//! `Undecided { [end(k, ns), hi] }`.
//!
//! `k` and the level-60 index are `u64`; a 32-bit kernel keeps them in a pair of `u32` or
//! limits the levels to 31. A `T` with an infinite end cannot be cut this way: it is
//! rejected whole or left undecided.

use interval_core::Interval;

use super::finder::{RootCounters, RootFinder, RootResult, RootSettings};
use super::search::{begin, is_small, may_vanish, settle_piece};
use crate::ibox::ival;
use crate::ray::RayFn;

/// The deepest level: sections of level 60 are `2^−60` of `T`, below the resolution of
/// `f64` for any `T` whose ends are of similar size to its width.
pub const MAX_LEVEL: u32 = 60;

/// Bisection driven by the counters `ns` (level) and `k` (section), without a stack.
#[derive(Copy, Clone, Debug, Default)]
pub struct CounterBisection;

/// The end `k` of the sections of level `ns` of `[lo, hi]` (`k ≤ 2^ns`, `ns ≤ 60`, finite
/// ends): see the module documentation.
pub fn section_end(lo: f64, hi: f64, k: u64, ns: u32) -> f64 {
    debug_assert!(ns <= MAX_LEVEL && k <= 1u64 << ns);
    let j = k << (MAX_LEVEL - ns);
    if j >= 1u64 << MAX_LEVEL {
        return hi;
    }
    // 2^-60 is exact; so is scaling by it (unless hi − lo is below 2^-962).
    let step = (hi - lo) * (1.0 / (1u64 << MAX_LEVEL) as f64);
    (lo + j as f64 * step).min(hi)
}

impl RootFinder for CounterBisection {
    fn name(&self) -> &'static str {
        "counter-bisection"
    }

    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        let Some((mut ev, mut budget)) = begin(g, t, settings, counters) else {
            return RootResult::NoRoot;
        };
        if !t.is_common_interval() {
            return if may_vanish(ev.g(t)) {
                RootResult::Undecided { t }
            } else {
                RootResult::NoRoot
            };
        }
        let (lo, hi) = (t.inf(), t.sup());
        let mut ns: u32 = 0;
        let mut k: u64 = 0;
        loop {
            let a = section_end(lo, hi, k, ns);
            let b = section_end(lo, hi, k + 1, ns);
            let x = ival(a, b);
            let vanish = may_vanish(ev.g(x));
            let last = vanish && (ns == MAX_LEVEL || is_small(x, settings.epsilon));
            if last {
                // The final section: the same end-value test and look-ahead as every
                // other finder (a kernel runs it as a fixed epilogue), so that a
                // section a few widths before a simple root becomes a proven root. A
                // section it rejects (a domain boundary, no root) is passed like one
                // whose value excludes 0.
                let (_, cont) = ev.checked(x);
                if let Some(root) = settle_piece(&mut ev, x, cont, None, t) {
                    return root;
                }
            }
            if vanish && !last {
                if let Some(undecided) = budget.step(a) {
                    return undecided;
                }
                ev.counters.bisections += 1;
                ns += 1;
                k *= 2;
            } else {
                if k.is_multiple_of(2) {
                    k += 1;
                } else {
                    ns -= 1;
                    k = k.div_ceil(2);
                }
                if k >= 1u64 << ns {
                    return RootResult::NoRoot;
                }
            }
        }
    }
}
