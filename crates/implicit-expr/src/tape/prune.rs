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
use crate::error::Error;
use crate::number::Choice;

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
        Ok(Tape::compiled(
            self.ssa(),
            self.consts(),
            self.ssa_outputs(),
            self.var_count() as u32,
            |i| self.choice_index(i).map_or(Choice::Both, |k| choices[k]),
        ))
    }
}
