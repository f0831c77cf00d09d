//! # gpu-backend
//!
//! A wgpu compute backend for reliable interval rendering of implicit surfaces, with
//! outward rounding emulated in WGSL.
//!
//! * [`Gpu`]: a headless device on whatever adapter wgpu finds (Vulkan, Metal, DX12, GL),
//!   software drivers included; set-up failures are [`GpuError`]s with a hint, never panics.
//! * [`library`]: the WGSL interval library over `f32`. WGSL has no rounding modes, so
//!   each operation widens its result outward by the error bound the WGSL specification
//!   guarantees, stepping the bit pattern; no bound is ever NaN, infinite or subnormal, so
//!   the library stays sound on GPUs that flush subnormals or assume finite math.
//!   [`library::OpRunner`] runs any library function on many inputs, which is how the
//!   tests check every operation against exact results computed on the CPU.
//!
//! ```no_run
//! use gpu_backend::Gpu;
//! use gpu_backend::library::OpRunner;
//! use implicit_expr::{BinaryOp, Op};
//!
//! let gpu = Gpu::new()?;
//! println!("adapter: {}", gpu.name());
//! let runner = OpRunner::new(&gpu, false)?;
//! // [1, 2] + [0.1, 0.1] as bit patterns.
//! let input = [1f32.to_bits(), 2f32.to_bits(), 0.1f32.to_bits(), 0.1f32.to_bits()];
//! let [lo, hi] = runner.run(&gpu, Op::Binary(BinaryOp::Add), &[input])?[0];
//! assert!(lo <= 1.1 && 2.1 <= hi);
//! # Ok::<(), gpu_backend::GpuError>(())
//! ```
//!
//! * [`beams::BeamKernel`]: every beam and ray search of the renderer (primary beams, rays,
//!   shadow segments, shadow beams and sub-beams) with the counter-based non-recursive
//!   bisection and the rejection and inclusion tests.
//! * [`GpuBackend`]: the GPU as a backend of beam-trace's one render pipeline
//!   ([`beam_trace::render_on`], `render --backend gpu`): beams, rays, shadow segments, soft
//!   shadows (the shadow methods of beam-trace run in rounds of batched questions) and
//!   Phong ([`shading::ShadingKernel`]) on the GPU; the queries it does not answer
//!   (shading points, normals, IAA's normal variation) go to the CPU, as the printed routing
//!   says.

pub mod backend;
pub mod beams;
mod device;
mod dispatch;
mod error;
mod escalation;
pub mod library;
pub mod shading;
pub mod surface;

pub use backend::GpuBackend;
pub use device::Gpu;
pub use error::GpuError;
