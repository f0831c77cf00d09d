//! Restriction of a surface to a ray or a beam (thesis 4.3.2 and 5.4.1).
//!
//! For an origin `c` and a direction `D` (a point for a ray, a box of directions for a
//! beam), the root finders work on one-variable functions of the ray parameter `t`:
//!
//! * `g(t) = f(c + t·D)`,
//! * `g'(t) = ∇f(c + t·D) · D` (the derivative along the ray).
//!
//! [`RayFunction::new`] builds both once per surface, as graphs in the variables
//! `cx cy cz t dx dy dz` (then the surface's parameters), with `g'` obtained by symbolic
//! differentiation of `g` by `t` (the chain rule gives exactly `∇f · D`) and sharing its
//! nodes with `g`. A [`RayEvaluator`] then evaluates them for any number type: set the ray
//! once with [`RayEvaluator::set_ray`], call [`RayEvaluator::g`] or
//! [`RayEvaluator::g_dg`] per parameter interval. Over intervals, `c + T·D` encloses every
//! point of every ray of the beam for `t ∈ T`, so `0 ∉ g(T)` proves that no ray of the beam
//! meets the surface for `t ∈ T` (the rejection test).

use crate::context::{Context, NodeId, Var};
use crate::contractor::Contractor;
use crate::error::Error;
use crate::eval::{Evaluator, Number};
use crate::tape::Tape;
use crate::tape::cache::PruneCache;
use interval_core::Interval;

/// Names of the variable slots of a ray function, in slot order (then the surface's
/// parameters, in the surface context's order).
pub const RAY_VARS: [&str; 7] = ["cx", "cy", "cz", "t", "dx", "dy", "dz"];

/// Slot of the ray parameter `t`.
const T: Var = Var(3);

/// `g` and `g'` of a surface, compiled. See the [module documentation](self).
#[derive(Clone, Debug)]
pub struct RayFunction {
    g: Tape,
    g_dg: Tape,
    context: Context,
    roots: [NodeId; 2],
    params: Vec<String>,
    /// The HC4-revise contractor of `g` (on the graph, not the tape).
    hc4: Contractor<f64>,
}

impl RayFunction {
    /// Builds `g` and `g'` for the surface `f` of `ctx` (whose slots 3.. are parameters).
    ///
    /// Returns an error if a tape cannot be built.
    pub fn new(ctx: &Context, f: NodeId) -> Result<Self, Error> {
        let mut rc = Context::new();
        // Slots 0..3 are x, y, z in every context; here they stand for cx, cy, cz.
        let c = [rc.x(), rc.y(), rc.z()];
        let t = rc.named_var("t");
        let d = [rc.named_var("dx"), rc.named_var("dy"), rc.named_var("dz")];
        let params: Vec<String> = ctx.var_names()[3..].to_vec();
        let mut param_nodes = Vec::with_capacity(params.len());
        for p in &params {
            // Parameter names cannot clash with the ray's own: prefix them in the ray context.
            param_nodes.push(rc.named_var(&format!("param:{p}")));
        }
        let g = rc.copy_graph(ctx, f, |rc, v| match v.index() {
            i @ 0..3 => {
                let td = rc.mul(t, d[i]);
                rc.add(c[i], td)
            }
            i => param_nodes[i - 3],
        });
        let dg = rc.deriv(g, T);
        Ok(Self {
            g: Tape::new(&rc, &[g])?,
            g_dg: Tape::new(&rc, &[g, dg])?,
            hc4: Contractor::new(&rc, g),
            context: rc,
            roots: [g, dg],
            params,
        })
    }

    /// `g` and `g'` of a `g` given as a tape in the ray's variables ([`RAY_VARS`], no
    /// parameters): what [`RayEvaluator::scope`] returns after a
    /// [`restrict`](RayEvaluator::restrict), the function pruned to a region, which then
    /// gets a derivative of its own (equal to `g'` inside the region wherever `g` is
    /// differentiable there, and often much shorter).
    ///
    /// Returns an error when the tape uses more variable slots than a ray has, or a tape
    /// cannot be built.
    pub fn from_ray_tape(tape: &Tape) -> Result<Self, Error> {
        if tape.var_count() > RAY_VARS.len() {
            return Err(Error::Unsupported(format!(
                "a ray tape has {} variable slots, this one {}",
                RAY_VARS.len(),
                tape.var_count()
            )));
        }
        let (mut rc, roots) = tape.to_context(&RAY_VARS)?;
        // Every slot of the ray exists in the context, also where the tape does not use it.
        for name in &RAY_VARS[3..] {
            rc.named_var(name);
        }
        let [g] = roots[..] else {
            return Err(Error::Unsupported(format!(
                "a ray tape has one output, this one {}",
                roots.len()
            )));
        };
        let dg = rc.deriv(g, T);
        Ok(Self {
            // The tape computes `g` already.
            g: tape.clone(),
            g_dg: Tape::new(&rc, &[g, dg])?,
            hc4: Contractor::new(&rc, g),
            context: rc,
            roots: [g, dg],
            params: Vec::new(),
        })
    }

