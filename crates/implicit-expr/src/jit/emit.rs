//! A register tape turned into x86-64 code for `Interval<f64>` arguments.
//!
//! Every interval is held as `[−lo, hi]` in one SSE register, and the code runs with the
//! rounding mode set to upward: then `[−lo, hi]` of a sum is one `addpd` (the lower bound
//! `−RU(−a − b) = RD(a + b)`), a difference adds the second argument's lanes swapped, a
//! product takes the largest of the four corner products in each lane, all rounded upward,
//! which is the tight product's bounds. The square root's lower bound is the upward root
//! stepped down one ulp unless its square is exact. `min` and `max` are lane-wise `max`
//! and `min` of the negated lower bounds and the upper bounds. So each bound is the one the
//! interpreter's tight arithmetic computes.
//!
//! The function begins by saving `mxcsr` and loading upward rounding with every exception
//! masked; it ends by restoring `mxcsr`. A NaN made anywhere tells the caller to evaluate
//! with the interpreter instead, whose rules for empty sets and the limits at infinity
//! apply there. The variables are nonempty (the evaluator checks before it runs a code),
//! and on nonempty intervals (no lower bound `+∞`, no upper bound `−∞`) only two
//! operations can make a NaN: a product of a zero and an infinite bound (`0 · ∞`, at a
//! corner of a product, where the largest of the corners would hide it), and the root of
//! an argument entirely below 0. Those add their NaN lanes to a mask (`xmm8`,
//! [`flag_nan`]), which the function returns as a flag; sums, differences, `min`, `max`
//! and the other operations keep the bounds' signs apart and make none. (Reading the invalid-operation flag of `mxcsr` instead waits for
//! every operation of the code to finish: a third to a half of an evaluation of a short
//! tape.)
//!
//! The long operations (product, square, absolute value, square root, `not`, and the
//! comparison behind a recorded choice) are assembled once, as the [`Runtime`]'s routines,
//! and each code calls them through a table of their addresses in its pool: a code is a
//! third to a half shorter than with every operation written out, and a render compiles
//! thousands of codes, each into fresh executable memory.

use interval_core::Interval;

use super::x64::{Asm, Cmp, Mem, Sse, Xmm};
use super::{MAX_OUTPUTS, MAX_VARS, supported};
use crate::number::Number;
use crate::op::{BinaryOp, UnaryOp};
use crate::tape::{Opcode, Tape};

/// Working registers a compiled tape keeps on its stack frame at most (the frame stays
/// within a page, so no stack probe is needed).
const MAX_SLOTS: usize = 240;

// The pool: masks, `mxcsr`, the choice tables, the routines' addresses, then the
// constants.
const SIGN_LO: u32 = 0;
const SIGN_BOTH: u32 = 16;
const ABS: u32 = 32;
const ZERO: u32 = 48;
const CSR: u32 = 64;
const MIN_TABLE: u32 = 68;
const MAX_TABLE: u32 = 72;
const ONE_HI: u32 = 80;
const MINUS_ONE_LO: u32 = 96;
const HI_LANE: u32 = 112;
const ROUTINE_TABLE: u32 = 128;
const CONSTS: u32 = ROUTINE_TABLE + 8 * ROUTINES as u32;

/// Upward rounding (`RC = 10`), every exception masked, no flag, no flush to zero.
const MXCSR_UP: u32 = 0x5F80;

/// The choice byte for each `movmskpd` of `[a.hi ≤ b.lo, b.hi ≤ a.lo]`, in the codes of
/// [`super::choice_of`]: `min` takes `a` (Left, 0) where `a.hi ≤ b.lo` first, then `b`
/// (Right, 1), else both (2); `max` takes `a` where `b.hi ≤ a.lo` first.
const MIN_CHOICES: [u8; 4] = [2, 0, 1, 0];
const MAX_CHOICES: [u8; 4] = [2, 1, 0, 0];

const X0: Xmm = Xmm(0);
const X1: Xmm = Xmm(1);
const X2: Xmm = Xmm(2);
const X3: Xmm = Xmm(3);
const X4: Xmm = Xmm(4);
const X5: Xmm = Xmm(5);
const X6: Xmm = Xmm(6);
/// The accumulated flags: in the low lane "some square root's argument reaches below 0",
/// in the high lane "some step (`not`) may jump".
const PARTIAL: Xmm = Xmm(7);

