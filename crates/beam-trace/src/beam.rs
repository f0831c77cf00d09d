//! Beam classification: the rejection test, the inclusion test and EvaluateBox
//! (thesis 5.4.2-5.4.3, Figs 5.6, 5.9 and 5.10).
//!
//! A beam is searched over its parameter ranges front to back, depth first, left half
//! first, with the enclosure `G(T)` of `g` over every ray of the beam:
//!
//! * **rejection** — `0 ∉ G(T)`: no ray of the beam meets the surface for `t ∈ T`;
//! * **inclusion** — the enclosures of `g` at the two ends of `T` have opposite signs for
//!   every ray, and `g` is proven continuous over the beam and `T`: by the intermediate
//!   value theorem every ray has a root in `T`. With everything before `T` rejected, every
//!   ray's *first* root lies in `T`, which is then tightened into `T_final`.
//!
//! The thesis states the inclusion test with the meet of *inner*-rounded values
//! `Inn(fR(X_s, Y_s, t))` at the ends of `T` (eq. 5.6). Written with the modal meet, the
//! condition `R_a ∧ R_b ⊆ [0, 0]` says that one end value is `≥ 0` and the other `≤ 0` for
//! every ray. For that to be a proof the end values must be *outer* enclosures of `g` over
//! the beam: an inner rounding may drop the very values that would contradict the sign, so
//! this implementation takes the meet of outer-rounded enclosures ([`sign_change`]), and
//! adds the continuity check the intermediate value theorem needs (a formula with a pole
//! or a step changes sign without a root).

use implicit_expr::Tape;
use interval_core::Interval;

use crate::free_ranges::covered;
use crate::ibox::{IBox, ipoint};
use crate::ray::{Beam, RayFn};
use crate::root::RootCounters;
pub use crate::root::search::sign_change;
use crate::root::search::{Eval, may_vanish, no_root_on_either_side, sign_change_ahead};

/// Where the rendered surface lives along a beam: the scene bounds, outside which rays do
/// not search. An inclusion proof must place every ray's root inside them, so its two end
/// parameters must put every ray of the beam inside the bounds (which are convex: the
/// segment between, and the root on it, is inside too).
#[derive(Copy, Clone, Debug)]
pub struct Extent<'a> {
    /// The beam.
    pub beam: &'a Beam,
    /// The bounds.
    pub bounds: &'a IBox,
}

impl Extent<'_> {
    /// Whether every ray of the beam is inside the bounds at parameter `t`.
    pub fn holds(&self, t: f64) -> bool {
        let p = self.beam.points(ipoint(t));
        p.iter().zip(self.bounds).all(|(p, b)| p.subset(*b))
    }
}

/// What EvaluateBox proved about a beam.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum BoxClass {
    /// Rejection: no ray of the beam meets the surface in the searched ranges.
    Miss,
    /// Inclusion: every ray of the beam meets the surface, and its first root lies in
    /// `t_final`.
    Hit {
        /// Enclosure of the first root of every ray of the beam (thesis `T_final`).
        t_final: Interval<f64>,
    },
    /// Neither test decided; some ray may meet the surface in `t` (the first range that
    /// could not be rejected), none before it.
    Undecided {
        /// The first parameter range not rejected.
        t: Interval<f64>,
    },
}

/// The parameters a beam lying inside a classified parent beam needs to search: every ray
/// of an Undecided parent is root-free before the parent's undecided range, and every ray
/// of a Hit parent has its first root in the parent's `T_final`. A part of a beam has a
/// subset of its rays, so the same holds for it. For an Undecided parent the window starts
/// a few widths of its undecided range earlier (still in the rejected prefix), so that `g`
/// has one strict sign at the window's start, which the inclusion test needs.
pub fn child_window(parent: Option<&BoxClass>) -> Interval<f64> {
    match parent {
        None => forward(),
        Some(BoxClass::Hit { t_final }) => *t_final,
        Some(BoxClass::Undecided { t }) => {
            let start = (t.inf() - 8.0 * t.wid()).max(0.0);
            Interval::new_unchecked(start, f64::INFINITY)
        }
        Some(BoxClass::Miss) => Interval::EMPTY,
    }
}