    /// The tape of `g` alone (variables as in [`RAY_VARS`], then the parameters).
    pub fn g_tape(&self) -> &Tape {
        &self.g
    }

    /// The tape with outputs `g` and `g'`.
    pub fn g_dg_tape(&self) -> &Tape {
        &self.g_dg
    }

    /// The graph of `g` and `g'` (for code generation), and their roots `[g, g']`.
    pub fn graph(&self) -> (&Context, [NodeId; 2]) {
        (&self.context, self.roots)
    }

    /// The surface's parameter names, in slot order.
    pub fn params(&self) -> &[String] {
        &self.params
    }
}

/// Evaluates `g` and `g'` of one [`RayFunction`] on rays or beams of number type `N`. Owns
/// its scratch space: make one per thread.
#[derive(Clone, Debug)]
pub struct RayEvaluator<N> {
    g: Evaluator<N>,
    /// `g`'s whole tape (the evaluator `g` may hold a pruned one, see
    /// [`RayEvaluator::restrict`]).
    g_full: Tape,
    trace: Vec<crate::Choice>,
    /// The parameters and tape of the evaluation whose choices `trace` holds, where it was
    /// [`RayEvaluator::g_traced`] for the ray or beam set now.
    traced: Option<(N, Tape)>,
    /// The prunings of `g` made so far, for the restrictions that prune a tape by choices
    /// it was pruned by before (sibling cells, neighbouring beams).
    prunings: PruneCache,
    g_dg: Evaluator<N>,
    vars: Vec<N>,
    out: [N; 2],
    /// `g`'s contractor and its box (used by `RayEvaluator<Interval<f64>>::contract`).
    hc4: Contractor<f64>,
    hc4_box: Vec<Interval<f64>>,
}

impl<N: Number> RayEvaluator<N> {
    /// An evaluator for `f` with the surface parameters' values `params` (in the order of
    /// [`RayFunction::params`]).
    ///
    /// Returns an error when the number of parameter values differs from the surface's.
    pub fn new(f: &RayFunction, params: &[N]) -> Result<Self, Error> {
        if params.len() != f.params.len() {
            return Err(Error::Unsupported(format!(
                "the surface has {} parameters ({}), {} values given",
                f.params.len(),
                f.params.join(", "),
                params.len()
            )));
        }
        let zero = N::constant(&crate::Constant::ZERO);
        let mut vars = vec![zero; RAY_VARS.len()];
        vars.extend_from_slice(params);
        Ok(Self {
            g: Evaluator::new(&f.g),
            g_full: f.g.clone(),
            trace: Vec::new(),
            traced: None,
            prunings: PruneCache::new(),
            g_dg: Evaluator::new(&f.g_dg),
            vars,
            out: [zero; 2],
            hc4: f.hc4.clone(),
            hc4_box: Vec::new(),
        })
    }

    /// Switches to another function with the same parameters (a pruned version of the
    /// same surface, say), keeping the ray or beam set and the parameters' values. Cheap
    /// when `f`'s tapes are the ones already set.
    ///
    /// Returns an error when `f` has another number of parameters.
    pub fn set_function(&mut self, f: &RayFunction) -> Result<(), Error> {
        if f.params.len() + RAY_VARS.len() != self.vars.len() {
            return Err(Error::Unsupported(format!(
                "the function has {} parameters, the evaluator {}",
                f.params.len(),
                self.vars.len() - RAY_VARS.len()
            )));
        }
        if !self.g_full.ptr_eq(&f.g) {
            self.g_full = f.g.clone();
            self.g_dg.set_tape(&f.g_dg);
            self.hc4.set_formula(&f.hc4);
        }
        self.g.set_tape(&f.g);
        Ok(())
    }