/// The operations assembled once, out of line ([`Runtime`]), in the order of their
/// addresses in a code's pool.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Routine {
    /// `X0 = X0 · X1` ([`mul`]).
    Mul,
    /// `X0 = X0²`.
    Sqr,
    /// `X0 = |X0|`.
    Abs,
    /// `X0 = √X0` ([`sqrt`]).
    Sqrt,
    /// `X0 = not(X0)` ([`not`]).
    Not,
    /// `eax` = the mask `[a.hi ≤ b.lo, b.hi ≤ a.lo]` of `a = X0`, `b = X1`
    /// ([`choice_mask`]).
    ChoiceMask,
}

/// The number of routines.
const ROUTINES: usize = 6;

impl Routine {
    const ALL: [Routine; ROUTINES] = [
        Routine::Mul,
        Routine::Sqr,
        Routine::Abs,
        Routine::Sqrt,
        Routine::Not,
        Routine::ChoiceMask,
    ];

    /// Assembles the routine's body (without its `ret`).
    fn body(self, a: &mut Asm) {
        match self {
            Routine::Mul => mul(a),
            Routine::Sqr => {
                // [−mig, mag] · [mig, mag], rounded upward: [−RD(mig²), RU(mag²)].
                abs(a);
                a.rr(Sse::MovApd, X0, X2);
                a.rm(Sse::XorPd, X0, Mem::Pool(SIGN_LO));
                a.rr(Sse::MulPd, X0, X2);
            }
            Routine::Abs => {
                abs(a);
                a.rr(Sse::MovApd, X0, X2);
            }
            Routine::Sqrt => sqrt(a),
            Routine::Not => not(a),
            Routine::ChoiceMask => choice_mask(a),
        }
    }

    /// Calls the routine through its address in the pool.
    fn call(self, a: &mut Asm) {
        a.call_pool(ROUTINE_TABLE + 8 * self as u32);
    }
}

/// The routines, assembled once into executable memory `M`, and their addresses.
pub(super) struct Runtime<M> {
    /// The memory that holds them (kept as long as the runtime, so for the whole process).
    _mem: M,
    entries: [u64; ROUTINES],
}

/// The routines placed by `place`, whose result gives the address of its first byte by
/// `address`; `None` where `place` fails.
pub(super) fn runtime<M>(
    place: impl FnOnce(&[u8]) -> Option<M>,
    address: impl Fn(&M) -> *const u8,
) -> Option<Runtime<M>> {
    let mut a = Asm::default();
    let mut offsets = [0usize; ROUTINES];
    for (r, offset) in Routine::ALL.iter().zip(&mut offsets) {
        *offset = a.len();
        r.body(&mut a);
        a.ret();
    }
    let mut pool = Vec::with_capacity(CONSTS as usize);
    pool_header(&mut pool, &[0; ROUTINES]);
    let mem = place(a.finish(&pool))?;
    let base = address(&mem) as u64;
    Some(Runtime {
        entries: offsets.map(|o| base + o as u64),
        _mem: mem,
    })
}

/// The pool's fixed part, up to [`CONSTS`]: the masks, `mxcsr`, the choice tables and the
/// routines' addresses `entries`.
fn pool_header(pool: &mut Vec<u8>, entries: &[u64; ROUTINES]) {
    let pair = |pool: &mut Vec<u8>, lanes: [u64; 2]| {
        for l in lanes {
            pool.extend_from_slice(&l.to_le_bytes());
        }
    };
    let (sign, one, minus_one) = ((-0.0f64).to_bits(), 1.0f64.to_bits(), (-1.0f64).to_bits());
    for lanes in [[sign, 0], [sign, sign], [!sign, !sign], [0, 0]] {
        pair(pool, lanes);
    }
    pool.extend_from_slice(&MXCSR_UP.to_le_bytes());
    pool.extend_from_slice(&MIN_CHOICES);
    pool.extend_from_slice(&MAX_CHOICES);
    pool.resize(ONE_HI as usize, 0);
    for lanes in [[0, one], [minus_one, 0], [0, u64::MAX]] {
        pair(pool, lanes);
    }
    for e in entries {
        pool.extend_from_slice(&e.to_le_bytes());
    }
    debug_assert_eq!(pool.len(), CONSTS as usize);
}

