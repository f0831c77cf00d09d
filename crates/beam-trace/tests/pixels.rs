//! Pixels resolved by their beams, on the CPU: the cases of `pixel_cases`.

#[macro_use]
mod pixel_cases;

use beam_trace::{NoProgress, Scene, render};

/// Runs `case` with the CPU renderer.
fn on_cpu(case: fn(pixel_cases::Render<'_>)) {
    case(&|scene: &Scene| render(scene, &NoProgress).expect("the render succeeds"));
}

pixel_tests!(on_cpu);