/// A restriction of the scene function to a beam over the parameters `t` (a tape pruned by
/// [`RayFn::restrict`], see [`RayFn::scope`]), which a beam lying inside that beam may start
/// its own restrictions from: over any `t' ⊆ t` its rays' points lie in the region the tape
/// was pruned for. Only meaningful to evaluators of the function it was pruned from. The
/// pruning holds in real arithmetic (a `min` or `max` is decided only where the enclosures
/// of its arguments are disjoint), so an evaluator of any precision may evaluate a scope
/// made in another (escalated beams hand double-double scopes to `f64` beams and rays):
/// its interval enclosures stay sound; only its rounded point values may differ in the last
/// bits from the whole function's.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamScope {
    /// The pruned tape.
    pub tape: Tape,
    /// The parameters it holds for.
    pub t: Interval<f64>,
    /// Whether it was pruned in a higher precision than the plan's (by an escalated
    /// search, or inside a scope that was): its evaluation in the plan's precision is then
    /// not the plain interval extension of the whole function, which the proofs of a block
    /// of frames rely on ([`Inherited::free`]).
    pub escalated: bool,
}

/// `[0, +∞]`: rays start at their origin.
pub fn forward() -> Interval<f64> {
    Interval::new_unchecked(0.0, f64::INFINITY)
}

/// Tolerances of the beam tests.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct BeamSettings {
    /// Width of `T` below which the subdivision stops (thesis `ε_T`).
    pub epsilon: f64,
    /// Width of `T`, relative to its start `inf T`, below which the subdivision stops too
    /// (0: only the absolute `epsilon`). Shadow beams, whose cross-section grows with `t`,
    /// stop where the piece is small against the cross-section: thinner pieces would not
    /// narrow the enclosure further.
    pub rel_epsilon: f64,
    /// Largest number of bisections per beam.
    pub max_bisections: u64,
    /// Bisection steps spent tightening `T_final` after an inclusion.
    pub refine_steps: u32,
    /// A search that ends undecided because rounding, not the beam's width, keeps `g`
    /// open (on the beam's central ray, as [`crate::root::rounding_dominates`] decides) is
    /// run again from there in the next precision ([`RayFn::escalate`]; double-double
    /// over a beam is narrowed by the centred form of [`crate::centred`]).
    pub escalate: bool,
    /// How far the inclusion test looks past a final undecided piece: up to
    /// `2^look_ahead` widths of that piece.
    pub look_ahead: u32,
}

impl Default for BeamSettings {
    fn default() -> Self {
        Self {
            epsilon: 1e-4,
            rel_epsilon: 0.0,
            max_bisections: 1024,
            refine_steps: 12,
            escalate: true,
            look_ahead: LOOK_AHEAD,
        }
    }
}

/// The rejection test (Fig. 5.6): `true` when every range of `ranges` is proven free of
/// roots for every ray of the beam, subdividing down to `settings.epsilon`.
pub fn rejection_test(
    g: &mut dyn RayFn,
    ranges: &[Interval<f64>],
    settings: &BeamSettings,
    counters: &mut RootCounters,
) -> bool {
    rejection_search(g, ranges, settings, counters) == BoxClass::Miss
}

/// The inclusion test on one range `t` (Fig. 5.9, made sound as described in the module
/// documentation): `true` when every ray of the beam has a root in `t` (`g` proven
/// continuous over `t` by its form, [`RayFn::continuous_everywhere`], or by a checked
/// evaluation).
pub fn inclusion_test(g: &mut dyn RayFn, t: Interval<f64>, counters: &mut RootCounters) -> bool {
    Eval::new(&mut *g, counters).continuous(t)
        && ends_change_sign(g, t, &mut Ends::default(), counters)
}

