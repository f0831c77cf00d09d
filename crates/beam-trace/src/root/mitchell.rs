//! Mitchell's root finder (thesis 4.3.2, Fig. 4.6), kept reliable in every step.
//!
//! ```text
//! pop X = [a, b] (leftmost first)
//!   0 ∉ G(X)                        → reject X
//!   0 ∉ G'(X), g continuous on X:   (g is strictly monotone on X)
//!       G(a), G(b) of one sign      → reject X (g(X) lies between g(a) and g(b))
//!       G(a), G(b) of opposite sign → exactly one root in X: refine it, return it (Unique)
//!   X final (width ≤ ε)             → return X (settled by its end values, as in bisection)
//!   otherwise                       → bisect X, left half first
//! ```
//!
//! Mitchell refined the isolated root with point bisection or point Newton; here the
//! refinement stays reliable. Since the root `r` is unique and `g` monotone, the sign of
//! `g` left of `r` is the sign at `a`; each step evaluates the degenerate interval `G([m])`
//! at the midpoint `m` of the current piece and keeps the half whose ends still have
//! opposite signs. When `G([m])` holds 0 (the midpoint is within rounding of the root) one
//! interval Newton step `m − G([m]) / G'(X)` encloses the root in a piece a few ulps wide.
//! The signs at the ends come from outward-rounded enclosures and continuity from
//! `g_checked`, so the returned piece provably holds the root.

use interval_core::Interval;

use super::finder::{Proof, RootCounters, RootFinder, RootResult, RootSettings};
use super::search::{
    Budget, Eval, Stack, begin, excludes_zero, is_small, may_vanish, newton, same_sign, settle,
    sign, sign_change,
};
use crate::ibox::{ipoint, ival};
use crate::ray::RayFn;

/// Mitchell's method: rejection by `G`, isolation by `0 ∉ G'` and a sign change, then
/// reliable refinement of the isolated root.
#[derive(Copy, Clone, Debug, Default)]
pub struct Mitchell;

impl RootFinder for Mitchell {
    fn name(&self) -> &'static str {
        "mitchell"
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
            let (gx, cont) = ev.checked(x);
            if !may_vanish(gx) {
                continue;
            }
            let (_, dg) = ev.g_dg(x);
            let monotone = cont && excludes_zero(dg);
            let small = is_small(x, settings.epsilon);
            if monotone || small {
                let (a, b) = (x.inf(), x.sup());
                let (ga, gb) = (ev.at(a), ev.at(b));
                if monotone && sign_change(ga, gb) {
                    return refine(&mut ev, x, ga, gb, dg, settings, &mut budget);
                }
                if monotone && same_sign(ga, gb) {
                    continue;
                }
                if small {
                    match settle(&mut ev, x, (ga, gb), cont, monotone, t) {
                        Some(root) => return root,
                        None => continue,
                    }
                }
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

/// Refines the unique root of `x`, where `g` is continuous and strictly monotone
/// (`dg = G'(x)` excludes 0) and `ga · gb ≤ 0` at the ends. Returns it with
/// [`Proof::Unique`], narrowed to width `ε` unless the budget runs out first (the piece
/// reached is still a proven enclosure).
fn refine(
    ev: &mut Eval<'_>,
    x: Interval<f64>,
    ga: Interval<f64>,
    gb: Interval<f64>,
    dg: Interval<f64>,
    settings: &RootSettings,
    budget: &mut Budget,
) -> RootResult {
    let unique = |t| RootResult::Root {
        t,
        proof: Proof::Unique,
    };
    // A zero end value: the root is that end.
    if ga == ipoint(0.0) {
        return unique(ipoint(x.inf()));
    }
    if gb == ipoint(0.0) {
        return unique(ipoint(x.sup()));
    }
    // The sign of `g` left of the root: `g` increases when `g(a) ≤ 0 ≤ g(b)`.
    let left: i8 = if ga.sup() <= 0.0 && gb.inf() >= 0.0 {
        -1
    } else {
        1
    };
    let mut x = x;
    loop {
        if settings.unique_settled(x) || budget.step(x.inf()).is_some() {
            return unique(x);
        }
        let m = x.mid();
        let gm = ev.at(m);
        let s = sign(gm);
        if s == left {
            ev.counters.bisections += 1;
            x = ival(m, x.sup());
        } else if s == -left {
            ev.counters.bisections += 1;
            x = ival(x.inf(), m);
        } else {
            let (n, _) = newton(x, m, gm, dg);
            if n.is_empty() || n.wid() >= x.wid() {
                return unique(x);
            }
            x = n;
        }
    }
}
