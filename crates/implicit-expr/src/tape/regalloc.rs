//! From an SSA list to a register tape in one backward pass: liveness, the forwarding of
//! decided `min`/`max` operations and register allocation together (a reverse linear scan,
//! as fidget does).
//!
//! Walking from the outputs towards the inputs, a value gets a register at its last use
//! (the first one met) and gives it back at its definition, so the pass sees every value's
//! whole life at once and never visits a dead one twice. A `min`/`max` whose choice is
//! decided, and a copy, hands its register to the argument it forwards when that argument
//! has none yet; otherwise it becomes a copy. Constants get their own registers, numbered
//! before the working ones. The cost is one step per operation of the input and a few per
//! operation of the output, which is what pruning a tape per tile needs.

use super::{Instr, Opcode, SsaOp};
use crate::constant::Constant;
use crate::number::Choice;
use crate::op::BinaryOp;

/// The SSA positions an operation reads.
pub(super) fn operands(op: &SsaOp) -> ([u32; 2], usize) {
    match op.op {
        Opcode::Var | Opcode::Const => ([0, 0], 0),
        Opcode::Copy | Opcode::Unary(_) | Opcode::Pown => ([op.a, 0], 1),
        Opcode::Binary(_) => ([op.a, op.b], 2),
    }
}

/// Whether an operation is a `min` or a `max` (one entry of a choice trace).
pub(super) fn is_choice(op: &SsaOp) -> bool {
    matches!(op.op, Opcode::Binary(BinaryOp::Min | BinaryOp::Max))
}

/// A compiled tape's parts, in the buffers of the thread's [`Scratch`]: the SSA list
/// (constants first), its constants and outputs, the register instructions (one per
/// non-constant SSA operation, in the same order), the output registers, the register
/// count, the number of `min`/`max` operations, each SSA operation's index among them
/// ([`NO_CHOICE`] for the others), and the hash of the content (see [`content_hash`]).
pub(super) struct Compiled<'a> {
    pub(super) ssa: &'a [SsaOp],
    pub(super) consts: &'a [Constant],
    pub(super) ssa_outputs: &'a [u32],
    pub(super) instrs: &'a [Instr],
    pub(super) outputs: &'a [u32],
    pub(super) reg_count: u32,
    pub(super) choice_count: u32,
    pub(super) choice_index: &'a [u32],
    pub(super) hash: u64,
}

/// The hash of what two tapes must share to be equal (variable count, outputs, operations,
/// constants), one word per operation.
pub(super) fn content_hash(
    var_count: u32,
    ssa_outputs: &[u32],
    ssa: &[SsaOp],
    consts: &[Constant],
) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = rustc_hash::FxHasher::default();
    h.write_u32(var_count);
    ssa_outputs.hash(&mut h);
    h.write_usize(ssa.len());
    for op in ssa {
        let code = match op.op {
            Opcode::Var => 0,
            Opcode::Const => 1,
            Opcode::Copy => 2,
            Opcode::Pown => 3,
            Opcode::Unary(u) => 16 + u as u64,
            Opcode::Binary(b) => 128 + b as u64,
        };
        h.write_u64(code << 32 | u64::from(op.a));
        h.write_u32(op.b);
    }
    consts.hash(&mut h);
    h.finish()
}

/// The [`Compiled::choice_index`] of an operation that is not a `min` or `max`.
pub(super) const NO_CHOICE: u32 = u32::MAX;

