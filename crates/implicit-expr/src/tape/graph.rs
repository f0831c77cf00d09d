//! From a tape back to an expression graph, and tapes compared by content.
//!
//! A pruned tape ([`Tape::simplify`]) is a new formula, valid inside the region it was
//! pruned for. Whatever is derived from formulas (derivatives, the restriction to a ray of
//! [`RayFunction`](crate::RayFunction)) is derived from the graph that
//! [`Tape::to_context`] rebuilds. Many regions prune to the same tape: [`Tape`] compares
//! and hashes by content (its SSA operations, constants and outputs), so that a cache keyed
//! by tapes holds each distinct formula once.

use std::hash::{Hash, Hasher};

use super::{Opcode, Tape};
use crate::context::{Context, NodeId, Var};
use crate::error::Error;

impl Tape {
    /// The graph of the tape's SSA operations in a new context whose variable slots are
    /// named `names` (slot `i` is `names[i]`; slots 0, 1, 2 are `x`, `y`, `z` in every
    /// context, whatever `names` says), and the nodes of the outputs, in order.
    ///
    /// Returns an error when fewer names than the tape's variable slots are given.
    pub fn to_context(&self, names: &[&str]) -> Result<(Context, Vec<NodeId>), Error> {
        if names.len() < self.var_count() {
            return Err(Error::MissingVar {
                slot: names.len() as u32,
                given: names.len(),
            });
        }
        let mut ctx = Context::new();
        let vars: Vec<NodeId> = (0..self.var_count())
            .map(|i| match i {
                0 => ctx.x(),
                1 => ctx.y(),
                2 => ctx.z(),
                i => ctx.named_var(names[i]),
            })
            .collect();
        let mut nodes: Vec<NodeId> = Vec::with_capacity(self.ssa().len());
        for op in self.ssa() {
            let node = match op.op {
                Opcode::Var => vars[Var(op.a).index()],
                Opcode::Const => ctx.constant_enclosed(self.consts()[op.a as usize]),
                Opcode::Copy => nodes[op.a as usize],
                Opcode::Unary(u) => ctx.unary(u, nodes[op.a as usize]),
                Opcode::Binary(b) => ctx.binary(b, nodes[op.a as usize], nodes[op.b as usize]),
                Opcode::Pown => ctx.pown(nodes[op.a as usize], op.b as i32),
            };
            nodes.push(node);
        }
        let outputs = self
            .ssa_outputs()
            .iter()
            .map(|&o| nodes[o as usize])
            .collect();
        Ok((ctx, outputs))
    }
}

/// Tapes are equal when they compute the same operations on the same constants in the same
/// order, with the same outputs and variable slots (two handles of one tape always are).
impl PartialEq for Tape {
    fn eq(&self, other: &Tape) -> bool {
        self.ptr_eq(other)
            || (self.var_count() == other.var_count()
                && self.ssa_outputs() == other.ssa_outputs()
                && self.ssa() == other.ssa()
                && self.consts() == other.consts())
    }
}

impl Eq for Tape {}

impl Hash for Tape {
    /// The content's hash (made once per tape and kept): interning pruned
    /// tapes and finding their compiled code hash each one more than once.
    fn hash<H: Hasher>(&self, state: &mut H) {
        state.write_u64(self.content_hash());
    }
}

impl Tape {
    /// A hash of what [`PartialEq`] compares (variable count, outputs, operations,
    /// constants), computed on first use and kept.
    pub(crate) fn content_hash(&self) -> u64 {
        *self.0.content_hash.get_or_init(|| {
            super::regalloc::content_hash(
                self.var_count() as u32,
                self.ssa_outputs(),
                self.ssa(),
                self.consts(),
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;

    use crate::context::Context;
    use crate::eval::Evaluator;
    use crate::number::Choice;
    use crate::parse::parse;
    use crate::tape::Tape;

    #[test]
    fn a_tape_rebuilt_as_a_graph_computes_the_same() {
        let mut ctx = Context::new();
        let f = parse(
            &mut ctx,
            "min(sqrt(x^2 + y^2) - 0.5, max(z, 2*x)) + sin(y)^3",
            &[],
        )
        .unwrap();
        let tape = Tape::new(&ctx, &[f]).unwrap();
        let (rebuilt, roots) = tape.to_context(&["x", "y", "z"]).unwrap();
        assert_eq!(Tape::new(&rebuilt, &roots).unwrap().len(), tape.len());
        let mut e = Evaluator::<f64>::new(&tape);
        for p in [[0.1, 0.2, 0.3], [-1.0, 2.0, 0.5], [3.0, -0.25, -2.0]] {
            assert_eq!(
                e.eval(&p).unwrap(),
                rebuilt.eval::<f64>(roots[0], &p).unwrap()
            );
        }
        assert!(tape.to_context(&["x"]).is_err());
    }

    #[test]
    fn pruned_tapes_compare_by_content() {
        let mut ctx = Context::new();
        let f = parse(&mut ctx, "min(x, y) + max(y, z)", &[]).unwrap();
        let tape = Tape::new(&ctx, &[f]).unwrap();
        let a = tape.simplify(&[Choice::Left, Choice::Both]).unwrap();
        let b = tape.simplify(&[Choice::Left, Choice::Both]).unwrap();
        let c = tape.simplify(&[Choice::Right, Choice::Both]).unwrap();
        assert!(!a.ptr_eq(&b));
        assert_eq!(a, b);
        assert_ne!(a, c);
        let set: HashSet<Tape> = [a, b, c, tape.clone(), tape].into_iter().collect();
        assert_eq!(set.len(), 3);
    }
}
