//! San Juan-Estrada et al.'s MRF and MRFro (thesis 4.3.3): interval bisection with
//! conditions on the values of `g` at the ends and the midpoint of each piece.
//!
//! # MRF
//!
//! For a piece `[t1, t2]` with midpoint `tm`, if `sup(G([t1]) · G([tm])) ≤ 0` then
//! `g(t1) · g(tm) ≤ 0`, and where `g` is continuous on the piece a root lies in
//! `[t1, tm]`. For a **first**-root search this means more than "`[tm, t2]` is rejected":
//! the first root of all of `T` is at most `tm`, so `[tm, t2]` and every piece after it
//! need not be searched, and the search goes on in `[t1, tm]` alone (the pending pieces are
//! dropped). The rejection test `0 ∉ G(X)` runs on every piece.
//!
//! ```text
//! pop X = [a, m, b] with G([a]) known (leftmost first)
//!   0 ∉ G(X)                           → reject X
//!   X final                            → return X (settled by its end values)
//!   g continuous on X and G([a])·G([m]) ≤ 0 → drop everything after m, search [a, m]
//!   otherwise                          → bisect, left half first
//! ```
//!
//! # MRFro
//!
//! MRFro evaluates `G` over a piece only when `G([t1]) · G([t2]) > 0`: when the product of
//! the end values is `≤ 0` a root exists in the piece, so it is bisected at once, and again
//! nothing after it need be searched.
//!
//! As published, MRFro is not sound under rounding (the thesis notes it): it takes a
//! product `≤ 0` computed in floating point as a proof that `0 ∈ G([t1, t2])`, and a sign
//! change of a discontinuous `g` as a root. Here the decision is made on outward-rounded
//! enclosures `G([t1])`, `G([t2])` (the root is proven only when the *upper bound* of their
//! product is `≤ 0`; a product whose enclosure straddles 0 falls back to evaluating
//! `G([t1, t2])`), and only where `g_checked` has proven `g` continuous on the piece or on a
//! piece containing it (continuity is inherited by sub-pieces, so it is checked once at the
//! top of the search and again only below a piece where it was not proven).
//!
//! End values are inherited too: bisecting `[a, b]` at `m` evaluates `G([m])` once for
//! both halves, so MRFro costs one degenerate evaluation per bisection, plus `G(X)` where
//! no root is proven. [`MrfroNewton`](super::mrfro_newton::MrfroNewton) adds a Newton step
//! to the same search.

use interval_core::Interval;

use super::finder::{Proof, RootCounters, RootFinder, RootResult, RootSettings};
use super::search::{
    Eval, Stack, begin, excludes_zero, is_small, may_vanish, newton, settle, shrunk, sign_change,
};
use crate::ray::RayFn;

/// MRF: interval bisection that drops everything after the midpoint once the left half
/// is proven to hold a root.
#[derive(Copy, Clone, Debug, Default)]
pub struct Mrf;

/// MRFro: interval bisection that skips the evaluation of `G` over pieces proven to hold a
/// root by the signs at their ends (made sound; see the module documentation).
#[derive(Copy, Clone, Debug, Default)]
pub struct Mrfro;

impl RootFinder for Mrf {
    fn name(&self) -> &'static str {
        "mrf"
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
        let ga = ev.at(t.inf());
        let mut stack = Stack::new((t, ga));
        while let Some((x, ga)) = stack.pop() {
            let (gx, cont) = ev.checked(x);
            if !may_vanish(gx) {
                continue;
            }
            if is_small(x, settings.epsilon) {
                let gb = ev.at(x.sup());
                match settle(&mut ev, x, (ga, gb), cont, false, t) {
                    Some(root) => return root,
                    None => continue,
                }
            }
            if let Some(undecided) = budget.step(x.inf()) {
                return undecided;
            }
            let (l, r) = ev.bisect(x);
            let gm = ev.at(l.sup());
            if cont && sign_change(ga, gm) {
                // The first root of T lies in l: nothing after it is searched.
                stack.clear();
                stack.push((l, ga));
            } else {
                stack.push_pair((l, ga), (r, gm));
            }
        }
        RootResult::NoRoot
    }
}

impl RootFinder for Mrfro {
    fn name(&self) -> &'static str {
        "mrfro"
    }

    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        mrfro_search(g, t, settings, counters, false)
    }
}

/// A piece of the MRFro search: its end values where known, whether `g` is proven
/// continuous on it, and whether it is proven to hold exactly one root (Newton variant).
#[derive(Copy, Clone, Debug)]
struct Piece {
    t: Interval<f64>,
    ga: Option<Interval<f64>>,
    gb: Option<Interval<f64>>,
    cont: bool,
    unique: bool,
}

