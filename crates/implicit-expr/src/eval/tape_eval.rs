//! The walk over a register tape, for one point (or box) at a time and for slices.

use std::any::Any;

use interval_core::{Decoration, Interval, isa};

use crate::constant::Constant;
use crate::error::Error;
use crate::jit::{self, Flags, MAX_OUTPUTS, MAX_VARS};
use crate::number::{Choice, Number};
use crate::op::BinaryOp;
use crate::tape::{Instr, Opcode, Tape};

/// Evaluates a [`Tape`] on one input at a time. Owns its registers: make one per thread
/// (they are cheap) and reuse it across calls and tapes.
#[derive(Clone, Debug)]
pub struct Evaluator<N> {
    tape: Tape,
    regs: Vec<N>,
    /// The choice bytes of compiled traced evaluations.
    choice_bytes: Vec<u8>,
}

/// The outputs of `tape` at `vars` by its machine code ([`crate::jit`]) into `out`, where
/// `N` is `Interval<f64>`, every variable is non-empty and the tape has code (compiled now
/// if it is due); with the choices in `trace` where given (`bytes` is the buffer). `None`
/// where the interpreter must evaluate.
#[inline(always)]
fn compiled<N: Number>(
    tape: &Tape,
    vars: &[N],
    (bytes, trace): (&mut Vec<u8>, Option<&mut Vec<Choice>>),
    out: &mut [[f64; 2]; MAX_OUTPUTS],
) -> Option<Flags> {
    if std::any::TypeId::of::<N>() != std::any::TypeId::of::<Interval<f64>>()
        || tape.var_count() > MAX_VARS
    {
        return None;
    }
    let code = tape.code(trace.is_some())?;
    let mut xs = [[0.0f64; 2]; MAX_VARS];
    for (x, v) in xs.iter_mut().zip(&vars[..tape.var_count()]) {
        let (lo, hi) = (v as &dyn Any).downcast_ref::<Interval<f64>>()?.bounds()?;
        *x = [lo, hi];
    }
    // Traced code (also what serves a plain evaluation where the tape has it) writes a
    // byte per choice.
    bytes.resize(code.choices(), 2);
    let flags = code.run(&xs, bytes, out)?;
    if let Some(trace) = trace {
        if !flags.defined() {
            // As the interpreter: nothing may be pruned where the formula is undefined.
            trace.clear();
            trace.resize(tape.choice_count(), Choice::Both);
        } else {
            jit::choices_into(bytes, trace);
        }
    }
    Some(flags)
}

/// `[lo, hi]` as `N`, where `N` is `Interval<f64>` (as in [`compiled`]).
#[inline(always)]
fn number<N: Number>(b: [f64; 2]) -> Option<N> {
    let v = Interval::new_unchecked(b[0], b[1]);
    (&v as &dyn Any).downcast_ref::<N>().copied()
}

/// The first output by [`compiled`].
#[inline(always)]
fn compiled_first<N: Number>(
    tape: &Tape,
    vars: &[N],
    trace: (&mut Vec<u8>, Option<&mut Vec<Choice>>),
) -> Option<(N, Flags)> {
    let mut out = [[0.0f64; 2]; MAX_OUTPUTS];
    let flags = compiled(tape, vars, trace, &mut out)?;
    Some((number(out[0])?, flags))
}

/// Makes `regs` a register file of `width` lanes per register for a tape, and fills lanes
/// `lanes` of its constant registers (constant `i` lives in register `i`). The working
/// registers keep whatever they held (each is written before it is read), so switching
/// tapes costs the constants only. The register count is padded to a power of two, so that
/// the scalar loop can index with a mask instead of a bounds check; the file only grows.
fn load_registers<N: Number>(
    tape: &Tape,
    width: usize,
    regs: &mut Vec<N>,
    lanes: std::ops::Range<usize>,
) {
    let need = tape.reg_count().next_power_of_two() * width;
    if regs.len() < need {
        regs.resize(need, N::constant(&Constant::ZERO));
    }
    if lanes.is_empty() {
        return;
    }
    for (reg, c) in regs.chunks_exact_mut(width).zip(tape.consts()) {
        reg[lanes.clone()].fill(N::constant(c));
    }
}

