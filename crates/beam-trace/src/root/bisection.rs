//! Classic interval bisection (thesis 4.3.3): the rejection test `0 ∉ G(T)` alone.
//!
//! ```text
//! search(T):  push T
//!   pop X (leftmost first)
//!   if X is final (width ≤ ε):  if 0 ∈ G(X): return X, else reject
//!   if 0 ∉ G(X): reject X
//!   else bisect X, left half first
//! ```
//!
//! A final piece is settled by the signs of `g` at its ends: a sign change of a `g` proven
//! continuous on it proves a root ([`Proof::Exists`](super::Proof::Exists)). Where both
//! ends have one sign, the piece usually lies a few widths before a simple root (the
//! interval extension overestimates `g` there); the search then looks for the sign change
//! at points `b + w·2^k` just after it (`w` its width, `k ≤ 10`), and where one is found
//! with `g` continuous it returns `[a, p]` as a proven root, wider than `ε`. Otherwise a
//! root is only possible in the piece ([`Proof::Possible`](super::Proof::Possible)).
//! Every interval method but the counter bisection settles its final pieces this way.

use interval_core::Interval;

use super::finder::{RootCounters, RootFinder, RootResult, RootSettings};
use super::search::{Stack, begin, is_small, may_vanish, settle_piece};
use crate::ray::RayFn;

/// Classic interval bisection: reject by `0 ∉ G(X)`, otherwise halve, to width `ε`.
#[derive(Copy, Clone, Debug, Default)]
pub struct Bisection;

impl RootFinder for Bisection {
    fn name(&self) -> &'static str {
        "bisection"
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
        let mut stack = Stack::new(t);
        while let Some(x) = stack.pop() {
            if is_small(x, settings.epsilon) {
                let (gx, cont) = ev.checked(x);
                if !may_vanish(gx) {
                    continue;
                }
                if let Some(root) = settle_piece(&mut ev, x, cont, None, t) {
                    return root;
                }
                continue;
            }
            if !may_vanish(ev.g(x)) {
                continue;
            }
            if let Some(undecided) = budget.step(x.inf()) {
                return undecided;
            }
            let (l, r) = ev.bisect(x);
            stack.push_pair(l, r);
        }
        RootResult::NoRoot
    }
}
