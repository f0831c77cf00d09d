//! Pixels resolved by their beams, through the GPU backend (when an adapter exists:
//! Mesa's lavapipe in CI): the same cases as the CPU's, from beam-trace's test suite.

#[path = "../../beam-trace/tests/pixel_cases/mod.rs"]
#[macro_use]
mod pixel_cases;

use beam_trace::{NoProgress, RenderOutput, Scene, render_on};
use gpu_backend::{Gpu, GpuBackend};

/// Runs `case` with the GPU backend ([`Gpu::for_tests`] says why when there is none).
fn on_gpu(case: fn(pixel_cases::Render<'_>)) {
    let Some(gpu) = Gpu::for_tests() else {
        return;
    };
    let backend = GpuBackend::new(gpu);
    let run = |scene: &Scene| -> RenderOutput {
        render_on(scene, &backend, &NoProgress).expect("the GPU render succeeds")
    };
    case(&run);
}

pixel_tests!(on_gpu);