/// Whether `g` changes sign between the ends of `t` for every ray ([`sign_change`]). A
/// left end whose enclosure holds both signs changes sign only against a right end of
/// exactly `[0, 0]`, which is not tried.
fn ends_change_sign(
    g: &mut dyn RayFn,
    t: Interval<f64>,
    ends: &mut Ends,
    counters: &mut RootCounters,
) -> bool {
    let ra = ends.at(g, t.inf(), counters);
    if ra.inf() < 0.0 && ra.sup() > 0.0 {
        return false;
    }
    let rb = ends.at(g, t.sup(), counters);
    sign_change(ra, rb)
}

/// The enclosures of `g` at the last few ends a search's inclusion tests took. Bisection
/// gives a piece one end of its parent's and one of its sibling's, so a depth-first search
/// asks each end about twice; the second is answered from here. An enclosure made under
/// one restriction of `g` holds under every other that holds at the same parameter (they
/// are all enclosures of the same function there), so the answer is a proof either way.
#[derive(Default)]
struct Ends {
    kept: [(f64, Interval<f64>); ENDS_KEPT],
    len: usize,
    next: usize,
}

/// Ends [`Ends`] keeps.
const ENDS_KEPT: usize = 4;

impl Ends {
    /// The enclosure of `g` at `t`: kept, or evaluated and kept.
    fn at(&mut self, g: &mut dyn RayFn, t: f64, counters: &mut RootCounters) -> Interval<f64> {
        if let Some(&(_, v)) = self.kept[..self.len].iter().find(|(k, _)| *k == t) {
            return v;
        }
        let v = g.g(ipoint(t));
        counters.g_evals += 1;
        self.kept[self.next] = (t, v);
        self.next = (self.next + 1) % ENDS_KEPT;
        self.len = (self.len + 1).min(ENDS_KEPT);
        v
    }
}

/// The rejection test that also says where it failed: [`BoxClass::Miss`], or
/// [`BoxClass::Undecided`] with the first piece that could not be rejected (every ray of
/// the beam is proven root-free before it).
pub fn rejection_search(
    g: &mut dyn RayFn,
    ranges: &[Interval<f64>],
    settings: &BeamSettings,
    counters: &mut RootCounters,
) -> BoxClass {
    escalating_search(
        g,
        ranges,
        None,
        settings,
        false,
        Inherited::default(),
        None,
        counters,
    )
    .0
}

/// EvaluateBox (Fig. 5.10): the rejection and inclusion tests in one front-to-back search
/// over `ranges` (increasing, as the regular grid gives them). With an `extent`, an
/// inclusion counts only where it places every ray's root inside the extent's bounds.
pub fn evaluate_box(
    g: &mut dyn RayFn,
    ranges: &[Interval<f64>],
    extent: Option<&Extent<'_>>,
    settings: &BeamSettings,
    counters: &mut RootCounters,
) -> BoxClass {
    escalating_search(
        g,
        ranges,
        extent,
        settings,
        true,
        Inherited::default(),
        None,
        counters,
    )
    .0
}

