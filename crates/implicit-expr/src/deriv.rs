//! Symbolic differentiation on the graph.
//!
//! [`Context::deriv`] builds ∂f/∂v as nodes of the same context, so the derivative shares
//! every common subexpression with `f` (and with the other partials): a tape with outputs
//! `f, ∂f/∂x, ∂f/∂y, ∂f/∂z` evaluates each shared node once. The rules are the usual ones;
//! `min`/`max` differentiate through a selection that interval evaluation widens to both
//! branches where undecided, and the step functions differentiate to their slopes (zero
//! away from jumps, unbounded across them), so interval enclosures of derivatives stay
//! sound wherever they are used for mean-value arguments.
//!
//! The pass is a loop over node ids (no recursion).

use rustc_hash::FxHashMap as HashMap;

use crate::context::{Context, Node, NodeId, Var};
use crate::op::{BinaryOp, UnaryOp};

impl Context {
    /// ∂`f`/∂`v` as a node of this context.
    pub fn deriv(&mut self, f: NodeId, v: Var) -> NodeId {
        let order = self.reachable(&[f]);
        let zero = self.constant(0.0).expect("finite");
        let one = self.constant(1.0).expect("finite");
        let mut d: HashMap<NodeId, NodeId> =
            HashMap::with_capacity_and_hasher(order.len(), Default::default());
        for id in order {
            let node = *self.get(id);
            let di = match node {
                Node::Var(w) => {
                    if w == v {
                        one
                    } else {
                        zero
                    }
                }
                Node::Const(_) => zero,
                Node::Unary(op, a) => {
                    let da = d[&a];
                    if da == zero {
                        zero
                    } else {
                        let s = self.unary_slope(op, a, id);
                        self.mul(s, da)
                    }
                }
                Node::Pown(a, n) => {
                    let da = d[&a];
                    if da == zero {
                        zero
                    } else {
                        let p = self.pown(a, n - 1);
                        let k = self.constant(f64::from(n)).expect("finite");
                        let s = self.mul(k, p);
                        self.mul(s, da)
                    }
                }
                Node::Binary(op, a, b) => {
                    let (da, db) = (d[&a], d[&b]);
                    if da == zero && db == zero {
                        zero
                    } else {
                        self.binary_deriv(op, a, b, da, db, id)
                    }
                }
            };
            d.insert(id, di);
        }
        d[&f]
    }

    /// The gradient `[∂f/∂x, ∂f/∂y, ∂f/∂z]`.
    pub fn gradient(&mut self, f: NodeId) -> [NodeId; 3] {
        [Var::X, Var::Y, Var::Z].map(|v| self.deriv(f, v))
    }

    /// d op(a) / da, where `node = op(a)`.
    fn unary_slope(&mut self, op: UnaryOp, a: NodeId, node: NodeId) -> NodeId {
        let one = self.constant(1.0).expect("finite");
        match op {
            UnaryOp::Neg => self.constant(-1.0).expect("finite"),
            // |a| = max(a, -a), so |a|' = 1 + (-1 - 1)·[a <= -a]: -1, 1, or [-1, 1]
            // over an interval holding 0.
            UnaryOp::Abs => {
                let na = self.neg(a);
                let m1 = self.constant(-1.0).expect("finite");
                self.select_slope(BinaryOp::Max, a, na, one, m1)
            }
            UnaryOp::Sqr => {
                let two = self.constant(2.0).expect("finite");
                self.mul(two, a)
            }
            UnaryOp::Sqrt => {
                let half = self.constant(0.5).expect("finite");
                self.div(half, node)
            }
            UnaryOp::Recip => {
                let s = self.sqr(node);
                self.neg(s)
            }
            UnaryOp::Exp => node,
            UnaryOp::Ln => self.unary(UnaryOp::Recip, a),
            UnaryOp::Log10 => {
                let ln10 = std::f64::consts::LN_10;
                let c = crate::Constant::enclosed(ln10, ln10.next_down(), ln10.next_up())
                    .expect("finite");
                let k = self.constant_enclosed(c);
                let p = self.mul(a, k);
                self.unary(UnaryOp::Recip, p)
            }
            UnaryOp::Sin => self.unary(UnaryOp::Cos, a),
            UnaryOp::Cos => {
                let s = self.unary(UnaryOp::Sin, a);
                self.neg(s)
            }
            UnaryOp::Tan => {
                let s = self.sqr(node);
                self.add(one, s)
            }
            UnaryOp::Asin | UnaryOp::Acos => {
                let s = self.sqr(a);
                let r = self.sub(one, s);
                let r = self.sqrt(r);
                let r = self.unary(UnaryOp::Recip, r);
                if op == UnaryOp::Acos { self.neg(r) } else { r }
            }
            UnaryOp::Atan => {
                let s = self.sqr(a);
                let r = self.add(one, s);
                self.unary(UnaryOp::Recip, r)
            }
            UnaryOp::Floor | UnaryOp::Ceil => self.unary(UnaryOp::SlopeFloor, a),
            UnaryOp::Round => self.unary(UnaryOp::SlopeRound, a),
            UnaryOp::Not => self.unary(UnaryOp::SlopeNot, a),
            UnaryOp::SlopeFloor | UnaryOp::SlopeRound | UnaryOp::SlopeNot => self.unary(op, a),
        }
    }

