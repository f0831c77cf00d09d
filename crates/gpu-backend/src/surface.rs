//! A surface's interval function on the GPU: implicit-expr's WGSL output for a tape, pasted
//! after the interval library, evaluated on many boxes at once.

use bytemuck::{Pod, Zeroable};
use implicit_expr::{Tape, wgsl};
use interval_core::Interval;

use crate::device::Gpu;
use crate::dispatch::{Kernel, max_elements};
use crate::error::GpuError;
use crate::library::{BIG, INTERVAL_LIBRARY};

/// A box in space, as the CPU renderer writes it.
pub type IBox = [Interval<f64>; 3];

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
        let mut out = Vec::with_capacity(boxes.len());
        for chunk in boxes.chunks(max_elements(gpu, std::mem::size_of::<[u32; 6]>())) {
            let input: Vec<[u32; 6]> = chunk.iter().map(box_bits).collect();
            let params = Params {
                count: chunk.len() as u32,
                pad: [0; 3],
            };
            let bytes = self.kernel.run(
                gpu,
                bytemuck::bytes_of(&params),
                bytemuck::cast_slice(&input),
                chunk.len(),
                std::mem::size_of::<[f32; 2]>(),
            )?;
            out.extend(
                bytemuck::pod_collect_to_vec::<u8, [f32; 2]>(&bytes)
                    .into_iter()
                    .map(|[lo, hi]| to_f64(lo, hi)),
            );
        }
        Ok(out)
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
    let widen = |x: f32| {
        if x >= BIG {
            f64::INFINITY
        } else if x <= -BIG {
            f64::NEG_INFINITY
        } else {
            f64::from(x)
        }
    };
    Interval::new(widen(lo), widen(hi)).unwrap_or(Interval::EMPTY)
}
