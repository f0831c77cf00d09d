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
use implicit_expr::{Op, wgsl};

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

/// The kernel's number of `op`: its position in [`Op::ALL`].
fn op_index(op: Op) -> usize {
    Op::ALL
        .iter()
        .position(|&o| o == op)
        .expect("every op is in Op::ALL")
}

/// The WGSL function `run_op(op, a, b, n)` that the op kernel calls: a `switch` over the
/// kernel's operation numbers ([`Op::ALL`] order), each calling its library function
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
/// [`Op::Pown`], `b.lo` holds the exponent as `i32` bits).
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
    pub fn run(&self, gpu: &Gpu, op: Op, inputs: &[OpInput]) -> Result<Vec<[f32; 2]>, GpuError> {
        self.kernel.map(gpu, inputs, |count| {
            bytemuck::bytes_of(&Params {
                op: op_index(op) as u32,
                count: count as u32,
            })
            .to_vec()
        })
    }
}