    /// The derivative of `min(a, b)` or `max(a, b)` given `da` and `db`.
    ///
    /// With the indicator `H = [a <= b] = not(max(a - b, 0))`, `min(a, b)' = db + (da - db)·H`
    /// and `max(a, b)' = da + (db - da)·H`. Over intervals where the order of `a` and `b` is
    /// decided, `H` is exactly 0 or 1 and the result is the taken branch's derivative; where
    /// it is not, `H = [0, 1]` and the result encloses the hull of both derivatives (Clarke's
    /// generalised gradient), which keeps mean-value arguments sound.
    fn select_slope(
        &mut self,
        op: BinaryOp,
        a: NodeId,
        b: NodeId,
        da: NodeId,
        db: NodeId,
    ) -> NodeId {
        if da == db {
            return da;
        }
        let zero = self.constant(0.0).expect("finite");
        let diff = self.sub(a, b);
        let pos = self.max(diff, zero);
        let h = self.unary(UnaryOp::Not, pos);
        let (base, other) = if op == BinaryOp::Min {
            (db, da)
        } else {
            (da, db)
        };
        let delta = self.sub(other, base);
        let t = self.mul(delta, h);
        self.add(base, t)
    }

    fn binary_deriv(
        &mut self,
        op: BinaryOp,
        a: NodeId,
        b: NodeId,
        da: NodeId,
        db: NodeId,
        node: NodeId,
    ) -> NodeId {
        match op {
            BinaryOp::Add => self.add(da, db),
            BinaryOp::Sub => self.sub(da, db),
            BinaryOp::Mul => {
                let l = self.mul(a, db);
                let r = self.mul(b, da);
                self.add(l, r)
            }
            BinaryOp::Div => {
                // (da - (a/b)·db) / b
                let q = self.mul(node, db);
                let n = self.sub(da, q);
                self.div(n, b)
            }
            BinaryOp::Min | BinaryOp::Max => self.select_slope(op, a, b, da, db),
            // `f'` inside the domain, the absent object's `+inf` outside, and unbounded
            // (the slope of `not`) over any interval where `d` crosses 0, the jump.
            BinaryOp::Domain => {
                let inside = self.binary(BinaryOp::Domain, a, db);
                let jump = self.unary(UnaryOp::SlopeNot, a);
                self.add(inside, jump)
            }
            BinaryOp::Pow => {
                // b·a^(b-1)·da + a^b·ln(a)·db
                let one = self.constant(1.0).expect("finite");
                let bm1 = self.sub(b, one);
                let p = self.binary(BinaryOp::Pow, a, bm1);
                let sa = self.mul(b, p);
                let ta = self.mul(sa, da);
                let l = self.unary(UnaryOp::Ln, a);
                let sb = self.mul(node, l);
                let tb = self.mul(sb, db);
                self.add(ta, tb)
            }
        }
    }
}
