//! The compiled form of an expression: an SSA list of operations and, from it, a flat
//! register tape that every evaluator walks.
//!
//! [`Tape::new`] takes the nodes that the outputs depend on, in topological order (the SSA
//! form), and allocates registers by a backward linear scan: constants sit in fixed
//! registers that evaluators fill once per tape, every other value gets a register that is
//! reused above its definition. An instruction's output register never equals one of its inputs, so slice
//! evaluators can borrow them as disjoint slices.
//!
//! Tapes are cheap to clone (an `Arc`) and immutable; [`Tape::simplify`] makes the shorter
//! tape valid inside a region from the `min`/`max` choices of an interval evaluation there.

pub mod cache;
mod forward;
mod graph;
mod prune;
mod regalloc;
mod zero_vars;

use std::sync::Arc;

use crate::constant::Constant;
use crate::context::{Context, Node, NodeId};
use crate::error::Error;
use crate::number::Choice;
use crate::op::{BinaryOp, UnaryOp};

/// What an instruction does.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Opcode {
    /// Load variable slot `a`.
    Var,
    /// Load constant `a` (SSA form only: in the register tape constants live in registers).
    Const,
    /// Copy register `a` (the register tape never needs it; kept for completeness of SSA
    /// rewrites).
    Copy,
    /// A one-argument operation on `a`.
    Unary(UnaryOp),
    /// A two-argument operation on `a` and `b`.
    Binary(BinaryOp),
    /// `a^n`, with `n` stored in `b` as the bits of an `i32`.
    Pown,
}

/// One SSA operation: its result is the value numbered by its position; `a` and `b` are
/// earlier positions (or a slot / constant index / exponent, by [`Opcode`]).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct SsaOp {
    /// The operation.
    pub op: Opcode,
    /// First argument.
    pub a: u32,
    /// Second argument.
    pub b: u32,
}

/// One register-tape instruction: `out = op(a, b)` on registers.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct Instr {
    /// The operation.
    pub op: Opcode,
    /// Output register.
    pub out: u32,
    /// First argument register (the slot for [`Opcode::Var`]).
    pub a: u32,
    /// Second argument register (the exponent bits for [`Opcode::Pown`]).
    pub b: u32,
}

#[derive(Debug)]
struct TapeData {
    ssa: Vec<SsaOp>,
    ssa_outputs: Vec<u32>,
    consts: Vec<Constant>,
    instrs: Vec<Instr>,
    outputs: Vec<u32>,
    reg_count: u32,
    var_count: u32,
    choice_count: u32,
    /// Each SSA operation's index in a choice trace ([`regalloc::NO_CHOICE`] when it is not
    /// a `min` or `max`).
    choice_index: Vec<u32>,
    /// See [`Tape::is_continuous_everywhere`]: found when first asked (most pruned tapes
    /// never are).
    continuous_everywhere: std::sync::OnceLock<bool>,
    /// The machine code of the tape, compiled once it is evaluated often enough.
    jit: crate::jit::Slot,
    /// See [`Tape::content_hash`].
    content_hash: std::sync::OnceLock<u64>,
}

/// A compiled expression with one or more outputs. See the [module documentation](self).
#[derive(Clone, Debug)]
pub struct Tape(Arc<TapeData>);

impl Tape {
    /// Compiles the nodes `roots` of `ctx` (each one an output, in order).
    ///
    /// Returns an error when `roots` is empty.
    pub fn new(ctx: &Context, roots: &[NodeId]) -> Result<Self, Error> {
        if roots.is_empty() {
            return Err(Error::Unsupported(
                "a tape needs at least one output".into(),
            ));
        }
        let order = ctx.reachable(roots);
        let mut pos = vec![u32::MAX; ctx.len()];
        let mut ssa = Vec::with_capacity(order.len());
        let mut consts = Vec::new();
        for id in order {
            let op = match *ctx.get(id) {
                Node::Var(v) => SsaOp {
                    op: Opcode::Var,
                    a: v.0,
                    b: 0,
                },
                Node::Const(c) => {
                    consts.push(c);
                    SsaOp {
                        op: Opcode::Const,
                        a: (consts.len() - 1) as u32,
                        b: 0,
                    }
                }
                Node::Unary(op, a) => SsaOp {
                    op: Opcode::Unary(op),
                    a: pos[a.index()],
                    b: 0,
                },
                Node::Binary(op, a, b) => SsaOp {
                    op: Opcode::Binary(op),
                    a: pos[a.index()],
                    b: pos[b.index()],
                },
                Node::Pown(a, n) => SsaOp {
                    op: Opcode::Pown,
                    a: pos[a.index()],
                    b: n as u32,
                },
            };
            pos[id.index()] = ssa.len() as u32;
            ssa.push(op);
        }
        let outputs: Vec<u32> = roots.iter().map(|r| pos[r.index()]).collect();
        Ok(Self::compiled(
            &ssa,
            &consts,
            &outputs,
            ctx.var_count() as u32,
            |_| Choice::Both,
        ))
    }