/// [`evaluate_box`] (the rejection test alone without `inclusion`) for a beam lying inside
/// a beam whose search ended undecided on `near`: each range starts as pieces graded from
/// `near` ([`Inherited::near`]), so that the search starts at the scale where the other
/// stopped.
pub fn evaluate_box_near(
    g: &mut dyn RayFn,
    ranges: &[Interval<f64>],
    (extent, inclusion): (Option<&Extent<'_>>, bool),
    near: Interval<f64>,
    settings: &BeamSettings,
    counters: &mut RootCounters,
) -> BoxClass {
    let inherited = Inherited {
        near: Some(near),
        ..Inherited::default()
    };
    escalating_search(
        g, ranges, extent, settings, inclusion, inherited, None, counters,
    )
    .0
}

/// What a beam lying inside a classified beam starts its search from.
#[derive(Copy, Clone, Debug, Default)]
pub struct Inherited<'a> {
    /// The parent's restriction: a range inside its `t` is restricted starting from its
    /// tape rather than the whole function.
    pub scope: Option<&'a BeamScope>,
    /// The parent's undecided piece: each range starts as pieces that grow from it (its
    /// ends, then `near.sup() + w·2^k` with `w` its width) instead of the whole range, so
    /// that the search starts at the scale where the parent stopped, not from the range's
    /// length again. The pieces are cut at other points than bisection's; every proof is
    /// the same kind.
    pub near: Option<Interval<f64>>,
    /// Pieces of this beam's parameter range proven root-free by the search of a block of
    /// frames whose geometry encloses this one's, in this search's precision (sorted by
    /// lower end; see [`crate::free_ranges`]): a piece inside one of them is rejected
    /// without evaluating `g`, with the outcome the evaluation would have had.
    pub free: &'a [Interval<f64>],
}

/// [`evaluate_box`] for a beam lying inside a classified beam, starting from what it
/// `inherited` from it. Also returns a restriction for the beams and rays inside this one:
/// of a Hit, `g` restricted to the beam over `T_final`; of an Undecided beam, the
/// restriction of the range its undecided piece lies in; `None` for a Miss.
///
/// With `record`, the pieces the search (in its first precision) proves root-free by a
/// rejection test are appended to it: what a block of frames hands its frames as
/// [`Inherited::free`].
pub fn evaluate_box_within(
    g: &mut dyn RayFn,
    ranges: &[Interval<f64>],
    inherited: Inherited<'_>,
    extent: Option<&Extent<'_>>,
    settings: &BeamSettings,
    record: Option<&mut Vec<Interval<f64>>>,
    counters: &mut RootCounters,
) -> (BoxClass, Option<BeamScope>) {
    escalating_search(
        g, ranges, extent, settings, true, inherited, record, counters,
    )
}

/// [`search`], and where it ends undecided because rounding keeps `g` open (see
/// [`BeamSettings::escalate`]), the search again in the next precision from the start of
/// the undecided piece (every ray is proven root-free before it), over the rest of its
/// range and the ranges after it. Counted in `escalated` and `escalated_resolved`.
#[allow(clippy::too_many_arguments)]
fn escalating_search(
    g: &mut dyn RayFn,
    ranges: &[Interval<f64>],
    extent: Option<&Extent<'_>>,
    settings: &BeamSettings,
    inclusion: bool,
    inherited: Inherited<'_>,
    record: Option<&mut Vec<Interval<f64>>>,
    counters: &mut RootCounters,
) -> (BoxClass, Option<BeamScope>) {
    let mut enclosure = Interval::EMPTY;
    // A scope made from an escalated one is escalated too.
    let tainted = inherited.scope.is_some_and(|s| s.escalated);
    let mark = |(class, scope): (BoxClass, Option<BeamScope>), escalated: bool| {
        let scope = scope.map(|s| BeamScope {
            escalated: s.escalated || escalated,
            ..s
        });
        (class, scope)
    };
    let found = search(
        g,
        ranges,
        extent,
        settings,
        inclusion,
        inherited,
        record,
        &mut enclosure,
        counters,
    );
    if !settings.escalate {
        return mark(found, tainted);
    }
    let mut restore = None;
    let mut again = found;
    // Escalate as long as the search ends undecided and a higher precision may decide it.
    while let BoxClass::Undecided { t } = again.0 {
        let range_end = rest_end(ranges, t);
        if !g.escalation_helps(t, enclosure, range_end, settings.epsilon, counters) {
            break;
        }
        let Some(previous) = g.escalate() else {
            break;
        };
        restore.get_or_insert(previous);
        counters.escalated += 1;
        let rest: Vec<Interval<f64>> = std::iter::once(Interval::new_unchecked(t.inf(), range_end))
            .chain(ranges.iter().filter(|r| r.inf() >= range_end).copied())
            .collect();
        again = search(
            g,
            &rest,
            extent,
            settings,
            inclusion,
            Inherited::default(),
            None,
            &mut enclosure,
            counters,
        );
        if !matches!(again.0, BoxClass::Undecided { .. }) {
            counters.escalated_resolved += 1;
        }
    }
    let escalated = restore.is_some();
    if let Some(previous) = restore {
        g.restore(previous);
    }
    mark(again, tainted || escalated)
}

