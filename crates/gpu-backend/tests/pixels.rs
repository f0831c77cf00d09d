//! Pixels resolved by their beams, through the GPU backend (when an adapter exists:
//! Mesa's lavapipe in CI): the same cases as the CPU's, from beam-trace's test suite.

#[path = "../../beam-trace/tests/pixel_cases/mod.rs"]
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

#[test]
fn wires_of_a_millionth_of_a_pixel_appear_in_every_pixel_they_cross() {
    on_gpu(pixel_cases::wires_of_a_millionth_of_a_pixel_appear_in_every_pixel_they_cross);
}

#[test]
fn point_rays_lose_the_wire_the_beams_keep() {
    on_gpu(pixel_cases::point_rays_lose_the_wire_the_beams_keep);
}

#[test]
fn two_wires_crossing_inside_a_pixel_both_appear() {
    on_gpu(pixel_cases::two_wires_crossing_inside_a_pixel_both_appear);
}

#[test]
fn a_sphere_smaller_than_a_pixel_has_its_coverage_bounded() {
    on_gpu(pixel_cases::a_sphere_smaller_than_a_pixel_has_its_coverage_bounded);
}

#[test]
fn the_drops_neck_is_kept_wherever_dense_rays_see_it() {
    on_gpu(pixel_cases::the_drops_neck_is_kept_wherever_dense_rays_see_it);
}
