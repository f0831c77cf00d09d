//! The expression graph: a hash-consed DAG of operations on variables and constants.
//!
//! Every node is created through a [`Context`] method that first simplifies (constant
//! folding and the identities listed on [`Context::binary`] and [`Context::unary`]) and then
//! looks the node up, so equal subexpressions are one node. Children are always created
//! before their parents: node ids are a topological order, and every pass over the graph
//! is a loop over ids, never a recursion (deep formulas cannot overflow the stack).

use rustc_hash::FxHashMap as HashMap;
use std::fmt;

use crate::constant::Constant;
use crate::error::Error;
use crate::number::Number;
use crate::op::{BinaryOp, UnaryOp};
use interval_core::Interval;

/// A node of a [`Context`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct NodeId(u32);

impl NodeId {
    /// The position of the node in its context (a topological order).
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for NodeId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "_{}", self.0)
    }
}

/// A variable slot. `x`, `y` and `z` are slots 0, 1 and 2; parameters and any other named
/// variables follow in the order they were declared.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Var(pub u32);

impl Var {
    /// The `x` coordinate.
    pub const X: Var = Var(0);
    /// The `y` coordinate.
    pub const Y: Var = Var(1);
    /// The `z` coordinate.
    pub const Z: Var = Var(2);

    /// The slot index: the position of this variable's value in an evaluator's input.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// One node of the graph.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A variable.
    Var(Var),
    /// A constant.
    Const(Constant),
    /// A one-argument operation.
    Unary(UnaryOp, NodeId),
    /// A two-argument operation.
    Binary(BinaryOp, NodeId, NodeId),
    /// An integer power `a^n` (IEEE 1788 `pown`).
    Pown(NodeId, i32),
}

/// The expression graph. See the [module documentation](self).
#[derive(Clone, Debug)]
pub struct Context {
    nodes: Vec<Node>,
    index: HashMap<Node, NodeId>,
    var_names: Vec<String>,
}

impl Default for Context {
    fn default() -> Self {
        Self::new()
    }
}