impl<N: Number> Evaluator<N> {
    /// An evaluator for `tape`.
    pub fn new(tape: &Tape) -> Self {
        let mut regs = Vec::new();
        load_registers(tape, 1, &mut regs, 0..1);
        Self {
            tape: tape.clone(),
            regs,
            choice_bytes: Vec::new(),
        }
    }

    /// Switches to another tape, reusing the register storage.
    pub fn set_tape(&mut self, tape: &Tape) {
        if !self.tape.ptr_eq(tape) {
            self.tape = tape.clone();
            load_registers(tape, 1, &mut self.regs, 0..1);
        }
    }

    /// The tape being evaluated.
    pub fn tape(&self) -> &Tape {
        &self.tape
    }

    fn check(&self, vars: &[N]) -> Result<(), Error> {
        if vars.len() < self.tape.var_count() {
            return Err(Error::MissingVar {
                slot: vars.len() as u32,
                given: vars.len(),
            });
        }
        Ok(())
    }

    /// The first output at `vars` (one value per variable slot: `x`, `y`, `z`, then the
    /// other variables in declaration order).
    ///
    /// Returns an error when fewer values than the tape's variable slots are given.
    pub fn eval(&mut self, vars: &[N]) -> Result<N, Error> {
        self.check(vars)?;
        if let Some((v, _)) = compiled_first(&self.tape, vars, (&mut self.choice_bytes, None)) {
            return Ok(v);
        }
        run::<N, false, NO_CHECK, NO_SIDE>(
            self.tape.instrs(),
            &mut self.regs,
            vars,
            &mut Vec::new(),
            &mut 0,
        );
        Ok(self.regs[self.tape.outputs()[0] as usize])
    }

    /// Like [`eval`](Self::eval), with the decoration of the evaluation (IEEE 1788 §11.7):
    /// the least decoration of any operation on its arguments over the region, by the rules
    /// of [`interval_core::decorated::rules`], and `Dac` at most where an intermediate
    /// result is unbounded. For set types:
    ///
    /// * at least [`Decoration::Dac`]: the formula is defined and continuous on the whole
    ///   region, so a sign change between two of its points proves a root between them (the
    ///   inclusion test of a beam, the sign-change proofs of the root finders);
    /// * [`Decoration::Def`]: defined on the whole region, but it may jump there (a step
    ///   function across a jump, a `domain` test taking both signs), so the sign of the
    ///   value still holds at every point;
    /// * [`Decoration::Trv`]: possibly undefined somewhere in the region.
    ///
    /// The same decoration as evaluating on [`DecInterval`](interval_core::DecInterval)s
    /// with `com` inputs, at the cost of the plain evaluation and a comparison per
    /// operation. Point types give `Com`.
    ///
    /// Returns an error when fewer values than the tape's variable slots are given.
    pub fn eval_decorated(&mut self, vars: &[N]) -> Result<(N, Decoration), Error> {
        self.check(vars)?;
        let dec = run::<N, false, DECORATION, NO_SIDE>(
            self.tape.instrs(),
            &mut self.regs,
            vars,
            &mut Vec::new(),
            &mut 0,
        );
        Ok((
            self.regs[self.tape.outputs()[0] as usize],
            self.with_constants(dec),
        ))
    }

    /// Like [`eval`](Self::eval), also telling whether the formula is proven defined and
    /// continuous on the whole region: whether [`eval_decorated`](Self::eval_decorated)
    /// would give at least [`Decoration::Dac`], found at less cost (only the partial and the
    /// discontinuous operations are checked).
    ///
    /// Returns an error when fewer values than the tape's variable slots are given.
    pub fn eval_continuous(&mut self, vars: &[N]) -> Result<(N, bool), Error> {
        self.check(vars)?;
        if let Some((v, flags)) = compiled_first(&self.tape, vars, (&mut self.choice_bytes, None)) {
            return Ok((
                v,
                flags.continuous() && v.value_decoration() >= Decoration::Dac,
            ));
        }
        let dec = run::<N, false, CONTINUITY, NO_SIDE>(
            self.tape.instrs(),
            &mut self.regs,
            vars,
            &mut Vec::new(),
            &mut 0,
        );
        let v = self.regs[self.tape.outputs()[0] as usize];
        Ok((v, dec.min(v.value_decoration()) >= Decoration::Dac))
    }

