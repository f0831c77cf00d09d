//! Interval tests on the split function over `Prop(X)`: the domain condition of the
//! theorems, the monotony of each incidence and of each variable, and tree-optimality
//! (thesis 3.5.2).
//!
//! * **Ranges.** One forward pass of [`Interval<f64>`] over the split function gives an
//!   enclosure of every subexpression over `Prop(X)`, and checks that every operation is
//!   defined and continuous there (the theorems' "`Out(fR(Prop(X)))` does exist").
//! * **Local slopes.** For each operation kind, the partial derivatives with respect to its
//!   arguments are the symbolic derivatives of [`Context::deriv`] on `op(x, y)`, compiled once
//!   into a [`Tape`] and evaluated with intervals on the argument ranges.
//! * **Incidence partials.** `∂g/∂x_k` of the split function `g` is accumulated backwards
//!   from the root (reverse mode) as the product of the local slope enclosures along the
//!   path to incidence `k`: an enclosure of the same chain-rule product that the symbolic
//!   partial evaluates, in time linear in the tree for all incidences at once.
//! * **Variable partials.** `∂f/∂x` of the original formula is the symbolic derivative on
//!   the original graph (shared variables, so without the loss of splitting), evaluated with
//!   intervals; it is intersected with `Σ_k ∂g/∂x_k`, another enclosure of the same
//!   derivative.
//! * **Refinement.** A sign left undecided on the whole box is retried by bisection
//!   ([`refine_sign`]): dependency makes enclosures of derivatives such as
//!   `∂(xy/(x+y))/∂y = (x - xy/(x+y))/(x+y)` straddle zero on the thesis' box, while on
//!   small pieces their sign shows. The work is bounded, and an undecided sign only makes
//!   the analysis choose a weaker theorem.
//!
//! Every enclosure is sound for the Clarke generalised gradient as well (`abs`, `min`, `max`
//! differentiate to the hull of both sides where undecided), so a sign decided over the box
//! proves monotony by the mean-value inequality.

use std::collections::HashMap;
use std::fmt;

use interval_core::Interval;

use super::incidence::SplitFunction;
use crate::context::{Context, Node, NodeId, Var};
use crate::error::Error;
use crate::eval::{Evaluator, Number};
use crate::op::{BinaryOp, UnaryOp};
use crate::tape::Tape;

/// The sign of a partial derivative over `Prop(X)`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Monotony {
    /// The derivative is `>= 0` everywhere (non-decreasing); its enclosure is not `[0, 0]`.
    Increasing,
    /// The derivative is `<= 0` everywhere (non-increasing); its enclosure is not `[0, 0]`.
    Decreasing,
    /// The derivative is zero everywhere (enclosure `[0, 0]`): both senses at once. As the global sense of a
    /// variable it counts as increasing.
    Constant,
    /// The sign could not be decided over the box.
    Undecided,
}

impl Monotony {
    /// The sign of an enclosure `d` of a derivative.
    pub fn of(d: Interval<f64>) -> Self {
        match d.bounds() {
            None => Monotony::Undecided,
            Some((lo, hi)) if lo == 0.0 && hi == 0.0 => Monotony::Constant,
            Some((lo, _)) if lo >= 0.0 => Monotony::Increasing,
            Some((_, hi)) if hi <= 0.0 => Monotony::Decreasing,
            Some(_) => Monotony::Undecided,
        }
    }

    /// Whether the sign is decided (uniform monotony).
    pub fn is_monotone(self) -> bool {
        self != Monotony::Undecided
    }

    /// Whether an incidence of this sense is contrary to the global sense `global` of its
    /// variable (and so is dualised by theorems 3, 4 and 6). A `Constant` global sense
    /// counts as increasing; a `Constant` incidence is never contrary.
    pub fn is_contrary_to(self, global: Monotony) -> bool {
        matches!(
            (self, global),
            (Monotony::Increasing, Monotony::Decreasing)
                | (
                    Monotony::Decreasing,
                    Monotony::Increasing | Monotony::Constant
                )
        )
    }
}

