//! Tape pruning: after an interval evaluation over a region has recorded which argument each
//! `min` and `max` took, the operations that cannot affect the outputs inside that region
//! are dropped (as fidget and libfive do).
//!
//! A `min(a, b)` whose choice is [`Choice::Left`] equals `a` at every point of the region
//! (the interval evaluation proved `a <= b` there, with sound rounding), so it becomes `a`
//! and `b`'s subtree is dead unless used elsewhere. The pruned tape is therefore equal to
//! the original at every point of the region, for real arithmetic and for the floating-point
//! evaluators alike (their values lie inside the intervals that decided the choice).

use super::Tape;
use super::regalloc::{Compiled, compile};
use crate::error::Error;
use crate::number::Choice;

impl Tape {
    /// The tape valid inside the region where `choices` were recorded (by
    /// [`Evaluator::eval_traced`](crate::eval::Evaluator::eval_traced) on this tape).
    ///
    /// Returns this tape itself (a cheap clone) when no choice is decided, and an error when
    /// `choices` does not have one entry per `min`/`max`.
    pub fn simplify(&self, choices: &[Choice]) -> Result<Tape, Error> {
        self.pruned_with(choices, Tape::of_parts)
    }

    /// [`simplify`](Self::simplify), where the pruned tape is made by `keep` from its
    /// parts and variable count (or found among tapes made before: a pruning that arrives
    /// at a formula made before then allocates nothing).
    pub(super) fn pruned_with(
        &self,
        choices: &[Choice],
        keep: impl FnOnce(&Compiled<'_>, u32) -> Tape,
    ) -> Result<Tape, Error> {
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
        let var_count = self.var_count() as u32;
        Ok(compile(
            (self.ssa(), self.consts(), self.ssa_outputs(), var_count),
            |i| self.choice_index(i).map_or(Choice::Both, |k| choices[k]),
            |c| keep(&c, var_count),
        ))
    }
}
