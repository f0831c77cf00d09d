//! Pruned tapes kept for reuse: a renderer prunes the same tape by the same choices again
//! and again (the sibling cells of a subdivision, the neighbouring tiles of a region that
//! one branch of the model fills), and a lookup costs a hash of the choices where a
//! [`Tape::simplify`] costs a pass over the whole tape.

use std::hash::{Hash, Hasher};

use rustc_hash::{FxHashMap, FxHasher};

use super::Tape;
use crate::error::Error;
use crate::number::Choice;

/// The instructions of tapes a [`PruneCache`] holds (each entry's pruned tape and the tape
/// it was pruned from, counted again for every entry that holds it) before it starts
/// afresh: a few megabytes.
const HELD_INSTRS: usize = 1 << 18;

/// One pruning kept: the tape, the choices and the result.
#[derive(Clone, Debug)]
struct Pruned {
    /// Held, so that its address is not reused by another tape while the entry lives.
    parent: Tape,
    choices: Box<[Choice]>,
    pruned: Tape,
}

/// [`Tape::simplify`] with the results kept: pruning a tape by choices it was pruned by
/// before returns the tape made then (the very same `Arc`, so evaluators that hold it do
/// not reload their constants), bit for bit what `simplify` makes.
///
/// Keyed by the tape's identity and the choices (compared in full on a hit, so a hash
/// collision only costs a pruning). The pruned tapes are also interned by content: a
/// pruning that arrives at a formula made before (from another tape: on the CSG models
/// three prunings in four do) returns the tape made then, so that what is keyed or counted
/// by tape identity downstream (this cache's own entries for the prunings of that tape,
/// the evaluations after which a tape is compiled, [`crate::jit`]) is shared. It holds
/// at most about 2^18 instructions of tapes (the pruned ones and those they were pruned
/// from, which it keeps alive) and empties itself when full. Make one per thread, next to
/// the evaluator that prunes.
#[derive(Clone, Debug, Default)]
pub struct PruneCache {
    entries: FxHashMap<(usize, u64), Pruned>,
    /// The pruned tapes made, by the hash of their content.
    interned: FxHashMap<u64, Tape>,
    held: usize,
    hits: u64,
    misses: u64,
}

impl PruneCache {
    /// An empty cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// `tape.simplify(choices)`, from the cache where that pruning was made before.
    ///
    /// Returns the error of [`Tape::simplify`] when `choices` does not have one entry per
    /// `min`/`max` of `tape`.
    pub fn simplify(&mut self, tape: &Tape, choices: &[Choice]) -> Result<Tape, Error> {
        if choices.len() != tape.choice_count() || choices.iter().all(|&c| c == Choice::Both) {
            // An error, or the tape itself: nothing to keep.
            return tape.simplify(choices);
        }
        let mut h = FxHasher::default();
        choices.hash(&mut h);
        let key = (tape.id(), h.finish());
        if let Some(e) = self.entries.get(&key)
            && e.parent.ptr_eq(tape)
            && *e.choices == *choices
        {
            self.hits += 1;
            return Ok(e.pruned.clone());
        }
        self.misses += 1;
        let interned = &mut self.interned;
        let pruned = tape.pruned_with(choices, |c, var_count| match interned.get(&c.hash) {
            Some(same) if same.has_parts(c, var_count) => same.clone(),
            _ => {
                // A new formula (or, rarely, another of the same hash, which then takes
                // its place).
                let made = Tape::of_parts(c, var_count);
                interned.insert(c.hash, made.clone());
                made
            }
        })?;
        let size = tape.len() + pruned.len();
        if self.held + size > HELD_INSTRS {
            self.clear();
        }
        self.held += size;
        let entry = Pruned {
            parent: tape.clone(),
            choices: choices.into(),
            pruned: pruned.clone(),
        };
        if let Some(old) = self.entries.insert(key, entry) {
            // A collision of the hash: the older entry goes.
            self.held -= old.parent.len() + old.pruned.len();
        }
        Ok(pruned)
    }

    /// The prunings answered from the cache so far.
    pub fn hits(&self) -> u64 {
        self.hits
    }

    /// The prunings made (not found in the cache) so far.
    pub fn misses(&self) -> u64 {
        self.misses
    }

    /// Forgets every pruning kept (and the tapes they hold).
    pub fn clear(&mut self) {
        self.entries.clear();
        self.interned.clear();
        self.held = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::context::Context;
    use crate::eval::Evaluator;
    use interval_core::Interval;

    fn tape() -> Tape {
        let mut ctx = Context::new();
        let root = crate::parse::parse(&mut ctx, "min(max(x - 1, y), min(x * x - 2, y + z))", &[])
            .expect("parses");
        Tape::new(&ctx, &[root]).expect("compiles")
    }

    /// Over boxes that decide some choices, the cache returns what `simplify` makes, the
    /// same tape object on a repeat, and for another tape with equal choices a pruning made
    /// afresh, interned as the equal formula made before.
    #[test]
    fn cached_prunings_equal_fresh_ones() {
        let t = tape();
        let mut ev = Evaluator::<Interval<f64>>::new(&t);
        let mut cache = PruneCache::new();
        let mut trace = Vec::new();
        let iv = |a: f64, b: f64| Interval::new(a, b).expect("ordered");
        let boxes = [
            [iv(3.0, 4.0), iv(-1.0, 0.0), iv(0.0, 1.0)],
            [iv(-4.0, -3.0), iv(5.0, 6.0), iv(-9.0, -8.0)],
            [iv(3.0, 4.0), iv(-1.0, 0.0), iv(0.0, 1.0)],
            [iv(-1.0, 1.0), iv(-1.0, 1.0), iv(-1.0, 1.0)],
        ];
        let mut seen = Vec::new();
        for b in &boxes {
            ev.eval_traced(b, &mut trace).expect("three slots");
            let fresh = t.simplify(&trace).expect("one entry per choice");
            let cached = cache.simplify(&t, &trace).expect("one entry per choice");
            assert_eq!(fresh.instrs(), cached.instrs());
            assert_eq!(fresh.ssa(), cached.ssa());
            assert_eq!(fresh.outputs(), cached.outputs());
            seen.push(cached);
        }
        assert!(seen[0].ptr_eq(&seen[2]), "a repeat is the same tape");
        // Other choices, the same formula (`y + z`): a miss, interned as the first.
        assert!(seen[0].ptr_eq(&seen[1]));
        assert!(!seen[0].ptr_eq(&seen[3]));
        assert_eq!(cache.hits(), 1);
        // Another tape with the same number of choices, pruned by the same choices, is
        // pruned afresh (a miss), to the formula made before: the same tape object.
        let other = tape();
        ev.set_tape(&other);
        ev.eval_traced(&boxes[0], &mut trace).expect("three slots");
        let misses = cache.misses();
        let p = cache
            .simplify(&other, &trace)
            .expect("one entry per choice");
        assert_eq!((cache.hits(), cache.misses()), (1, misses + 1));
        assert!(p.ptr_eq(&seen[0]), "interned");
        // A formula not made before is its own tape.
        let other_box = [iv(10.0, 11.0), iv(-3.0, -2.0), iv(-5.0, -4.0)];
        ev.eval_traced(&other_box, &mut trace).expect("three slots");
        let q = cache
            .simplify(&other, &trace)
            .expect("one entry per choice");
        assert_eq!(q.ssa(), other.simplify(&trace).expect("pruned").ssa());
        // A wrong number of choices is the same error as simplify's.
        assert!(cache.simplify(&t, &trace[1..]).is_err());
    }
}