    /// The tape of the values of `ssa` that `outputs` depend on, each decided `min`/`max`
    /// forwarded to the argument it took (`choice(i)` for the operation at position `i`).
    fn compiled(
        ssa: &[SsaOp],
        consts: &[Constant],
        outputs: &[u32],
        var_count: u32,
        choice: impl Fn(usize) -> Choice,
    ) -> Self {
        regalloc::compile((ssa, consts, outputs, var_count), choice, |c| {
            Self::of_parts(&c, var_count)
        })
    }

    /// A tape of its own holding `c`'s parts.
    pub(in crate::tape) fn of_parts(c: &regalloc::Compiled<'_>, var_count: u32) -> Self {
        Tape(Arc::new(TapeData {
            ssa: c.ssa.to_vec(),
            ssa_outputs: c.ssa_outputs.to_vec(),
            consts: c.consts.to_vec(),
            instrs: c.instrs.to_vec(),
            outputs: c.outputs.to_vec(),
            reg_count: c.reg_count,
            var_count,
            choice_count: c.choice_count,
            choice_index: c.choice_index.to_vec(),
            continuous_everywhere: std::sync::OnceLock::new(),
            jit: crate::jit::Slot::default(),
            content_hash: std::sync::OnceLock::from(c.hash),
        }))
    }

    /// Whether this tape has `c`'s content (what [`PartialEq`] compares) with `var_count`
    /// variable slots.
    pub(in crate::tape) fn has_parts(&self, c: &regalloc::Compiled<'_>, var_count: u32) -> bool {
        self.content_hash() == c.hash
            && self.0.var_count == var_count
            && self.ssa_outputs() == c.ssa_outputs
            && self.ssa() == c.ssa
            && self.consts() == c.consts
    }

    /// The register instructions, in evaluation order.
    pub fn instrs(&self) -> &[Instr] {
        &self.0.instrs
    }

    /// The SSA operations (constants included), in evaluation order.
    pub fn ssa(&self) -> &[SsaOp] {
        &self.0.ssa
    }

    /// The SSA positions of the outputs.
    pub fn ssa_outputs(&self) -> &[u32] {
        &self.0.ssa_outputs
    }

    /// The constants; constant `i` lives in register `i`.
    pub fn consts(&self) -> &[Constant] {
        &self.0.consts
    }

    /// The registers holding the outputs, in order.
    pub fn outputs(&self) -> &[u32] {
        &self.0.outputs
    }

    /// Number of registers an evaluator needs.
    pub fn reg_count(&self) -> usize {
        self.0.reg_count as usize
    }

    /// Number of variable slots an evaluator must be given.
    pub fn var_count(&self) -> usize {
        self.0.var_count as usize
    }

    /// Whether the tape holds a [`domain`](BinaryOp::Domain) operation (an object absent
    /// where its formula is undefined), whose boundaries a search tests from both sides
    /// ([`Evaluator::eval_sides`](crate::Evaluator::eval_sides)).
    pub fn has_domain(&self) -> bool {
        self.instrs()
            .iter()
            .any(|ins| ins.op == Opcode::Binary(BinaryOp::Domain))
    }

    /// Whether every operation of the tape is continuous on its domain: no step function
    /// (`floor`, `ceil`, `round`, `not`) and no slope of one. On a region where
    /// [`Evaluator::eval_decorated`](crate::Evaluator::eval_decorated) decorates the result
    /// at least `def` (every operation defined), such a tape is then a continuous function of
    /// its variables (the decoration is then at least `dac`).
    pub fn is_continuous(&self) -> bool {
        self.instrs().iter().all(|ins| match ins.op {
            Opcode::Unary(op) => !op.is_discontinuous(),
            _ => true,
        })
    }

    /// Whether every operation of the tape is defined on the whole real line
    /// ([`UnaryOp::is_total`], [`BinaryOp::is_total`], non-negative integer powers): the
    /// tape is then defined at every point and its interval evaluation on every box. Agrees
    /// with [`Context::is_total`] on the nodes the tape was compiled from.
    pub fn is_total(&self) -> bool {
        self.instrs().iter().all(|ins| match ins.op {
            Opcode::Var | Opcode::Const | Opcode::Copy => true,
            Opcode::Unary(op) => op.is_total(),
            Opcode::Binary(op) => op.is_total(),
            Opcode::Pown => (ins.b as i32) >= 0,
        })
    }

    /// Whether the tape is [total](Self::is_total) and [continuous](Self::is_continuous):
    /// defined and continuous everywhere (`+ − ×`, `min`, `max`, `abs`, `sqr`, `−a`,
    /// non-negative integer powers, `exp`, `sin`, `cos`, `atan`). A sign change of such a
    /// function between two points then proves a root between them (intermediate value
    /// theorem).
    pub fn is_total_and_continuous(&self) -> bool {
        self.is_total() && self.is_continuous()
    }

