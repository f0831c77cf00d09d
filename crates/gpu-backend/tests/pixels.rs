//! Pixels resolved by their beams, through the GPU backend (when an adapter exists:
//! Mesa's lavapipe in CI): the same cases as the CPU's, from beam-trace's test suite, with
//! the default anti-aliasing and without any.

#[path = "../../beam-trace/tests/pixel_cases/mod.rs"]
#[macro_use]
mod pixel_cases;

use beam_trace::scene::AaMode;
use beam_trace::{NoProgress, RenderOutput, Scene, render_on};
use gpu_backend::{Gpu, GpuBackend};

/// Runs `case` with the GPU backend ([`Gpu::for_tests`] says why when there is none), with
/// anti-aliasing off unless the case asks for some where `plain`.
fn with_gpu(case: fn(pixel_cases::Render<'_>), plain: bool) {
    let Some(gpu) = Gpu::for_tests() else {
        return;
    };
    let backend = GpuBackend::new(gpu);
    let run = |scene: &Scene| -> RenderOutput {
        let mut s = scene.clone();
        if plain {
            s.settings.aa.get_or_insert(AaMode::None);
        }
        render_on(&s, &backend, &NoProgress).expect("the GPU render succeeds")
    };
    case(&run);
}

/// Runs `case` with the GPU backend.
fn on_gpu(case: fn(pixel_cases::Render<'_>)) {
    with_gpu(case, false);
}

pixel_tests!(on_gpu);

/// The same cases where a scene names no anti-aliasing rendered without it (`aa = "none"`).
mod without_anti_aliasing {
    use super::{pixel_cases, with_gpu};

    /// Runs `case` with the GPU backend, anti-aliasing off unless the case asks for some.
    fn on_gpu(case: fn(pixel_cases::Render<'_>)) {
        with_gpu(case, true);
    }

    pixel_tests!(on_gpu);
}
