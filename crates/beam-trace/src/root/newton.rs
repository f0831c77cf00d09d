//! Interval Newton (thesis 4.3.3, Fig. 4.7).
//!
//! ```text
//! pop X (leftmost first)
//!   0 ∉ G(X)                       → reject X
//!   X final (width ≤ ε)            → return X (settled by its end values and G'(X))
//!   0 ∉ G'(X), g continuous on X:  N = (m − G([m]) / G'(X)) ∩ X,  m = mid(X)
//!       N = ∅                      → no root in X
//!       N ⊂ interior(X)            → exactly one root, in N (searched on as Unique)
//!       continue with N (bisected first if it is not at most half as wide as X)
//!   otherwise                      → bisect X, left half first
//! ```
//!
//! A piece known to hold exactly one root skips the rejection test (it cannot fail) and
//! is returned as [`Proof::Unique`] once final. The Newton operator rests on the mean value
//! theorem, so it is applied only where `g_checked` proved `g` continuous; elsewhere the
//! piece is bisected. [`NewtonAlefeldHansen`](super::alefeld_hansen::NewtonAlefeldHansen)
//! runs the same search with the extended-division step added.

use interval_core::Interval;

use super::finder::{Proof, RootCounters, RootFinder, RootResult, RootSettings};
use super::search::{
    Eval, Stack, begin, excludes_zero, is_small, may_vanish, newton, settle_piece, shrunk,
};
use crate::ibox::ipoint;
use crate::ray::RayFn;

/// Interval Newton with bisection where `0 ∈ G'(X)`.
#[derive(Copy, Clone, Debug, Default)]
pub struct Newton;

impl RootFinder for Newton {
    fn name(&self) -> &'static str {
        "newton"
    }

    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        newton_search(g, t, settings, counters, Variant::default())
    }
}

/// What a [`newton_search`] adds to the plain interval Newton search.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct Variant {
    /// The Alefeld–Hansen extended-division step where `0 ∈ G'(X)`.
    pub extended: bool,
    /// A contraction of every piece that may hold a root ([`RayFn::contract`]) before its
    /// Newton step.
    pub contract: bool,
}

/// A piece of the search: `unique` when it is proven to hold exactly one root, with `g`
/// continuous and `0 ∉ G'` on it.
#[derive(Copy, Clone, Debug)]
struct Piece {
    t: Interval<f64>,
    unique: bool,
}

impl Piece {
    fn open(t: Interval<f64>) -> Self {
        Self { t, unique: false }
    }
}

/// The interval Newton search; with `variant.extended`, the Alefeld–Hansen step where
/// `0 ∈ G'(X)` and `0 ∉ G([m])` (see [`NewtonAlefeldHansen`](super::alefeld_hansen::NewtonAlefeldHansen));
/// with `variant.contract`, each piece that may hold a root contracted first (see
/// [`NewtonHc4`](super::newton_hc4::NewtonHc4)).
pub(crate) fn newton_search(
    g: &mut dyn RayFn,
    t: Interval<f64>,
    settings: &RootSettings,
    counters: &mut RootCounters,
    variant: Variant,
) -> RootResult {
    let extended = variant.extended;
    let Some((mut ev, mut budget)) = begin(g, t, settings, counters) else {
        return RootResult::NoRoot;
    };
    let mut stack = Stack::new(Piece::open(t));
    while let Some(p) = stack.pop() {
        let x = p.t;
        if p.unique && settings.unique_settled(x) {
            return RootResult::Root {
                t: x,
                proof: Proof::Unique,
            };
        }
        let cont = if p.unique {
            true
        } else {
            let (gx, cont) = ev.checked(x);
            if !may_vanish(gx) {
                continue;
            }
            cont
        };
        let (_, dg) = ev.g_dg(x);
        if is_small(x, settings.epsilon) {
            match settle_piece(&mut ev, x, cont, Some(dg), t) {
                Some(root) => return root,
                None => continue,
            }
        }
        if let Some(undecided) = budget.step(x.inf()) {
            return undecided;
        }
        if cont && excludes_zero(dg) {
            let m = x.mid();
            let gm = ev.at(m);
            let (n, inside) = newton(x, m, gm, dg);
            if n.is_empty() {
                continue;
            }
            push_reduced(&mut ev, &mut stack, n, x, p.unique || inside);
        } else if extended && cont {
            let m = x.mid();
            let gm = ev.at(m);
            if may_vanish(gm) {
                bisect(&mut ev, &mut stack, x);
                continue;
            }
            // Every root r of X satisfies g'(ξ)·(m − r) = g(m): m − r lies in the extended
            // quotient G([m]) / G'(X), one or two pieces. m − (second piece) lies left of
            // m − (first piece), so the second is searched first.
            let (q1, q2) = dg.mul_rev_to_pair(gm);
            let right = (ipoint(m) - q1).intersection(x);
            let left = (ipoint(m) - q2).intersection(x);
            if !right.is_empty() {
                push_reduced(&mut ev, &mut stack, right, x, false);
            }
            if !left.is_empty() {
                push_reduced(&mut ev, &mut stack, left, x, false);
            }
        } else if variant.contract {
            // Where Newton cannot narrow, the contractor may: what it leaves is searched
            // (bisected unless it is at most half as wide).
            if let Some(c) = ev.contract(x) {
                push_reduced(&mut ev, &mut stack, c, x, false);
            }
        } else {
            bisect(&mut ev, &mut stack, x);
        }
    }
    RootResult::NoRoot
}

/// Bisects `x` onto the stack, left half first.
fn bisect(ev: &mut Eval<'_>, stack: &mut Stack<Piece>, x: Interval<f64>) {
    let (l, r) = ev.bisect(x);
    stack.push_pair(Piece::open(l), Piece::open(r));
}

/// Pushes the contracted piece `n ⊆ x`, or its halves when it is not at most half as wide
/// as `x` (so that every step at least halves the width searched). A unique piece stays
/// unique only while it is whole.
fn push_reduced(
    ev: &mut Eval<'_>,
    stack: &mut Stack<Piece>,
    n: Interval<f64>,
    x: Interval<f64>,
    unique: bool,
) {
    if shrunk(n, x) {
        stack.push(Piece { t: n, unique });
    } else {
        bisect(ev, stack, n);
    }
}