impl Context {
    /// A context with the variables `x`, `y` and `z` declared (slots 0, 1, 2).
    pub fn new() -> Self {
        Self {
            nodes: Vec::new(),
            index: HashMap::default(),
            var_names: vec!["x".into(), "y".into(), "z".into()],
        }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the context holds no node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The node `id`.
    ///
    /// # Panics
    /// If `id` belongs to another, larger context.
    pub fn get(&self, id: NodeId) -> &Node {
        &self.nodes[id.index()]
    }

    /// All nodes, in id (topological) order.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The names of the variable slots, in slot order (`x`, `y`, `z`, then the others).
    pub fn var_names(&self) -> &[String] {
        &self.var_names
    }

    /// Number of variable slots (an evaluator's input length).
    pub fn var_count(&self) -> usize {
        self.var_names.len()
    }

    /// The slot of the variable called `name`, if declared.
    pub fn find_var(&self, name: &str) -> Option<Var> {
        self.var_names
            .iter()
            .position(|n| n == name)
            .map(|i| Var(i as u32))
    }

    /// Declares the variable `name` (or finds it) and returns its slot.
    pub fn declare_var(&mut self, name: &str) -> Var {
        match self.find_var(name) {
            Some(v) => v,
            None => {
                self.var_names.push(name.to_string());
                Var((self.var_names.len() - 1) as u32)
            }
        }
    }

    /// The node of variable `v`.
    ///
    /// Returns an error when `v` is not a declared slot.
    pub fn var(&mut self, v: Var) -> Result<NodeId, Error> {
        if v.index() >= self.var_names.len() {
            return Err(Error::UnknownVar(v.0));
        }
        Ok(self.intern(Node::Var(v)))
    }

    /// The node of the variable called `name`, declaring it if needed.
    pub fn named_var(&mut self, name: &str) -> NodeId {
        let v = self.declare_var(name);
        self.intern(Node::Var(v))
    }

    /// `x`.
    pub fn x(&mut self) -> NodeId {
        self.intern(Node::Var(Var::X))
    }

    /// `y`.
    pub fn y(&mut self) -> NodeId {
        self.intern(Node::Var(Var::Y))
    }

    /// `z`.
    pub fn z(&mut self) -> NodeId {
        self.intern(Node::Var(Var::Z))
    }

    /// An exactly representable constant.
    ///
    /// Returns an error for NaN and infinities.
    pub fn constant(&mut self, v: f64) -> Result<NodeId, Error> {
        let c = Constant::exact(v).ok_or(Error::NonFiniteConstant(v))?;
        Ok(self.intern(Node::Const(c)))
    }

    /// A constant given by its enclosure.
    pub fn constant_enclosed(&mut self, c: Constant) -> NodeId {
        self.intern(Node::Const(c))
    }

    /// The constant of node `id`, if it is one.
    pub fn as_const(&self, id: NodeId) -> Option<Constant> {
        match self.get(id) {
            Node::Const(c) => Some(*c),
            _ => None,
        }
    }

    fn is_const(&self, id: NodeId, v: f64) -> bool {
        self.as_const(id).is_some_and(|c| c.is(v))
    }

    fn intern(&mut self, node: Node) -> NodeId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = NodeId(self.nodes.len() as u32);
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    /// Folds `node` if all its arguments are constants and the result is defined.
    fn fold(&self, node: &Node) -> Option<Constant> {
        let (enc, val) = match *node {
            Node::Unary(op, a) => {
                let a = self.as_const(a)?;
                (Interval::unary(op, a.interval()), f64::unary(op, a.value()))
            }
            Node::Binary(op, a, b) => {
                let (a, b) = (self.as_const(a)?, self.as_const(b)?);
                (
                    Interval::binary(op, a.interval(), b.interval()),
                    f64::binary(op, a.value(), b.value()),
                )
            }
            Node::Pown(a, n) => {
                let a = self.as_const(a)?;
                (Interval::pown(a.interval(), n), f64::pown(a.value(), n))
            }
            _ => return None,
        };
        if enc.is_empty() || !enc.inf().is_finite() || !enc.sup().is_finite() {
            return None;
        }
        // The point value is the float computation; keep it inside the enclosure.
        let val = val.clamp(enc.inf(), enc.sup());
        Constant::enclosed(val, enc.inf(), enc.sup())
    }

    /// `op(a)`, simplified.
    ///
    /// Besides constant folding, the identities used are `-(-a) = a`, `|(-a)| = |a|`,
    /// `||a|| = |a|`, `|a²| = a²`, `(-a)² = a²` and `|a|² = a²`: each holds for every real
    /// `a` and for every interval, empty and unbounded ones included.
    pub fn unary(&mut self, op: UnaryOp, a: NodeId) -> NodeId {
        let node = Node::Unary(op, a);
        if let Some(c) = self.fold(&node) {
            return self.constant_enclosed(c);
        }
        let inner = *self.get(a);
        match (op, inner) {
            (UnaryOp::Neg, Node::Unary(UnaryOp::Neg, b)) => return b,
            (UnaryOp::Abs, Node::Unary(UnaryOp::Neg | UnaryOp::Abs, b)) => {
                return self.unary(UnaryOp::Abs, b);
            }
            (UnaryOp::Abs, Node::Unary(UnaryOp::Sqr, _)) => return a,
            (UnaryOp::Sqr, Node::Unary(UnaryOp::Neg | UnaryOp::Abs, b)) => {
                return self.unary(UnaryOp::Sqr, b);
            }
            _ => {}
        }
        self.intern(node)
    }

    /// `op(a, b)`, simplified.
    ///
    /// Besides constant folding and a canonical argument order for `+ * min max`, the
    /// identities used are `a + 0 = a`, `a - 0 = a`, `0 - a = -a`, `a * 1 = a`, `a / 1 = a`,
    /// `a * -1 = -a`, `min(a, a) = max(a, a) = a`, `a * a = a²`, and two that change
    /// interval results: `a - a = 0` and `a * 0 = 0`. Those two hold for every real `a`
    /// (they tighten `[1, 2] - [1, 2] = [-1, 1]` to the true range `[0, 0]`), and `a * 0 = 0`
    /// is also IEEE 1788's interval product; but on an empty `a` the result is `{0}`
    /// instead of empty. An exponent that is an exact integer constant makes `pow` a
    /// [`pown`](Self::pown).
    pub fn binary(&mut self, op: BinaryOp, a: NodeId, b: NodeId) -> NodeId {
        let (a, b) = if op.is_commutative() && b < a {
            (b, a)
        } else {
            (a, b)
        };
        // An exact integer exponent makes `pow` a `pown` (whose domain includes negative
        // bases) before anything is folded with `pow`'s real-exponent domain.
        if op == BinaryOp::Pow
            && let Some(n) = self.as_const(b).and_then(|c| c.as_i32())
        {
            return self.pown(a, n);
        }
        let node = Node::Binary(op, a, b);
        if let Some(c) = self.fold(&node) {
            return self.constant_enclosed(c);
        }
        match op {
            BinaryOp::Add => {
                if self.is_const(a, 0.0) {
                    return b;
                }
                if self.is_const(b, 0.0) {
                    return a;
                }
            }
            BinaryOp::Sub => {
                if self.is_const(b, 0.0) {
                    return a;
                }
                if self.is_const(a, 0.0) {
                    return self.unary(UnaryOp::Neg, b);
                }
                if a == b {
                    return self.intern(Node::Const(Constant::ZERO));
                }
            }
            BinaryOp::Mul => {
                for (p, q) in [(a, b), (b, a)] {
                    if self.is_const(q, 1.0) {
                        return p;
                    }
                    if self.is_const(q, 0.0) {
                        return q;
                    }
                    if self.is_const(q, -1.0) {
                        return self.unary(UnaryOp::Neg, p);
                    }
                }
                if a == b {
                    return self.unary(UnaryOp::Sqr, a);
                }
            }
            BinaryOp::Div => {
                if self.is_const(b, 1.0) {
                    return a;
                }
            }
            BinaryOp::Min | BinaryOp::Max => {
                if a == b {
                    return a;
                }
            }
            BinaryOp::Pow | BinaryOp::Domain => {}
        }
        self.intern(node)
    }

    /// `a^n` for an integer `n` (IEEE 1788 `pown`: `a^0 = 1` for every `a`, negative `n`
    /// divides).
    ///
    /// `n = 0` gives the constant 1, `n = 1` gives `a`, `n = 2` gives `sqr(a)`, `n = -1`
    /// gives `recip(a)`, and an even `n >= 4` gives `sqr(a^(n/2))`.
    pub fn pown(&mut self, a: NodeId, n: i32) -> NodeId {
        match n {
            0 => return self.intern(Node::Const(Constant::ONE)),
            1 => return a,
            2 => return self.unary(UnaryOp::Sqr, a),
            -1 => return self.unary(UnaryOp::Recip, a),
            // a^(2k) = (a^k)²: the same real function, and over intervals the same range
            // (squaring encloses the exact range of any interval), with cheap tight squares in
            // place of a general power.
            _ if n >= 4 && n % 2 == 0 => {
                let h = self.pown(a, n / 2);
                return self.unary(UnaryOp::Sqr, h);
            }
            _ => {}
        }
        let node = Node::Pown(a, n);
        if let Some(c) = self.fold(&node) {
            return self.constant_enclosed(c);
        }
        self.intern(node)
    }

    /// `a + b`.
    pub fn add(&mut self, a: NodeId, b: NodeId) -> NodeId {
        self.binary(BinaryOp::Add, a, b)
    }

    /// `a - b`.
    pub fn sub(&mut self, a: NodeId, b: NodeId) -> NodeId {
        self.binary(BinaryOp::Sub, a, b)
    }

    /// `a * b`.
    pub fn mul(&mut self, a: NodeId, b: NodeId) -> NodeId {
        self.binary(BinaryOp::Mul, a, b)
    }

    /// `a / b`.
    pub fn div(&mut self, a: NodeId, b: NodeId) -> NodeId {
        self.binary(BinaryOp::Div, a, b)
    }

    /// `min(a, b)`.
    pub fn min(&mut self, a: NodeId, b: NodeId) -> NodeId {
        self.binary(BinaryOp::Min, a, b)
    }

    /// `max(a, b)`.
    pub fn max(&mut self, a: NodeId, b: NodeId) -> NodeId {
        self.binary(BinaryOp::Max, a, b)
    }

    /// `-a`.
    pub fn neg(&mut self, a: NodeId) -> NodeId {
        self.unary(UnaryOp::Neg, a)
    }

    /// `a²`.
    pub fn sqr(&mut self, a: NodeId) -> NodeId {
        self.unary(UnaryOp::Sqr, a)
    }

    /// `√a`.
    pub fn sqrt(&mut self, a: NodeId) -> NodeId {
        self.unary(UnaryOp::Sqrt, a)
    }

    /// The nodes `root` depends on (itself included), in topological order.
    pub fn reachable(&self, roots: &[NodeId]) -> Vec<NodeId> {
        // A depth-first walk from the roots, so the cost is that of the nodes reached (a
        // context may hold far more: every reduced formula of a scene's grid cells).
        let mut seen = vec![0_u64; self.nodes.len().div_ceil(64)];
        let mut mark = |id: NodeId| {
            let (w, b) = (id.index() / 64, 1_u64 << (id.index() % 64));
            let new = seen[w] & b == 0;
            seen[w] |= b;
            new
        };
        let mut out = Vec::new();
        let mut stack: Vec<NodeId> = Vec::new();
        for &r in roots {
            if mark(r) {
                stack.push(r);
            }
        }
        while let Some(id) = stack.pop() {
            out.push(id);
            match self.nodes[id.index()] {
                Node::Unary(_, a) | Node::Pown(a, _) => {
                    if mark(a) {
                        stack.push(a);
                    }
                }
                Node::Binary(_, a, b) => {
                    for c in [a, b] {
                        if mark(c) {
                            stack.push(c);
                        }
                    }
                }
                Node::Var(_) | Node::Const(_) => {}
            }
        }
        // Operands come before their users in a context: index order is topological.
        out.sort_unstable();
        out
    }

    /// Whether every node `root` depends on is an operation defined on the whole real line
    /// ([`UnaryOp::is_total`], [`BinaryOp::is_total`], non-negative integer powers): the
    /// formula is then defined at every point, and its interval evaluation on every box.
    /// [`Tape::is_total`](crate::Tape::is_total) answers the same for a compiled tape.
    pub fn is_total(&self, root: NodeId) -> bool {
        self.reachable(&[root])
            .into_iter()
            .all(|id| match self.nodes[id.index()] {
                Node::Var(_) | Node::Const(_) => true,
                Node::Unary(op, _) => op.is_total(),
                Node::Binary(op, _, _) => op.is_total(),
                Node::Pown(_, n) => n >= 0,
            })
    }

    /// `root` with each variable of `map` replaced by its node (for example a parameter
    /// bound to a constant, which then folds into the rest of the graph).
    ///
    /// Rebuilds the nodes that depend on a replaced variable through the simplifying
    /// constructors; the others are shared.
    pub fn substitute(&mut self, root: NodeId, map: &[(Var, NodeId)]) -> NodeId {
        let nodes = self.subgraph(root);
        self.rebuild(&nodes, root, |c, v| {
            map.iter()
                .find(|(w, _)| *w == v)
                .map_or_else(|| c.intern(Node::Var(v)), |&(_, node)| node)
        })
    }

    /// A new context holding only what `root` depends on, and `root` in it. Variables keep
    /// their names; `x`, `y`, `z` keep slots 0, 1, 2 and the other variables that `root`
    /// uses follow in their old order (unused ones, such as parameters bound by
    /// [`substitute`](Self::substitute), are gone).
    pub fn extract(&self, root: NodeId) -> (Context, NodeId) {
        let nodes = self.subgraph(root);
        let mut out = Context::new();
        let mut used: Vec<Var> = nodes
            .iter()
            .filter_map(|&(_, node)| match node {
                Node::Var(v) if v.index() >= 3 => Some(v),
                _ => None,
            })
            .collect();
        used.sort();
        for v in &used {
            out.declare_var(&self.var_names[v.index()]);
        }
        let r = out.rebuild(&nodes, root, |c, v| c.named_var(&self.var_names[v.index()]));
        (out, r)
    }

    /// Copies the graph of `root` from `src` into this context through its simplifying
    /// constructors, each variable `v` of `src` becoming `var(self, v)` (a variable of this
    /// context, or any expression: a ray substitutes `c + t·d` for `x`, `y`, `z`). Returns
    /// the copy of `root`.
    pub fn copy_graph(
        &mut self,
        src: &Context,
        root: NodeId,
        var: impl FnMut(&mut Context, Var) -> NodeId,
    ) -> NodeId {
        self.rebuild(&src.subgraph(root), root, var)
    }

    /// The nodes `root` depends on with their contents, in topological order.
    fn subgraph(&self, root: NodeId) -> Vec<(NodeId, Node)> {
        self.reachable(&[root])
            .into_iter()
            .map(|id| (id, *self.get(id)))
            .collect()
    }

    /// Builds `nodes` (a [`subgraph`](Self::subgraph), possibly of another context) in this
    /// context, mapping variables with `var`; returns the node built for `root`.
    fn rebuild(
        &mut self,
        nodes: &[(NodeId, Node)],
        root: NodeId,
        mut var: impl FnMut(&mut Context, Var) -> NodeId,
    ) -> NodeId {
        let mut new: HashMap<NodeId, NodeId> =
            HashMap::with_capacity_and_hasher(nodes.len(), Default::default());
        for &(id, node) in nodes {
            let n = match node {
                Node::Var(v) => var(self, v),
                Node::Const(c) => self.constant_enclosed(c),
                Node::Unary(op, a) => self.unary(op, new[&a]),
                Node::Binary(op, a, b) => self.binary(op, new[&a], new[&b]),
                Node::Pown(a, k) => self.pown(new[&a], k),
            };
            new.insert(id, n);
        }
        new[&root]
    }

    /// Evaluates `root` directly on the graph (a reference evaluator for tests and one-off
    /// use; compile a [`Tape`](crate::Tape) for speed).
    ///
    /// Returns an error when `vars` is shorter than the number of variable slots used.
    pub fn eval<N: Number>(&self, root: NodeId, vars: &[N]) -> Result<N, Error> {
        let order = self.reachable(&[root]);
        let mut values: HashMap<NodeId, N> =
            HashMap::with_capacity_and_hasher(order.len(), Default::default());
        for id in order {
            let v = match *self.get(id) {
                Node::Var(v) => *vars.get(v.index()).ok_or(Error::MissingVar {
                    slot: v.0,
                    given: vars.len(),
                })?,
                Node::Const(c) => N::constant(&c),
                Node::Unary(op, a) => N::unary(op, values[&a]),
                Node::Binary(op, a, b) => N::binary(op, values[&a], values[&b]),
                Node::Pown(a, n) => N::pown(values[&a], n),
            };
            values.insert(id, v);
        }
        Ok(values[&root])
    }
}
