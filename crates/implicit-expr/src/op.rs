//! The operations of the expression language: one enum for every node kind of the graph and
//! every instruction of the tape.

use std::fmt;

/// A one-argument operation.
///
/// `Floor`, `Ceil`, `Round` and `Not` come from the `.vm` format; their derivatives are the
/// "slope" operations, which are zero where the step function is constant and unbounded
/// (the interval `[-inf, +inf]`) over any interval that contains a jump, so that interval
/// Newton and monotonicity tests stay sound across discontinuities.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum UnaryOp {
    /// `-a`
    Neg,
    /// `|a|`
    Abs,
    /// `a²`
    Sqr,
    /// `√a`
    Sqrt,
    /// `1 / a`
    Recip,
    /// `eᵃ`
    Exp,
    /// natural logarithm
    Ln,
    /// base-10 logarithm (`log` in formulas)
    Log10,
    /// sine
    Sin,
    /// cosine
    Cos,
    /// tangent
    Tan,
    /// arcsine
    Asin,
    /// arccosine
    Acos,
    /// arctangent
    Atan,
    /// largest integer `<= a`
    Floor,
    /// smallest integer `>= a`
    Ceil,
    /// nearest integer, halves away from zero
    Round,
    /// logical not: `1` where `a == 0`, else `0`
    Not,
    /// derivative of `Floor` and `Ceil`: zero between the integers, unbounded across one
    SlopeFloor,
    /// derivative of `Round`: zero between the half-integers, unbounded across one
    SlopeRound,
    /// derivative of `Not`: zero away from `0`, unbounded on an interval that holds it
    SlopeNot,
}

/// A two-argument operation.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BinaryOp {
    /// `a + b`
    Add,
    /// `a - b`
    Sub,
    /// `a * b`
    Mul,
    /// `a / b`
    Div,
    /// `min(a, b)`
    Min,
    /// `max(a, b)`
    Max,
    /// `a ^ b` for a real exponent (IEEE 1788 `pow`: defined for `a > 0`, and `a = 0, b > 0`)
    Pow,
    /// `domain(d, f)`: `f` where `d <= 0`, and `+inf` (no object: outside every solid)
    /// where `d > 0`. The scene function wraps a formula with a partial domain in it
    /// ([`Context::domain_extension`](crate::Context::domain_extension)), so that where the
    /// formula is undefined its object is absent instead of hiding the others. It jumps
    /// where `d` crosses 0: over an interval on which `d` takes both signs its value is
    /// `[inf F, +inf]` and it counts as undefined (no continuity proof holds there).
    Domain,
}

impl UnaryOp {
    /// Every unary operation, in declaration order.
    pub const ALL: [UnaryOp; 21] = [
        UnaryOp::Neg,
        UnaryOp::Abs,
        UnaryOp::Sqr,
        UnaryOp::Sqrt,
        UnaryOp::Recip,
        UnaryOp::Exp,
        UnaryOp::Ln,
        UnaryOp::Log10,
        UnaryOp::Sin,
        UnaryOp::Cos,
        UnaryOp::Tan,
        UnaryOp::Asin,
        UnaryOp::Acos,
        UnaryOp::Atan,
        UnaryOp::Floor,
        UnaryOp::Ceil,
        UnaryOp::Round,
        UnaryOp::Not,
        UnaryOp::SlopeFloor,
        UnaryOp::SlopeRound,
        UnaryOp::SlopeNot,
    ];

    /// Whether the operation is defined on the whole real line (`√`, `1/a`, the logarithms,
    /// `tan`, `asin` and `acos` are not): an interval evaluation of it is then defined on
    /// every box.
    pub fn is_total(self) -> bool {
        !matches!(
            self,
            UnaryOp::Sqrt
                | UnaryOp::Recip
                | UnaryOp::Ln
                | UnaryOp::Log10
                | UnaryOp::Tan
                | UnaryOp::Asin
                | UnaryOp::Acos
        )
    }

    /// Whether the operation jumps somewhere inside its domain (the step functions and their
    /// slopes). Every other unary operation is continuous wherever it is defined.
    pub fn is_discontinuous(self) -> bool {
        matches!(
            self,
            UnaryOp::Floor
                | UnaryOp::Ceil
                | UnaryOp::Round
                | UnaryOp::Not
                | UnaryOp::SlopeFloor
                | UnaryOp::SlopeRound
                | UnaryOp::SlopeNot
        )
    }

