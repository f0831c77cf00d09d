//! Primary visibility on the GPU: for each screen rectangle (a pixel or a screen box), the
//! beam from the eye through it, searched with the counter-based non-recursive bisection
//! and classified by the rejection and inclusion tests, as the CPU renderer's beams are.
//!
//! The inclusion test needs `g` continuous and defined along every ray; the kernel has no
//! definedness tracking, so it runs only for surfaces built from total continuous
//! operations ([`is_total_and_continuous`]); for the others every non-rejected beam is
//! reported undecided, which is sound.

use beam_trace::camera::Camera;
use beam_trace::ray::IBox;
use beam_trace::screen::PixelRect;
use bytemuck::{Pod, Zeroable};
use implicit_expr::tape::Opcode;
use implicit_expr::{BinaryOp, Tape, UnaryOp, wgsl};
use interval_core::Interval;

use crate::device::Gpu;
use crate::dispatch::{Kernel, MAX_ELEMENTS};
use crate::error::GpuError;
use crate::library::INTERVAL_LIBRARY;

const PRIMARY_KERNEL: &str = include_str!("wgsl/primary.wgsl");

/// What the GPU proved about one rectangle's beam.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum GpuClass {
    /// No ray of the beam meets the surface inside the scene bounds.
    Miss,
    /// Every ray of the beam has its first root in `t`.
    Hit {
        /// The section holding every ray's first root.
        t: Interval<f64>,
    },
    /// The first section that could be neither rejected nor proven (every ray is root-free
    /// before it).
    Undecided {
        /// That section.
        t: Interval<f64>,
    },
}

/// One rectangle's result.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct GpuPixel {
    /// The class.
    pub class: GpuClass,
    /// Sections evaluated.
    pub steps: u32,
}

/// Settings of the GPU search.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct PrimarySettings {
    /// Width of a final section (absolute, in the ray parameter).
    pub epsilon: f32,
    /// Largest number of descents per beam.
    pub max_steps: u32,
}

impl Default for PrimarySettings {
    fn default() -> Self {
        Self {
            epsilon: 1e-4,
            max_steps: 4096,
        }
    }
}

#[repr(C)]
#[derive(Copy, Clone, Pod, Zeroable)]
struct SceneParams {
    eye: [[f32; 4]; 2],
    corner: [[f32; 4]; 2],
    du: [[f32; 4]; 2],
    dv: [[f32; 4]; 2],
    bounds: [[f32; 4]; 2],
    tol: [f32; 4],
    ints: [u32; 4],
}

/// Whether every operation of `tape` is defined and continuous everywhere (`+ − ×`, `min`,
/// `max`, `abs`, `sqr`, `−x`, non-negative integer powers, `exp`, `sin`, `cos`, `atan`):
/// then a sign change of `g` between two parameters proves a root between them.
pub fn is_total_and_continuous(tape: &Tape) -> bool {
    tape.instrs().iter().all(|ins| match ins.op {
        Opcode::Var | Opcode::Const | Opcode::Copy => true,
        Opcode::Binary(op) => matches!(
            op,
            BinaryOp::Add | BinaryOp::Sub | BinaryOp::Mul | BinaryOp::Min | BinaryOp::Max
        ),
        Opcode::Pown => (ins.b as i32) >= 0,
        Opcode::Unary(op) => matches!(
            op,
            UnaryOp::Neg
                | UnaryOp::Abs
                | UnaryOp::Sqr
                | UnaryOp::Exp
                | UnaryOp::Sin
                | UnaryOp::Cos
                | UnaryOp::Atan
        ),
    })
}

/// The primary-visibility kernel of one surface.
#[derive(Debug)]
pub struct PrimaryKernel {
    kernel: Kernel,
    inclusion: bool,
}

impl PrimaryKernel {
    /// Compiles the kernel for the scene function `tape` (a function of `x y z`).
    ///
    /// # Errors
    ///
    /// [`GpuError::Expr`] if the tape cannot be written as WGSL, [`GpuError::Validation`]
    /// if the adapter rejects the shader.
    pub fn new(gpu: &Gpu, tape: &Tape) -> Result<PrimaryKernel, GpuError> {
        let generator = wgsl::Generator::new(tape, "surface")?;
        let source = format!(
            "{INTERVAL_LIBRARY}\n{}\n{PRIMARY_KERNEL}",
            generator.interval_source()
        );
        Ok(PrimaryKernel {
            kernel: Kernel::new(gpu, "primary visibility kernel", source, &[])?,
            inclusion: is_total_and_continuous(tape),
        })
    }

