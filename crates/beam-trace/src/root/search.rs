//! The pieces every interval root finder shares: counted evaluations, the depth-first
//! stack, the step budget, the width test, the sign tests at the ends of a piece and the
//! interval Newton operator.
//!
//! # Why the search finds the *first* root
//!
//! Every finder keeps the pieces of `T` still to be searched on a [`Stack`] in order: the
//! piece on top is the leftmost one, and the pieces below it follow it along the ray.
//! [`Stack::push_pair`] pushes the right piece first, so the left one is searched first.
//! A piece leaves the stack only by being rejected (`0 ∉ G(piece)`, or an empty Newton
//! image), replaced by sub-pieces that cover every root it holds, or returned as a root.
//! So when a piece is returned, everything before its lower end has been proven free of
//! roots, and when the budget runs out the undecided part is `[piece.inf(), T.sup()]`.
//!
//! # Proofs
//!
//! A sign test proves a root only where `g` is continuous, and `RayFn::g_checked` is the only
//! source of that: [`Eval::checked`] is used for the rejection test of every piece whose
//! ends may later be compared, so the continuity proof costs no extra evaluation.
//! Continuity over a piece holds on each of its sub-pieces.

use interval_core::Interval;

use super::finder::{Proof, RootCounters, RootResult, RootSettings};
use crate::ibox::{ipoint, ival};
use crate::ray::RayFn;

/// A [`RayFn`] with the evaluations it does counted in [`RootCounters`].
pub(crate) struct Eval<'a> {
    g: &'a mut dyn RayFn,
    /// The counters of the search.
    pub counters: &'a mut RootCounters,
}

impl<'a> Eval<'a> {
    /// Wraps `g`, counting into `counters`.
    pub fn new(g: &'a mut dyn RayFn, counters: &'a mut RootCounters) -> Self {
        Self { g, counters }
    }

    /// `G(x)`.
    #[inline]
    pub fn g(&mut self, x: Interval<f64>) -> Interval<f64> {
        self.counters.g_evals += 1;
        self.g.g(x)
    }

    /// `G(x)` and whether `g` is proven continuous over `x`.
    #[inline]
    pub fn checked(&mut self, x: Interval<f64>) -> (Interval<f64>, bool) {
        self.counters.g_evals += 1;
        self.g.g_checked(x)
    }

    /// Whether `g` is proven continuous over `x`: by its form where it is continuous
    /// everywhere ([`RayFn::continuous_everywhere`], no evaluation), else by a checked
    /// evaluation ([`checked`](Self::checked)).
    #[inline]
    pub fn continuous(&mut self, x: Interval<f64>) -> bool {
        self.g.continuous_everywhere() || self.checked(x).1
    }

    /// `G([t, t])`: an enclosure of the value at one parameter, rounded outward.
    #[inline]
    pub fn at(&mut self, t: f64) -> Interval<f64> {
        self.counters.g_evals += 1;
        self.g.g(ipoint(t))
    }

    /// `G(x)` on each side of the one domain boundary `x` may cross ([`RayFn::g_sides`]).
    #[inline]
    pub fn sides(&mut self, x: Interval<f64>) -> Option<(Interval<f64>, Interval<f64>)> {
        self.counters.g_evals += 2;
        self.g.g_sides(x)
    }

    /// `x` narrowed by the contractor of `g` ([`RayFn::contract`]); counted as two
    /// evaluations of `g` (its forward and backward passes).
    #[inline]
    pub fn contract(&mut self, x: Interval<f64>) -> Option<Interval<f64>> {
        self.counters.g_evals += 2;
        self.g.contract(x)
    }

    /// `(G(x), G'(x))`.
    #[inline]
    pub fn g_dg(&mut self, x: Interval<f64>) -> (Interval<f64>, Interval<f64>) {
        self.counters.dg_evals += 1;
        self.g.g_dg(x)
    }

    /// The point value `g(t)`, rounded to nearest (baselines only).
    #[inline]
    pub fn point(&mut self, t: f64) -> f64 {
        self.counters.point_evals += 1;
        self.g.g_point(t)
    }

    /// Splits `x` at its midpoint, counting one bisection.
    #[inline]
    pub fn bisect(&mut self, x: Interval<f64>) -> (Interval<f64>, Interval<f64>) {
        self.counters.bisections += 1;
        x.bisect()
    }
}

/// The prologue every search over `t` shares: an empty `t` holds no root (`None`: the
/// search answers [`RootResult::NoRoot`] without evaluating anything); otherwise the counted
/// evaluations of `g` and the step budget of the search.
#[inline]
pub(crate) fn begin<'a>(
    g: &'a mut dyn RayFn,
    t: Interval<f64>,
    settings: &RootSettings,
    counters: &'a mut RootCounters,
) -> Option<(Eval<'a>, Budget)> {
    if t.is_empty() {
        return None;
    }
    Some((Eval::new(g, counters), Budget::new(settings, t)))
}

