//! Tapes compiled to machine code for `Interval<f64>` evaluation (x86-64 on Linux; elsewhere
//! nothing compiles and the interpreter evaluates every tape).
//!
//! An interpreter pays for each instruction of a tape a dispatch (loading the opcode, an
//! indirect jump, loading the operands) and, for a tight directed-rounded bound, an
//! error-free transformation with its checks: about 60 machine instructions for an interval
//! sum. The compiled code of a tape is straight-line SSE2, each interval operation a few
//! instructions under upward rounding (see `emit` for how each bound is made), the longer
//! ones (product, square, root) calls of routines assembled once per process, with the
//! same bounds as the interpreter's arithmetic. [`Evaluator`](crate::Evaluator)s use it
//! for their plain, traced, definedness- and continuity-checked and all-outputs
//! evaluations of a tape once it has been evaluated [`COMPILE_AFTER`] times, so that tapes
//! evaluated once or twice (most pruned tapes of a large scene) do not pay for compiling;
//! a tape equal to one compiled before (in another thread, or in an earlier render of the
//! same scene) takes its code from its first evaluation on.
//! The compiled operations: `+ − ×`, negation, `abs`, square, square root, `min`, `max`
//! and `not`; a tape with any other is left to the interpreter.
//!
//! Where a code meets an infinite limit (`0 · ∞`) or a square root of a negative interval,
//! it says so (a NaN it made, flagged where it was made) and the evaluator runs the
//! interpreter instead, as it does for an empty variable (which never reaches a code), so
//! every result is the interpreter's.
//!
//! Before the first tape is compiled, a compiled sum checks that the machine honours the
//! rounding mode; where it does not (valgrind's emulation of SSE rounds to nearest
//! whatever `mxcsr` says) nothing is compiled and the interpreter evaluates every tape.

#[cfg(all(target_arch = "x86_64", target_os = "linux"))]
mod emit;
#[cfg(all(target_arch = "x86_64", target_os = "linux"))]
mod memory;
#[cfg(all(target_arch = "x86_64", target_os = "linux"))]
mod x64;

use std::collections::HashMap;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use rustc_hash::FxBuildHasher;

use crate::number::Choice;
use crate::op::{BinaryOp, UnaryOp};
use crate::tape::{Instr, Opcode, Tape};

/// Evaluations of a tape (through any evaluator, counted on the tape) after which it is
/// compiled.
pub const COMPILE_AFTER: u32 = 8;

/// Variables a compiled tape takes at most.
pub(crate) const MAX_VARS: usize = 16;

/// Outputs a compiled tape has at most (a value and its gradient, a few formulas).
pub(crate) const MAX_OUTPUTS: usize = 8;

/// Whether this build compiles tapes at all.
pub const AVAILABLE: bool = cfg!(all(target_arch = "x86_64", target_os = "linux"));

/// The choice a byte of a compiled tape's trace stands for.
#[inline(always)]
fn choice_of(b: u8) -> Choice {
    match b {
        0 => Choice::Left,
        1 => Choice::Right,
        _ => Choice::Both,
    }
}

/// What a compiled evaluation found beside its value.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct Flags {
    /// Some square root's argument reached below 0 (the formula is undefined on part of the
    /// region: no longer continuous there, and not to be pruned).
    pub(crate) partial: bool,
    /// Some step (`not`) may jump in the region (defined, not continuous).
    pub(crate) jump: bool,
}

impl Flags {
    /// The formula is defined on the whole region: the compiled operations are total but
    /// for the square root.
    pub(crate) fn defined(self) -> bool {
        !self.partial
    }

    /// The formula is defined and continuous on the whole region: the compiled operations
    /// are continuous but for `not`.
    pub(crate) fn continuous(self) -> bool {
        self.defined() && !self.jump
    }
}

/// One tape's machine code (never made where this build compiles nothing).
#[cfg_attr(
    not(all(target_arch = "x86_64", target_os = "linux")),
    allow(dead_code)
)]
pub(crate) struct Code {
    #[cfg(all(target_arch = "x86_64", target_os = "linux"))]
    mem: memory::ExecMemory,
    choices: usize,
}

impl std::fmt::Debug for Code {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Code")
            .field("choices", &self.choices)
            .finish_non_exhaustive()
    }
}

/// The signature of a compiled tape: the variables as `[lo, hi]` pairs, the choice bytes
/// (written only by traced code), the outputs as `[lo, hi]` pairs; returns the flags (bit
/// 0: a NaN made, bit 1: partial square root, bit 2: a step that may jump).
#[cfg(all(target_arch = "x86_64", target_os = "linux"))]
type Entry = unsafe extern "sysv64" fn(*const [f64; 2], *mut u8, *mut [f64; 2]) -> u32;