/// The end of the range of `ranges` (increasing) that holds the start of `t`; should none
/// hold it, the end of the last range (searching further is never wrong).
fn rest_end(ranges: &[Interval<f64>], t: Interval<f64>) -> f64 {
    let last = ranges.last().map_or(t.sup(), |r| r.sup()).max(t.sup());
    ranges
        .iter()
        .find(|r| r.inf() <= t.inf() && t.inf() <= r.sup())
        .map_or(last, |r| r.sup())
}

/// Largest number of pieces a range is cut into from [`Inherited::near`].
const GRADED_PIECES: usize = 48;

/// The pieces of `range` cut at the ends of `near` and at `near.sup() + w·2^k`, in order.
fn graded(range: Interval<f64>, near: Interval<f64>) -> Vec<Interval<f64>> {
    let w = near.wid();
    let mut cuts = vec![near.inf(), near.sup()];
    if w > 0.0 && w.is_finite() {
        let mut step = w;
        while cuts.len() < GRADED_PIECES && near.sup() + step < range.sup() {
            cuts.push(near.sup() + step);
            step *= 2.0;
        }
    }
    let mut out = Vec::with_capacity(cuts.len() + 1);
    let mut lo = range.inf();
    for c in cuts {
        if c > lo && c < range.sup() {
            out.push(Interval::new_unchecked(lo, c));
            lo = c;
        }
    }
    out.push(Interval::new_unchecked(lo, range.sup()));
    out
}

