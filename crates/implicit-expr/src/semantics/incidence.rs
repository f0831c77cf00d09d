//! Incidences of the variables in the syntax tree of a formula, and the incidence-split
//! function of thesis 3.5.2 ("taking the multi-incident components as independent
//! components": `x·y/(x+y)` becomes `x1·y1/(x2+y2)`).
//!
//! Incidences are counted in the syntax *tree*, not in the graph: a [`Context`] shares equal
//! subexpressions, and a shared subexpression used twice contributes each of its variables
//! twice. Unfolding the graph into its tree can multiply its size exponentially, so both
//! passes below first measure the tree and refuse one of more than [`MAX_TREE_SIZE`]
//! nodes. Every pass is a loop with an explicit stack (no recursion).

use std::collections::{HashMap, HashSet};

use crate::context::{Context, Node, NodeId, Var};
use crate::error::Error;

/// The largest syntax tree (nodes counted with multiplicity, leaves included) that
/// [`split_incidences`] and the semantic analysis unfold.
pub const MAX_TREE_SIZE: usize = 10_000;

/// One occurrence of a variable in the syntax tree of a formula.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Incidence {
    /// The variable, as a slot of the original context.
    pub var: Var,
    /// Which occurrence of `var` this is, counting from 1, left to right in the tree.
    pub occurrence: usize,
    /// How many occurrences `var` has in the tree (`1`: uni-incident).
    pub count: usize,
    /// The independent variable standing for this occurrence, as a slot of the split
    /// function's context.
    pub slot: Var,
}

/// The incidence-split function: the formula with every occurrence of every variable made
/// an independent variable. It has the same syntax tree as the original, so its modal
/// rational extension on the incidence vector `(X_v, ..., X_v, ...)` is the original's
/// `fR(X)`.
#[derive(Clone, Debug)]
pub struct SplitFunction {
    /// The context holding the split function. Its variable slots are named after the
    /// original variables: `x` for a uni-incident `x`, `x1`, `x2`, ... for the occurrences
    /// of a multi-incident one (a `'` is appended on a clash with another name).
    pub context: Context,
    /// The root of the split function in [`context`](Self::context).
    pub root: NodeId,
    /// The occurrences of the variables, left to right in the tree (the thesis' order:
    /// `x1, y1, x2, y2` for `x·y/(x+y)`). Vectors of the semantic analysis follow this
    /// order.
    pub incidences: Vec<Incidence>,
}

impl SplitFunction {
    /// The name of the independent variable of incidence `i` (e.g. `"x2"`).
    ///
    /// # Panics
    /// If `i` is not an incidence index.
    pub fn name(&self, i: usize) -> &str {
        &self.context.var_names()[self.incidences[i].slot.index()]
    }

    /// Whether `var` occurs more than once in the tree.
    pub fn is_multi_incident(&self, var: Var) -> bool {
        self.incidences
            .iter()
            .any(|inc| inc.var == var && inc.count > 1)
    }

    /// Values given per incidence (in [`incidences`](Self::incidences) order) laid out per
    /// slot of the split context, unused slots holding `filler`: the input of an evaluator.
    pub(crate) fn slot_values<N: Copy>(&self, by_incidence: &[N], filler: N) -> Vec<N> {
        let mut out = vec![filler; self.context.var_count()];
        for (inc, &v) in self.incidences.iter().zip(by_incidence) {
            out[inc.slot.index()] = v;
        }
        out
    }
}

/// Checks that `f` is a node of `ctx` (a node id of another context would index out of
/// bounds).
pub(crate) fn check_node(ctx: &Context, f: NodeId) -> Result<(), Error> {
    if f.index() >= ctx.len() {
        return Err(Error::Unsupported(format!(
            "node {f} is not in this context ({} nodes)",
            ctx.len()
        )));
    }
    Ok(())
}