    /// Whether the kernel runs the inclusion test (the surface is total and continuous).
    pub fn proves_hits(&self) -> bool {
        self.inclusion
    }

    /// Classifies the beam of each rectangle of `camera`'s image inside `bounds`.
    ///
    /// # Errors
    ///
    /// [`GpuError`] if the GPU rejects the work or the results cannot be read back.
    pub fn classify(
        &self,
        gpu: &Gpu,
        camera: &Camera,
        bounds: &IBox,
        rects: &[PixelRect],
        settings: &PrimarySettings,
    ) -> Result<Vec<GpuPixel>, GpuError> {
        let (corner, du, dv) = camera.frame();
        let vec = |v: glam::DVec3| point_bounds([v.x, v.y, v.z]);
        let b = bounds.map(|i| wgsl::enclose_f32(i.inf(), i.sup()));
        let mut out = Vec::with_capacity(rects.len());
        for chunk in rects.chunks(MAX_ELEMENTS) {
            let params = SceneParams {
                eye: vec(camera.eye()),
                corner: vec(corner),
                du: vec(du),
                dv: vec(dv),
                bounds: [[b[0].0, b[1].0, b[2].0, 0.0], [b[0].1, b[1].1, b[2].1, 0.0]],
                tol: [settings.epsilon, 0.0, 0.0, 0.0],
                ints: [
                    chunk.len() as u32,
                    settings.max_steps,
                    u32::from(self.inclusion),
                    0,
                ],
            };
            let input: Vec<[u32; 6]> = chunk
                .iter()
                .map(|r| rect_input(camera, bounds, r))
                .collect();
            let bytes = self.kernel.run(
                gpu,
                bytemuck::bytes_of(&params),
                bytemuck::cast_slice(&input),
                chunk.len(),
                std::mem::size_of::<[u32; 4]>(),
            )?;
            out.extend(
                bytemuck::pod_collect_to_vec::<u8, [u32; 4]>(&bytes)
                    .into_iter()
                    .map(decode),
            );
        }
        Ok(out)
    }
}

/// The f32 enclosures of a point's coordinates, as (lower, upper) rows.
fn point_bounds(p: [f64; 3]) -> [[f32; 4]; 2] {
    let e = p.map(|x| wgsl::enclose_f32(x, x));
    [[e[0].0, e[1].0, e[2].0, 0.0], [e[0].1, e[1].1, e[2].1, 0.0]]
}

/// The kernel input of a rectangle: its pixel ranges and the beam's parameter range
/// inside the bounds (as f32 bits, outward; an empty range as `t1 < t0`).
fn rect_input(camera: &Camera, bounds: &IBox, r: &PixelRect) -> [u32; 6] {
    let (x0, x1) = (f64::from(r.x0), f64::from(r.x1));
    let (y0, y1) = (f64::from(r.y0), f64::from(r.y1));
    let beam = camera.beam(x0, y0, x1, y1);
    let (t0, t1) = match beam.t_range(bounds) {
        Some(t) => wgsl::enclose_f32(t.inf().max(0.0), t.sup()),
        None => (1.0, 0.0),
    };
    let (t0, t1) = if t1.is_finite() { (t0, t1) } else { (1.0, 0.0) };
    [
        (x0 as f32).to_bits(),
        (x1 as f32).to_bits(),
        (y0 as f32).to_bits(),
        (y1 as f32).to_bits(),
        t0.to_bits(),
        t1.to_bits(),
    ]
}

fn decode(r: [u32; 4]) -> GpuPixel {
    let t = || {
        let (lo, hi) = (f32::from_bits(r[1]), f32::from_bits(r[2]));
        Interval::new(f64::from(lo), f64::from(hi)).unwrap_or(Interval::EMPTY)
    };
    let class = match r[0] {
        0 => GpuClass::Miss,
        1 => GpuClass::Hit { t: t() },
        _ => GpuClass::Undecided { t: t() },
    };
    GpuPixel { class, steps: r[3] }
}