/// The sound MRFro search; with `with_newton`, an interval Newton step on every piece
/// where `0 ∉ G'(X)` (see [`MrfroNewton`](super::mrfro_newton::MrfroNewton)).
pub(crate) fn mrfro_search(
    g: &mut dyn RayFn,
    t: Interval<f64>,
    settings: &RootSettings,
    counters: &mut RootCounters,
    with_newton: bool,
) -> RootResult {
    let Some((mut ev, mut budget)) = begin(g, t, settings, counters) else {
        return RootResult::NoRoot;
    };
    let mut stack = Stack::new(Piece {
        t,
        ga: None,
        gb: None,
        cont: false,
        unique: false,
    });
    while let Some(p) = stack.pop() {
        let x = p.t;
        let (a, b) = (x.inf(), x.sup());
        let small = is_small(x, settings.epsilon);
        if p.unique && settings.unique_settled(x) {
            return RootResult::Root {
                t: x,
                proof: Proof::Unique,
            };
        }
        let mut cont = p.cont;
        if !p.unique {
            let ga = p.ga.unwrap_or_else(|| ev.at(a));
            let gb = p.gb.unwrap_or_else(|| ev.at(b));
            let mut evaluated = false;
            let mut exists = false;
            if sign_change(ga, gb) {
                if !cont {
                    let (gx, c) = ev.checked(x);
                    if !may_vanish(gx) {
                        continue;
                    }
                    cont = c;
                    evaluated = true;
                }
                exists = cont;
            }
            if !exists && !evaluated {
                let (gx, c) = ev.checked(x);
                if !may_vanish(gx) {
                    continue;
                }
                cont |= c;
            }
            if exists {
                // The first root of T lies in X: nothing after it is searched.
                stack.clear();
            }
            if small {
                match settle(&mut ev, x, (ga, gb), cont, false, t) {
                    Some(root) => return root,
                    None => continue,
                }
            }
            if let Some(undecided) = budget.step(a) {
                return undecided;
            }
            if !with_newton {
                bisect(&mut ev, &mut stack, x, ga, gb, cont);
                continue;
            }
            let (_, dg) = ev.g_dg(x);
            if cont && excludes_zero(dg) {
                let m = x.mid();
                let gm = ev.at(m);
                let (n, inside) = newton(x, m, gm, dg);
                if n.is_empty() {
                    continue;
                }
                // A root exists in X and g is monotone there, or N ⊂ int(X): one root, in N.
                let unique = inside || exists;
                newton_piece(&mut ev, &mut stack, n, x, Some((ga, gb)), cont, unique);
            } else {
                bisect(&mut ev, &mut stack, x, ga, gb, cont);
            }
            continue;
        }
        // A piece with exactly one root (Newton variant only): Newton until final.
        if let Some(undecided) = budget.step(a) {
            return undecided;
        }
        let (_, dg) = ev.g_dg(x);
        if excludes_zero(dg) {
            let m = x.mid();
            let gm = ev.at(m);
            let (n, _) = newton(x, m, gm, dg);
            if !n.is_empty() {
                newton_piece(&mut ev, &mut stack, n, x, None, cont, true);
                continue;
            }
        }
        // Not possible for a sound g (G' over a sub-piece excludes 0 as over the piece that
        // proved it unique, and the root lies in N); search the piece afresh.
        let (l, r) = ev.bisect(x);
        stack.push_pair(open(l, cont), open(r, cont));
    }
    RootResult::NoRoot
}

/// A piece with nothing known but (maybe) continuity.
fn open(t: Interval<f64>, cont: bool) -> Piece {
    Piece {
        t,
        ga: None,
        gb: None,
        cont,
        unique: false,
    }
}

/// Bisects `[a, b]` onto the stack, left half first, evaluating `G([m])` once for both.
fn bisect(
    ev: &mut Eval<'_>,
    stack: &mut Stack<Piece>,
    x: Interval<f64>,
    ga: Interval<f64>,
    gb: Interval<f64>,
    cont: bool,
) {
    let (l, r) = ev.bisect(x);
    let gm = ev.at(l.sup());
    let half = |t, ga, gb| Piece {
        t,
        ga: Some(ga),
        gb: Some(gb),
        cont,
        unique: false,
    };
    stack.push_pair(half(l, ga, gm), half(r, gm, gb));
}

/// Pushes the Newton image `n ⊆ x` (or its halves when it did not at least halve `x`),
/// reusing the end values of `x` where an end did not move. A unique piece drops every
/// pending piece: the first root lies in it.
fn newton_piece(
    ev: &mut Eval<'_>,
    stack: &mut Stack<Piece>,
    n: Interval<f64>,
    x: Interval<f64>,
    ends: Option<(Interval<f64>, Interval<f64>)>,
    cont: bool,
    unique: bool,
) {
    if unique {
        stack.clear();
    }
    let ga = ends.filter(|_| n.inf() == x.inf()).map(|e| e.0);
    let gb = ends.filter(|_| n.sup() == x.sup()).map(|e| e.1);
    if shrunk(n, x) {
        stack.push(Piece {
            t: n,
            ga,
            gb,
            cont,
            unique,
        });
    } else {
        let (l, r) = ev.bisect(n);
        let gm = ev.at(l.sup());
        let half = |t: Interval<f64>, ga, gb| Piece {
            t,
            ga,
            gb,
            cont,
            unique: false,
        };
        stack.push_pair(half(l, ga, Some(gm)), half(r, Some(gm), gb));
    }
}
