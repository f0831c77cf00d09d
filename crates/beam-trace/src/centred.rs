//! Centred (mean-value) forms of a ray function over a box of points, in double-double.
//!
//! Over a beam, the natural interval extension of a formula whose large terms cancel
//! (`(x + K)² − 2K·x − K² + …`) is `4K` times the beam's width wide, in any precision: each
//! large term varies by `K·w` over the beam and the extension cannot see that they cancel.
//! More precision alone does not decide such a beam. The mean-value form
//!
//! ```text
//! f(B) ⊆ f(m) + ∇f(B)·(B − m)        (m the centre of the box B)
//! ```
//!
//! has width about `|∇f|·wid(B)` plus the rounding of `f(m)`: with `f(m)` in double-double
//! (rounding `2^-104·K²` instead of `2^-52·K²`) and the gradient in `f64` (the derivative of
//! a cancelling formula cancels additively, `2(x + K) − 2K`, so its rounding is only
//! `ulp(K)`), the enclosure is as narrow as the surface's own variation over the beam.
//!
//! The form holds where `f` is Lipschitz on `B`: it is used only where the decorated
//! evaluation over `B` proves `f` continuous there (at least `dac`), and the gradient
//! enclosures of `min`, `max` and `abs` hold Clarke's generalised gradient; an unbounded
//! slope (`√` at 0) makes the form unbounded, never wrong.

use implicit_expr::tape::cache::PruneCache;
use implicit_expr::{Choice, Evaluator, Grad, Tape};
use interval_core::{DdInterval, Interval};
use rustc_hash::FxHashMap;

use crate::ibox::IBox;

/// Slots of a ray tape (`cx cy cz t dx dy dz`): the box's points go in `c`, with `t = 0`
/// and `d = 0`, so that `g = f(c + 0·0) = f(c)`.
const RAY_SLOTS: usize = 7;

/// The slots of `t` and `d` in a ray tape, 0 in the forms.
const RAY_ZERO_SLOTS: [u32; 4] = [3, 4, 5, 6];

/// The evaluators of the centred form of one ray tape at a time. Owns its scratch space.
#[derive(Clone, Debug)]
pub struct Centred {
    value: Evaluator<Interval<f64>>,
    grad: Evaluator<Grad<Interval<f64>>>,
    centre: Evaluator<DdInterval>,
    centre64: Evaluator<Interval<f64>>,
    vars: Vec<Interval<f64>>,
    grad_vars: Vec<Grad<Interval<f64>>>,
    centre_vars: Vec<DdInterval>,
    centre64_vars: Vec<Interval<f64>>,
    /// The last gradient enclosure computed, with its box and tape: it holds over every
    /// box inside that one ([`Centred::enclose_f64_reused`]). Keeping the enclosures of
    /// the chain of pieces a search cut from one another instead (up to 16) saved no time;
    /// nor did the last 8 or 32 of any piece, which also serve the beams over parts of a
    /// part searched before (`certified:0.05`: a third of the forms without the last
    /// gradient found one, 3 % fewer fresh gradients, 4 to 9 % slower).
    last: Option<Slope>,
    /// The last value at a centre evaluated in `f64` ([`Centred::form_f64`]): a form
    /// with the reused gradient that does not decide is followed by one with the piece's
    /// own gradient at the same centre.
    last_centre: Option<(Tape, [f64; 3], Interval<f64>)>,
    /// The last ray tape given, and the same with `t` and `d` fixed at 0
    /// ([`Tape::with_zero_vars`]): the forms evaluate that one (its first operations,
    /// `c + 0·0`, folded away).
    folded: Option<(Tape, Tape)>,
    /// The last folded tape's gradient tape ([`Centred::gradient_tape`]), `None` where it
    /// is not a polynomial (the slopes then come from the gradient tape of its pruning to
    /// the box, or from the forward-mode evaluator, `grad`), and its evaluator.
    gradient: Option<(Tape, Option<Tape>)>,
    slopes: Evaluator<Interval<f64>>,
    /// Where the folded tape has `min` or `max`: its prunings to the boxes
    /// ([`Centred::pruned_gradient_tape`]), their gradient tapes, and the evaluator and
    /// choices of the traced evaluations that prune.
    prunings: PruneCache,
    pruned_gradients: FxHashMap<Tape, Option<Tape>>,
    traced: Evaluator<Interval<f64>>,
    choices: Vec<Choice>,
    /// The last box over which an interval evaluation decided every `min` and `max` of a
    /// folded tape ([`Centred::pruned_gradient_tape`]), with that tape, its pruning there
    /// and the pruning's gradient tape: over every box inside it, the folded tape's
    /// function is the pruning's.
    last_pruned: Option<Pruned>,
}