    /// Whether the tape is defined and continuous at every real point of its variables:
    /// [total and continuous](Self::is_total_and_continuous) but for square roots whose
    /// argument is non-negative by its form (a square, an absolute value, a square root, an
    /// exponential, an even power, a non-negative constant, the product of a value with
    /// itself, and sums, products, `min`s of such; a `max` with one of them), as in the
    /// distance `sqrt(x² + y² + z²)`. A sign change between two points then proves a root
    /// between them without a decorated evaluation. Computed once, when first asked.
    pub fn is_continuous_everywhere(&self) -> bool {
        *self
            .0
            .continuous_everywhere
            .get_or_init(|| continuous_everywhere(&self.0.ssa, &self.0.consts))
    }

    /// Number of `min`/`max` operations: the length of a choice trace.
    pub fn choice_count(&self) -> usize {
        self.0.choice_count as usize
    }

    /// The index in a choice trace of the SSA operation at `i`, when it is a `min` or `max`.
    fn choice_index(&self, i: usize) -> Option<usize> {
        let k = self.0.choice_index[i];
        (k != regalloc::NO_CHOICE).then_some(k as usize)
    }

    /// Number of instructions of the register tape (the work of one evaluation).
    pub fn len(&self) -> usize {
        self.0.instrs.len()
    }

    /// Whether the tape has no instruction (its outputs are constants).
    pub fn is_empty(&self) -> bool {
        self.0.instrs.is_empty()
    }

    /// Whether two handles share one tape.
    pub fn ptr_eq(&self, other: &Tape) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }

    /// The tape's machine code for `Interval<f64>` evaluation, `traced` or not, where it is
    /// compiled or due ([`crate::jit`]); counts an evaluation otherwise.
    #[inline]
    pub(crate) fn code(&self, traced: bool) -> Option<&crate::jit::Code> {
        self.0.jit.code(self, traced)
    }

    /// Whether the tape has plain code, and traced code, of its own ([`crate::jit`]).
    #[cfg(test)]
    pub(crate) fn code_kinds(&self) -> (bool, bool) {
        self.0.jit.kinds()
    }

    /// Says that this tape will be evaluated many more times: its machine code (where the
    /// platform has a code generator, [`crate::jit`]) is compiled at its next interval
    /// evaluation instead of after [`COMPILE_AFTER`](crate::jit::COMPILE_AFTER)
    /// interpreted ones. A caller that knows a tape will serve many evaluations (a renderer's
    /// tape for a large region, whose cells and rays inside it evaluate it) saves the
    /// interpretations; the results are the same either way.
    pub fn expect_reuse(&self) {
        self.0.jit.expect_reuse();
    }

    /// Whether every operation of the tape is one the code generator of [`crate::jit`]
    /// compiles (no division, general power or elementary function), with few enough
    /// outputs and variables: on a platform with the generator its interval evaluation
    /// then runs as machine code once compiled. The answer is the same on every platform,
    /// so a caller that picks between two ways to a result by it gets the same results
    /// everywhere.
    pub fn has_code_ops(&self) -> bool {
        crate::jit::handles(self)
    }

    /// The identity of the shared tape (its address): equal for handles that
    /// [`ptr_eq`](Self::ptr_eq), and not reused while a handle lives.
    pub(crate) fn id(&self) -> usize {
        Arc::as_ptr(&self.0) as usize
    }
}

/// See [`Tape::is_continuous_everywhere`]: every operation of `ssa` defined and continuous
/// on the whole real line, each square root's argument non-negative by its form.
fn continuous_everywhere(ssa: &[SsaOp], consts: &[Constant]) -> bool {
    // Whether each value is non-negative at every point, by its form.
    let mut nonneg = Vec::with_capacity(ssa.len());
    for op in ssa {
        let (a, b) = (op.a as usize, op.b as usize);
        let (ok, nn) = match op.op {
            Opcode::Var => (true, false),
            Opcode::Const => (true, consts[a].lo() >= 0.0),
            Opcode::Copy => (true, nonneg[a]),
            Opcode::Unary(UnaryOp::Sqrt) => (nonneg[a], true),
            Opcode::Unary(u) => (
                u.is_total() && !u.is_discontinuous(),
                matches!(u, UnaryOp::Sqr | UnaryOp::Abs | UnaryOp::Exp),
            ),
            Opcode::Binary(bop) => (
                bop.is_total(),
                match bop {
                    BinaryOp::Add | BinaryOp::Min => nonneg[a] && nonneg[b],
                    BinaryOp::Mul => a == b || (nonneg[a] && nonneg[b]),
                    BinaryOp::Max => nonneg[a] || nonneg[b],
                    _ => false,
                },
            ),
            Opcode::Pown => {
                let n = op.b as i32;
                (n >= 0, n >= 0 && n % 2 == 0)
            }
        };
        if !ok {
            return false;
        }
        nonneg.push(nn);
    }
    true
}