/// A thread's buffers for compiling, kept from one code to the next.
#[derive(Default)]
struct Buffers {
    asm: Asm,
    pool: Vec<u8>,
    /// For each register, the instruction that last wrote it ([`NEVER`]: none yet).
    def: Vec<u32>,
    /// For each instruction, whether its result must be stored ([`check_and_plan`]).
    stored: Vec<bool>,
}

thread_local! {
    static BUFFERS: std::cell::RefCell<Buffers> = std::cell::RefCell::new(Buffers::default());
}

/// No instruction wrote the register (yet).
const NEVER: u32 = u32::MAX;

/// The machine code of `tape`'s outputs, writing choice bytes where `traced`, handed
/// to `place` (which copies it where it will run); `None` where the tape uses an operation
/// the code generator lacks, or is too large for its frame.
pub(super) fn compile<M, R>(
    tape: &Tape,
    traced: bool,
    runtime: &Runtime<M>,
    place: impl FnOnce(&[u8]) -> Option<R>,
) -> Option<R> {
    BUFFERS.with_borrow_mut(|b| {
        b.asm.clear();
        b.pool.clear();
        assemble(b, tape, traced, &runtime.entries)?;
        place(b.asm.finish(&b.pool))
    })
}

/// Assembles the code of `tape` into `b.asm` and its constant pool into `b.pool`, calling
/// the routines at `entries`; `None` where the tape cannot be compiled.
fn assemble(b: &mut Buffers, tape: &Tape, traced: bool, entries: &[u64; ROUTINES]) -> Option<()> {
    let nconst = tape.consts().len();
    let slots = tape.reg_count().saturating_sub(nconst);
    let outputs = tape.outputs();
    if outputs.is_empty()
        || outputs.len() > MAX_OUTPUTS
        || tape.var_count() > MAX_VARS
        || slots > MAX_SLOTS
        || !check_and_plan(tape, &mut b.def, &mut b.stored)
    {
        return None;
    }
    let (a, pool, stored) = (&mut b.asm, &mut b.pool, &b.stored);
    // Room for the code at once: a call of a routine with its loads and store takes about
    // 30 bytes, a recorded `min` about 40; the prologue and epilogue less than 96.
    a.reserve(96 + 40 * tape.instrs().len());
    pool.reserve(CONSTS as usize + 16 * nconst);
    pool_header(pool, entries);
    for c in tape.consts() {
        let (lo, hi) = <Interval<f64> as Number>::constant(c).bounds()?;
        pool.extend_from_slice(&(-lo).to_bits().to_le_bytes());
        pool.extend_from_slice(&hi.to_bits().to_le_bytes());
    }

    let reg = |r: u32| -> Mem {
        let r = r as usize;
        if r < nconst {
            Mem::Pool(CONSTS + 16 * r as u32)
        } else {
            Mem::Stack(16 + 16 * (r - nconst) as i32)
        }
    };
    // 16 bytes for `mxcsr`, the slots, and 8 to align `rsp` (8 mod 16 at the call).
    let frame = 16 + 16 * slots as i32 + 8;

    a.sub_rsp(frame);
    a.stmxcsr(Mem::Stack(0));
    a.ldmxcsr(Mem::Pool(CSR));
    a.rr(Sse::XorPd, PARTIAL, PARTIAL);
    a.clear_nan_mask();
    if traced {
        a.lea_rcx_pool(MIN_TABLE);
    }
    let instrs = tape.instrs();
    // The register whose value `X0` holds: the previous instruction's output.
    let mut in_x0 = None;
    let mut choice = 0i32;
    for (ins, &store) in instrs.iter().zip(stored) {
        let load = |a: &mut Asm, x: Xmm, r: u32| {
            if in_x0 == Some(r) {
                if x != X0 {
                    a.rr(Sse::MovApd, x, X0);
                }
            } else {
                a.rm(Sse::MovUpd, x, reg(r));
            }
        };
        match ins.op {
            Opcode::Var => {
                a.rm(Sse::MovUpd, X0, Mem::Vars(16 * ins.a as i32));
                a.rm(Sse::XorPd, X0, Mem::Pool(SIGN_LO));
            }
            Opcode::Const | Opcode::Copy => load(a, X0, ins.a),
            Opcode::Unary(op) => {
                load(a, X0, ins.a);
                unary(a, op);
            }
            Opcode::Binary(op) => {
                // `X1` first: it may copy `X0` before `X0` is loaded.
                load(a, X1, ins.b);
                load(a, X0, ins.a);
                if traced && matches!(op, BinaryOp::Min | BinaryOp::Max) {
                    let table = if op == BinaryOp::Min {
                        0
                    } else {
                        MAX_TABLE - MIN_TABLE
                    };
                    record_choice(a, table as i8, choice);
                    choice += 1;
                }
                binary(a, op);
            }
            Opcode::Pown => unreachable!("checked by `supported`"),
        }
        if store {
            a.store(reg(ins.out), X0);
        }
        in_x0 = Some(ins.out);
    }
    // Every output as `[lo, hi]`: the first may still be in `X0`, the others are stored.
    for (i, &o) in outputs.iter().enumerate() {
        if i > 0 || in_x0 != Some(o) {
            a.rm(Sse::MovUpd, X0, reg(o));
        }
        a.rm(Sse::XorPd, X0, Mem::Pool(SIGN_LO));
        a.store(Mem::Out(16 * i as i32), X0);
    }
    // Flags: bit 0 a NaN made, bit 1 a partial square root, bit 2 a jump.
    a.nan_mask_eax();
    a.movmskpd_ecx(PARTIAL);
    a.merge_flags();
    a.ldmxcsr(Mem::Stack(0));
    a.add_rsp(frame);
    a.ret();
    Some(())
}

