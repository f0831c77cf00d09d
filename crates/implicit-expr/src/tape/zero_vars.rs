//! Tapes with some variables fixed at 0: the operations that then pass one argument through
//! unchanged are forwarded away, as pruning forwards a decided `min`/`max`.
//!
//! A ray tape `g(c, t, d) = f(c + t·d)` evaluated with `t = 0` and `d = 0` (the value of
//! `f` over a box of points `c`, as a centred form asks) spends its first operations on
//! `c + 0·0`: three products of zeros and three sums. With `t` and `d` fixed at 0 they fold
//! to `c` itself.

use super::Tape;
use super::regalloc::compile;
use crate::number::Choice;
use crate::op::{BinaryOp, UnaryOp};

use super::Opcode;

impl Tape {
    /// The tape equal to this one wherever the variables of the slots in `slots` are 0:
    /// each value that is then 0 (those variables, the product of two such values or of one
    /// with a variable, the sum or difference of two, a negated one) is known, and an
    /// operation that adds or subtracts a 0, or multiplies by one, passes the other
    /// argument (or the 0) through. A product with a 0 is folded only where the other
    /// factor is a variable or a 0 as well, which every point defines (`x · 0` is not 0
    /// where `x` is undefined). The variable slots stay as they are; this tape itself
    /// (a cheap clone) where nothing folds.
    ///
    /// Equal means: the same intervals, and the same forward-mode gradients with respect to
    /// variables not in `slots` (those in `slots` must be constants of the differentiation:
    /// `x · y` at `x = 0` folds to `x`, whose derivative in `x` is not `y`'s); a point
    /// evaluation may give a zero of the other sign (`x · t` with `x < 0`).
    pub fn with_zero_vars(&self, slots: &[u32]) -> Tape {
        let ssa = self.ssa();
        let mut zero = vec![false; ssa.len()];
        let mut choice = vec![Choice::Both; ssa.len()];
        let mut folds = false;
        for (i, op) in ssa.iter().enumerate() {
            let (a, b) = (op.a as usize, op.b as usize);
            let var = |k: usize| ssa[k].op == Opcode::Var;
            let (z, c) = match op.op {
                Opcode::Var => (slots.contains(&op.a), Choice::Both),
                Opcode::Copy => (zero[a], Choice::Both),
                Opcode::Unary(UnaryOp::Neg) if zero[a] => (true, Choice::Left),
                Opcode::Binary(BinaryOp::Mul) if zero[a] && (zero[b] || var(b)) => {
                    (true, Choice::Left)
                }
                Opcode::Binary(BinaryOp::Mul) if zero[b] && var(a) => (true, Choice::Right),
                Opcode::Binary(BinaryOp::Add | BinaryOp::Sub) if zero[b] => (zero[a], Choice::Left),
                Opcode::Binary(BinaryOp::Add) if zero[a] => (zero[b], Choice::Right),
                _ => (false, Choice::Both),
            };
            zero[i] = z;
            choice[i] = c;
            folds |= c != Choice::Both;
        }
        if !folds {
            return self.clone();
        }
        let var_count = self.var_count() as u32;
        compile(
            (ssa, self.consts(), self.ssa_outputs(), var_count),
            |i| choice[i],
            |c| Tape::of_parts(&c, var_count),
        )
    }
}
