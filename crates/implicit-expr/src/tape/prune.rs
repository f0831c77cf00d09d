//! Tape pruning: after an interval evaluation over a region has recorded which argument each
//! `min` and `max` took, the operations that cannot affect the outputs inside that region
//! are dropped (as fidget and libfive do).
//!
//! A `min(a, b)` whose choice is [`Choice::Left`] equals `a` at every point of the region
//! (the interval evaluation proved `a <= b` there, with sound rounding), so it becomes `a`
//! and `b`'s subtree is dead unless used elsewhere. The pruned tape is therefore equal to
//! the original at every point of the region, for real arithmetic and for the floating-point
//! evaluators alike (their values lie inside the intervals that decided the choice).

use super::regalloc::operands;
use super::{Opcode, SsaOp, Tape};
use crate::error::Error;
use crate::number::Choice;
use crate::op::BinaryOp;

/// Buffers of [`Tape::simplify`], kept per thread: a renderer prunes once per tile.
#[derive(Default)]
struct Scratch {
    choice_of: Vec<Choice>,
    live: Vec<bool>,
    new_pos: Vec<u32>,
}

thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

impl Tape {
    /// The tape valid inside the region where `choices` were recorded (by
    /// [`Evaluator::eval_traced`](crate::eval::Evaluator::eval_traced) on this tape).
    ///
    /// Returns this tape itself (a cheap clone) when no choice is decided, and an error when
    /// `choices` does not have one entry per `min`/`max`.
    pub fn simplify(&self, choices: &[Choice]) -> Result<Tape, Error> {
        if choices.len() != self.choice_count() {
            return Err(Error::Unsupported(format!(
                "choice trace has {} entries, the tape has {} min/max operations",
                choices.len(),
                self.choice_count()
            )));
        }
        if choices.iter().all(|&c| c == Choice::Both) {
            return Ok(self.clone());
        }
        SCRATCH.with_borrow_mut(|scratch| self.simplify_with(choices, scratch))
    }

    fn simplify_with(&self, choices: &[Choice], scratch: &mut Scratch) -> Result<Tape, Error> {
        let ssa = self.ssa();
        let n = ssa.len();
        let Scratch {
            choice_of,
            live,
            new_pos,
        } = scratch;
        // Choice index of each min/max, in SSA order.
        choice_of.clear();
        choice_of.resize(n, Choice::Both);
        let mut k = 0;
        for (i, op) in ssa.iter().enumerate() {
            if matches!(op.op, Opcode::Binary(BinaryOp::Min | BinaryOp::Max)) {
                choice_of[i] = choices[k];
                k += 1;
            }
        }
        // Backward pass: liveness, with decided min/max forwarding to one argument.
        live.clear();
        live.resize(n, false);
        for &o in self.ssa_outputs() {
            live[o as usize] = true;
        }
        for i in (0..n).rev() {
            if !live[i] {
                continue;
            }
            let op = &ssa[i];
            match choice_of[i] {
                Choice::Left => live[op.a as usize] = true,
                Choice::Right => live[op.b as usize] = true,
                Choice::Both => {
                    let (args, k) = operands(op);
                    for &a in &args[..k] {
                        live[a as usize] = true;
                    }
                }
            }
        }
        // Forward pass: renumber, resolving forwarded min/max to their argument.
        new_pos.clear();
        new_pos.resize(n, u32::MAX);
        let mut out: Vec<SsaOp> = Vec::with_capacity(n);
        let mut consts = Vec::new();
        for i in 0..n {
            if !live[i] {
                continue;
            }
            let op = ssa[i];
            match choice_of[i] {
                Choice::Left => {
                    new_pos[i] = new_pos[op.a as usize];
                    continue;
                }
                Choice::Right => {
                    new_pos[i] = new_pos[op.b as usize];
                    continue;
                }
                Choice::Both => {}
            }
            let mut new = op;
            match op.op {
                Opcode::Const => {
                    consts.push(self.consts()[op.a as usize]);
                    new.a = (consts.len() - 1) as u32;
                }
                Opcode::Var => {}
                _ => {
                    let (_, k) = operands(&op);
                    if k >= 1 {
                        new.a = new_pos[op.a as usize];
                    }
                    if k == 2 {
                        new.b = new_pos[op.b as usize];
                    }
                }
            }
            new_pos[i] = out.len() as u32;
            out.push(new);
        }
        let outputs = self
            .ssa_outputs()
            .iter()
            .map(|&o| new_pos[o as usize])
            .collect();
        Ok(Tape::from_ssa(
            out,
            consts,
            outputs,
            self.var_count() as u32,
        ))
    }
}