/// The front-to-back search of EvaluateBox (or of the rejection test alone, without
/// `inclusion`). Where it ends undecided, `enclosure` is set to the enclosure of `g` over
/// the undecided piece.
#[allow(clippy::too_many_arguments)]
fn search(
    g: &mut dyn RayFn,
    ranges: &[Interval<f64>],
    extent: Option<&Extent<'_>>,
    settings: &BeamSettings,
    inclusion: bool,
    inherited: Inherited<'_>,
    mut record: Option<&mut Vec<Interval<f64>>>,
    enclosure: &mut Interval<f64>,
    counters: &mut RootCounters,
) -> (BoxClass, Option<BeamScope>) {
    let Inherited {
        scope: inherited,
        near,
        free,
    } = inherited;
    let inside = |t: f64| extent.is_none_or(|e| e.holds(t));
    // Each piece carries the range it came from (its end: how far a look-ahead may go)
    // and the restriction of `g` it lies in.
    let mut stack: Vec<Piece> = Vec::new();
    for r in ranges.iter().rev() {
        let pieces = match near {
            Some(n) => graded(*r, n),
            None => vec![*r],
        };
        let first = stack.len() + pieces.len() - 1;
        stack.extend(pieces.into_iter().rev().map(|t| Piece {
            t,
            range: *r,
            within: Within::Range,
        }));
        stack[first].within = Within::Open;
    }
    let mut bisections = 0u64;
    let mut ends = Ends::default();
    // The restriction of the range being searched.
    let mut range_scope: Option<BeamScope> = None;
    while let Some(Piece { t, range, within }) = stack.pop() {
        let end = range.sup();
        let mut scope = match within {
            // The first piece of a range opens the range: every later evaluation of its
            // pieces, look-ahead and T_final lies inside it.
            Within::Open => {
                g.unrestrict();
                let mut start = None;
                if let Some(s) = inherited
                    && range.subset(s.t)
                {
                    g.set_scope(&s.tape);
                    start = Some(s.tape.clone());
                }
                let tape = match g.scope() {
                    Some(tape) if tape.len() > RESTRICT_MIN_LEN => {
                        g.restrict(range);
                        g.scope()
                    }
                    _ => start,
                };
                range_scope = tape.map(|tape| BeamScope {
                    tape,
                    t: range,
                    escalated: false,
                });
                range_scope.clone()
            }
            // Back to the range's restriction (a piece searched before this one may have
            // left `g` restricted to a part of the range that does not hold this one).
            Within::Range => {
                match &range_scope {
                    Some(r) => g.set_scope(&r.tape),
                    None => g.unrestrict(),
                }
                range_scope.clone()
            }
            Within::Piece(s) => {
                // Free when it is the restriction set already.
                g.set_scope(&s.tape);
                Some(s)
            }
        };
        if covered(free, t) {
            // The block proved it: this piece's own evaluation would reject it (nothing
            // is searched inside it, so it needs no restriction of its own).
            counters.block_proven += 1;
            continue;
        }
        if let Some(s) = &scope
            && t.wid() <= RESTRICT_AGAIN * s.t.wid()
            && s.tape.len() > RESTRICT_MIN_LEN
        {
            // Deep enough below the last restriction: prune again, for this piece and
            // everything searched inside it.
            g.restrict(t);
            scope = g.scope().map(|tape| BeamScope {
                tape,
                t,
                escalated: false,
            });
        }
        let (gt, continuous) = g.g_checked(t);
        counters.g_evals += 1;
        if !may_vanish(gt) {
            if let Some(r) = record.as_deref_mut() {
                r.push(t);
            }
            continue;
        }
        if !continuous && no_root_on_either_side(&mut Eval::new(g, counters), t) {
            continue;
        }
        if inclusion
            && continuous
            && inside(t.inf())
            && inside(t.sup())
            && ends_change_sign(g, t, &mut ends, counters)
        {
            return hit(g, t, settings, counters);
        }
        if t.wid() <= settings.epsilon.max(settings.rel_epsilon * t.inf())
            || bisections >= settings.max_bisections
        {
            // The look-ahead leaves the piece: back to the range's restriction.
            if let Some(r) = &range_scope {
                g.set_scope(&r.tape);
            }
            if inclusion
                && inside(t.inf())
                && let Some(t) = look_ahead(g, (t, end, settings), &mut ends, &inside, counters)
            {
                return hit(g, t, settings, counters);
            }
            *enclosure = gt;
            return (BoxClass::Undecided { t }, range_scope);
        }
        let (l, r) = t.bisect();
        bisections += 1;
        counters.bisections += 1;
        let within = || match &scope {
            Some(s) => Within::Piece(s.clone()),
            None => Within::Range,
        };
        stack.push(Piece {
            t: r,
            range,
            within: within(),
        });
        stack.push(Piece {
            t: l,
            range,
            within: within(),
        });
    }
    (BoxClass::Miss, None)
}

/// The answer of an inclusion on `t` (every ray has its first root in `t`, and `g` is set
/// to a restriction that holds over `t`): the class with `T_final`, and the restriction of
/// `g` to the beam over `T_final`, what the beams and rays inside this one search (for
/// functions without restrictions, none).
fn hit(
    g: &mut dyn RayFn,
    t: Interval<f64>,
    settings: &BeamSettings,
    counters: &mut RootCounters,
) -> (BoxClass, Option<BeamScope>) {
    let t_final = t_final(g, t, settings, counters);
    g.restrict(t_final);
    let scope = g.scope().map(|tape| BeamScope {
        tape,
        t: t_final,
        escalated: false,
    });
    (BoxClass::Hit { t_final }, scope)
}

/// A piece of a beam's search: its parameters, the range it belongs to, and the
/// restriction it is searched with.
struct Piece {
    t: Interval<f64>,
    range: Interval<f64>,
    within: Within,
}