/// Checks that the code generator handles every instruction of `tape` ([`supported`]),
/// that every register it reads is a constant or written before, every output register
/// a working one and every variable slot one of the tape's (what the frame and the
/// variables buffer hold: the register allocator makes no other tapes), and marks in
/// `stored` each instruction whose result must be stored to its register: where it is
/// read later than by the next instruction (which takes it from `X0`), or is an output
/// read after the last instruction from memory (all but the first output: `X0` holds the
/// first). One pass; `def` is a buffer.
fn check_and_plan(tape: &Tape, def: &mut Vec<u32>, stored: &mut Vec<bool>) -> bool {
    let (nconst, nregs) = (tape.consts().len(), tape.reg_count());
    let instrs = tape.instrs();
    def.clear();
    def.resize(nregs, NEVER);
    stored.clear();
    stored.resize(instrs.len(), false);
    // Reads register `r` at instruction `at`: false where it holds nothing yet.
    let mut read = |def: &[u32], r: u32, at: usize| -> bool {
        let r = r as usize;
        if r < nconst {
            return true;
        }
        match def.get(r) {
            Some(&d) if d != NEVER => {
                if d as usize + 1 != at {
                    stored[d as usize] = true;
                }
                true
            }
            _ => false,
        }
    };
    for (j, ins) in instrs.iter().enumerate() {
        let ok = supported(ins)
            && match ins.op {
                Opcode::Var => (ins.a as usize) < tape.var_count(),
                Opcode::Const | Opcode::Copy | Opcode::Unary(_) => read(def, ins.a, j),
                Opcode::Binary(_) => read(def, ins.a, j) && read(def, ins.b, j),
                Opcode::Pown => false,
            };
        let out = ins.out as usize;
        if !ok || out < nconst || out >= nregs {
            return false;
        }
        def[out] = j as u32;
    }
    let end = instrs.len();
    tape.outputs()
        .iter()
        .enumerate()
        .all(|(i, &o)| read(def, o, end + i))
}

/// `X0 = op(X0)`; uses `X1` to `X5`.
fn unary(a: &mut Asm, op: UnaryOp) {
    match op {
        // [−(−hi), −lo]: the lanes swapped.
        UnaryOp::Neg => a.swap(X0),
        UnaryOp::Abs => Routine::Abs.call(a),
        UnaryOp::Sqr => Routine::Sqr.call(a),
        UnaryOp::Sqrt => Routine::Sqrt.call(a),
        UnaryOp::Not => Routine::Not.call(a),
        _ => unreachable!("checked by `supported`"),
    }
}

/// `X2 = [−mig, mag]` of `X0 = [−lo, hi]` (`|x|`): `−mig = min(−lo, hi, 0)` (the lower
/// bound when positive, minus the upper when negative, else 0), `mag = max(|lo|, |hi|)`.
fn abs(a: &mut Asm) {
    across(a, Sse::MinSd, X2, X0);
    a.rm(Sse::MinSd, X2, Mem::Pool(ZERO));
    a.rr(Sse::MovApd, X3, X0);
    a.rm(Sse::AndPd, X3, Mem::Pool(ABS));
    across(a, Sse::MaxSd, X4, X3);
    a.rr(Sse::UnpckLPd, X2, X4);
}

