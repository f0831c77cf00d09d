//! HC4-revise contractors (Benhamou et al. 1999): the box of a formula's variables narrowed
//! to the points where the formula's value lies in a target, by one forward pass of
//! interval evaluation over the expression graph and one backward pass of the reverse
//! operations of interval-core (IEEE 1788 `sqrRev`, `mulRev`, `sinRev`, ...).
//!
//! Forward, every node gets the enclosure of its values over the box; the root's is
//! intersected with the target. Backward, from the root down (reverse topological order,
//! so that a node shared by several parents has met all of them), each node's enclosure
//! narrows its arguments' to the values that can produce it: for `r = a + b`,
//! `a ∩ (r − b)` and `b ∩ (r − a)`; for `r = a²`, `a ∩ sqrRev(r)`; and so on
//! (the `project` module). The variables' enclosures are the contracted box.
//!
//! **Soundness.** Every point of the box where the formula is defined and its value lies in
//! the target stays in the contracted box: at such a point every node's value lies in its
//! forward enclosure and in the target at the root, and each projection keeps every
//! argument value that, with values of the other arguments in their enclosures, gives a
//! value of the node in its enclosure. Points where the formula is undefined may be
//! removed (they hold no root). Operations without a reverse (the step functions, `atan`'s
//! range end, `domain`) narrow nothing. An empty result proves that no point of the box
//! has its value in the target.
//!
//! ```
//! use implicit_expr::{Context, contractor::Contractor, parse::parse};
//! use interval_core::Interval;
//!
//! let mut ctx = Context::new();
//! let f = parse(&mut ctx, "x^2 + y^2 - 1", &[])?;
//! let mut hc4 = Contractor::<f64>::new(&ctx, f);
//! let iv = |a, b| Interval::new(a, b).unwrap();
//! // The unit circle inside [0.5, 2] × [0.5, 2] × {0}: x and y at most √0.75.
//! let mut b = [iv(0.5, 2.0), iv(0.5, 2.0), iv(0.0, 0.0)];
//! assert!(hc4.contract(&mut b, Interval::ZERO));
//! assert!(b[0].sup() < 0.8661 && b[1].sup() < 0.8661);
//! # Ok::<(), implicit_expr::Error>(())
//! ```

mod project;

use std::sync::Arc;

use interval_core::{Float, Interval};

use crate::constant::Constant;
use crate::context::{Context, Node, NodeId};
use crate::eval::Number;

/// One node of the contractor's program: an operation on earlier nodes (by position), a
/// variable slot or a constant.
#[derive(Copy, Clone, Debug)]
enum Step {
    Var(usize),
    Const(Constant),
    Unary(crate::UnaryOp, usize),
    Binary(crate::BinaryOp, usize, usize),
    Pown(usize, i32),
}

/// The nodes of a formula in topological order, the root last.
#[derive(Debug)]
struct Program {
    steps: Vec<Step>,
    /// How many variable slots the formula uses (the highest slot plus one).
    var_count: usize,
}

/// An HC4-revise contractor of one formula (see the [module documentation](self)). Cloning
/// shares the formula and starts with scratch space of its own: make one per thread.
#[derive(Debug)]
pub struct Contractor<T: Float = f64> {
    program: Arc<Program>,
    /// Each node's enclosure, forward then backward (sized by the first contraction).
    values: Vec<Interval<T>>,
}

impl<T: Float> Clone for Contractor<T> {
    fn clone(&self) -> Self {
        Self {
            program: Arc::clone(&self.program),
            values: Vec::new(),
        }
    }
}

impl<T: Float> Contractor<T> {
    /// The contractor of `root` in `ctx`: the nodes `root` reaches, in topological order.
    pub fn new(ctx: &Context, root: NodeId) -> Self {
        let order = ctx.reachable(&[root]);
        let mut position = vec![usize::MAX; ctx.len()];
        let mut steps = Vec::with_capacity(order.len());
        let mut var_count = 0;
        for (k, &id) in order.iter().enumerate() {
            position[id.index()] = k;
            let at = |n: NodeId| position[n.index()];
            steps.push(match *ctx.get(id) {
                Node::Var(v) => {
                    var_count = var_count.max(v.index() + 1);
                    Step::Var(v.index())
                }
                Node::Const(c) => Step::Const(c),
                Node::Unary(op, a) => Step::Unary(op, at(a)),
                Node::Binary(op, a, b) => Step::Binary(op, at(a), at(b)),
                Node::Pown(a, n) => Step::Pown(at(a), n),
            });
        }
        debug_assert_eq!(order.last(), Some(&root), "the root comes last");
        Self {
            program: Arc::new(Program { steps, var_count }),
            values: Vec::new(),
        }
    }

    /// Switches to `other`'s formula, keeping this contractor's scratch space. Free when
    /// it is the formula already.
    pub fn set_formula(&mut self, other: &Contractor<T>) {
        if !Arc::ptr_eq(&self.program, &other.program) {
            self.program = Arc::clone(&other.program);
        }
    }

    /// The number of variable slots the formula uses: `contract` needs at least as many.
    pub fn var_count(&self) -> usize {
        self.program.var_count
    }

    /// Narrows `vars` (the box, one interval per variable slot) to the points where the
    /// formula's value lies in `target`, by one HC4-revise pass. Returns `false` when the
    /// box holds no such point (the variables are then left partly narrowed and must not be
    /// used), `true` otherwise.
    ///
    /// # Panics
    /// When `vars` has fewer slots than [`var_count`](Self::var_count).
    pub fn contract(&mut self, vars: &mut [Interval<T>], target: Interval<T>) -> bool {
        let program = &*self.program;
        assert!(
            vars.len() >= program.var_count,
            "{} variable slots given, the formula uses {}",
            vars.len(),
            program.var_count
        );
        let steps = &program.steps;
        let values = &mut self.values;
        values.resize(steps.len(), Interval::EMPTY);
        for (k, step) in steps.iter().enumerate() {
            values[k] = match *step {
                Step::Var(slot) => vars[slot],
                Step::Const(c) => <Interval<T> as Number>::constant(&c),
                Step::Unary(op, a) => <Interval<T> as Number>::unary(op, values[a]),
                Step::Binary(op, a, b) => <Interval<T> as Number>::binary(op, values[a], values[b]),
                Step::Pown(a, n) => values[a].pown(n),
            };
        }
        let root = steps.len() - 1;
        values[root] = values[root].intersection(target);
        if values[root].is_empty() {
            return false;
        }
        for k in (0..steps.len()).rev() {
            let r = values[k];
            if r.is_empty() {
                return false;
            }
            match steps[k] {
                Step::Var(slot) => {
                    vars[slot] = vars[slot].intersection(r);
                    if vars[slot].is_empty() {
                        return false;
                    }
                }
                Step::Const(_) => {}
                Step::Unary(op, a) => values[a] = project::unary(op, r, values[a]),
                Step::Binary(op, a, b) => {
                    let (na, nb) = project::binary(op, r, values[a], values[b]);
                    // `a` and `b` may be one node (`x·x`): narrow it by both projections.
                    values[a] = na;
                    values[b] = if a == b { na.intersection(nb) } else { nb };
                }
                Step::Pown(a, n) => values[a] = r.pown_rev_in(values[a], n),
            }
        }
        true
    }
}