/// The restriction of `g` a piece is searched with.
enum Within {
    /// The first piece of its range: restrict `g` to the range.
    Open,
    /// The range's restriction (a graded piece, or a part of a piece that had no
    /// restriction of its own).
    Range,
    /// A restriction that holds for the piece.
    Piece(BeamScope),
}

/// A piece at most this fraction of its restriction's width is restricted again: every two
/// bisections (each restriction costs about three evaluations of the tape it prunes).
const RESTRICT_AGAIN: f64 = 0.25;

/// Tapes this short are not pruned (further): a restriction costs about three evaluations
/// of the tape it prunes, which a short tape does not win back.
const RESTRICT_MIN_LEN: usize = 128;

/// How far the inclusion test's look-ahead looks by default
/// ([`BeamSettings::look_ahead`]): up to `2^LOOK_AHEAD` widths of the final piece.
const LOOK_AHEAD: u32 = 8;

/// The inclusion test across piece boundaries. Bisection cuts `T` at the same dyadic
/// points at every level, so when the roots of the beam's rays straddle such a point, no
/// piece ever holds them with a margin and the test on single pieces never succeeds; the
/// thesis's search avoids this by accumulating the meet over every evaluated end. Here the
/// final piece `[a, b]` (everything before `a` rejected, so `g(a)` usually has one strict
/// sign for all rays) is paired with ends `b' = b + w·2^k` further on (the root finders'
/// probe, [`sign_change_ahead`]): a sign change between `a` and `b'` with `g` continuous on
/// `[a, b']` proves that every ray's first root lies in `[a, b']`.
fn look_ahead(
    g: &mut dyn RayFn,
    (t, end, settings): (Interval<f64>, f64, &BeamSettings),
    ends: &mut Ends,
    inside: &dyn Fn(f64) -> bool,
    counters: &mut RootCounters,
) -> Option<Interval<f64>> {
    let ra = ends.at(g, t.inf(), counters);
    let mut ev = Eval::new(g, counters);
    sign_change_ahead(&mut ev, t, ra, end, settings.look_ahead, inside)
}

