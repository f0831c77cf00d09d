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

/// The kernel that applies one library function to an array of inputs.
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

/// The library functions the op kernel runs.
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
    /// Every operation, in the kernel's order.
    pub const ALL: [LibraryOp; 29] = [
        LibraryOp::Add,
        LibraryOp::Sub,
        LibraryOp::Mul,
        LibraryOp::Div,
        LibraryOp::Min,
        LibraryOp::Max,
        LibraryOp::Pown,
        LibraryOp::Neg,
        LibraryOp::Abs,
        LibraryOp::Sqr,
        LibraryOp::Sqrt,
        LibraryOp::Recip,
        LibraryOp::Floor,
        LibraryOp::Ceil,
        LibraryOp::Exp,
        LibraryOp::Ln,
        LibraryOp::Log10,
        LibraryOp::Sin,
        LibraryOp::Cos,
        LibraryOp::Tan,
        LibraryOp::Asin,
        LibraryOp::Acos,
        LibraryOp::Atan,
        LibraryOp::Pow,
        LibraryOp::Round,
        LibraryOp::Not,
        LibraryOp::SlopeFloor,
        LibraryOp::SlopeRound,
        LibraryOp::SlopeNot,
    ];

    /// The WGSL function's name.
    pub fn name(self) -> &'static str {
        match self {
            LibraryOp::Add => "i_add",
            LibraryOp::Sub => "i_sub",
            LibraryOp::Mul => "i_mul",
            LibraryOp::Div => "i_div",
            LibraryOp::Min => "i_min",
            LibraryOp::Max => "i_max",
            LibraryOp::Pown => "i_pown",
            LibraryOp::Neg => "i_neg",
            LibraryOp::Abs => "i_abs",
            LibraryOp::Sqr => "i_sqr",
            LibraryOp::Sqrt => "i_sqrt",
            LibraryOp::Recip => "i_recip",
            LibraryOp::Floor => "i_floor",
            LibraryOp::Ceil => "i_ceil",
            LibraryOp::Exp => "i_exp",
            LibraryOp::Ln => "i_ln",
            LibraryOp::Log10 => "i_log10",
            LibraryOp::Sin => "i_sin",
            LibraryOp::Cos => "i_cos",
            LibraryOp::Tan => "i_tan",
            LibraryOp::Asin => "i_asin",
            LibraryOp::Acos => "i_acos",
            LibraryOp::Atan => "i_atan",
            LibraryOp::Pow => "i_pow",
            LibraryOp::Round => "i_round",
            LibraryOp::Not => "i_not",
            LibraryOp::SlopeFloor => "i_slope_floor",
            LibraryOp::SlopeRound => "i_slope_round",
            LibraryOp::SlopeNot => "i_slope_not",
        }
    }

    /// Whether it takes a second interval.
    pub fn is_binary(self) -> bool {
        matches!(
            self,
            LibraryOp::Add
                | LibraryOp::Sub
                | LibraryOp::Mul
                | LibraryOp::Div
                | LibraryOp::Min
                | LibraryOp::Max
                | LibraryOp::Pow
        )
    }

    fn index(self) -> u32 {
        LibraryOp::ALL
            .iter()
            .position(|&o| o == self)
            .expect("every op is in ALL") as u32
    }
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
        let source = format!("{INTERVAL_LIBRARY}\n{OPS_KERNEL}");
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
                op: op.index(),
                count: count as u32,
            })
            .to_vec()
        })
    }
}