    /// Prunes `g` to the region of the ray or beam set over the parameters `t`: an
    /// evaluation of `g` over it records the `min`/`max` choices, and later calls of
    /// [`g`](Self::g) and [`g_checked`](Self::g_checked) evaluate the pruned tape
    /// ([`Tape::simplify`]), which equals `g` at every point of the region and gives the
    /// same enclosure over every part of it. `g'` is not pruned. Where the trace cannot be
    /// taken, `g` stays as it was. A pruning made before by the same choices of the same
    /// tape is taken from the evaluator's [`PruneCache`] (the same tape, bit for bit).
    ///
    /// The tape pruned is the one evaluated now: the whole `g`, or the tape of an earlier
    /// `restrict` (or [`scope`](Self::scope) set again by [`set_scope`](Self::set_scope))
    /// whose region holds this one, so nested restrictions cost less and less. Only
    /// parameters inside `t` may be asked until the scope changes again;
    /// [`unrestrict`](Self::unrestrict), [`set_ray`](Self::set_ray) and
    /// [`set_function`](Self::set_function) return to the whole `g`.
    pub fn restrict(&mut self, t: N) {
        if self.g.tape().choice_count() == 0 {
            // Nothing to prune: no evaluation spent.
            return;
        }
        self.vars[T.index()] = t;
        if self.g.eval_traced(&self.vars, &mut self.trace).is_ok() {
            self.prune_by_trace();
        }
    }

    /// Switches `g` to its tape pruned by the choices `trace` holds (from the cache where
    /// that pruning was made before); unchanged where they do not fit the tape.
    fn prune_by_trace(&mut self) {
        if let Ok(p) = self.prunings.simplify(self.g.tape(), &self.trace) {
            self.g.set_tape(&p);
        }
    }

    /// `g(t)`, recording the `min`/`max` choices of the evaluation, so that a
    /// [`restrict_traced`](Self::restrict_traced) to the same `t` right after prunes
    /// without evaluating again (the same enclosure as [`g`](Self::g)).
    pub fn g_traced(&mut self, t: N) -> N {
        self.vars[T.index()] = t;
        let g = self
            .g
            .eval_traced(&self.vars, &mut self.trace)
            .expect("slot count checked at construction");
        self.traced = Some((t, self.g.tape().clone()));
        g
    }

    /// Whether the choices recorded last are those of a [`g_traced`](Self::g_traced) over
    /// `t` with the ray or beam and the tape set now.
    fn traced_over(&self, t: N) -> bool
    where
        N: PartialEq,
    {
        matches!(&self.traced, Some((at, tape)) if *at == t && tape.ptr_eq(self.g.tape()))
    }

    /// The share of `g`'s `min`/`max` operations whose choice the last
    /// [`g_traced`](Self::g_traced) decided, where it was over `t` with the ray or beam and
    /// the tape set now (what a [`restrict_traced`](Self::restrict_traced) to `t` would
    /// prune by); `None` otherwise, or where the tape has no `min`/`max`.
    pub fn decided_share(&self, t: N) -> Option<f64>
    where
        N: PartialEq,
    {
        if !self.traced_over(t) || self.trace.is_empty() {
            return None;
        }
        let decided = self
            .trace
            .iter()
            .filter(|&&c| c != crate::Choice::Both)
            .count();
        Some(decided as f64 / self.trace.len() as f64)
    }

    /// [`restrict`](Self::restrict) to `t`, by the choices that the last
    /// [`g_traced`](Self::g_traced) recorded where it was over `t` with the tape and the
    /// ray or beam set now (no evaluation spent); otherwise as `restrict`.
    pub fn restrict_traced(&mut self, t: N)
    where
        N: PartialEq,
    {
        if !self.traced_over(t) || self.g.tape().choice_count() == 0 {
            self.restrict(t);
            return;
        }
        self.vars[T.index()] = t;
        self.prune_by_trace();
    }

    /// Undoes every [`restrict`](Self::restrict): `g` is evaluated whole again.
    pub fn unrestrict(&mut self) {
        self.g.set_tape(&self.g_full);
    }