impl fmt::Display for Monotony {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Monotony::Increasing => "increasing",
            Monotony::Decreasing => "decreasing",
            Monotony::Constant => "constant",
            Monotony::Undecided => "undecided",
        })
    }
}

/// The interval facts about the split function over `Prop(X)`.
pub(crate) struct Ranges {
    /// The nodes of the split function, in topological order.
    pub order: Vec<NodeId>,
    /// Enclosure of each node over `Prop(X)` (indexed by node).
    pub range: Vec<Interval<f64>>,
    /// Number of varying (non-point) incidences below each node, saturated at 2.
    pub varying: Vec<u8>,
}

fn not_defined(what: String) -> Error {
    Error::Unsupported(format!(
        "the modal interpretability theorems need the formula defined and continuous on \
         Prop(X), but {what}"
    ))
}

/// The forward pass: ranges of every node of the split function over the boxes `inputs`
/// (one per slot of the split context), with the domain check. `varying_slot` tells which
/// slots hold a non-point interval.
pub(crate) fn ranges(
    split: &SplitFunction,
    inputs: &[Interval<f64>],
    varying_slot: &[bool],
) -> Result<Ranges, Error> {
    let ctx = &split.context;
    let order = ctx.reachable(&[split.root]);
    let mut range = vec![Interval::EMPTY; ctx.len()];
    let mut varying = vec![0u8; ctx.len()];
    for &id in &order {
        let (r, v) = match *ctx.get(id) {
            Node::Var(s) => (inputs[s.index()], u8::from(varying_slot[s.index()])),
            Node::Const(c) => (<Interval<f64> as Number>::constant(&c), 0),
            Node::Unary(op, a) => {
                let x = range[a.index()];
                let r = <Interval<f64> as Number>::unary(op, x);
                if let Some(why) = unary_domain(op, x, r) {
                    return Err(not_defined(format!("{} {why} on {x}", op.name())));
                }
                (r, varying[a.index()])
            }
            Node::Pown(a, n) => {
                let x = range[a.index()];
                let r = x.pown(n);
                if n < 0 && x.contains(0.0) {
                    return Err(not_defined(format!("x^{n} has a pole on {x}")));
                }
                (r, varying[a.index()])
            }
            Node::Binary(op, a, b) => {
                let (x, y) = (range[a.index()], range[b.index()]);
                let r = <Interval<f64> as Number>::binary(op, x, y);
                let bad = match op {
                    BinaryOp::Div if y.contains(0.0) => Some(format!("the divisor {y} holds 0")),
                    BinaryOp::Pow if x.is_empty() || x.inf() <= 0.0 => {
                        Some(format!("pow needs a base > 0, not {x}"))
                    }
                    _ => None,
                };
                if let Some(why) = bad {
                    return Err(not_defined(why));
                }
                (
                    r,
                    varying[a.index()].saturating_add(varying[b.index()]).min(2),
                )
            }
        };
        if r.is_empty() || !r.inf().is_finite() || !r.sup().is_finite() {
            return Err(not_defined(format!(
                "a subexpression has no bounded enclosure ({r}) over Prop(X)"
            )));
        }
        range[id.index()] = r;
        varying[id.index()] = v;
    }
    Ok(Ranges {
        order,
        range,
        varying,
    })
}