impl Code {
    /// The code of `tape`'s outputs, recording choices where `traced`; `None` where
    /// the tape uses an operation the compiler lacks or the platform has none.
    pub(crate) fn compile(tape: &Tape, traced: bool) -> Option<Self> {
        #[cfg(all(target_arch = "x86_64", target_os = "linux"))]
        {
            Some(Self {
                mem: emit::compile(tape, traced, runtime()?, memory::ExecMemory::new)?,
                choices: if traced { tape.choice_count() } else { 0 },
            })
        }
        #[cfg(not(all(target_arch = "x86_64", target_os = "linux")))]
        {
            let _ = (tape, traced);
            None
        }
    }

    /// The bytes of choices the code writes (none for untraced code).
    pub(crate) fn choices(&self) -> usize {
        self.choices
    }

    /// The outputs at `vars` (`[lo, hi]` of each slot, the unused ones anything: the
    /// variables must be nonempty, the caller checks) into `out` (`[lo, hi]` of each output,
    /// in order), with the choices of every `min`/`max` in `trace` for traced code (which
    /// must hold one byte per choice); returns the flags, or `None` where the interpreter
    /// must evaluate instead (an infinite limit or a root of a negative interval met).
    #[inline]
    pub(crate) fn run(
        &self,
        vars: &[[f64; 2]; MAX_VARS],
        trace: &mut [u8],
        out: &mut [[f64; 2]; MAX_OUTPUTS],
    ) -> Option<Flags> {
        #[cfg(all(target_arch = "x86_64", target_os = "linux"))]
        {
            assert!(trace.len() >= self.choices, "trace buffer too short");
            // SAFETY: the code was made by `emit::compile` for a tape of at most `MAX_VARS`
            // variables and `MAX_OUTPUTS` outputs, reads only `vars`, writes at most
            // `self.choices` bytes of `trace` and one pair of `out` per output, and restores
            // `mxcsr`.
            let flags = unsafe {
                let entry: Entry = std::mem::transmute(self.mem.as_ptr());
                entry(vars.as_ptr(), trace.as_mut_ptr(), out.as_mut_ptr())
            };
            (flags & 1 == 0).then_some(Flags {
                partial: flags & 2 != 0,
                jump: flags & 4 != 0,
            })
        }
        #[cfg(not(all(target_arch = "x86_64", target_os = "linux")))]
        {
            let _ = (vars, trace, out);
            None
        }
    }
}

/// The routines every code calls ([`emit::Runtime`]), assembled at the first compilation;
/// `None` where executable memory cannot be had.
#[cfg(all(target_arch = "x86_64", target_os = "linux"))]
fn runtime() -> Option<&'static emit::Runtime<memory::ExecMemory>> {
    static RUNTIME: OnceLock<Option<emit::Runtime<memory::ExecMemory>>> = OnceLock::new();
    RUNTIME
        .get_or_init(|| emit::runtime(memory::ExecMemory::new, memory::ExecMemory::as_ptr))
        .as_ref()
}

/// Codes kept by tape content at most ([`SHARED`]); the table is emptied when full (the
/// codes live on in the tapes that hold them).
const SHARED_MAX: usize = 4096;

/// The codes by the content of their tape and kind: a formula that the pruning of many
/// regions arrives at from different parent tapes (three in four of the tapes the 3D octree
/// compiles on the CSG models) is compiled once.
static SHARED: Mutex<CodeTable> = Mutex::new(HashMap::with_hasher(FxBuildHasher));

/// Codes by tape content and kind (traced or not).
type CodeTable = HashMap<(Tape, bool), Arc<Code>, FxBuildHasher>;

/// Whether the machine rounds as the code sets it to, found once by running a compiled
/// sum whose upper bound rounds upward: a machine that ignores the rounding mode (an
/// emulator, such as valgrind's) would make every code unsound, so none is used there.
fn rounding_honoured() -> bool {
    static HONOURED: OnceLock<bool> = OnceLock::new();
    *HONOURED.get_or_init(|| {
        let mut ctx = crate::context::Context::new();
        let (x, y) = (ctx.x(), ctx.y());
        let sum = ctx.add(x, y);
        let Ok(tape) = Tape::new(&ctx, &[sum]) else {
            return false;
        };
        let Some(code) = Code::compile(&tape, false) else {
            return false;
        };
        let tiny = 2f64.powi(-60);
        let mut vars = [[0.0; 2]; MAX_VARS];
        vars[0] = [1.0, 1.0];
        vars[1] = [tiny, tiny];
        let mut out = [[0.0; 2]; MAX_OUTPUTS];
        code.run(&vars, &mut [], &mut out).is_some() && out[0] == [1.0, 1.0f64.next_up()]
    })
}

/// Forgets the codes kept for equal tapes, so that the tapes made from now on are compiled
/// afresh (after [`COMPILE_AFTER`] evaluations each), as in the first render of a process:
/// what a benchmark calls before each timed render to time that first render again rather
/// than one that finds its tapes compiled by the renders before it. Tapes that hold a code
/// keep it.
pub fn forget_shared() {
    SHARED.lock().unwrap_or_else(|e| e.into_inner()).clear();
}