/// Tightens the range `t` of an inclusion into `T_final` (thesis Fig. 5.11): every ray has
/// no root before `t.inf()` and a sign change (so a root) before `t.sup()`. The lower end
/// moves up over parts that the rejection test removes, the upper end down to parameters
/// where the sign has already changed for every ray; each side halves its step when a move
/// fails, at most `settings.refine_steps` times and not below `settings.epsilon / 8`.
fn t_final(
    g: &mut dyn RayFn,
    t: Interval<f64>,
    settings: &BeamSettings,
    counters: &mut RootCounters,
) -> Interval<f64> {
    let (mut lo, mut hi) = (t.inf(), t.sup());
    let start = g.g(ipoint(lo));
    counters.g_evals += 1;
    let finest = settings.epsilon / 8.0;
    let mut step = 0.5 * (hi - lo);
    for _ in 0..settings.refine_steps {
        if step < finest {
            break;
        }
        let m = lo + step;
        if m <= lo {
            break;
        }
        if m >= hi {
            step *= 0.5;
            continue;
        }
        let left = g.g(Interval::new_unchecked(lo, m));
        counters.g_evals += 1;
        if !may_vanish(left) {
            // No ray has a root in [lo, m]; the sign at m is the sign at lo.
            lo = m;
        } else {
            step *= 0.5;
        }
    }
    let mut step = 0.5 * (hi - lo);
    for _ in 0..settings.refine_steps {
        if step < finest {
            break;
        }
        let m = hi - step;
        if m >= hi {
            break;
        }
        if m <= lo {
            step *= 0.5;
            continue;
        }
        let rm = g.g(ipoint(m));
        counters.g_evals += 1;
        if sign_change(start, rm) {
            // Every ray changes sign on [lo, m] (g is continuous on all of t).
            hi = m;
        } else {
            step *= 0.5;
        }
    }
    Interval::new_unchecked(lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `g(t) = t − 0.3`, or `(t − 0.3)(t − b)` with `b`, over a beam of one ray, with its
    /// interval evaluations counted.
    #[derive(Default)]
    struct Line {
        b: Option<f64>,
        calls: u32,
    }

    impl RayFn for Line {
        fn g(&mut self, t: Interval<f64>) -> Interval<f64> {
            self.calls += 1;
            let first = t - ipoint(0.3);
            match self.b {
                Some(b) => first * (t - ipoint(b)),
                None => first,
            }
        }
        fn g_dg(&mut self, t: Interval<f64>) -> (Interval<f64>, Interval<f64>) {
            (self.g(t), ipoint(1.0))
        }
        fn g_checked(&mut self, t: Interval<f64>) -> (Interval<f64>, bool) {
            (self.g(t), true)
        }
        fn g_point(&mut self, t: f64) -> f64 {
            (t - 0.3) * self.b.map_or(1.0, |b| t - b)
        }
    }

    #[test]
    fn ends_answer_a_kept_parameter_without_evaluating() {
        let (mut g, mut ends, mut c) = (Line::default(), Ends::default(), RootCounters::default());
        let a = ends.at(&mut g, 0.5, &mut c);
        assert_eq!(a, Line::default().g(ipoint(0.5)));
        assert_eq!((g.calls, c.g_evals), (1, 1));
        assert_eq!(ends.at(&mut g, 0.5, &mut c), a);
        assert_eq!((g.calls, c.g_evals), (1, 1));
        // Only the last ENDS_KEPT parameters are kept.
        for t in [0.1, 0.2, 0.3, 0.4] {
            ends.at(&mut g, t, &mut c);
        }
        assert_eq!(g.calls, 5);
        ends.at(&mut g, 0.4, &mut c);
        assert_eq!(g.calls, 5);
        ends.at(&mut g, 0.5, &mut c);
        assert_eq!((g.calls, c.g_evals), (6, 6));
    }

    #[test]
    fn a_left_end_of_both_signs_is_not_paired() {
        let (mut g, mut c) = (Line::default(), RootCounters::default());
        // g(0.2) < 0 < g(0.4): a sign change, both ends evaluated.
        assert!(ends_change_sign(
            &mut g,
            ival(0.2, 0.4),
            &mut Ends::default(),
            &mut c
        ));
        assert_eq!(g.calls, 2);
        // A left end of both signs (a wide beam's cross-section): the right end is not asked.
        let mut wide = Ends::default();
        wide.kept[0] = (0.25, ival(-0.1, 0.1));
        wide.len = 1;
        assert!(!ends_change_sign(
            &mut g,
            ival(0.25, 0.9),
            &mut wide,
            &mut c
        ));
        assert_eq!(g.calls, 2);
    }

    #[test]
    fn the_search_asks_each_shared_end_once() {
        // g = (t − 0.3)(t − 0.9) on [0, 1]: positive at both ends, so the range is halved;
        // [0, 0.5] changes sign. Evaluations: [0, 1], g(0), g(1), [0, 0.5], g(0.5) (g(0)
        // is kept), and T_final's start: 6, where asking every end afresh takes 7.
        let settings = BeamSettings {
            epsilon: 1e-3,
            refine_steps: 0,
            escalate: false,
            ..BeamSettings::default()
        };
        let mut g = Line {
            b: Some(0.9),
            calls: 0,
        };
        let mut c = RootCounters::default();
        let class = evaluate_box(&mut g, &[ival(0.0, 1.0)], None, &settings, &mut c);
        assert_eq!(
            class,
            BoxClass::Hit {
                t_final: ival(0.0, 0.5)
            }
        );
        assert_eq!((g.calls, c.g_evals), (6, 6));
    }

    fn ival(a: f64, b: f64) -> Interval<f64> {
        Interval::new_unchecked(a, b)
    }
}
