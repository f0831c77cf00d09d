//! A surface's interval function on the GPU: implicit-expr's WGSL output for a tape, pasted
//! after the interval library, evaluated on many boxes at once.

use bytemuck::{Pod, Zeroable};
use implicit_expr::{Tape, wgsl};
use interval_core::Interval;

use crate::device::Gpu;
use crate::dispatch::Kernel;
use crate::error::GpuError;
use crate::library::{INTERVAL_LIBRARY, bound_to_f64};

/// A box in space, as the CPU renderer writes it.
pub use beam_trace::ray::IBox;

const BOXES_KERNEL: &str = include_str!("wgsl/boxes.wgsl");

#[repr(C)]
#[derive(Copy, Clone, Pod, Zeroable)]
struct Params {
    count: u32,
    pad: [u32; 3],
}

/// The interval function of a surface, compiled for the GPU.
#[derive(Debug)]
pub struct SurfaceKernel {
    kernel: Kernel,
}

impl SurfaceKernel {
    /// Compiles the interval function of `tape`, a function of `x y z` with one output and
    /// no parameters (a scene's geometry tape, for instance).
    ///
    /// # Errors
    ///
    /// [`GpuError::Expr`] if the tape cannot be written as WGSL (parameters left, several
    /// outputs), [`GpuError::Validation`] if the adapter rejects the shader.
    pub fn new(gpu: &Gpu, tape: &Tape) -> Result<SurfaceKernel, GpuError> {
        let generator = wgsl::Generator::new(tape, "surface")?;
        let source = format!(
            "{INTERVAL_LIBRARY}\n{}\n{BOXES_KERNEL}",
            generator.interval_source()
        );
        Ok(SurfaceKernel {
            kernel: Kernel::new(gpu, "surface box kernel", source, &[])?,
        })
    }

    /// An enclosure of the function over each box. Box bounds are rounded outward to `f32`;
    /// a result is empty where the function is nowhere defined on the box.
    ///
    /// # Errors
    ///
    /// [`GpuError`] if the GPU rejects the work or the results cannot be read back.
    pub fn eval(&self, gpu: &Gpu, boxes: &[IBox]) -> Result<Vec<Interval<f64>>, GpuError> {
        let input: Vec<[u32; 6]> = boxes.iter().map(box_bits).collect();
        let out: Vec<[f32; 2]> = self.kernel.map(gpu, &input, |count| {
            bytemuck::bytes_of(&Params {
                count: count as u32,
                pad: [0; 3],
            })
            .to_vec()
        })?;
        Ok(out.into_iter().map(|[lo, hi]| to_f64(lo, hi)).collect())
    }
}

/// The bit patterns of a box rounded outward to `f32` (an empty axis: `[+inf, -inf]`).
fn box_bits(b: &IBox) -> [u32; 6] {
    let mut out = [0u32; 6];
    for (k, axis) in b.iter().enumerate() {
        let (lo, hi) = match axis.bounds() {
            Some((lo, hi)) => wgsl::enclose_f32(lo, hi),
            None => (f32::INFINITY, f32::NEG_INFINITY),
        };
        out[2 * k] = lo.to_bits();
        out[2 * k + 1] = hi.to_bits();
    }
    out
}

/// A library interval as `f64`: `±BIG` is infinite, `lo > hi` empty.
pub fn to_f64(lo: f32, hi: f32) -> Interval<f64> {
    Interval::new(bound_to_f64(lo), bound_to_f64(hi)).unwrap_or(Interval::EMPTY)
}