    /// The first output at `vars` on each side of a domain boundary: where exactly one
    /// [`domain`](crate::BinaryOp::Domain) operation has a test that takes both signs over
    /// the region, `Some((inside, outside))`, the value with that operation taking its
    /// formula's value and with it absent. Every point of the region is on one side, so the
    /// first output there lies in one of the two. `None` where no `domain` or more than one
    /// is undecided (then the sides of two boundaries could mix).
    ///
    /// Returns an error when fewer values than the tape's variable slots are given.
    pub fn eval_sides(&mut self, vars: &[N]) -> Result<Option<(N, N)>, Error> {
        self.check(vars)?;
        let out = self.tape.outputs()[0] as usize;
        let mut undecided = 0;
        let instrs = self.tape.instrs();
        run::<N, false, NO_CHECK, INSIDE>(
            instrs,
            &mut self.regs,
            vars,
            &mut Vec::new(),
            &mut undecided,
        );
        if undecided != 1 {
            return Ok(None);
        }
        let inside = self.regs[out];
        run::<N, false, NO_CHECK, OUTSIDE>(instrs, &mut self.regs, vars, &mut Vec::new(), &mut 0);
        Ok(Some((inside, self.regs[out])))
    }

    /// Every output at `vars`, written to `out` (which must hold one value per output).
    ///
    /// Returns an error when `vars` or `out` is too short.
    pub fn eval_outputs(&mut self, vars: &[N], out: &mut [N]) -> Result<(), Error> {
        self.check(vars)?;
        if out.len() < self.tape.outputs().len() {
            return Err(Error::Unsupported(format!(
                "output buffer holds {} values, the tape has {} outputs",
                out.len(),
                self.tape.outputs().len()
            )));
        }
        let mut buf = [[0.0f64; 2]; MAX_OUTPUTS];
        // `N` is `Interval<f64>` where the code ran, so every output converts.
        let n = self.tape.outputs().len();
        if compiled(&self.tape, vars, (&mut self.choice_bytes, None), &mut buf).is_some()
            && out
                .iter_mut()
                .zip(&buf[..n])
                .all(|(o, &b)| number(b).map(|v| *o = v).is_some())
        {
            return Ok(());
        }
        run::<N, false, NO_CHECK, NO_SIDE>(
            self.tape.instrs(),
            &mut self.regs,
            vars,
            &mut Vec::new(),
            &mut 0,
        );
        for (o, &r) in out.iter_mut().zip(self.tape.outputs()) {
            *o = self.regs[r as usize];
        }
        Ok(())
    }

    /// Like [`eval`](Self::eval), also recording in `trace` (cleared first) which argument
    /// each `min`/`max` took, in tape order: the input of [`Tape::simplify`].
    ///
    /// Where some operation is undefined on part of its argument (`sqrt` of an interval
    /// reaching below 0, a division by an interval holding 0, ...), every choice is recorded
    /// as [`Choice::Both`]: the formula is then partly undefined in the region, and a pruned
    /// tape, defined where the full one is not, would change it. An undecided
    /// [`domain`](crate::BinaryOp::Domain) does not count: it is defined everywhere (the
    /// formula or the absent object), only not continuous, and a choice made over its
    /// enclosure holds at every point.
    pub fn eval_traced(&mut self, vars: &[N], trace: &mut Vec<Choice>) -> Result<N, Error> {
        self.check(vars)?;
        if let Some((v, _)) =
            compiled_first(&self.tape, vars, (&mut self.choice_bytes, Some(trace)))
        {
            return Ok(v);
        }
        trace.clear();
        run::<N, true, NO_CHECK, NO_SIDE>(self.tape.instrs(), &mut self.regs, vars, trace, &mut 0);
        Ok(self.regs[self.tape.outputs()[0] as usize])
    }