/// A folded tape pruned to a box over which every `min` and `max` of it is decided (see
/// [`Centred::pruned_gradient_tape`]).
#[derive(Clone, Debug)]
struct Pruned {
    folded: Tape,
    over: IBox,
    pruned: Tape,
    gradient: Option<Tape>,
}

impl Pruned {
    /// Whether it holds for `folded` over `b`: `folded` is its tape and `b` lies inside
    /// its box. Each `min` and `max` its evaluation decided takes one branch at every point
    /// of its box (the enclosures of the branches were apart there), so over `b` too
    /// `folded`'s function is the pruning's, and the pruning's gradient encloses its
    /// slopes: no evaluation over `b` is needed to know it. (With inclusion-isotone
    /// operations, as a polynomial's are, an evaluation over `b` would make the same
    /// choices: the bits are the same.)
    fn holds(&self, folded: &Tape, b: &[Interval<f64>]) -> bool {
        self.folded.ptr_eq(folded) && (0..3).all(|i| b[i].subset(self.over[i]))
    }
}

/// The gradient tapes of prunings kept at most ([`Centred::pruned_gradient_tape`]) before
/// they are forgotten: a pass meets a few (one per branch of its occluders' `min` and
/// `max`).
const PRUNED_GRADIENTS: usize = 64;

/// `tape`'s gradient tape ([`Tape::gradient_tape`]), marked to be compiled at its first
/// evaluation: it is evaluated at every slope of a pass.
fn compiled_gradient(tape: &Tape) -> Option<Tape> {
    let g = tape.gradient_tape()?;
    g.expect_reuse();
    Some(g)
}

/// `held` where it is `tape` (the same shared tape), else a new owner of `tape`: a tape
/// that every thread shares is cloned only when it changes, since each clone moves its
/// count of owners to this thread's cache.
fn kept(held: Option<Tape>, tape: &Tape) -> Tape {
    match held {
        Some(t) if t.ptr_eq(tape) => t,
        _ => tape.clone(),
    }
}

/// A gradient enclosure of a tape's function over a box, where the function was proven
/// continuous.
#[derive(Clone, Debug)]
struct Slope {
    tape: Tape,
    over: IBox,
    d: [Interval<f64>; 3],
}

impl Centred {
    /// Evaluators for `tape` (a ray tape without parameters; another tape may be given to
    /// each [`Centred::enclose`]).
    pub fn new(tape: &Tape) -> Self {
        Self {
            value: Evaluator::new(tape),
            grad: Evaluator::new(tape),
            centre: Evaluator::new(tape),
            centre64: Evaluator::new(tape),
            vars: vec![Interval::ZERO; RAY_SLOTS],
            grad_vars: vec![Grad::constant_value(Interval::ZERO); RAY_SLOTS],
            centre_vars: vec![DdInterval::point(0.0); RAY_SLOTS],
            centre64_vars: vec![Interval::ZERO; RAY_SLOTS],
            last: None,
            last_centre: None,
            folded: None,
            gradient: None,
            slopes: Evaluator::new(tape),
            prunings: PruneCache::new(),
            pruned_gradients: FxHashMap::default(),
            traced: Evaluator::new(tape),
            choices: Vec::new(),
            last_pruned: None,
        }
    }