/// `dst = op(src with its lanes swapped, src)`: for a scalar `op` the low lane combines
/// both lanes of `src`, for a packed one both lanes do.
fn across(a: &mut Asm, op: Sse, dst: Xmm, src: Xmm) {
    a.rr(Sse::MovApd, dst, src);
    a.swap(dst);
    a.rr(op, dst, src);
}

/// `X0 = √X0` over the argument's non-negative part; flags a negative lower bound in
/// [`PARTIAL`]. The argument entirely below 0 gives NaN, added to the NaN mask.
fn sqrt(a: &mut Asm) {
    // PARTIAL |= (0 < −lo).
    a.rm(Sse::MovSd, X1, Mem::Pool(ZERO));
    a.cmpsd(X1, X0, Cmp::Lt);
    a.rr(Sse::OrPd, PARTIAL, X1);
    // X2.lo = max(lo, 0) (as −min(−lo, 0)).
    a.rr(Sse::MovApd, X2, X0);
    a.rm(Sse::MinSd, X2, Mem::Pool(ZERO));
    a.rm(Sse::XorPd, X2, Mem::Pool(SIGN_LO));
    a.rr(Sse::MovApd, X3, X2);
    // s = RU(√lo'); stepped down one ulp where RU(s²) ≠ lo' (then √lo' is inexact and s is
    // its upward rounding, positive and finite): RD(√lo').
    a.rr(Sse::SqrtSd, X2, X2);
    a.rr(Sse::MovApd, X4, X2);
    a.rr(Sse::MulSd, X4, X2);
    a.cmpsd(X4, X3, Cmp::Neq);
    a.rr(Sse::PAddQ, X2, X4);
    a.rm(Sse::XorPd, X2, Mem::Pool(SIGN_LO));
    // RU(√hi).
    a.rr(Sse::MovApd, X5, X0);
    a.rr(Sse::UnpckHPd, X5, X5);
    a.rr(Sse::SqrtSd, X5, X5);
    a.rr(Sse::UnpckLPd, X2, X5);
    a.rr(Sse::MovApd, X0, X2);
    // The root of an upper bound below 0 (the argument entirely negative) is NaN.
    flag_nan(a, X0, X0);
}

/// Adds to the NaN mask the lanes where `x` or `y` is NaN. Uses `X1`.
fn flag_nan(a: &mut Asm, x: Xmm, y: Xmm) {
    a.rr(Sse::MovApd, X1, x);
    a.cmppd(X1, y, Cmp::Unord);
    a.or_nan_mask(X1);
}

/// `X0 = not(X0)`: `[1, 1]` on `[0, 0]`, `[0, 1]` on an interval holding 0, else
/// `[0, 0]`; flags a possible jump (0 inside, not the point 0) in [`PARTIAL`]'s high lane.
/// Uses `X1` to `X4`.
fn not(a: &mut Asm) {
    // X1 = [lo ≤ 0, hi ≥ 0] (signalling on NaN); X2 = both: 0 inside.
    a.rm(Sse::MovUpd, X1, Mem::Pool(ZERO));
    a.cmppd(X1, X0, Cmp::Le);
    across(a, Sse::AndPd, X2, X1);
    // X3 = [−lo = 0, hi = 0]; X4 = both: the point 0.
    a.rr(Sse::MovApd, X3, X0);
    a.rm(Sse::CmpEqPd, X3, Mem::Pool(ZERO));
    across(a, Sse::AndPd, X4, X3);
    // A jump is possible where 0 is inside and the interval is not the point 0.
    a.rr(Sse::MovApd, X1, X4);
    a.rr(Sse::AndNPd, X1, X2);
    a.rm(Sse::AndPd, X1, Mem::Pool(HI_LANE));
    a.rr(Sse::OrPd, PARTIAL, X1);
    // [−res_lo, res_hi] = [point ? −1 : 0, inside ? 1 : 0].
    a.rm(Sse::AndPd, X2, Mem::Pool(ONE_HI));
    a.rm(Sse::AndPd, X4, Mem::Pool(MINUS_ONE_LO));
    a.rr(Sse::OrPd, X2, X4);
    a.rr(Sse::MovApd, X0, X2);
}