/// The register tape of the values of `ssa` that `outputs` depend on, where `choice(i)` tells
/// which argument the operation at position `i` takes when it is a decided `min`/`max`
/// (it is forwarded to that argument) and is [`Choice::Both`] otherwise, handed to `keep`
/// in the thread's buffers (a tape is made of it only where `keep` makes one: a pruning
/// that arrives at a formula made before allocates nothing).
pub(super) fn compile<R>(
    (ssa, consts, outputs, var_count): (&[SsaOp], &[Constant], &[u32], u32),
    choice: impl Fn(usize) -> Choice,
    keep: impl FnOnce(Compiled<'_>) -> R,
) -> R {
    SCRATCH.with_borrow_mut(|scratch| {
        let (reg_count, choice_count) = scratch.compile(ssa, consts, outputs, choice);
        let out = &scratch.out;
        keep(Compiled {
            ssa: &out.ssa,
            consts: &out.consts,
            ssa_outputs: &out.ssa_outputs,
            instrs: &out.instrs,
            outputs: &out.outputs,
            reg_count,
            choice_count,
            choice_index: &out.choice_index,
            hash: content_hash(var_count, &out.ssa_outputs, &out.ssa, &out.consts),
        })
    })
}

/// A value not (yet) live.
const UNASSIGNED: u32 = u32::MAX;
/// Marks a constant's register in [`Scratch::reg`], and a constant's index in
/// [`Scratch::pos`].
const CONST: u32 = 1 << 31;
/// Marks, in [`Scratch::pos`], a forwarded value: the rest is the input position it equals.
const ALIAS: u32 = 1 << 30;

/// Buffers of [`compile`], kept per thread: a renderer prunes once per tile.
#[derive(Default)]
struct Scratch {
    /// Register of each input value once live: a working register, or `CONST | k`.
    reg: Vec<u32>,
    /// Where each live input value ended: the index (counted from the end) of the operation
    /// that computes it, `CONST | k`, or `ALIAS | position` of the value it forwards.
    pos: Vec<u32>,
    /// Working registers given back, to reuse.
    free: Vec<u32>,
    /// The output operations, last first: SSA arguments as input positions, and the
    /// instruction with working registers and `CONST`-marked constant registers.
    emitted: Vec<(SsaOp, Instr)>,
    /// The tape made last.
    out: Output,
}

/// The parts of the tape [`Scratch::compile`] made last (see [`Compiled`]).
#[derive(Default)]
struct Output {
    ssa: Vec<SsaOp>,
    consts: Vec<Constant>,
    ssa_outputs: Vec<u32>,
    instrs: Vec<Instr>,
    outputs: Vec<u32>,
    choice_index: Vec<u32>,
}

thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

impl Scratch {
    fn compile(
        &mut self,
        ssa: &[SsaOp],
        in_consts: &[Constant],
        in_outputs: &[u32],
        choice: impl Fn(usize) -> Choice,
    ) -> (u32, u32) {
        let n = ssa.len();
        self.reg.clear();
        self.reg.resize(n, UNASSIGNED);
        // Every entry read is written first (at the value's definition, met after its uses).
        if self.pos.len() < n {
            self.pos.resize(n, 0);
        }
        self.free.clear();
        self.emitted.clear();
        let mut consts = std::mem::take(&mut self.out.consts);
        consts.clear();
        let mut working = 0u32;
        let mut reg_of = |p: u32, reg: &mut [u32], free: &mut Vec<u32>| -> u32 {
            let p = p as usize;
            if reg[p] == UNASSIGNED {
                reg[p] = if ssa[p].op == Opcode::Const {
                    consts.push(in_consts[ssa[p].a as usize]);
                    CONST | (consts.len() - 1) as u32
                } else {
                    free.pop().unwrap_or_else(|| {
                        working += 1;
                        working - 1
                    })
                };
            }
            reg[p]
        };
        for &o in in_outputs {
            reg_of(o, &mut self.reg, &mut self.free);
        }
        let mut choice_count = 0;
        for i in (0..n).rev() {
            let out = self.reg[i];
            if out == UNASSIGNED {
                continue;
            }
            let op = ssa[i];
            if op.op == Opcode::Const {
                self.pos[i] = out;
                continue;
            }
            let forward = match (op.op, choice(i)) {
                (_, Choice::Left) | (Opcode::Copy, _) => Some(op.a),
                (_, Choice::Right) => Some(op.b),
                _ => None,
            };
            let (ssa_op, instr) = match forward {
                // The forwarded value takes over the register.
                Some(a)
                    if self.reg[a as usize] == UNASSIGNED
                        && ssa[a as usize].op != Opcode::Const =>
                {
                    self.reg[a as usize] = out;
                    self.pos[i] = ALIAS | a;
                    continue;
                }
                Some(a) => {
                    let ra = reg_of(a, &mut self.reg, &mut self.free);
                    let copy = SsaOp {
                        op: Opcode::Copy,
                        a,
                        b: 0,
                    };
                    (
                        copy,
                        Instr {
                            op: Opcode::Copy,
                            out,
                            a: ra,
                            b: 0,
                        },
                    )
                }
                None => {
                    let (args, arity) = operands(&op);
                    let mut instr = Instr {
                        op: op.op,
                        out,
                        a: op.a,
                        b: op.b,
                    };
                    // The arguments' registers are taken while `out` is still held, so the
                    // output register differs from both.
                    if arity >= 1 {
                        instr.a = reg_of(args[0], &mut self.reg, &mut self.free);
                    }
                    if arity == 2 {
                        instr.b = reg_of(args[1], &mut self.reg, &mut self.free);
                    }
                    choice_count += u32::from(is_choice(&op));
                    (op, instr)
                }
            };
            // Above its definition the value is not live: its register is free there.
            self.free.push(out);
            self.pos[i] = self.emitted.len() as u32;
            self.emitted.push((ssa_op, instr));
        }
        self.finish(consts, working, choice_count, in_outputs)
    }

    /// Puts the operations emitted last-first in order, into [`Scratch::out`]: constants
    /// first in the SSA list and in registers `0..consts.len()`, working registers after
    /// them. Returns the register count and the number of `min`/`max` operations.
    fn finish(
        &mut self,
        consts: Vec<Constant>,
        working: u32,
        choice_count: u32,
        in_outputs: &[u32],
    ) -> (u32, u32) {
        let nc = consts.len() as u32;
        let m = self.emitted.len() as u32;
        let reg = |r: u32| if r & CONST != 0 { r & !CONST } else { r + nc };
        let pos = &self.pos;
        // The final SSA position of input value `p`.
        let position = |mut p: u32| loop {
            let v = pos[p as usize];
            if v & CONST != 0 {
                return v & !CONST;
            }
            if v & ALIAS != 0 {
                p = v & !ALIAS;
                continue;
            }
            return nc + (m - 1 - v);
        };
        let out = &mut self.out;
        out.consts = consts;
        out.ssa.clear();
        out.ssa.extend((0..nc).map(|c| SsaOp {
            op: Opcode::Const,
            a: c,
            b: 0,
        }));
        out.instrs.clear();
        out.choice_index.clear();
        out.choice_index.resize((nc + m) as usize, NO_CHOICE);
        let mut choices = 0;
        for &(op, ins) in self.emitted.iter().rev() {
            if is_choice(&op) {
                out.choice_index[out.ssa.len()] = choices;
                choices += 1;
            }
            let mut op = op;
            let mut ins = ins;
            let (_, arity) = operands(&op);
            ins.out = reg(ins.out);
            if arity >= 1 {
                op.a = position(op.a);
                ins.a = reg(ins.a);
            }
            if arity == 2 {
                op.b = position(op.b);
                ins.b = reg(ins.b);
            }
            out.ssa.push(op);
            out.instrs.push(ins);
        }
        out.ssa_outputs.clear();
        out.ssa_outputs
            .extend(in_outputs.iter().map(|&o| position(o)));
        out.outputs.clear();
        out.outputs
            .extend(in_outputs.iter().map(|&o| reg(self.reg[o as usize])));
        (nc + working, choice_count)
    }
}