    /// The name used in formulas and in printed graphs (`neg` prints as a prefix `-`).
    pub fn name(self) -> &'static str {
        match self {
            UnaryOp::Neg => "neg",
            UnaryOp::Abs => "abs",
            UnaryOp::Sqr => "sqr",
            UnaryOp::Sqrt => "sqrt",
            UnaryOp::Recip => "recip",
            UnaryOp::Exp => "exp",
            UnaryOp::Ln => "ln",
            UnaryOp::Log10 => "log",
            UnaryOp::Sin => "sin",
            UnaryOp::Cos => "cos",
            UnaryOp::Tan => "tan",
            UnaryOp::Asin => "asin",
            UnaryOp::Acos => "acos",
            UnaryOp::Atan => "atan",
            UnaryOp::Floor => "floor",
            UnaryOp::Ceil => "ceil",
            UnaryOp::Round => "round",
            UnaryOp::Not => "not",
            UnaryOp::SlopeFloor => "slope_floor",
            UnaryOp::SlopeRound => "slope_round",
            UnaryOp::SlopeNot => "slope_not",
        }
    }

    /// Whether the operation is non-decreasing on its whole domain.
    pub fn is_increasing(self) -> bool {
        matches!(
            self,
            UnaryOp::Sqrt
                | UnaryOp::Exp
                | UnaryOp::Ln
                | UnaryOp::Log10
                | UnaryOp::Asin
                | UnaryOp::Atan
                | UnaryOp::Floor
                | UnaryOp::Ceil
                | UnaryOp::Round
        )
    }

    /// Whether the operation is non-increasing on its whole domain.
    pub fn is_decreasing(self) -> bool {
        matches!(self, UnaryOp::Neg | UnaryOp::Acos)
    }
}

impl BinaryOp {
    /// Every binary operation, in declaration order.
    pub const ALL: [BinaryOp; 8] = [
        BinaryOp::Add,
        BinaryOp::Sub,
        BinaryOp::Mul,
        BinaryOp::Div,
        BinaryOp::Min,
        BinaryOp::Max,
        BinaryOp::Pow,
        BinaryOp::Domain,
    ];

    /// The name used in printed graphs and in the `.vm` format.
    pub fn name(self) -> &'static str {
        match self {
            BinaryOp::Add => "add",
            BinaryOp::Sub => "sub",
            BinaryOp::Mul => "mul",
            BinaryOp::Div => "div",
            BinaryOp::Min => "min",
            BinaryOp::Max => "max",
            BinaryOp::Pow => "pow",
            BinaryOp::Domain => "domain",
        }
    }

    /// Whether the operation is defined for every pair of reals (`a / b` and `a ^ b` are
    /// not), and continuous wherever it is (`domain` jumps, so it counts as partial: its
    /// interval evaluation is checked on every box).
    pub fn is_total(self) -> bool {
        !matches!(self, BinaryOp::Div | BinaryOp::Pow | BinaryOp::Domain)
    }

    /// Whether `op(a, b) == op(b, a)` for all values (used to share `a + b` and `b + a`).
    pub fn is_commutative(self) -> bool {
        matches!(
            self,
            BinaryOp::Add | BinaryOp::Mul | BinaryOp::Min | BinaryOp::Max
        )
    }
}

impl fmt::Display for UnaryOp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Display for BinaryOp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Any operation that computes an instruction's value from other values: a binary or unary
/// operation, or the integer power `a^n` (whose exponent `n` is part of the instruction).
///
/// [`Op::ALL`] lists them all, derived from [`BinaryOp::ALL`] and [`UnaryOp::ALL`]: code
/// that must cover every operation (the WGSL interval library's contract, its kernels and
/// tests) iterates over it instead of keeping a list of its own.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Op {
    /// A two-argument operation.
    Binary(BinaryOp),
    /// `a^n` for an integer `n`.
    Pown,
    /// A one-argument operation.
    Unary(UnaryOp),
}

impl Op {
    /// Every operation: the binary ones (in [`BinaryOp::ALL`] order), [`Op::Pown`], then the
    /// unary ones (in [`UnaryOp::ALL`] order).
    pub const ALL: [Op; BinaryOp::ALL.len() + 1 + UnaryOp::ALL.len()] = {
        let mut all = [Op::Pown; BinaryOp::ALL.len() + 1 + UnaryOp::ALL.len()];
        let mut i = 0;
        while i < BinaryOp::ALL.len() {
            all[i] = Op::Binary(BinaryOp::ALL[i]);
            i += 1;
        }
        let mut k = 0;
        while k < UnaryOp::ALL.len() {
            all[BinaryOp::ALL.len() + 1 + k] = Op::Unary(UnaryOp::ALL[k]);
            k += 1;
        }
        all
    };

    /// The name in printed graphs: the operation's own, `pown` for the integer power.
    pub fn name(self) -> &'static str {
        match self {
            Op::Binary(b) => b.name(),
            Op::Pown => "pown",
            Op::Unary(u) => u.name(),
        }
    }

    /// Whether the operation takes a second value (an interval or a real number, not the
    /// integer exponent of [`Op::Pown`]).
    pub fn is_binary(self) -> bool {
        matches!(self, Op::Binary(_))
    }
}

impl From<UnaryOp> for Op {
    fn from(op: UnaryOp) -> Self {
        Op::Unary(op)
    }
}

impl From<BinaryOp> for Op {
    fn from(op: BinaryOp) -> Self {
        Op::Binary(op)
    }
}

impl fmt::Display for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