/// Why `op` is not defined and continuous on `x` (with interval result `r`), if it is not.
fn unary_domain(op: UnaryOp, x: Interval<f64>, r: Interval<f64>) -> Option<&'static str> {
    let Some((lo, hi)) = x.bounds() else {
        return Some("is applied to an empty set");
    };
    let step = |slope: UnaryOp| <Interval<f64> as Number>::unary(slope, x) != Interval::ZERO;
    let bad = match op {
        UnaryOp::Sqrt => lo < 0.0,
        UnaryOp::Ln | UnaryOp::Log10 => lo <= 0.0,
        UnaryOp::Recip => x.contains(0.0),
        UnaryOp::Asin | UnaryOp::Acos => lo < -1.0 || hi > 1.0,
        UnaryOp::Tan => r.is_entire(),
        UnaryOp::Floor | UnaryOp::Ceil => step(UnaryOp::SlopeFloor),
        UnaryOp::Round => step(UnaryOp::SlopeRound),
        UnaryOp::Not => step(UnaryOp::SlopeNot),
        UnaryOp::SlopeFloor | UnaryOp::SlopeRound | UnaryOp::SlopeNot => r != Interval::ZERO,
        _ => false,
    };
    bad.then_some(match op {
        UnaryOp::Floor
        | UnaryOp::Ceil
        | UnaryOp::Round
        | UnaryOp::Not
        | UnaryOp::SlopeFloor
        | UnaryOp::SlopeRound
        | UnaryOp::SlopeNot => "jumps",
        UnaryOp::Recip | UnaryOp::Tan => "has a pole",
        _ => "is not defined everywhere",
    })
}

/// Which local slope: the operation kind of a node.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
enum SlopeKey {
    Unary(UnaryOp),
    Binary(BinaryOp),
    Pown(i32),
}

/// The partial derivatives of each operation with respect to its arguments, as tapes built
/// from [`Context::deriv`] on `op(x, y)`, compiled on first use.
#[derive(Default)]
pub(crate) struct Slopes {
    cache: HashMap<SlopeKey, Evaluator<Interval<f64>>>,
}

impl Slopes {
    /// Enclosures of `∂op/∂a` and `∂op/∂b` (the second is zero for one argument) for the
    /// operation of `node`, over the argument ranges `a` and `b`.
    pub(crate) fn of(
        &mut self,
        node: &Node,
        a: Interval<f64>,
        b: Interval<f64>,
    ) -> Result<[Interval<f64>; 2], Error> {
        let key = match *node {
            Node::Unary(op, _) => SlopeKey::Unary(op),
            Node::Binary(op, _, _) => SlopeKey::Binary(op),
            Node::Pown(_, n) => SlopeKey::Pown(n),
            Node::Var(_) | Node::Const(_) => return Ok([Interval::ZERO; 2]),
        };
        let eval = match self.cache.entry(key) {
            std::collections::hash_map::Entry::Occupied(e) => e.into_mut(),
            std::collections::hash_map::Entry::Vacant(e) => {
                let mut c = Context::new();
                let (u, v) = (c.x(), c.y());
                let g = match key {
                    SlopeKey::Unary(op) => c.unary(op, u),
                    SlopeKey::Binary(op) => c.binary(op, u, v),
                    SlopeKey::Pown(n) => c.pown(u, n),
                };
                let du = c.deriv(g, Var::X);
                let dv = c.deriv(g, Var::Y);
                e.insert(Evaluator::new(&Tape::new(&c, &[du, dv])?))
            }
        };
        let mut out = [Interval::ZERO; 2];
        eval.eval_outputs(&[a, b, Interval::ZERO], &mut out)?;
        Ok(out)
    }
}

/// Enclosures of `∂g/∂x_k` over the box `inputs` (one interval per slot of the split
/// context) for every incidence `k` of the split function `g` (in incidence order), by
/// reverse accumulation of the local slopes, refined by [`refine_sign`] where undecided.
pub(crate) fn incidence_partials(
    split: &SplitFunction,
    inputs: &[Interval<f64>],
    varying_slot: &[bool],
    r: &Ranges,
    slopes: &mut Slopes,
) -> Result<Vec<Interval<f64>>, Error> {
    let mut partials = accumulate(split, r, slopes)?;
    let undecided = partials
        .iter()
        .filter(|&&d| !Monotony::of(d).is_monotone())
        .count();
    if undecided == 0 {
        return Ok(partials);
    }
    let budget = INCIDENCE_BUDGET.min(INCIDENCE_WORK / (r.order.len() * undecided).max(1));
    for (k, partial) in partials.iter_mut().enumerate() {
        if Monotony::of(*partial).is_monotone() {
            continue;
        }
        *partial = refine_sign(inputs.to_vec(), varying_slot, budget, |b| {
            let sub = ranges(split, b, varying_slot)?;
            Ok(accumulate(split, &sub, slopes)?[k])
        })?;
    }
    Ok(partials)
}

