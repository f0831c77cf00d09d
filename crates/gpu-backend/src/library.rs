//! The WGSL interval library, and a kernel that runs its functions on many inputs (the
//! soundness tests read its results back and check them on the CPU).
//!
//! [`INTERVAL_LIBRARY`] defines `struct Interval { lo: f32, hi: f32 }` and the functions
//! that implicit-expr's WGSL generator calls (`i_add`, `i_mul`, ...). WGSL has no rounding
//! modes, so every result is widened outward by the error bound the WGSL specification
//! guarantees for the operation (its "Floating Point Accuracy" tables), by stepping the bit
//! pattern; the representation avoids infinities, NaNs and subnormal bounds, which the
//! specification lets an implementation assume absent or flush. `docs/numerics.md` of the
//! repository lists the bound used for each operation.

use bytemuck::{Pod, Zeroable};
use implicit_expr::{BinaryOp, Op, UnaryOp, wgsl};

use crate::device::Gpu;
use crate::dispatch::Kernel;
use crate::error::GpuError;

/// The WGSL source of the interval library: the representation, the arithmetic and the
/// elementary functions.
pub const INTERVAL_LIBRARY: &str = concat!(
    include_str!("wgsl/interval.wgsl"),
    "\n",
    include_str!("wgsl/elementary.wgsl")
);

/// The kernel that applies one library function to an array of inputs (through `run_op`,
/// written by `dispatch_source`).
const OPS_KERNEL: &str = include_str!("wgsl/ops.wgsl");

/// The largest finite `f32`: as a bound, it stands for infinity.
pub const BIG: f32 = f32::MAX;

/// A bound of a library interval as `f64`: `±BIG` is infinite.
pub fn bound_to_f64(x: f32) -> f64 {
    if x >= BIG {
        f64::INFINITY
    } else if x <= -BIG {
        f64::NEG_INFINITY
    } else {
        f64::from(x)
    }
}

/// The library functions the op kernel runs: one per operation of implicit-expr's tapes
/// ([`Op`]), named as the operations are. [`LibraryOp::of`] matches every operation, so the
/// compiler names one missing here; the order ([`LibraryOp::ALL`]), the WGSL names and the
/// kernel's dispatch follow from [`Op::ALL`] and [`wgsl::function`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum LibraryOp {
    /// `i_add(a, b)`.
    Add,
    /// `i_sub(a, b)`.
    Sub,
    /// `i_mul(a, b)`.
    Mul,
    /// `i_div(a, b)`.
    Div,
    /// `i_min(a, b)`.
    Min,
    /// `i_max(a, b)`.
    Max,
    /// `i_pown(a, n)`, `n` in the bits of the second input's lower bound.
    Pown,
    /// `i_neg(a)`.
    Neg,
    /// `i_abs(a)`.
    Abs,
    /// `i_sqr(a)`.
    Sqr,
    /// `i_sqrt(a)`.
    Sqrt,
    /// `i_recip(a)`.
    Recip,
    /// `i_floor(a)`.
    Floor,
    /// `i_ceil(a)`.
    Ceil,
    /// `i_exp(a)`.
    Exp,
    /// `i_ln(a)`.
    Ln,
    /// `i_log10(a)`.
    Log10,
    /// `i_sin(a)`.
    Sin,
    /// `i_cos(a)`.
    Cos,
    /// `i_tan(a)`.
    Tan,
    /// `i_asin(a)`.
    Asin,
    /// `i_acos(a)`.
    Acos,
    /// `i_atan(a)`.
    Atan,
    /// `i_pow(a, b)`.
    Pow,
    /// `i_round(a)`.
    Round,
    /// `i_not(a)`.
    Not,
    /// `i_slope_floor(a)`.
    SlopeFloor,
    /// `i_slope_round(a)`.
    SlopeRound,
    /// `i_slope_not(a)`.
    SlopeNot,
}

impl LibraryOp {
    /// Every operation, in [`Op::ALL`] order (the kernel's).
    pub const ALL: [LibraryOp; Op::ALL.len()] = {
        let mut all = [LibraryOp::Add; Op::ALL.len()];
        let mut i = 0;
        while i < Op::ALL.len() {
            all[i] = LibraryOp::of(Op::ALL[i]);
            i += 1;
        }
        all
    };