    /// Like [`eval_traced`](Self::eval_traced), also telling whether the formula is proven
    /// defined at every point of the region: whether
    /// [`eval_decorated`](Self::eval_decorated) would give at least [`Decoration::Def`],
    /// found by the traced evaluation itself (it checks the partial operations to decide
    /// whether choices may be kept). One evaluation where a classification of the region
    /// and its pruning would take two.
    ///
    /// Returns an error when fewer values than the tape's variable slots are given.
    pub fn eval_traced_defined(
        &mut self,
        vars: &[N],
        trace: &mut Vec<Choice>,
    ) -> Result<(N, bool), Error> {
        self.check(vars)?;
        if let Some((v, flags)) =
            compiled_first(&self.tape, vars, (&mut self.choice_bytes, Some(trace)))
        {
            // An empty result would have sent it to the interpreter.
            return Ok((v, flags.defined()));
        }
        trace.clear();
        let dec = run::<N, true, NO_CHECK, NO_SIDE>(
            self.tape.instrs(),
            &mut self.regs,
            vars,
            trace,
            &mut 0,
        );
        let v = self.regs[self.tape.outputs()[0] as usize];
        let dec = self.with_constants(dec);
        Ok((v, dec.min(v.value_decoration()) >= Decoration::Def))
    }

    /// `dec` lowered to the least decoration of the constants: they live in the first
    /// registers, loaded with the tape (an enclosure of a literal beyond the format's range
    /// is unbounded).
    fn with_constants(&self, dec: Decoration) -> Decoration {
        let consts = self.tape.consts().len();
        self.regs[..consts]
            .iter()
            .fold(dec, |d, c| d.min(c.value_decoration()))
    }

    /// The tape pruned to the region `vars`: an [`eval_traced`](Self::eval_traced) there,
    /// then [`Tape::simplify`] by its trace (`trace` is the buffer). Equal to the tape at
    /// every point of the region, with the same enclosure over every part of it; the tape
    /// itself where nothing is decided.
    ///
    /// Returns an error when fewer values than the tape's variable slots are given.
    pub fn pruned(&mut self, vars: &[N], trace: &mut Vec<Choice>) -> Result<Tape, Error> {
        self.eval_traced(vars, trace)?;
        self.tape.simplify(trace)
    }
}

/// [`run`]'s `SIDE`: `domain` as [`Number::binary`] evaluates it.
const NO_SIDE: u8 = 0;
/// [`run`]'s `SIDE`: a `domain` whose test takes both signs takes its formula's value.
const INSIDE: u8 = 1;
/// [`run`]'s `SIDE`: a `domain` whose test takes both signs is absent.
const OUTSIDE: u8 = 2;

/// [`run`]'s `CHECK`: no decoration.
const NO_CHECK: u8 = 0;
/// [`run`]'s `CHECK`: whether the formula is defined and continuous, decorations at least
/// `dac` told apart from the others only: the local decorations of the partial and
/// discontinuous operations (the caller checks the output for emptiness).
const CONTINUITY: u8 = 1;
/// [`run`]'s `CHECK`: the IEEE 1788 decoration, with every intermediate value's own.
const DECORATION: u8 = 2;