    /// The gradient tape of the folded tape `folded` pruned to the box `b` (by the
    /// `min`/`max` choices of an interval evaluation over it), where every `min` and `max`
    /// is decided there and the pruned tape is a polynomial: the gradient evaluator's
    /// `min` and `max` take the decided branch's derivative, which the pruned tape's
    /// gradient is, so its enclosures are the forward-mode evaluator's over `b`. `self.vars`
    /// holds `b` in its first three slots.
    fn pruned_gradient_tape(&mut self, folded: &Tape) -> Option<Tape> {
        if folded.choice_count() == 0 {
            return None;
        }
        if let Some(p) = self
            .last_pruned
            .as_ref()
            .filter(|p| p.holds(folded, &self.vars))
        {
            return p.gradient.clone();
        }
        self.traced.set_tape(folded);
        self.traced
            .eval_traced(&self.vars, &mut self.choices)
            .ok()?;
        let pruned = self.prunings.simplify(folded, &self.choices).ok()?;
        if pruned.choice_count() > 0 {
            return None;
        }
        let gradient = match self.pruned_gradients.get(&pruned) {
            Some(g) => g.clone(),
            None => {
                if self.pruned_gradients.len() >= PRUNED_GRADIENTS {
                    self.pruned_gradients.clear();
                }
                let g = compiled_gradient(&pruned);
                self.pruned_gradients.insert(pruned.clone(), g.clone());
                g
            }
        };
        let held = self.last_pruned.take();
        self.last_pruned = Some(Pruned {
            folded: kept(held.map(|p| p.folded), folded),
            over: std::array::from_fn(|i| self.vars[i]),
            pruned,
            gradient: gradient.clone(),
        });
        gradient
    }

    /// The gradient tape of the folded tape `folded` ([`Tape::gradient_tape`]: its partial
    /// derivatives by the box's slots `cx`, `cy`, `cz` as the outputs of one tape, where it
    /// is a polynomial), kept for the last tape given. Its interval evaluation gives the
    /// forward-mode evaluator's enclosures, and runs as machine code where the platform has
    /// the code generator: the certified soft shadows spent most of their time in the
    /// forward-mode interpreter. Whether there is one depends on the tape only, so the
    /// results are the same on every platform.
    fn gradient_tape(&mut self, folded: &Tape) -> Option<Tape> {
        if let Some((t, g)) = &self.gradient
            && t.ptr_eq(folded)
        {
            return g.clone();
        }
        let g = compiled_gradient(folded);
        self.gradient = Some((folded.clone(), g.clone()));
        g
    }

    /// `tape` with the ray's `t` and `d` fixed at 0, as the forms evaluate it (kept for the
    /// last tape given).
    fn folded(&mut self, tape: &Tape) -> Tape {
        match &self.folded {
            Some((t, f)) if t.ptr_eq(tape) => f.clone(),
            _ => {
                let f = tape.with_zero_vars(&RAY_ZERO_SLOTS);
                self.folded = Some((tape.clone(), f.clone()));
                f
            }
        }
    }

    /// The centre of `b` and the gradient of `f` over it, where the mean-value form holds:
    /// `f` proven continuous on `b` (by `continuous`, already known, or by a decorated
    /// evaluation), `b` bounded and not empty, every slope defined.
    fn slope(
        &mut self,
        tape: &Tape,
        b: &IBox,
        continuous: bool,
    ) -> Option<([f64; 3], [Interval<f64>; 3])> {
        if tape.var_count() > RAY_SLOTS || !b.iter().all(|x| x.is_common_interval()) {
            return None;
        }
        let m = Self::centre(b)?;
        let folded = self.folded(tape);
        self.vars[..3].copy_from_slice(b);
        if !continuous {
            self.value.set_tape(tape);
            let (_, continuous) = self.value.eval_continuous(&self.vars).ok()?;
            if !continuous {
                return None;
            }
        }
        let gradient = match self.gradient_tape(&folded) {
            Some(g) => Some(g),
            None => self.pruned_gradient_tape(&folded),
        };
        let d = match gradient {
            Some(g) => {
                self.slopes.set_tape(&g);
                let mut d = [Interval::EMPTY; 3];
                self.slopes.eval_outputs(&self.vars, &mut d).ok()?;
                d
            }
            None => {
                self.grad.set_tape(&folded);
                for (i, (v, &x)) in self.grad_vars.iter_mut().zip(b).enumerate() {
                    *v = Grad::var(x, i);
                }
                self.grad.eval(&self.grad_vars).ok()?.d
            }
        };
        if d.iter().any(|d| d.is_empty()) {
            return None;
        }
        self.last = Some(Slope {
            tape: kept(self.last.take().map(|s| s.tape), tape),
            over: *b,
            d,
        });
        Some((m, d))
    }