    /// The library function of `op`.
    pub const fn of(op: Op) -> LibraryOp {
        match op {
            Op::Binary(b) => match b {
                BinaryOp::Add => LibraryOp::Add,
                BinaryOp::Sub => LibraryOp::Sub,
                BinaryOp::Mul => LibraryOp::Mul,
                BinaryOp::Div => LibraryOp::Div,
                BinaryOp::Min => LibraryOp::Min,
                BinaryOp::Max => LibraryOp::Max,
                BinaryOp::Pow => LibraryOp::Pow,
            },
            Op::Pown => LibraryOp::Pown,
            Op::Unary(u) => match u {
                UnaryOp::Neg => LibraryOp::Neg,
                UnaryOp::Abs => LibraryOp::Abs,
                UnaryOp::Sqr => LibraryOp::Sqr,
                UnaryOp::Sqrt => LibraryOp::Sqrt,
                UnaryOp::Recip => LibraryOp::Recip,
                UnaryOp::Exp => LibraryOp::Exp,
                UnaryOp::Ln => LibraryOp::Ln,
                UnaryOp::Log10 => LibraryOp::Log10,
                UnaryOp::Sin => LibraryOp::Sin,
                UnaryOp::Cos => LibraryOp::Cos,
                UnaryOp::Tan => LibraryOp::Tan,
                UnaryOp::Asin => LibraryOp::Asin,
                UnaryOp::Acos => LibraryOp::Acos,
                UnaryOp::Atan => LibraryOp::Atan,
                UnaryOp::Floor => LibraryOp::Floor,
                UnaryOp::Ceil => LibraryOp::Ceil,
                UnaryOp::Round => LibraryOp::Round,
                UnaryOp::Not => LibraryOp::Not,
                UnaryOp::SlopeFloor => LibraryOp::SlopeFloor,
                UnaryOp::SlopeRound => LibraryOp::SlopeRound,
                UnaryOp::SlopeNot => LibraryOp::SlopeNot,
            },
        }
    }

    /// The operation whose library function this is.
    pub fn op(self) -> Op {
        Op::ALL[self.index()]
    }

    /// The WGSL function's name.
    pub fn name(self) -> &'static str {
        wgsl::function(self.op())
    }

    /// Whether it takes a second interval.
    pub fn is_binary(self) -> bool {
        self.op().is_binary()
    }

    /// The position in [`LibraryOp::ALL`]: the kernel's number of the operation.
    fn index(self) -> usize {
        LibraryOp::ALL
            .iter()
            .position(|&o| o == self)
            .expect("every op is in ALL")
    }
}

impl From<Op> for LibraryOp {
    fn from(op: Op) -> Self {
        LibraryOp::of(op)
    }
}

/// The WGSL function `run_op(op, a, b, n)` that the op kernel calls: a `switch` over the
/// kernel's operation numbers ([`LibraryOp::ALL`] order), each calling its library function
/// with `a`, with `a, b` for a binary one, and with `a, n` for `i_pown`.
fn dispatch_source() -> String {
    let mut s = String::from(
        "fn run_op(op: u32, a: Interval, b: Interval, n: i32) -> Interval {\n    var r = i_entire();\n    switch op {\n",
    );
    for (k, op) in Op::ALL.into_iter().enumerate() {
        let args = match op {
            Op::Binary(_) => "a, b",
            Op::Pown => "a, n",
            Op::Unary(_) => "a",
        };
        s.push_str(&format!(
            "        case {k}u: {{ r = {}({args}); }}\n",
            wgsl::function(op)
        ));
    }
    s.push_str("        default: {}\n    }\n    return r;\n}\n");
    s
}

/// One input of the op kernel: the bit patterns of `a.lo, a.hi, b.lo, b.hi` (for
/// [`LibraryOp::Pown`], `b.lo` holds the exponent as `i32` bits).
pub type OpInput = [u32; 4];

#[repr(C)]
#[derive(Copy, Clone, Pod, Zeroable)]
struct Params {
    op: u32,
    count: u32,
}

/// The op kernel, compiled for one subnormal mode.
#[derive(Debug)]
pub struct OpRunner {
    kernel: Kernel,
}

impl OpRunner {
    /// Compiles the kernel. With `flush_subnormals`, every raw floating-point operation of
    /// the library flushes its operands and result to zero as a GPU without subnormals may,
    /// so that path is tested on any adapter.
    ///
    /// # Errors
    ///
    /// [`GpuError::Validation`] if the adapter rejects the shader.
    pub fn new(gpu: &Gpu, flush_subnormals: bool) -> Result<OpRunner, GpuError> {
        let source = format!("{INTERVAL_LIBRARY}\n{}\n{OPS_KERNEL}", dispatch_source());
        let flush = [("FLUSH_SUBNORMALS", if flush_subnormals { 1.0 } else { 0.0 })];
        Ok(OpRunner {
            kernel: Kernel::new(gpu, "interval library op kernel", source, &flush)?,
        })
    }

    /// `op` on every input: the `(lo, hi)` of each result.
    ///
    /// # Errors
    ///
    /// [`GpuError`] if the GPU rejects the work or the results cannot be read back.
    pub fn run(
        &self,
        gpu: &Gpu,
        op: LibraryOp,
        inputs: &[OpInput],
    ) -> Result<Vec<[f32; 2]>, GpuError> {
        self.kernel.map(gpu, inputs, |count| {
            bytemuck::bytes_of(&Params {
                op: op.index() as u32,
                count: count as u32,
            })
            .to_vec()
        })
    }
}