    /// The tape `g` is evaluated with now: the whole `g` or a [`restrict`](Self::restrict)ed
    /// one. Handing it back to [`set_scope`](Self::set_scope) later (for the same ray or
    /// beam and function) returns to that restriction without pruning again.
    pub fn scope(&self) -> &Tape {
        self.g.tape()
    }

    /// Evaluates `g` with `scope`, a tape that [`scope`](Self::scope) returned for the ray
    /// or beam set now; only parameters inside the region it was restricted to may be
    /// asked. Free when it is the tape set already.
    pub fn set_scope(&mut self, scope: &Tape) {
        self.g.set_tape(scope);
    }

    /// The number of instructions `g` is evaluated with now (fewer after a
    /// [`restrict`](Self::restrict) that pruned).
    pub fn g_len(&self) -> usize {
        self.g.tape().len()
    }

    /// Sets the origin `c` and direction `d` of the ray (points) or beam (boxes); `g` is
    /// evaluated whole again (see [`restrict`](Self::restrict)).
    pub fn set_ray(&mut self, origin: [N; 3], dir: [N; 3]) {
        self.g.set_tape(&self.g_full);
        self.set_ray_vars(origin, dir);
    }

    /// [`set_ray`](Self::set_ray) followed by [`set_scope`](Self::set_scope) with `scope`,
    /// a tape that [`scope`](Self::scope) returned for a ray or beam holding this one (its
    /// region holds this one's over the parameters it is asked about): without loading the
    /// whole `g` in between.
    pub fn set_ray_within(&mut self, origin: [N; 3], dir: [N; 3], scope: &Tape) {
        self.g.set_tape(scope);
        self.set_ray_vars(origin, dir);
    }

    /// The variable slots of the ray's origin and direction.
    fn set_ray_vars(&mut self, origin: [N; 3], dir: [N; 3]) {
        self.traced = None;
        self.vars[0..3].copy_from_slice(&origin);
        self.vars[4..7].copy_from_slice(&dir);
    }

    /// `g(t)`.
    pub fn g(&mut self, t: N) -> N {
        self.vars[T.index()] = t;
        self.g
            .eval(&self.vars)
            .expect("slot count checked at construction")
    }

    /// `g(t)`, and whether `g` is proven continuous over the region: the decoration of the
    /// evaluation ([`Evaluator::eval_decorated`]) is at least `dac`, so every operation is
    /// defined and continuous on its arguments (a step function is, on a region where it
    /// takes one value); found by [`Evaluator::eval_continuous`]. A sign change of `g`
    /// between two parameters proves a root between them only where this holds.
    pub fn g_checked(&mut self, t: N) -> (N, bool) {
        self.vars[T.index()] = t;
        self.g
            .eval_continuous(&self.vars)
            .expect("slot count checked at construction")
    }

    /// `g(t)` on each side of the one domain boundary the region may cross
    /// ([`Evaluator::eval_sides`]); `None` where it crosses none or several.
    pub fn g_sides(&mut self, t: N) -> Option<(N, N)> {
        self.vars[T.index()] = t;
        self.g
            .eval_sides(&self.vars)
            .expect("slot count checked at construction")
    }

    /// `(g(t), g'(t))`.
    ///
    /// Where the derivative is undefined somewhere on the beam (a singular point such as
    /// `sqrt` at 0) its enclosure is the whole line, never the empty set, so that a root
    /// finder never reads "no derivative" as "no root".
    pub fn g_dg(&mut self, t: N) -> (N, N) {
        self.vars[T.index()] = t;
        self.g_dg
            .eval_outputs(&self.vars, &mut self.out)
            .expect("slot count checked at construction");
        (self.out[0], self.out[1].widen_undefined())
    }
}

impl RayEvaluator<Interval<f64>> {
    /// `t` narrowed to the parameters where `g` may vanish for some ray of the set, by one
    /// HC4-revise pass over `g`'s graph ([`Contractor`]): every root of every ray in `t`
    /// stays in the result (wherever `g` is defined there). `None` when there is none.
    /// The whole `g` is contracted, whatever [`restrict`](Self::restrict) pruned.
    pub fn contract(&mut self, t: Interval<f64>) -> Option<Interval<f64>> {
        self.vars[T.index()] = t;
        self.hc4_box.clear();
        self.hc4_box.extend_from_slice(&self.vars);
        self.hc4
            .contract(&mut self.hc4_box, Interval::ZERO)
            .then(|| self.hc4_box[T.index()])
    }
}