    /// The centre of `b`, where it is finite.
    fn centre(b: &IBox) -> Option<[f64; 3]> {
        let m: [f64; 3] = std::array::from_fn(|i| b[i].mid());
        m.iter().all(|v| v.is_finite()).then_some(m)
    }

    /// `f(m) + slope·(b − m)` in `f64`, the centre's value included.
    fn form_f64(
        &mut self,
        tape: &Tape,
        b: &IBox,
        m: [f64; 3],
        slope: [Interval<f64>; 3],
    ) -> Option<Interval<f64>> {
        let acc = match &self.last_centre {
            Some((t, at, v)) if t.ptr_eq(tape) && *at == m => *v,
            _ => {
                let folded = self.folded(tape);
                // Where `b` lies in the box of the last pruning, its tape gives the same
                // value at the centre (each `min` and `max` decided the same way there) in
                // fewer operations.
                let short = self.last_pruned.as_ref().filter(|p| p.holds(&folded, b));
                self.centre64.set_tape(short.map_or(&folded, |p| &p.pruned));
                for (v, &c) in self.centre64_vars.iter_mut().zip(&m) {
                    *v = Interval::new_unchecked(c, c);
                }
                let v = self.centre64.eval(&self.centre64_vars).ok()?;
                let held = self.last_centre.take().map(|(t, ..)| t);
                self.last_centre = Some((kept(held, tape), m, v));
                v
            }
        };
        // In the evaluators' instruction set, as `Beam::points` (written out likewise).
        let term = |i: usize| (slope[i], b[i] - Interval::new_unchecked(m[i], m[i]));
        let [(s0, o0), (s1, o1), (s2, o2)] = [term(0), term(1), term(2)];
        let acc = interval_core::isa::dispatch(
            #[inline(always)]
            || acc + s0.mul_sign_cases(o0) + s1.mul_sign_cases(o1) + s2.mul_sign_cases(o2),
        );
        (!acc.is_empty()).then_some(acc)
    }

    /// The mean-value form of `f` over `b` in `f64` with the last gradient enclosure
    /// computed ([`enclose_f64`](Self::enclose_f64)), where it was computed for `tape` over
    /// a box holding `b`: every segment from the centre of `b` to a point of `b` lies
    /// in that box, where `f` was proven continuous and its gradient lies in the enclosure,
    /// so the form holds; it is as wide as that gradient makes it (wider than `b`'s own
    /// would), at the cost of one evaluation at the centre. `None` where no such gradient
    /// is at hand.
    pub fn enclose_f64_reused(&mut self, tape: &Tape, b: &IBox) -> Option<Interval<f64>> {
        let last = self.last.as_ref()?;
        if !last.tape.ptr_eq(tape) || !(0..3).all(|i| b[i].subset(last.over[i])) {
            return None;
        }
        let slope = last.d;
        let m = Self::centre(b)?;
        self.form_f64(tape, b, m, slope)
    }

    /// The mean-value form of `f` over `b` in `f64` throughout (the centre's value too):
    /// as [`enclose`](Self::enclose) where the terms of `f` do not cancel at a large scale
    /// (then `f64` rounding at the centre is far below the slope's term), at a few plain
    /// evaluations' cost. `continuous` says `f` is already proven continuous on `b` (by its
    /// form, or by the decorated evaluation that gave the natural enclosure); else it is
    /// checked. `None` where the form does not hold.
    pub fn enclose_f64(
        &mut self,
        tape: &Tape,
        b: &IBox,
        continuous: bool,
    ) -> Option<Interval<f64>> {
        let (m, slope) = self.slope(tape, b, continuous)?;
        self.form_f64(tape, b, m, slope)
    }

