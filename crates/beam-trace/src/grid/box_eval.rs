//! A per-thread interval evaluator over boxes, switched between the tapes of cells, leaves
//! and blocks, and the pruning of a tape to a box with it.

use implicit_expr::{Choice, Evaluator, Tape};
use interval_core::Interval;

use crate::ibox::IBox;

/// An interval evaluator created on first use and switched to each tape asked for, with
/// the buffer of its choice traces.
#[derive(Default)]
pub(super) struct BoxEval {
    eval: Option<Evaluator<Interval<f64>>>,
    trace: Vec<Choice>,
    /// The tape and box whose choices `trace` holds, after [`BoxEval::defined_on`].
    traced: Option<(Tape, IBox)>,
}

impl BoxEval {
    /// The evaluator, set to `tape`.
    pub(super) fn on(&mut self, tape: &Tape) -> &mut Evaluator<Interval<f64>> {
        if let Some(e) = &mut self.eval {
            e.set_tape(tape);
        }
        self.eval.get_or_insert_with(|| Evaluator::new(tape))
    }

    /// `tape` pruned to the box `b` ([`Evaluator::pruned`]): equal to it on `b`; `tape`
    /// itself where it has no `min`/`max` or nothing is decided. Right after
    /// [`defined_on`](Self::defined_on) of the same tape and box, without evaluating again.
    pub(super) fn pruned(&mut self, tape: &Tape, b: &IBox) -> Tape {
        if tape.choice_count() == 0 {
            return tape.clone();
        }
        if let Some((t, tb)) = self.traced.take()
            && t.ptr_eq(tape)
            && tb == *b
        {
            return tape.simplify(&self.trace).unwrap_or_else(|_| tape.clone());
        }
        let mut trace = std::mem::take(&mut self.trace);
        let p = self
            .on(tape)
            .pruned(b, &mut trace)
            .unwrap_or_else(|_| tape.clone());
        self.trace = trace;
        p
    }

    /// The enclosure of `tape` over `b`, and whether `tape` is proven defined at every point
    /// of `b` (decorated at least `def`: a jump, such as the boundary of a partial domain
    /// inside `b`, keeps the sign of the enclosure at every point). The evaluation records
    /// the `min`/`max` choices too, for a [`pruned`](Self::pruned) of the same box that
    /// follows.
    pub(super) fn defined_on(&mut self, tape: &Tape, b: &IBox) -> (Interval<f64>, bool) {
        let mut trace = std::mem::take(&mut self.trace);
        let r = self
            .on(tape)
            .eval_traced_defined(b, &mut trace)
            .expect("tape in x y z");
        self.trace = trace;
        self.traced = Some((tape.clone(), *b));
        r
    }
}

thread_local! {
    static THREAD_EVAL: std::cell::RefCell<BoxEval> = std::cell::RefCell::new(BoxEval::default());
}

/// `f` with this thread's [`BoxEval`], for work that runs outside a pass with its own
/// per-thread evaluators (tapes built on first use, the root of a classification).
pub(super) fn with_thread_eval<R>(f: impl FnOnce(&mut BoxEval) -> R) -> R {
    THREAD_EVAL.with_borrow_mut(f)
}