/// The interpreter loop. `TRACE` selects choice recording, `CHECK` the decoration
/// ([`NO_CHECK`], [`CONTINUITY`], [`DECORATION`]) and `SIDE` the side taken by an undecided
/// `domain` (counted in `undecided`) at compile time.
///
/// Returns the decoration of the evaluation (IEEE 1788 §11.7; every live operation of a
/// one-output tape feeds the output, so it is the least decoration of any operation on its
/// arguments and of any intermediate value):
///
/// * `DECORATION`: exactly that;
/// * `CONTINUITY`: at least `dac` exactly where that is, once the output is checked for
///   emptiness, without the cost of checking the operations that are defined and
///   continuous everywhere: an empty argument of one of them comes from a partial operation
///   (checked) or an empty variable, and the total operations return the empty set on an
///   empty argument, so an empty variable reaches the output (`domain`, which may not, is
///   checked with the partial operations);
/// * `TRACE` alone: `Trv` where a partial operation is undefined on part of its arguments,
///   `Com` otherwise (step functions and `domain` jump but are defined, which does not
///   stop pruning);
/// * neither: `Com`.
///
/// Runs the loop compiled for the instruction set in use ([`interval_core::isa`]).
#[inline(always)]
fn run<N: Number, const TRACE: bool, const CHECK: u8, const SIDE: u8>(
    instrs: &[Instr],
    regs: &mut [N],
    vars: &[N],
    trace: &mut Vec<Choice>,
    undecided: &mut u32,
) -> Decoration {
    isa::dispatch(
        #[inline(always)]
        || {
            // `regs.len()` is a power of two above every register index of the tape, so
            // masking changes no index and proves to the compiler that none is out of bounds.
            debug_assert!(regs.len().is_power_of_two());
            let mask = regs.len() - 1;
            let mut dec = Decoration::Com;
            for ins in instrs {
                let (a, b) = (ins.a as usize & mask, ins.b as usize & mask);
                let v = match ins.op {
                    Opcode::Var => vars[ins.a as usize],
                    Opcode::Const | Opcode::Copy => regs[a],
                    Opcode::Unary(op) => {
                        // The local decoration is needed of the operations that can fail
                        // (partial or step functions); traced runs ask only whether they are
                        // defined, which step functions always are.
                        if (CHECK != NO_CHECK && (!op.is_total() || op.is_discontinuous()))
                            || (TRACE && !op.is_total())
                        {
                            dec = dec.min(N::decoration_unary(op, regs[a]));
                        }
                        N::unary(op, regs[a])
                    }
                    Opcode::Binary(BinaryOp::Min) if TRACE => {
                        let (v, c) = N::min_choice(regs[a], regs[b]);
                        trace.push(c);
                        v
                    }
                    Opcode::Binary(BinaryOp::Max) if TRACE => {
                        let (v, c) = N::max_choice(regs[a], regs[b]);
                        trace.push(c);
                        v
                    }
                    Opcode::Binary(BinaryOp::Domain) if SIDE != NO_SIDE => {
                        let (v, open) = N::domain_side(regs[a], regs[b], SIDE == INSIDE);
                        *undecided += u32::from(open);
                        v
                    }
                    Opcode::Binary(op) => {
                        if (CHECK != NO_CHECK || TRACE) && !op.is_total() {
                            dec = dec.min(N::decoration_binary(op, regs[a], regs[b]));
                        }
                        N::binary(op, regs[a], regs[b])
                    }
                    Opcode::Pown => {
                        if (CHECK != NO_CHECK || TRACE) && (ins.b as i32) < 0 {
                            dec = dec.min(N::decoration_pown(regs[a], ins.b as i32));
                        }
                        N::pown(regs[a], ins.b as i32)
                    }
                };
                if CHECK == DECORATION {
                    dec = dec.min(v.value_decoration());
                }
                regs[ins.out as usize & mask] = v;
            }
            if TRACE && dec < Decoration::Def {
                // Somewhere in the region the formula is undefined: a pruned tape would be defined
                // there (it drops the undefined branch), so nothing may be pruned.
                trace.fill(Choice::Both);
            }
            dec
        },
    )
}

/// Number of inputs a [`SliceEvaluator`] processes per pass over the tape.
pub const SLICE_CHUNK: usize = 64;

/// Evaluates a [`Tape`] on many inputs: each instruction runs over a chunk of
/// [`SLICE_CHUNK`] inputs before the next, which amortises the interpretation and lets the
/// compiler vectorise the arithmetic.
#[derive(Clone, Debug)]
pub struct SliceEvaluator<N> {
    tape: Tape,
    regs: Vec<N>,
    /// The lanes of the constant registers filled so far for this tape (an evaluation of
    /// fewer inputs than a chunk fills only the lanes it uses).
    filled: usize,
}

