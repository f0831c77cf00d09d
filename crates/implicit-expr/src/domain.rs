//! Domain extension: a formula whose operations are undefined on part of space (`√`, the
//! logarithms, `asin`, `acos`, a real power) turned into one that is defined everywhere,
//! `f` where the formula is defined and `+∞` ("no object") where it is not.
//!
//! Interval arithmetic in IEEE 1788's set-based model evaluates an operation over the part
//! of its argument where it is defined and gives the empty set where it is nowhere defined.
//! In a scene function `min(f₁, f₂, …)` that empty set hides every other object: one object
//! undefined in a region erases the others there. The extension makes an object absent
//! where its formula is undefined, which is what `min` (union), `max` (intersection) and
//! `max(a, −b)` (difference) need: `+∞` is outside every solid, and `−(+∞)` is inside.
//!
//! [`Context::domain_split`] rewrites each partial operation `op(a)` to the total
//! `op(clamp(a))`, with `a` clamped to the operation's domain (`max(a, 0)` for `√`,
//! `max(a, 2^-126)` for `ln`, `log` and the base of `pow`, `[−1, 1]` for `asin` and `acos`),
//! and collects a test `t ≤ 0` of each domain (`−a`, `2^-126 − a` and `|a| − 1`): the
//! clamped formula equals the original wherever every test holds, and the tests are built
//! from clamped values, so they are total too. The logarithms and real powers thus count
//! arguments in `(0, 2^-126)` as outside their domain (absent): their values there, below
//! `ln 2^-126 ≈ −87.3`, are left out rather than approximated.
//! [`Context::domain_extension`] joins the tests by `max` into one function `d` and returns
//! [`BinaryOp::Domain`]`(d, f)`.
//!
//! The poles of `1/a`, `a/b` and `tan` are points or surfaces, not regions: they stay as
//! they are (a box around one is undefined, so no proof holds there).

use rustc_hash::FxHashMap as HashMap;

use crate::context::{Context, Node, NodeId};
use crate::op::{BinaryOp, UnaryOp};

/// The smallest argument of the logarithms and the smallest base of a real power inside
/// their domains here: `2^-126`, the smallest normal `f32` (exact in `f32` and `f64`). The
/// formulas are undefined at 0 (or unbounded, for negative exponents), so their clamped
/// forms stop at a positive number; in `f32` no smaller one keeps the clamp exact.
const SMALLEST_ARGUMENT: f64 = f32::MIN_POSITIVE as f64;

impl Context {
    /// The total form of `f` and the tests of its domain: `(g, tests)` where `g` equals `f`
    /// wherever every test is `≤ 0` and is defined everywhere else too (see the module
    /// documentation). `tests` is empty when `f` has no partial operation with a region as
    /// its domain (then `g == f`); tests that are constants `≤ 0` are left out.
    pub fn domain_split(&mut self, f: NodeId) -> (NodeId, Vec<NodeId>) {
        let order = self.reachable(&[f]);
        let zero = self.constant(0.0).expect("finite");
        let one = self.constant(1.0).expect("finite");
        let minus_one = self.constant(-1.0).expect("finite");
        let tiny = self.constant(SMALLEST_ARGUMENT).expect("finite");
        let mut total: HashMap<NodeId, NodeId> =
            HashMap::with_capacity_and_hasher(order.len(), Default::default());
        let mut tests = Vec::new();
        for id in order {
            let new = match *self.get(id) {
                Node::Var(_) | Node::Const(_) => id,
                Node::Unary(op, a) => {
                    let a = total[&a];
                    match op {
                        UnaryOp::Sqrt => {
                            tests.push(self.neg(a));
                            let c = self.max(a, zero);
                            self.unary(op, c)
                        }
                        UnaryOp::Ln | UnaryOp::Log10 => {
                            tests.push(self.sub(tiny, a));
                            let c = self.max(a, tiny);
                            self.unary(op, c)
                        }
                        UnaryOp::Asin | UnaryOp::Acos => {
                            let m = self.unary(UnaryOp::Abs, a);
                            tests.push(self.sub(m, one));
                            let c = self.max(a, minus_one);
                            let c = self.min(c, one);
                            self.unary(op, c)
                        }
                        _ => self.unary(op, a),
                    }
                }
                Node::Binary(op, a, b) => {
                    let (a, b) = (total[&a], total[&b]);
                    if op == BinaryOp::Pow {
                        tests.push(self.sub(tiny, a));
                        let c = self.max(a, tiny);
                        self.binary(op, c, b)
                    } else {
                        self.binary(op, a, b)
                    }
                }
                Node::Pown(a, n) => {
                    let a = total[&a];
                    self.pown(a, n)
                }
            };
            total.insert(id, new);
        }
        tests.retain(|&t| self.as_const(t).is_none_or(|c| c.hi() > 0.0));
        tests.sort_unstable();
        tests.dedup();
        (total[&f], tests)
    }

    /// `f` extended by "no object" where it is undefined: `domain(d, g)` with `(g, tests)`
    /// from [`domain_split`](Self::domain_split) and `d` the `max` of the tests; `f` itself
    /// when it has no domain test.
    pub fn domain_extension(&mut self, f: NodeId) -> NodeId {
        let (g, tests) = self.domain_split(f);
        match tests.into_iter().reduce(|acc, t| self.max(acc, t)) {
            Some(d) => self.binary(BinaryOp::Domain, d, g),
            None => f,
        }
    }
}