/// The pieces of `T` still to be searched, leftmost on top (see the module documentation).
/// An explicit stack: no finder recurses.
pub(crate) struct Stack<I> {
    items: Vec<I>,
}

impl<I> Stack<I> {
    /// A stack holding `first`.
    pub fn new(first: I) -> Self {
        let mut items = Vec::with_capacity(64);
        items.push(first);
        Self { items }
    }

    /// The leftmost piece.
    #[inline]
    pub fn pop(&mut self) -> Option<I> {
        self.items.pop()
    }

    /// Puts back one piece, to be searched next.
    #[inline]
    pub fn push(&mut self, item: I) {
        self.items.push(item);
    }

    /// Puts back two adjacent pieces so that `left` is searched before `right`.
    #[inline]
    pub fn push_pair(&mut self, left: I, right: I) {
        self.items.push(right);
        self.items.push(left);
    }

    /// Drops every piece after the current one: called when a root is proven in the current
    /// piece, so that the first root of `T` lies in it and nothing after it matters.
    #[inline]
    pub fn clear(&mut self) {
        self.items.clear();
    }
}

/// The budget of subdivision steps ([`RootSettings::max_steps`]) of one search.
pub(crate) struct Budget {
    left: u64,
    end: f64,
}

impl Budget {
    /// The budget of a search over `t`.
    pub fn new(settings: &RootSettings, t: Interval<f64>) -> Self {
        Self {
            left: settings.max_steps,
            end: t.sup(),
        }
    }

    /// Takes one step (a bisection or a Newton step) on the piece starting at `from`.
    /// `Some(Undecided { [from, T.sup()] })` when the budget is spent.
    #[inline]
    pub fn step(&mut self, from: f64) -> Option<RootResult> {
        if self.left == 0 {
            return Some(RootResult::Undecided {
                t: ival(from, self.end),
            });
        }
        self.left -= 1;
        None
    }
}

/// Whether `x` is a final piece: no wider than `epsilon`, or too narrow to split (its
/// midpoint is one of its ends, so floating point cannot refine it further).
#[inline]
pub(crate) fn is_small(x: Interval<f64>, epsilon: f64) -> bool {
    let m = x.mid();
    x.wid() <= epsilon || !(x.inf() < m && m < x.sup())
}

/// `0 ∈ v`: a root may lie where `v` was evaluated. False for the empty set (`g` is
/// undefined on the whole piece, so the surface does not pass there).
#[inline]
pub(crate) fn may_vanish(v: Interval<f64>) -> bool {
    v.contains(0.0)
}

/// `v` is non-empty and holds no zero: `v > 0` or `v < 0` everywhere. The test for a
/// derivative enclosure (an empty one proves nothing).
#[inline]
pub(crate) fn excludes_zero(v: Interval<f64>) -> bool {
    !v.is_empty() && (v.inf() > 0.0 || v.sup() < 0.0)
}

/// The meet test of eq. 5.6 on outer enclosures `ra`, `rb` of `g` at two parameters: `true`
/// when `ra ∧ rb ⊆ [0, 0]` as modal intervals, i.e. `max(inf) ≥ 0 ≥ min(sup)`: one is `≥ 0`
/// and the other `≤ 0` for every ray (then, for a continuous `g`, every ray has a root
/// between the two parameters). Equivalently `g(a) · g(b) ≤ 0` for every value of the two
/// enclosures; `false` if either is empty. The beams' inclusion test and the root finders'
/// sign tests both use it.
pub fn sign_change(ra: Interval<f64>, rb: Interval<f64>) -> bool {
    let (Some((a0, a1)), Some((b0, b1))) = (ra.bounds(), rb.bounds()) else {
        return false;
    };
    // The bounds of the (improper where they are disjoint) modal meet [max(a0, b0),
    // min(a1, b1)], and its inclusion in [0, 0].
    a0.max(b0) >= 0.0 && a1.min(b1) <= 0.0
}

/// `ga` and `gb` are both `> 0` or both `< 0`.
#[inline]
pub(crate) fn same_sign(ga: Interval<f64>, gb: Interval<f64>) -> bool {
    (ga.inf() > 0.0 && gb.inf() > 0.0) || (ga.sup() < 0.0 && gb.sup() < 0.0)
}

/// The sign of `v` as `1` or `-1`, or `0` when `v` may vanish (or is empty).
#[inline]
pub(crate) fn sign(v: Interval<f64>) -> i8 {
    if v.is_empty() {
        0
    } else if v.inf() > 0.0 {
        1
    } else if v.sup() < 0.0 {
        -1
    } else {
        0
    }
}