/// One reverse sweep: enclosures of all incidence partials over the box of `r`.
fn accumulate(
    split: &SplitFunction,
    r: &Ranges,
    slopes: &mut Slopes,
) -> Result<Vec<Interval<f64>>, Error> {
    let ctx = &split.context;
    let mut adj = vec![Interval::ZERO; ctx.len()];
    adj[split.root.index()] = Interval::ONE;
    let mut var_node: HashMap<Var, NodeId> = HashMap::new();
    for &id in r.order.iter().rev() {
        let node = *ctx.get(id);
        let (a, b) = match node {
            Node::Var(s) => {
                var_node.insert(s, id);
                continue;
            }
            Node::Const(_) => continue,
            Node::Unary(_, a) | Node::Pown(a, _) => (a, None),
            Node::Binary(_, a, b) => (a, Some(b)),
        };
        let ra = r.range[a.index()];
        let rb = b.map_or(Interval::ZERO, |b| r.range[b.index()]);
        let [sa, sb] = slopes.of(&node, ra, rb)?;
        let up = adj[id.index()];
        adj[a.index()] = adj[a.index()] + up * sa;
        if let Some(b) = b {
            adj[b.index()] = adj[b.index()] + up * sb;
        }
    }
    Ok(split
        .incidences
        .iter()
        .map(|inc| {
            var_node
                .get(&inc.slot)
                .map_or(Interval::ZERO, |n| adj[n.index()])
        })
        .collect())
}

/// Enclosures of `∂f/∂v` over the box `props` (one interval per slot of `ctx`) for each
/// variable of `vars`, from the symbolic derivatives on a copy of the graph of `f`, each
/// refined by [`refine_sign`] where its sign is undecided on the whole box.
pub(crate) fn variable_partials(
    ctx: &Context,
    f: NodeId,
    vars: &[Var],
    props: &[Interval<f64>],
) -> Result<Vec<Interval<f64>>, Error> {
    if vars.is_empty() {
        return Ok(Vec::new());
    }
    // A copy of the nodes of f only, with the same variable slots.
    let mut c = Context::new();
    for name in ctx.var_names().iter().skip(3) {
        c.declare_var(name);
    }
    let g = c.copy_graph(ctx, f, |c, v| c.named_var(&ctx.var_names()[v.index()]));
    let roots: Vec<NodeId> = vars.iter().map(|&v| c.deriv(g, v)).collect();
    let tape = Tape::new(&c, &roots)?;
    let mut eval = Evaluator::new(&tape);
    let mut out = vec![Interval::ZERO; roots.len()];
    let mut inputs = props.to_vec();
    inputs.resize(c.var_count(), Interval::ZERO);
    // Any variable of f may be split (points have width zero and never are).
    let mut used = vec![false; inputs.len()];
    for id in c.reachable(&[g]) {
        if let Node::Var(v) = *c.get(id) {
            used[v.index()] = true;
        }
    }
    let mut result = Vec::with_capacity(vars.len());
    for j in 0..vars.len() {
        let d = refine_sign(inputs.clone(), &used, VARIABLE_BUDGET, |b| {
            eval.eval_outputs(b, &mut out)?;
            Ok(out[j])
        })?;
        result.push(d);
    }
    Ok(result)
}

/// Most sub-boxes evaluated to decide the sign of one variable's partial derivative.
const VARIABLE_BUDGET: usize = 512;

/// Most sub-boxes evaluated to decide the sign of one incidence's partial derivative.
const INCIDENCE_BUDGET: usize = 128;

/// Most node evaluations spent on refining all incidence partials together (the budget per
/// incidence shrinks for large trees).
const INCIDENCE_WORK: usize = 4_000_000;