/// The number of nodes of the syntax tree of `f` (each use of a shared subexpression
/// counted again), saturating at `usize::MAX`.
///
/// Returns an error when `f` is not a node of `ctx`.
pub fn tree_size(ctx: &Context, f: NodeId) -> Result<usize, Error> {
    check_node(ctx, f)?;
    let mut size: HashMap<NodeId, usize> = HashMap::new();
    for id in ctx.reachable(&[f]) {
        let s = match *ctx.get(id) {
            Node::Var(_) | Node::Const(_) => 1,
            Node::Unary(_, a) | Node::Pown(a, _) => size[&a].saturating_add(1),
            Node::Binary(_, a, b) => size[&a].saturating_add(size[&b]).saturating_add(1),
        };
        size.insert(id, s);
    }
    Ok(size[&f])
}

/// One step of the iterative depth-first walk over the tree.
enum Step {
    /// Visit a node: a leaf is handled at once, an operation schedules its arguments.
    Enter(NodeId),
    /// All arguments of the operation are done.
    Exit(NodeId),
}

/// The variables at the leaves of the tree of `f`, left to right.
fn leaves(ctx: &Context, f: NodeId) -> Vec<Var> {
    let mut out = Vec::new();
    let mut stack = vec![f];
    while let Some(id) = stack.pop() {
        match *ctx.get(id) {
            Node::Var(v) => out.push(v),
            Node::Const(_) => {}
            Node::Unary(_, a) | Node::Pown(a, _) => stack.push(a),
            Node::Binary(_, a, b) => {
                stack.push(b);
                stack.push(a);
            }
        }
    }
    out
}

fn pop(values: &mut Vec<NodeId>) -> Result<NodeId, Error> {
    values.pop().ok_or_else(|| internal("value stack"))
}

fn internal(what: &str) -> Error {
    Error::Unsupported(format!("internal error while splitting incidences: {what}"))
}