/// The code of `tape` from [`SHARED`] where an equal tape's is kept there (only where the
/// machine honours the rounding mode: [`shared_code`] checks it before it keeps a code).
fn shared_only(tape: &Tape, traced: bool) -> Option<Arc<Code>> {
    let key = (tape.clone(), traced);
    SHARED
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .get(&key)
        .cloned()
}

/// The code of `tape` from [`SHARED`], compiled and kept there if it is not yet.
fn shared_code(tape: &Tape, traced: bool) -> Option<Arc<Code>> {
    if !rounding_honoured() {
        return None;
    }
    if let Some(c) = shared_only(tape, traced) {
        return Some(c);
    }
    // Compiled outside the lock: another thread may compile the same formula meanwhile,
    // and one of the two codes is kept.
    let code = Arc::new(Code::compile(tape, traced)?);
    let mut map = SHARED.lock().unwrap_or_else(|e| e.into_inner());
    if map.len() >= SHARED_MAX {
        map.clear();
    }
    Some(map.entry((tape.clone(), traced)).or_insert(code).clone())
}

/// A tape's compiled code, made on demand: an equal tape's code where [`SHARED`] holds
/// one at the first evaluation, else the evaluations counted until [`COMPILE_AFTER`], then
/// the code of each kind compiled once (or found compiled for an equal tape meanwhile).
/// A plain evaluation of a tape that has traced code runs that code (the same values and
/// flags, with choice bytes the caller ignores): a renderer evaluates its pruned tapes
/// traced where it may prune again and plain for its probes, and on `csg3d-2k` a quarter
/// of the instructions compiled were second, plain codes of tapes compiled traced.
#[derive(Debug, Default)]
pub(crate) struct Slot {
    evals: AtomicU32,
    plain: OnceLock<Option<Arc<Code>>>,
    traced: OnceLock<Option<Arc<Code>>>,
}

impl Slot {
    /// The code of `tape` (whose slot this is), `traced` or not, where it is compiled or now
    /// due; counts an evaluation otherwise.
    #[inline]
    pub(crate) fn code(&self, tape: &Tape, traced: bool) -> Option<&Code> {
        if !AVAILABLE {
            return None;
        }
        let cell = if traced { &self.traced } else { &self.plain };
        if let Some(c) = cell.get() {
            return c.as_deref();
        }
        if !traced && let Some(Some(c)) = self.traced.get() {
            // The traced code computes the same values: no second code for the tape.
            return Some(c);
        }
        let evals = self.evals.load(Ordering::Relaxed);
        if evals < COMPILE_AFTER {
            self.evals.fetch_add(1, Ordering::Relaxed);
            if evals == 0 {
                // An equal tape's code, compiled before (by another thread, or for a tape
                // since dropped), serves from the first evaluation on.
                if let Some(code) = shared_only(tape, traced) {
                    return cell.get_or_init(|| Some(code)).as_deref();
                }
            }
            return None;
        }
        cell.get_or_init(|| shared_code(tape, traced)).as_deref()
    }

    /// Whether the tape has plain code, and traced code, of its own.
    #[cfg(test)]
    pub(crate) fn kinds(&self) -> (bool, bool) {
        let made = |c: &OnceLock<Option<Arc<Code>>>| c.get().is_some_and(Option::is_some);
        (made(&self.plain), made(&self.traced))
    }

    /// Counts the tape as evaluated [`COMPILE_AFTER`] times already, so that its next
    /// evaluation compiles it (see [`Tape::expect_reuse`](crate::Tape::expect_reuse)).
    pub(crate) fn expect_reuse(&self) {
        self.evals.fetch_max(COMPILE_AFTER, Ordering::Relaxed);
    }
}

/// Whether the compiled code handles `ins`.
pub(crate) fn supported(ins: &Instr) -> bool {
    match ins.op {
        Opcode::Var | Opcode::Const | Opcode::Copy => true,
        Opcode::Unary(op) => matches!(
            op,
            UnaryOp::Neg | UnaryOp::Abs | UnaryOp::Sqr | UnaryOp::Sqrt | UnaryOp::Not
        ),
        Opcode::Binary(op) => matches!(
            op,
            BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Min | BinaryOp::Max
        ),
        Opcode::Pown => false,
    }
}

/// Whether the code generator handles every operation, the outputs and the variables of
/// `tape` (see [`Tape::has_code_ops`](crate::Tape::has_code_ops)), whatever the platform.
pub(crate) fn handles(tape: &Tape) -> bool {
    tape.outputs().len() <= MAX_OUTPUTS
        && tape.var_count() <= MAX_VARS
        && tape.instrs().iter().all(supported)
}

/// Choice bytes as choices, into `trace` (cleared first).
pub(crate) fn choices_into(bytes: &[u8], trace: &mut Vec<Choice>) {
    trace.clear();
    trace.extend(bytes.iter().map(|&b| choice_of(b)));
}

#[cfg(all(test, target_arch = "x86_64", target_os = "linux"))]
mod tests;
