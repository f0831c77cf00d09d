//! Linear-scan register allocation of an SSA list.

use super::{Instr, Opcode, SsaOp};

/// The SSA positions an operation reads.
pub(super) fn operands(op: &SsaOp) -> ([u32; 2], usize) {
    match op.op {
        Opcode::Var | Opcode::Const => ([0, 0], 0),
        Opcode::Copy | Opcode::Unary(_) | Opcode::Pown => ([op.a, 0], 1),
        Opcode::Binary(_) => ([op.a, op.b], 2),
    }
}

/// Assigns registers: constants `0..const_count` get their own; every other value a register
/// taken from a free list (or a new one), released after its last use. Outputs are never
/// released. Returns the instructions, the output registers and the register count.
pub(super) fn allocate(
    ssa: &[SsaOp],
    const_count: u32,
    outputs: &[u32],
) -> (Vec<Instr>, Vec<u32>, u32) {
    SCRATCH.with_borrow_mut(|scratch| allocate_with(ssa, const_count, outputs, scratch))
}

/// Buffers of [`allocate`], kept per thread so that the many small allocations of a
/// renderer's pruning (one per tile) reuse their storage.
#[derive(Default)]
struct Scratch {
    last_use: Vec<usize>,
    reg: Vec<u32>,
    free: Vec<u32>,
}

thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

fn allocate_with(
    ssa: &[SsaOp],
    const_count: u32,
    outputs: &[u32],
    scratch: &mut Scratch,
) -> (Vec<Instr>, Vec<u32>, u32) {
    let n = ssa.len();
    let Scratch {
        last_use,
        reg,
        free,
    } = scratch;
    last_use.clear();
    last_use.resize(n, 0);
    for (i, op) in ssa.iter().enumerate() {
        let (args, k) = operands(op);
        for &a in &args[..k] {
            last_use[a as usize] = i;
        }
    }
    for &o in outputs {
        last_use[o as usize] = usize::MAX;
    }
    reg.clear();
    reg.resize(n, u32::MAX);
    free.clear();
    let mut next = const_count;
    let mut instrs = Vec::with_capacity(n);
    for (i, op) in ssa.iter().enumerate() {
        if op.op == Opcode::Const {
            reg[i] = op.a;
            continue;
        }
        let out = free.pop().unwrap_or_else(|| {
            next += 1;
            next - 1
        });
        reg[i] = out;
        let (args, k) = operands(op);
        let mut instr = Instr {
            op: op.op,
            out,
            a: op.a,
            b: op.b,
        };
        if k >= 1 {
            instr.a = reg[args[0] as usize];
        }
        if k == 2 {
            instr.b = reg[args[1] as usize];
        }
        // Release the inputs that die here (after choosing `out`, so `out` differs from them).
        for (j, &a) in args[..k].iter().enumerate() {
            let a = a as usize;
            let dup = j == 1 && args[0] as usize == a;
            if last_use[a] == i && ssa[a].op != Opcode::Const && !dup {
                free.push(reg[a]);
            }
        }
        instrs.push(instr);
    }
    let out_regs = outputs.iter().map(|&o| reg[o as usize]).collect();
    (instrs, out_regs, next)
}
