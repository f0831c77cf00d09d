//! Pixels resolved by their beams, on the CPU: the cases of `pixel_cases`.

mod pixel_cases;

use beam_trace::{NoProgress, RenderOutput, Scene, render};

fn cpu(scene: &Scene) -> RenderOutput {
    render(scene, &NoProgress).expect("the render succeeds")
}

#[test]
fn wires_of_a_millionth_of_a_pixel_appear_in_every_pixel_they_cross() {
    pixel_cases::wires_of_a_millionth_of_a_pixel_appear_in_every_pixel_they_cross(&cpu);
}

#[test]
fn point_rays_lose_the_wire_the_beams_keep() {
    pixel_cases::point_rays_lose_the_wire_the_beams_keep(&cpu);
}

#[test]
fn two_wires_crossing_inside_a_pixel_both_appear() {
    pixel_cases::two_wires_crossing_inside_a_pixel_both_appear(&cpu);
}

#[test]
fn a_sphere_smaller_than_a_pixel_has_its_coverage_bounded() {
    pixel_cases::a_sphere_smaller_than_a_pixel_has_its_coverage_bounded(&cpu);
}

#[test]
fn the_drops_neck_is_kept_wherever_dense_rays_see_it() {
    pixel_cases::the_drops_neck_is_kept_wherever_dense_rays_see_it(&cpu);
}