/// What the values `ga`, `gb` at the ends of a final piece prove about it, given that
/// `0 ∈ G(piece)`: `cont` is continuity over the piece, `monotone` that moreover
/// `0 ∉ G'(piece)`.
///
/// * a sign change with continuity: a root exists (unique if monotone);
/// * monotone with both ends of one sign: `g(piece)` lies between the end values, so there
///   is no root (`None`: the piece is rejected);
/// * otherwise a root is only possible ([`settle`] then rejects a piece that only crosses a
///   domain boundary).
#[inline]
fn classify(ga: Interval<f64>, gb: Interval<f64>, cont: bool, monotone: bool) -> Option<Proof> {
    if cont && sign_change(ga, gb) {
        Some(if monotone {
            Proof::Unique
        } else {
            Proof::Exists
        })
    } else if cont && monotone && same_sign(ga, gb) {
        None
    } else {
        Some(Proof::Possible)
    }
}

/// The answer for a final piece `x = [a, b]` with `0 ∈ G(x)` and end values `ga`, `gb`:
/// [`classify`], and where that leaves only a possible root, [`look_around`] for a sign
/// change just around `x`. `None` rejects `x`. `range` is the whole `T` searched.
pub(crate) fn settle(
    ev: &mut Eval<'_>,
    x: Interval<f64>,
    (ga, gb): (Interval<f64>, Interval<f64>),
    cont: bool,
    monotone: bool,
    range: Interval<f64>,
) -> Option<RootResult> {
    let proof = classify(ga, gb, cont, monotone)?;
    if proof == Proof::Possible {
        if !cont && no_root_on_either_side(ev, x) {
            return None;
        }
        if cont && mean_value_excludes_zero(ev, x) {
            return None;
        }
        if let Some(r) = look_around(ev, x, (ga, gb), range) {
            return Some(r);
        }
    }
    Some(RootResult::Root { t: x, proof })
}

/// Whether the mean-value form `G([m]) + G'(x)·(x − m)` (`m` the midpoint of `x`) excludes
/// 0, which proves `x` free of roots where `g` is continuous on `x` (the derivative
/// enclosures hold the generalised gradient at kinks and are unbounded across jumps). Where
/// large terms cancel, the natural extension of `g` over `x` is wide (the dependency between
/// the terms) while `G'` is narrow: this form then rejects the pieces before a miss that
/// the natural extension cannot.
fn mean_value_excludes_zero(ev: &mut Eval<'_>, x: Interval<f64>) -> bool {
    let m = x.mid();
    let gm = ev.at(m);
    let (_, dg) = ev.g_dg(x);
    let mv = gm + dg * (x - ipoint(m));
    !mv.is_empty() && !may_vanish(mv)
}

/// Whether `x` crosses the boundary of one formula's domain and `g` excludes 0 on both
/// sides of it ([`RayFn::g_sides`]): every parameter of `x` is on one side, so `x` holds no
/// root. The jump of `g` there (to or from an absent object) is not a surface.
pub(crate) fn no_root_on_either_side(ev: &mut Eval<'_>, x: Interval<f64>) -> bool {
    ev.sides(x)
        .is_some_and(|(inside, outside)| !may_vanish(inside) && !may_vanish(outside))
}

/// [`settle`] for a final piece whose end values are not known yet; `dg` is `G'(x)` where
/// the finder has it.
pub(crate) fn settle_piece(
    ev: &mut Eval<'_>,
    x: Interval<f64>,
    cont: bool,
    dg: Option<Interval<f64>>,
    range: Interval<f64>,
) -> Option<RootResult> {
    let ends = (ev.at(x.inf()), ev.at(x.sup()));
    settle(ev, x, ends, cont, dg.is_some_and(excludes_zero), range)
}

/// How far [`look_around`] looks: `2^LOOK_AHEAD` widths of the final piece on each side.
const LOOK_AHEAD: u32 = 10;