/// Refines `eval(bx)`, an enclosure of a derivative over the box `bx`, by bisection until
/// its sign is decided: the box is split along its widest splittable component until every
/// piece has a decided sign. When all pieces agree, the hull of their enclosures (intersected
/// with the first one) is returned; otherwise, or after `budget` evaluations, or if a piece
/// cannot be evaluated, the enclosure over the whole box. Either way the result encloses the
/// derivative over `bx`.
pub(crate) fn refine_sign(
    bx: Vec<Interval<f64>>,
    splittable: &[bool],
    budget: usize,
    mut eval: impl FnMut(&[Interval<f64>]) -> Result<Interval<f64>, Error>,
) -> Result<Interval<f64>, Error> {
    let first = eval(&bx)?;
    if Monotony::of(first).is_monotone() {
        return Ok(first);
    }
    let mut stack = vec![bx];
    let mut hull = Interval::EMPTY;
    let (mut up, mut down) = (false, false);
    let mut evals = 0;
    while let Some(b) = stack.pop() {
        let widest = (0..b.len())
            .filter(|&k| splittable.get(k).copied().unwrap_or(false) && b[k].wid() > 0.0)
            .max_by(|&i, &j| b[i].wid().total_cmp(&b[j].wid()));
        let Some(k) = widest else {
            return Ok(first);
        };
        let (lo, hi) = b[k].bisect();
        for half in [lo, hi] {
            evals += 1;
            if evals > budget {
                return Ok(first);
            }
            let mut c = b.clone();
            c[k] = half;
            let Ok(d) = eval(&c) else {
                return Ok(first);
            };
            match Monotony::of(d) {
                Monotony::Undecided => {
                    stack.push(c);
                    continue;
                }
                Monotony::Increasing => up = true,
                Monotony::Decreasing => down = true,
                Monotony::Constant => {}
            }
            if up && down {
                return Ok(first);
            }
            hull = hull.convex_hull(d);
        }
    }
    Ok(hull.intersection(first))
}

/// Tree-optimality of the split function on `Prop(X)` (thesis 3.5.2: "any of its
/// non-uniformly monotonous operators is followed downwards only by one-variable
/// operators").
///
/// An operation is uniformly monotonous when the local slope with respect to each argument
/// that depends on a varying incidence has a decided sign over the argument ranges. Below a
/// non-uniformly monotonous operation, every argument must depend on at most one varying
/// incidence (so that everything below it is a one-variable function; a two-argument
/// operation of two one-variable functions, like `x·y` across zero, is itself computed
/// exactly by its semantic extension). Incidences held at a point count as constants. The
/// test is conservative: a sign left undecided by the interval enclosure counts as
/// non-uniform, which can only deny optimality, never claim it wrongly.
///
/// Returns the first offending node, or `None` when the function is tree-optimal.
pub(crate) fn non_optimal_node(
    split: &SplitFunction,
    r: &Ranges,
    slopes: &mut Slopes,
) -> Result<Option<NodeId>, Error> {
    let ctx = &split.context;
    for &id in &r.order {
        let node = *ctx.get(id);
        let args: Vec<NodeId> = match node {
            Node::Var(_) | Node::Const(_) => continue,
            Node::Unary(_, a) | Node::Pown(a, _) => vec![a],
            Node::Binary(_, a, b) => vec![a, b],
        };
        if r.varying[id.index()] == 0 {
            continue;
        }
        let ra = r.range[args[0].index()];
        let rb = args.get(1).map_or(Interval::ZERO, |b| r.range[b.index()]);
        let s = slopes.of(&node, ra, rb)?;
        let uniform = args
            .iter()
            .zip(s)
            .all(|(a, s)| r.varying[a.index()] == 0 || Monotony::of(s).is_monotone());
        if !uniform && args.iter().any(|a| r.varying[a.index()] > 1) {
            return Ok(Some(id));
        }
    }
    Ok(None)
}