/// `X0 = X0 op X1`; uses `X2` to `X6` (a product `X1` too).
fn binary(a: &mut Asm, op: BinaryOp) {
    match op {
        BinaryOp::Add => a.rr(Sse::AddPd, X0, X1),
        BinaryOp::Sub => {
            // [−lo_a + hi_b, hi_a − lo_b].
            a.swap(X1);
            a.rr(Sse::AddPd, X0, X1);
        }
        BinaryOp::Min => {
            // [max(−lo_a, −lo_b), min(hi_a, hi_b)].
            a.rr(Sse::MovApd, X2, X0);
            a.rr(Sse::MaxPd, X2, X1);
            a.rr(Sse::MinPd, X0, X1);
            a.rr(Sse::MovSd, X0, X2);
        }
        BinaryOp::Max => {
            // [min(−lo_a, −lo_b), max(hi_a, hi_b)].
            a.rr(Sse::MovApd, X2, X0);
            a.rr(Sse::MinPd, X2, X1);
            a.rr(Sse::MaxPd, X0, X1);
            a.rr(Sse::MovSd, X0, X2);
        }
        BinaryOp::Mul => Routine::Mul.call(a),
        _ => unreachable!("checked by `supported`"),
    }
}

/// `X0 = X0 · X1`: with `A = [−al, ah]`, `B = [−bl, bh]`, the lane-wise maximum of
/// `A·[bl, bh]`, `A·[bh, bl]`, `[ah, −al]·[−bl, −bl]` and `[ah, −al]·[−bh, −bh]`, rounded
/// upward: the negated products of the four corners in the low lane, the products in the
/// high one. A corner `0 · ∞` goes to the NaN mask. Uses `X1` to `X6`.
fn mul(a: &mut Asm) {
    a.rr(Sse::MovApd, X2, X1);
    a.rm(Sse::XorPd, X2, Mem::Pool(SIGN_LO)); // [bl, bh]
    a.rr(Sse::MovApd, X3, X2);
    a.swap(X3); // [bh, bl]
    a.rr(Sse::MovApd, X4, X0);
    a.swap(X4); // [ah, −al]
    a.rr(Sse::MovApd, X5, X1);
    a.rr(Sse::UnpckLPd, X5, X5); // [−bl, −bl]
    a.rr(Sse::MovApd, X6, X1);
    a.rr(Sse::UnpckHPd, X6, X6);
    a.rm(Sse::XorPd, X6, Mem::Pool(SIGN_BOTH)); // [−bh, −bh]
    a.rr(Sse::MulPd, X2, X0);
    a.rr(Sse::MulPd, X3, X0);
    a.rr(Sse::MulPd, X5, X4);
    a.rr(Sse::MulPd, X6, X4);
    // A corner `0 · ∞` is NaN, which `maxpd` would drop: into the NaN mask. `X2` and `X3`
    // hold the four corners (`X5` and `X6` the same ones, negated), and a product is NaN
    // whatever the signs.
    flag_nan(a, X2, X3);
    a.rr(Sse::MaxPd, X2, X3);
    a.rr(Sse::MaxPd, X5, X6);
    a.rr(Sse::MaxPd, X2, X5);
    a.rr(Sse::MovApd, X0, X2);
}

/// Writes choice byte `index` of a `min` (`table` 0) or `max` (`table` 4) of `X0`, `X1`:
/// the table entry for the mask `[a.hi ≤ b.lo, b.hi ≤ a.lo]` ([`Routine::ChoiceMask`]).
/// Uses `X3`, `X4`.
fn record_choice(a: &mut Asm, table: i8, index: i32) {
    Routine::ChoiceMask.call(a);
    a.load_table_byte(table);
    a.store_choice(index);
}

/// `eax` = the mask `[a.hi ≤ b.lo, b.hi ≤ a.lo]` of `a = X0`, `b = X1` (bit 0, bit 1).
/// Uses `X3`, `X4`.
fn choice_mask(a: &mut Asm) {
    a.rr(Sse::MovApd, X3, X0);
    a.rr(Sse::UnpckHPd, X3, X1); // [a.hi, b.hi]
    a.rr(Sse::MovApd, X4, X0);
    a.rr(Sse::UnpckLPd, X4, X1); // [−a.lo, −b.lo]
    a.swap(X4);
    a.rm(Sse::XorPd, X4, Mem::Pool(SIGN_BOTH)); // [b.lo, a.lo]
    a.cmppd(X3, X4, Cmp::Le);
    a.movmskpd_eax(X3);
}