impl<N: Number> SliceEvaluator<N> {
    /// An evaluator for `tape`.
    pub fn new(tape: &Tape) -> Self {
        let mut regs = Vec::new();
        load_registers(tape, SLICE_CHUNK, &mut regs, 0..0);
        Self {
            tape: tape.clone(),
            regs,
            filled: 0,
        }
    }

    /// Switches to another tape, reusing the register storage.
    pub fn set_tape(&mut self, tape: &Tape) {
        if !self.tape.ptr_eq(tape) {
            self.tape = tape.clone();
            load_registers(tape, SLICE_CHUNK, &mut self.regs, 0..0);
            self.filled = 0;
        }
    }

    /// The first output at every input: `vars[s][i]` is the value of slot `s` at input `i`;
    /// `out[i]` receives the result.
    ///
    /// Returns an error when fewer slots than the tape's are given or the lengths differ.
    pub fn eval(&mut self, vars: &[&[N]], out: &mut [N]) -> Result<(), Error> {
        self.prepare(vars, out.len())?;
        let output = self.tape.outputs()[0] as usize;
        let mut start = 0;
        while start < out.len() {
            let n = SLICE_CHUNK.min(out.len() - start);
            pass(self.tape.instrs(), &mut self.regs, vars, start, n);
            out[start..start + n].copy_from_slice(&self.regs[output * SLICE_CHUNK..][..n]);
            start += n;
        }
        Ok(())
    }

    /// Like [`eval`](Self::eval), also recording for every input `i` in `traces[i]`
    /// (cleared first) which argument each `min`/`max` took, as
    /// [`Evaluator::eval_traced`] does for one input: each trace is the input of
    /// [`Tape::simplify`] for the region of its input. Evaluates many regions (the
    /// sub-tiles of a tile, the boxes of a screen) in one pass over the tape.
    ///
    /// Returns an error when the slots or lengths do not match, or `traces` does not hold
    /// one trace per input.
    pub fn eval_traced(
        &mut self,
        vars: &[&[N]],
        out: &mut [N],
        traces: &mut [Vec<Choice>],
    ) -> Result<(), Error> {
        self.prepare(vars, out.len())?;
        if traces.len() != out.len() {
            return Err(Error::Unsupported(format!(
                "{} traces given for {} inputs",
                traces.len(),
                out.len()
            )));
        }
        for t in traces.iter_mut() {
            t.clear();
        }
        let output = self.tape.outputs()[0] as usize;
        let mut defined = [true; SLICE_CHUNK];
        let mut start = 0;
        while start < out.len() {
            let n = SLICE_CHUNK.min(out.len() - start);
            defined[..n].fill(true);
            let lanes = &mut traces[start..start + n];
            pass_traced(
                self.tape.instrs(),
                &mut self.regs,
                vars,
                (start, n),
                lanes,
                &mut defined,
            );
            out[start..start + n].copy_from_slice(&self.regs[output * SLICE_CHUNK..][..n]);
            for (t, &d) in lanes.iter_mut().zip(&defined[..n]) {
                if !d {
                    // Partly undefined region: nothing may be pruned (see `eval_traced`).
                    t.fill(Choice::Both);
                }
            }
            start += n;
        }
        Ok(())
    }

    /// Checks the inputs, and fills the constant lanes that `len` inputs use.
    fn prepare(&mut self, vars: &[&[N]], len: usize) -> Result<(), Error> {
        if vars.len() < self.tape.var_count() {
            return Err(Error::MissingVar {
                slot: vars.len() as u32,
                given: vars.len(),
            });
        }
        if let Some(bad) = vars.iter().position(|v| v.len() != len) {
            return Err(Error::Unsupported(format!(
                "variable slot {bad} has {} values, the output {len}",
                vars[bad].len(),
            )));
        }
        let lanes = SLICE_CHUNK.min(len);
        if lanes > self.filled {
            load_registers(&self.tape, SLICE_CHUNK, &mut self.regs, self.filled..lanes);
            self.filled = lanes;
        }
        Ok(())
    }
}

/// One pass of `instrs` over `n` inputs starting at `start`, in the loop compiled for the
/// instruction set in use ([`interval_core::isa`]).
fn pass<N: Number>(instrs: &[Instr], regs: &mut [N], vars: &[&[N]], start: usize, n: usize) {
    isa::dispatch(
        #[inline(always)]
        || {
            for ins in instrs {
                step(ins, regs, vars, start, n);
            }
        },
    );
}