/// Turns a possible root into a proven one where the sign changes just around the piece.
///
/// The final piece `x = [a, b]` of a search holds 0 in `G(x)` but its end values prove no
/// sign change. Two cases lead here: the natural interval extension overestimates `g` near
/// a root, so pieces occur a few widths *before* a simple root with one strict sign at
/// both ends, where no rejection test of the piece alone can remove them; and a Newton
/// contraction can leave a piece a few ulps wide around the root, where the enclosure of
/// `g` at an end holds 0 by rounding alone.
///
/// Nothing before `a` is a root (the search order). The probe finds a strict sign at `a`
/// or at some `l = a − w·2^k ≥ T.inf()`, then the opposite strict sign at `b` or at some
/// `p = b + w·2^k ≤ T.sup()` (`w` the width of `x`). With `g` proven continuous on `[l, p]`
/// it has a root there, none before `a`, so the first root of `T` lies in `[a, p]`: returned
/// with [`Proof::Unique`] where `0 ∉ G'([a, p])`, else [`Proof::Exists`]. Its width may
/// exceed `ε`; it is proven. `None` when nothing is found.
fn look_around(
    ev: &mut Eval<'_>,
    x: Interval<f64>,
    (ga, gb): (Interval<f64>, Interval<f64>),
    range: Interval<f64>,
) -> Option<RootResult> {
    let (a, b) = (x.inf(), x.sup());
    let w = x.wid();
    if w.is_nan() || w <= 0.0 {
        return None;
    }
    let (lo, s) = if sign(ga) != 0 {
        (a, sign(ga))
    } else {
        probe(ev, w, |step| (a - step).max(range.inf()), |v| sign(v) != 0)?
    };
    let (hi, _) = if sign(gb) == -s {
        (b, -s)
    } else {
        probe(ev, w, |step| (b + step).min(range.sup()), |v| sign(v) == -s)?
    };
    let (_, cont) = ev.checked(ival(lo, hi));
    if !cont {
        return None;
    }
    let t = ival(a, hi);
    let (_, dg) = ev.g_dg(t);
    let proof = if excludes_zero(dg) {
        Proof::Unique
    } else {
        Proof::Exists
    };
    Some(RootResult::Root { t, proof })
}

/// The first parameter `at(w·2^k)`, `k ≤ LOOK_AHEAD`, where `G` is `wanted`, with the sign
/// found there; `None` when the probe leaves the range (`at` stops moving) first.
fn probe(
    ev: &mut Eval<'_>,
    w: f64,
    at: impl Fn(f64) -> f64,
    wanted: impl Fn(Interval<f64>) -> bool,
) -> Option<(f64, i8)> {
    let mut step = w;
    let mut last = f64::NAN;
    for _ in 0..=LOOK_AHEAD {
        let p = at(step);
        if p == last {
            return None;
        }
        let v = ev.at(p);
        if wanted(v) {
            return Some((p, sign(v)));
        }
        last = p;
        step *= 2.0;
    }
    None
}

/// The probe of the beams' inclusion test: for the piece
/// `x = [a, b]` and `reference`, a strictly signed enclosure of `g` at `a` or `b` (with
/// `g` of that sign at both ends), the first `p = b + w·2^k` (`w` the width of `x`,
/// `k ≤ steps`, `p ≤ end`) where `G([p])` has the opposite sign ([`sign_change`]); `[a, p]`
/// when `accept(p)` and `g` is proven continuous on it (then `g` changes sign on it),
/// `None` otherwise or when no such `p` is found. At most `steps + 2` evaluations.
pub(crate) fn sign_change_ahead(
    ev: &mut Eval<'_>,
    x: Interval<f64>,
    reference: Interval<f64>,
    end: f64,
    steps: u32,
    accept: &dyn Fn(f64) -> bool,
) -> Option<Interval<f64>> {
    let (a, b) = (x.inf(), x.sup());
    let w = x.wid();
    if w.is_nan() || w <= 0.0 || sign(reference) == 0 {
        return None;
    }
    let mut step = w;
    for _ in 0..=steps {
        let p = (b + step).min(end);
        if p <= b {
            return None;
        }
        if sign_change(reference, ev.at(p)) {
            if !accept(p) {
                return None;
            }
            let h = ival(a, p);
            let (_, cont) = ev.checked(h);
            return cont.then_some(h);
        }
        if p >= end {
            return None;
        }
        step *= 2.0;
    }
    None
}

/// One interval Newton step over `x` from its point `m`, with `gm = G([m])` and
/// `dg = G'(x)` free of zero: `N = m − gm / dg`. Returns `N ∩ x` and whether `N` lies in the
/// interior of `x`.
///
/// By the mean value theorem every root `r ∈ x` satisfies `r = m − g(m)/g'(ξ)` for some `ξ`
/// in `x`, so `r ∈ N`: an empty `N ∩ x` proves that `x` holds no root, and `N ⊂ int(x)` proves
/// exactly one (the interval Newton theorem). Both need `g` continuous and differentiable on
/// `x` (the caller passes only continuous pieces).
#[inline]
pub(crate) fn newton(
    x: Interval<f64>,
    m: f64,
    gm: Interval<f64>,
    dg: Interval<f64>,
) -> (Interval<f64>, bool) {
    let n = ipoint(m) - gm / dg;
    let inside = !n.is_empty() && n.interior(x);
    (n.intersection(x), inside)
}

/// Whether a contracted piece `p ⊆ x` has made enough progress to be searched as it is: at
/// most half as wide as `x`. Otherwise the finders bisect it, so every step at least halves
/// the width and the search ends.
#[inline]
pub(crate) fn shrunk(p: Interval<f64>, x: Interval<f64>) -> bool {
    p.wid() <= 0.5 * x.wid()
}