/// Builds the incidence-split function of `f` (thesis 3.5.2): a new context in which every
/// occurrence of a multi-incident variable is its own variable, e.g. `x·y/(x+y)` becomes
/// `x1·y1/(x2+y2)`.
///
/// Returns [`Error::Unsupported`] when `f` is not a node of `ctx` or when its syntax tree has
/// more than [`MAX_TREE_SIZE`] nodes.
///
/// ```
/// use implicit_expr::Context;
/// use implicit_expr::semantics::split_incidences;
///
/// let mut ctx = Context::new();
/// let (x, y) = (ctx.x(), ctx.y());
/// let (num, den) = (ctx.mul(x, y), ctx.add(x, y));
/// let f = ctx.div(num, den);
/// let split = split_incidences(&ctx, f)?;
/// let names: Vec<&str> = (0..4).map(|i| split.name(i)).collect();
/// assert_eq!(names, ["x1", "y1", "x2", "y2"]);
/// # Ok::<(), implicit_expr::Error>(())
/// ```
pub fn split_incidences(ctx: &Context, f: NodeId) -> Result<SplitFunction, Error> {
    let size = tree_size(ctx, f)?;
    if size > MAX_TREE_SIZE {
        return Err(Error::Unsupported(format!(
            "the syntax tree of this formula has {} nodes (each use of a shared \
             subexpression counted again); the modal semantic analysis unfolds at most {}",
            if size == usize::MAX {
                "too many".to_string()
            } else {
                size.to_string()
            },
            MAX_TREE_SIZE
        )));
    }

    // The occurrences, left to right, and their independent variables.
    let leaves = leaves(ctx, f);
    let mut count: HashMap<Var, usize> = HashMap::new();
    for &v in &leaves {
        *count.entry(v).or_default() += 1;
    }
    let mut split = Context::new();
    let mut used: HashSet<Var> = HashSet::new();
    let mut seen: HashMap<Var, usize> = HashMap::new();
    let mut incidences = Vec::with_capacity(leaves.len());
    for &v in &leaves {
        let base = ctx
            .var_names()
            .get(v.index())
            .ok_or_else(|| internal("undeclared variable slot"))?;
        let n = count[&v];
        let k = seen.entry(v).or_default();
        *k += 1;
        let mut name = if n == 1 {
            base.clone()
        } else {
            format!("{base}{k}")
        };
        let slot = loop {
            match split.find_var(&name) {
                Some(s) if used.contains(&s) => name.push('\''),
                _ => break split.declare_var(&name),
            }
        };
        used.insert(slot);
        incidences.push(Incidence {
            var: v,
            occurrence: *k,
            count: n,
            slot,
        });
    }

    // The tree, rebuilt bottom-up with the k-th leaf variable replaced by incidence k.
    let mut stack = vec![Step::Enter(f)];
    let mut values: Vec<NodeId> = Vec::new();
    let mut leaf = 0;
    while let Some(step) = stack.pop() {
        match step {
            Step::Enter(id) => match *ctx.get(id) {
                Node::Var(_) => {
                    let inc = incidences.get(leaf).ok_or_else(|| internal("leaf count"))?;
                    leaf += 1;
                    values.push(split.var(inc.slot)?);
                }
                Node::Const(c) => values.push(split.constant_enclosed(c)),
                Node::Unary(_, a) | Node::Pown(a, _) => {
                    stack.push(Step::Exit(id));
                    stack.push(Step::Enter(a));
                }
                Node::Binary(_, a, b) => {
                    stack.push(Step::Exit(id));
                    stack.push(Step::Enter(b));
                    stack.push(Step::Enter(a));
                }
            },
            Step::Exit(id) => {
                let node = match *ctx.get(id) {
                    Node::Unary(op, _) => {
                        let a = pop(&mut values)?;
                        split.unary(op, a)
                    }
                    Node::Pown(_, n) => {
                        let a = pop(&mut values)?;
                        split.pown(a, n)
                    }
                    Node::Binary(op, _, _) => {
                        let b = pop(&mut values)?;
                        let a = pop(&mut values)?;
                        split.binary(op, a, b)
                    }
                    Node::Var(_) | Node::Const(_) => return Err(internal("leaf exit")),
                };
                values.push(node);
            }
        }
    }
    let root = pop(&mut values)?;
    Ok(SplitFunction {
        context: split,
        root,
        incidences,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_subexpressions_count_twice() {
        let mut c = Context::new();
        let (x, y) = (c.x(), c.y());
        let s = c.add(x, y);
        let f = c.mul(s, s); // becomes sqr(s): one use of s
        let g = c.div(s, f); // s twice in the tree
        assert_eq!(tree_size(&c, g).unwrap(), 3 + 4 + 1);
        let split = split_incidences(&c, g).unwrap();
        let names: Vec<&str> = (0..split.incidences.len()).map(|i| split.name(i)).collect();
        assert_eq!(names, ["x1", "y1", "x2", "y2"]);
        assert!(split.is_multi_incident(Var::X));
        let v = [1.0, 2.0, 1.0, 2.0];
        let vals = split.slot_values(&v, 0.0);
        let a = split.context.eval(split.root, &vals).unwrap();
        assert_eq!(a, c.eval(g, &[1.0, 2.0, 0.0]).unwrap());
    }

    #[test]
    fn uni_incident_names_and_clashes() {
        let mut c = Context::new();
        let x = c.x();
        let x1 = c.named_var("x1");
        let s = c.add(x, x1);
        let f = c.mul(s, x); // stored as x * (x + x1): `*` orders its arguments
        let split = split_incidences(&c, f).unwrap();
        let names: Vec<&str> = (0..3).map(|i| split.name(i)).collect();
        assert_eq!(names, ["x1", "x2", "x1'"]);
        assert_eq!(split.incidences[2].var, Var(3));
        assert_eq!(split.incidences[2].count, 1);
        assert_eq!(split.incidences[1].occurrence, 2);
    }

    #[test]
    fn huge_trees_are_refused() {
        let mut c = Context::new();
        let mut f = c.x();
        for _ in 0..200 {
            let g = c.unary(crate::op::UnaryOp::Sin, f);
            f = c.add(g, g); // the tree doubles at every step
        }
        assert_eq!(tree_size(&c, f).unwrap(), usize::MAX);
        let e = split_incidences(&c, f).unwrap_err();
        assert!(e.to_string().contains("at most 10000"), "{e}");
        let small = Context::new();
        assert!(split_incidences(&small, f).is_err());
    }
}
