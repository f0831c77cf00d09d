//! Rays searched with the scope of the beam they lie in.
//!
//! A classified beam hands on its scope ([`BeamScope`]): the scene function pruned to the
//! beam over the parameter range its search ended in. Every ray of the beam is inside that
//! region over those parameters, so a ray whose window lies in the range can be searched
//! with the pruned tape alone, which is *equal* to the scene function at every point of the
//! region: no grid walk, no cell functions, and often a handful of instructions instead of
//! hundreds. The pruned formula gets a derivative of its own
//! ([`RayFunction::from_ray_tape`]), equal to `g'` wherever `g` is differentiable in the
//! region, and tighter over intervals where a `min`/`max` was decided.
//!
//! Many beams prune to the same formula (the boxes on one face of a model), so the compiled
//! functions are shared by content, and each thread remembers the last one it used (the
//! rays of one box come one after the other).

use std::sync::{Arc, RwLock};

use implicit_expr::{RayFunction, Tape};
use interval_core::Interval;
use rustc_hash::FxHashMap;

use crate::beam::BeamScope;
use crate::grid::Grid;
use crate::ray::{BeamEval, Precision};

/// Scopes longer than this are not compiled for rays (each distinct one costs a symbolic
/// derivative and a compilation, which a ray through the grid's cells does not).
const SCOPED_MAX_LEN: usize = 64;

/// The instructions a ray form adds to a formula in `x y z` (`c + t·d` per axis).
const RAY_FORM: usize = 6;

/// The ray functions of the scopes rays were searched with, by tape content. A lookup
/// hashes the whole tape, once per ray whose scope differs from its thread's last one (the
/// undecided pixels of the frustum octree each have their own): Fx hashing, not SipHash,
/// whose resistance to chosen keys a cache of the renderer's own tapes does not need.
#[derive(Debug)]
pub(super) struct ScopedFunctions {
    map: RwLock<FxHashMap<Tape, Option<Arc<RayFunction>>>>,
    /// The longest scope searched instead of the grid's cells.
    max_len: usize,
}

impl ScopedFunctions {
    /// No function yet. With a `grid`, a scope is searched only where its tape is at most
    /// half again as long as the ray form of the grid's cell functions on average: walking
    /// the cells costs about as much as a few instructions per evaluation, and in a scene of
    /// many objects the cells' CSG reduction leaves less than a beam's pruning does.
    pub(super) fn new(grid: Option<&Grid>) -> Self {
        let max_len = match grid {
            Some(g) => ((g.stats().cell_instrs as usize + RAY_FORM) * 3 / 2).min(SCOPED_MAX_LEN),
            None => SCOPED_MAX_LEN,
        };
        Self {
            map: RwLock::default(),
            max_len,
        }
    }

    /// The ray function of `tape` (a scope's pruned tape), compiled on first use; `None`
    /// where it cannot be compiled (then the ray is searched as without a scope). Which
    /// function a ray is searched with depends on its scope's content only, never on which
    /// thread asked first.
    fn get(&self, tape: &Tape) -> Option<Arc<RayFunction>> {
        if let Ok(map) = self.map.read()
            && let Some(f) = map.get(tape)
        {
            return f.clone();
        }
        let f = RayFunction::from_ray_tape(tape).ok().map(Arc::new);
        if let Ok(mut map) = self.map.write() {
            map.entry(tape.clone()).or_insert_with(|| f.clone());
        }
        f
    }
}

/// A thread's evaluator of scoped functions, and the scope it was set to last.
#[derive(Clone, Debug)]
pub(super) struct ScopedEval {
    eval: BeamEval,
    last: Option<(Tape, Arc<RayFunction>)>,
}

impl ScopedEval {
    /// An evaluator (of `any` until a scope is set) in `precision`.
    pub(super) fn new(any: &RayFunction, precision: Precision) -> Self {
        Self {
            eval: BeamEval::with_precision(any, precision),
            last: None,
        }
    }

    /// The evaluator set to `scope`'s function, for a ray searched over `t`: `None` where
    /// there is no scope, `t` is not inside its parameters, or its function cannot be
    /// compiled. The ray is not set.
    pub(super) fn within(
        &mut self,
        functions: &ScopedFunctions,
        scope: Option<&BeamScope>,
        t: Interval<f64>,
    ) -> Option<&mut BeamEval> {
        let scope = scope
            .filter(|s| !t.is_empty() && t.subset(s.t) && s.tape.len() <= functions.max_len)?;
        let f = match &self.last {
            Some((tape, f)) if tape.ptr_eq(&scope.tape) => f.clone(),
            _ => {
                let f = functions.get(&scope.tape)?;
                self.last = Some((scope.tape.clone(), f.clone()));
                f
            }
        };
        self.eval.set_function(&f);
        Some(&mut self.eval)
    }
}