    /// An enclosure of `f` over every point of `b`, where `tape` is a ray tape of `f`
    /// (`g(c, t, d) = f(c + t·d)`, any restriction of it valid on `b`): the mean-value
    /// form with the centre's value in double-double. `None` where the form does not hold
    /// (`f` not proven continuous on `b`, `b` empty or unbounded, a slope undefined).
    pub fn enclose(&mut self, tape: &Tape, b: &IBox) -> Option<DdInterval> {
        let (m, slope) = self.slope(tape, b, false)?;
        let folded = self.folded(tape);
        self.centre.set_tape(&folded);
        for (v, &c) in self.centre_vars.iter_mut().zip(&m) {
            *v = DdInterval::point(c);
        }
        let mut acc = self.centre.eval(&self.centre_vars).ok()?;
        for i in 0..3 {
            let offset = DdInterval::from_interval(b[i]) - DdInterval::point(m[i]);
            acc = acc + DdInterval::from_interval(slope[i]) * offset;
        }
        (!acc.is_empty()).then_some(acc)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use implicit_expr::{Context, RayFunction};

    fn ray_tape(src: &str) -> Tape {
        let mut ctx = Context::new();
        let f = implicit_expr::parse::parse(&mut ctx, src, &[]).expect("parses");
        RayFunction::new(&ctx, f)
            .expect("compiles")
            .g_tape()
            .clone()
    }

    fn ibox(lo: [f64; 3], hi: [f64; 3]) -> IBox {
        std::array::from_fn(|i| Interval::new(lo[i], hi[i]).expect("ordered"))
    }

    /// A xorshift generator of numbers in `[0, 1)` from `seed`.
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The forward-mode evaluator's gradient enclosure over `b` (`grad` evaluates the
    /// folded tape).
    fn forward_mode_slopes(
        grad: &mut Evaluator<Grad<Interval<f64>>>,
        b: &IBox,
    ) -> [Interval<f64>; 3] {
        let mut vars = vec![Grad::constant_value(Interval::ZERO); RAY_SLOTS];
        for (i, &x) in b.iter().enumerate() {
            vars[i] = Grad::var(x, i);
        }
        grad.eval(&vars).expect("seven slots").d
    }

    /// The bits of an interval's ends, a zero of either sign counted as one (`x + 0` is
    /// `+0` for both zeros): to compare enclosures bit for bit.
    fn bits(x: Interval<f64>) -> (u64, u64) {
        ((x.inf() + 0.0).to_bits(), (x.sup() + 0.0).to_bits())
    }

    /// The slopes are the forward-mode evaluator's, bit for bit, whichever way they are
    /// computed: a polynomial's gradient tape, the gradient tape of a formula with `min`
    /// and `max` pruned to the box (decided there), or the evaluator itself (undecided).
    #[test]
    fn slopes_are_the_forward_mode_evaluators() {
        let formulas = [
            "(x^2 + y^2 + z^2 + 0.4275)^2 - 1.96 * (x^2 + y^2)",
            "min(x^2 + y^2 + z^2 - 0.64, max(y + 1.25, (x - 0.5)^2 - z))",
            "max(min(x*y - z, 0.3 - x), -(y^2) + 0.1*z)",
            "sqrt(x^2 + y^2 + 0.5) - z",
        ];
        let mut next = uniform(0x5eed_0f51_09e5);
        let (mut paths, mut checked) = ([0usize; 2], 0);
        for f in formulas {
            let tape = ray_tape(f);
            let mut c = Centred::new(&tape);
            let folded = tape.with_zero_vars(&RAY_ZERO_SLOTS);
            let mut grad = Evaluator::<Grad<Interval<f64>>>::new(&folded);
            for _ in 0..300 {
                let b = random_box(&mut next);
                let want = forward_mode_slopes(&mut grad, &b);
                let Some((_, got)) = c.slope(&tape, &b, true) else {
                    assert!(want.iter().any(|d| d.is_empty()), "{f} over {b:?}");
                    continue;
                };
                // Which way: a gradient tape of the whole formula or of its pruning.
                c.vars[..3].copy_from_slice(&b);
                let whole = c.gradient_tape(&folded).is_some();
                let pruned = !whole && c.pruned_gradient_tape(&folded).is_some();
                paths[0] += usize::from(whole || pruned);
                paths[1] += usize::from(!whole && !pruned);
                for (w, g) in want.iter().zip(&got) {
                    assert_eq!(
                        bits(*w),
                        bits(*g),
                        "{f} over {b:?}: {want:?} against {got:?}"
                    );
                }
                checked += 1;
            }
        }
        assert!(checked > 1000, "{checked} boxes");
        assert!(
            paths[0] > 300 && paths[1] > 10,
            "both ways are taken: {paths:?}"
        );
    }

    /// Over boxes inside one whose evaluation decided every `min` and `max`, the slopes
    /// taken from that box's pruning without evaluating again are the forward-mode
    /// evaluator's bit for bit, and the pruning's value at a box's centre is the whole
    /// formula's.
    #[test]
    fn prunings_serve_the_boxes_inside_theirs() {
        let formulas = [
            "min(x^2 + y^2 + z^2 - 0.64, max(y + 1.25, (x - 0.5)^2 - z))",
            "max(min(x*y - z, 0.3 - x), -(y^2) + 0.1*z)",
        ];
        let mut next = uniform(0x0dd_b1a5_e5ca_1ab1);
        let mut served = 0;
        for f in formulas {
            let tape = ray_tape(f);
            let mut c = Centred::new(&tape);
            // The form's own folded tape: a pruning is kept for it.
            let folded = c.folded(&tape);
            let mut grad = Evaluator::<Grad<Interval<f64>>>::new(&folded);
            let mut value = Evaluator::<Interval<f64>>::new(&folded);
            let mut short = Evaluator::<Interval<f64>>::new(&folded);
            for _ in 0..200 {
                let outer = random_box(&mut next);
                if c.slope(&tape, &outer, true).is_none() {
                    continue;
                }
                for _ in 0..4 {
                    let inner = inside(&outer, &mut next);
                    let by_pruning = c
                        .last_pruned
                        .as_ref()
                        .is_some_and(|p| p.holds(&folded, &inner));
                    let Some((m, got)) = c.slope(&tape, &inner, true) else {
                        continue;
                    };
                    let want = forward_mode_slopes(&mut grad, &inner);
                    for (w, g) in want.iter().zip(&got) {
                        assert_eq!(bits(*w), bits(*g), "{f} over {inner:?}");
                    }
                    if !by_pruning {
                        continue;
                    }
                    served += 1;
                    let p = c.last_pruned.as_ref().expect("kept");
                    short.set_tape(&p.pruned);
                    let mut centre = vec![Interval::ZERO; RAY_SLOTS];
                    for (v, &x) in centre.iter_mut().zip(&m) {
                        *v = Interval::new_unchecked(x, x);
                    }
                    let whole = value.eval(&centre).expect("evaluates");
                    let pruned = short.eval(&centre).expect("evaluates");
                    assert_eq!(bits(whole), bits(pruned), "{f} at {m:?}");
                }
                // A box reaching out of the pruning's is not served by it.
                if let Some(p) = &c.last_pruned {
                    let mut wider = p.over;
                    wider[1] = Interval::new_unchecked(wider[1].inf(), wider[1].sup() + 0.01);
                    assert!(!p.holds(&folded, &wider));
                }
            }
        }
        assert!(served > 100, "only {served} boxes served by a pruning");
    }

    /// A random box inside `outer`.
    fn inside(outer: &IBox, next: &mut impl FnMut() -> f64) -> IBox {
        std::array::from_fn(|i| {
            let (a, b) = (next(), next());
            let w = outer[i].wid();
            let (lo, hi) = (a.min(b), a.max(b));
            let lo = (outer[i].inf() + w * lo).min(outer[i].sup());
            let hi = (outer[i].inf() + w * hi).clamp(lo, outer[i].sup());
            Interval::new(lo, hi).expect("ordered")
        })
    }

    /// A random box in `[-1.2, 1.5]³` of side at most 0.3, mostly much less.
    fn random_box(next: &mut impl FnMut() -> f64) -> IBox {
        let lo: [f64; 3] = std::array::from_fn(|_| 2.4 * next() - 1.2);
        let w = 0.3 * next() * next();
        ibox(lo, lo.map(|v| v + w))
    }

    /// Asserts that `e` meets the double-double enclosure of `f`'s value (`point`
    /// evaluates its tape) at 20 random points of `b`; returns how many were checked.
    fn assert_meets_values(
        (formula, e, b): (&str, Interval<f64>, &IBox),
        point: &mut Evaluator<DdInterval>,
        next: &mut impl FnMut() -> f64,
    ) -> usize {
        for _ in 0..20 {
            let p: [f64; 3] = std::array::from_fn(|i| b[i].inf() + b[i].wid() * next());
            let mut vars = vec![DdInterval::point(0.0); RAY_SLOTS];
            for (v, &x) in vars.iter_mut().zip(&p) {
                *v = DdInterval::point(x);
            }
            let v = point.eval(&vars).expect("evaluates").to_interval();
            assert!(
                !v.intersection(e).is_empty(),
                "{formula}: f{p:?} in {v:?}, outside the form {e:?} over {b:?}"
            );
        }
        20
    }

    #[test]
    fn cancelling_sphere_is_as_narrow_as_the_plain_one() {
        let tape = ray_tape("(x + 1e11)^2 - 2e11*x - 1e22 + y^2 + z^2 - 1");
        let mut c = Centred::new(&tape);
        let b = ibox([0.5, 0.5, 0.5], [0.51, 0.51, 0.51]);
        let e = c.enclose(&tape, &b).expect("continuous").to_interval();
        // The plain sphere over the box: [-0.25, -0.2197]; the form is a little wider.
        assert!(e.inf() <= -0.25 + 1e-9 && e.sup() >= 0.51 * 0.51 * 3.0 - 1.0 - 1e-9);
        assert!(e.wid() < 0.1, "{e:?}");
        assert!(e.sup() < 0.0, "the box is inside the sphere: {e:?}");
    }

    #[test]
    fn encloses_sampled_values() {
        let tape = ray_tape("min(x*y - z, sqrt(x^2 + y^2) - 0.5) + sin(3*z)");
        let plain = {
            let mut ctx = Context::new();
            let f = implicit_expr::parse::parse(
                &mut ctx,
                "min(x*y - z, sqrt(x^2 + y^2) - 0.5) + sin(3*z)",
                &[],
            )
            .expect("parses");
            Tape::new(&ctx, &[f]).expect("compiles")
        };
        let mut ev = Evaluator::<f64>::new(&plain);
        let mut c = Centred::new(&tape);
        let b = ibox([-0.3, 0.1, -0.2], [0.4, 0.35, 0.1]);
        let e = c.enclose(&tape, &b).expect("continuous").to_interval();
        for i in 0..=10 {
            for j in 0..=10 {
                for k in 0..=10 {
                    let p = [
                        b[0].inf() + b[0].wid() * f64::from(i) / 10.0,
                        b[1].inf() + b[1].wid() * f64::from(j) / 10.0,
                        b[2].inf() + b[2].wid() * f64::from(k) / 10.0,
                    ];
                    let v = ev.eval(&p).expect("evaluates");
                    assert!(e.contains(v), "{v} outside {e:?} at {p:?}");
                }
            }
        }
    }

    /// Over random boxes of every catalog surface without parameters and of the cancelling
    /// formulas, the form meets the double-double enclosure of the value at every sampled
    /// point (both hold the true value, so an enclosure that missed it would show as two
    /// disjoint intervals somewhere).
    #[test]
    fn meets_the_value_at_sampled_points() {
        let mut formulas: Vec<String> = implicit_expr::catalog::all()
            .iter()
            .filter(|s| s.params.is_empty())
            .map(|s| s.formula.to_string())
            .collect();
        formulas.push("(x + 1e6)^2 - 2e6*x - 1e12 + y^2 + z^2 - 1".into());
        formulas.push("(x + 1e11)*(x - 1e11) + 1e22 + y^2 + z^2 - 1".into());
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        let mut checked = 0;
        for formula in &formulas {
            let tape = ray_tape(formula);
            let mut c = Centred::new(&tape);
            let mut point = Evaluator::<DdInterval>::new(&tape);
            for _ in 0..40 {
                let b = random_box(&mut next);
                let Some(e) = c.enclose(&tape, &b) else {
                    continue;
                };
                checked +=
                    assert_meets_values((formula, e.to_interval(), &b), &mut point, &mut next);
            }
        }
        assert!(checked > 1000, "only {checked} points checked");
    }

    /// Every catalog surface without parameters, and the soft-shadow scene's torus.
    fn surfaces_and_torus() -> Vec<String> {
        implicit_expr::catalog::all()
            .iter()
            .filter(|s| s.params.is_empty())
            .map(|s| s.formula.to_string())
            .chain(["(x^2 + y^2 + z^2 + 0.4275)^2 - 1.96 * (x^2 + y^2)".to_string()])
            .collect()
    }

    /// The `f64` form over random boxes of every catalog surface without parameters holds
    /// the value at every sampled point (a double-double enclosure of it meets the form),
    /// with continuity checked or taken from the tape's form alike.
    #[test]
    fn f64_form_meets_the_value_at_sampled_points() {
        let formulas = surfaces_and_torus();
        let mut next = uniform(0x2545_f491_4f6c_dd1d);
        let (mut checked, mut narrower) = (0, 0);
        for formula in &formulas {
            let tape = ray_tape(formula);
            let by_form = tape.is_continuous_everywhere();
            let mut c = Centred::new(&tape);
            let mut natural = Evaluator::<Interval<f64>>::new(&tape);
            let mut point = Evaluator::<DdInterval>::new(&tape);
            for k in 0..40 {
                let b = random_box(&mut next);
                let Some(e) = c.enclose_f64(&tape, &b, by_form && k % 2 == 0) else {
                    continue;
                };
                let mut vars = vec![Interval::ZERO; RAY_SLOTS];
                vars[..3].copy_from_slice(&b);
                let n = natural.eval(&vars).expect("evaluates");
                narrower += usize::from(e.wid() < n.wid());
                checked += assert_meets_values((formula, e, &b), &mut point, &mut next);
            }
        }
        assert!(checked > 1000, "only {checked} points checked");
        assert!(
            narrower > 0,
            "the form was never narrower than the natural enclosure"
        );
    }

    /// The form with the gradient of an enclosing box holds the value at sampled points of
    /// random boxes inside it, is at least as wide as the box's own form, and is refused
    /// for boxes not inside that box or of another tape.
    #[test]
    fn reused_form_meets_the_value_inside_the_gradients_box() {
        let formulas = surfaces_and_torus();
        let other = ray_tape("x - y");
        let mut next = uniform(0x5851_f42d_4c95_7f2d);
        let (mut checked, mut refused) = (0, 0);
        for formula in &formulas {
            let tape = ray_tape(formula);
            let mut c = Centred::new(&tape);
            let mut point = Evaluator::<DdInterval>::new(&tape);
            for _ in 0..20 {
                let outer = random_box(&mut next);
                if c.enclose_f64(&tape, &outer, false).is_none() {
                    continue;
                }
                for _ in 0..4 {
                    let inner = inside(&outer, &mut next);
                    let e = c
                        .enclose_f64_reused(&tape, &inner)
                        .expect("a box inside the gradient's box");
                    let own = Centred::new(&tape)
                        .enclose_f64(&tape, &inner, false)
                        .expect("continuous on a box inside");
                    assert!(
                        e.inf() <= own.inf() && e.sup() >= own.sup(),
                        "{formula}: the reused form {e:?} is narrower than the box's own {own:?}"
                    );
                    checked += assert_meets_values((formula, e, &inner), &mut point, &mut next);
                }
                let shifted: IBox = std::array::from_fn(|i| {
                    let d = outer[i].wid() + 0.01;
                    outer[i] + Interval::new_unchecked(d, d)
                });
                refused += usize::from(c.enclose_f64_reused(&tape, &shifted).is_none());
                assert!(c.enclose_f64_reused(&other, &outer).is_none());
            }
        }
        assert!(checked > 1000, "only {checked} points checked");
        assert!(refused > 0);
    }

    #[test]
    fn no_form_across_a_jump() {
        let tape = ray_tape("floor(4*x) - y");
        let mut c = Centred::new(&tape);
        let across = ibox([0.2, 0.0, 0.0], [0.3, 0.1, 0.1]);
        assert!(c.enclose(&tape, &across).is_none());
        let within = ibox([0.3, 0.0, 0.0], [0.4, 0.1, 0.1]);
        assert!(c.enclose(&tape, &within).is_some());
        assert!(c.enclose_f64(&tape, &across, false).is_none());
        assert!(c.enclose_f64(&tape, &within, false).is_some());
    }
}