/// [`pass`] recording choices and definedness per input (see [`step_traced`]).
fn pass_traced<N: Number>(
    instrs: &[Instr],
    regs: &mut [N],
    vars: &[&[N]],
    (start, n): (usize, usize),
    lanes: &mut [Vec<Choice>],
    defined: &mut [bool; SLICE_CHUNK],
) {
    isa::dispatch(
        #[inline(always)]
        || {
            for ins in instrs {
                step_traced(ins, regs, vars, start, n, lanes, defined);
            }
        },
    );
}

/// One instruction over `n` inputs starting at `start`.
#[inline(always)]
fn step<N: Number>(ins: &Instr, regs: &mut [N], vars: &[&[N]], start: usize, n: usize) {
    let c = SLICE_CHUNK;
    let o = ins.out as usize;
    // `out` differs from the inputs (register allocation guarantees it): split around it.
    let (below, rest) = regs.split_at_mut(o * c);
    let (out, above) = rest.split_at_mut(c);
    let out = &mut out[..n];
    let reg = |r: usize| -> &[N] {
        if r < o {
            &below[r * c..r * c + n]
        } else {
            &above[(r - o - 1) * c..(r - o - 1) * c + n]
        }
    };
    match ins.op {
        Opcode::Var => out.copy_from_slice(&vars[ins.a as usize][start..start + n]),
        Opcode::Const | Opcode::Copy => out.copy_from_slice(reg(ins.a as usize)),
        Opcode::Unary(op) => N::unary_slice(op, reg(ins.a as usize), out),
        Opcode::Binary(op) => N::binary_slice(op, reg(ins.a as usize), reg(ins.b as usize), out),
        Opcode::Pown => {
            let k = ins.b as i32;
            for (o, &x) in out.iter_mut().zip(reg(ins.a as usize)) {
                *o = N::pown(x, k);
            }
        }
    }
}

/// One instruction over `n` inputs, recording `min`/`max` choices per input in `lanes` and
/// clearing `defined[i]` where an operation is undefined on part of input `i`'s arguments.
#[inline(always)]
fn step_traced<N: Number>(
    ins: &Instr,
    regs: &mut [N],
    vars: &[&[N]],
    start: usize,
    n: usize,
    lanes: &mut [Vec<Choice>],
    defined: &mut [bool; SLICE_CHUNK],
) {
    let c = SLICE_CHUNK;
    let (a, b) = (ins.a as usize, ins.b as usize);
    match ins.op {
        Opcode::Binary(op @ (BinaryOp::Min | BinaryOp::Max)) => {
            let o = ins.out as usize;
            for i in 0..n {
                let (x, y) = (regs[a * c + i], regs[b * c + i]);
                let (v, choice) = if op == BinaryOp::Min {
                    N::min_choice(x, y)
                } else {
                    N::max_choice(x, y)
                };
                regs[o * c + i] = v;
                lanes[i].push(choice);
            }
            return;
        }
        // As in `run`: only partial operations can leave part of a region undefined; step
        // functions and an undecided `domain` jump, which does not stop pruning.
        Opcode::Unary(op) if !op.is_total() => {
            for (i, d) in defined.iter_mut().enumerate().take(n) {
                *d &= N::decoration_unary(op, regs[a * c + i]) >= Decoration::Def;
            }
        }
        Opcode::Binary(op) if !op.is_total() => {
            for (i, d) in defined.iter_mut().enumerate().take(n) {
                *d &= N::decoration_binary(op, regs[a * c + i], regs[b * c + i]) >= Decoration::Def;
            }
        }
        Opcode::Pown if (ins.b as i32) < 0 => {
            for (i, d) in defined.iter_mut().enumerate().take(n) {
                *d &= N::decoration_pown(regs[a * c + i], ins.b as i32) >= Decoration::Def;
            }
        }
        _ => {}
    }
    step(ins, regs, vars, start, n);
}
