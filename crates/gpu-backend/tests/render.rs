//! The GPU render path end to end on a small scene with a point light and an area light,
//! against the CPU renderer: the images agree, and no pixel the GPU proves lit or in the
//! umbra of the area light contradicts 256 reliable CPU shadow segments from the same pixel's
//! central ray (the two renderers place their shading points independently, each inside a
//! root enclosure of that ray).

use beam_trace::scene::{AaMode, PrimaryMode};
use beam_trace::shadow::ShadowClass;
use beam_trace::{NoProgress, Scene, render};
use gpu_backend::Gpu;

fn scene(method: &str) -> Scene {
    let text = format!(
        r#"
[camera]
eye = [0.0, 3.0, 6.0]
look_at = [0.0, -0.6, 0.0]
fov = 45.0
width = 40
height = 40

[[surfaces]]
name = "ball"
formula = "x^2 + y^2 + z^2 - 1"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]

[[surfaces]]
name = "floor"
formula = "y + 1.2"
bounds = [[-3.0, -1.5, -3.0], [3.0, -1.2, 3.0]]
clip = true

[[lights]]
type = "area"
center = [-1.0, 4.0, 1.0]
size = 1.5
normal = "y"

[[lights]]
type = "point"
position = [3.0, 5.0, 2.0]
intensity = 0.3

[render]
shadow_method = "{method}"
"#
    );
    Scene::from_toml(&text, "gpu.toml", None).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn gpu_render_agrees_with_the_cpu() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let s = scene("beam:4");
    let g = gpu_backend::render::render(&gpu, &s, &NoProgress).expect("the GPU renders");
    let c = render(&s, &NoProgress).expect("the CPU renders");
    for pass in ["screen-boxes", "hard-shadows", "soft-shadows", "shading"] {
        assert!(
            g.stats.pass(pass).is_some_and(|p| p.ran),
            "{pass} did not run"
        );
    }
    assert_eq!(g.stats.lights.len(), 1);
    let close = g
        .image
        .pixels
        .iter()
        .zip(&c.image.pixels)
        .filter(|(a, b)| a.iter().zip(b.iter()).all(|(x, y)| (x - y).abs() <= 0.1))
        .count();
    let share = close as f64 / g.image.pixels.len() as f64;
    eprintln!("{:.1} % of the pixels agree within 0.1", 100.0 * share);
    assert!(share >= 0.9, "only {share} of the pixels agree");
}

#[test]
fn gpu_shadow_proofs_agree_with_many_cpu_samples() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let g =
        gpu_backend::render::render(&gpu, &scene("beam:4"), &NoProgress).expect("the GPU renders");
    // One ray per pixel through its centre, the ray the GPU shades too.
    let mut cpu = scene("stochastic:256");
    cpu.settings.primary = PrimaryMode::PerPixel;
    cpu.settings.rays_per_pixel = 1;
    let reference = render(&cpu, &NoProgress).expect("the CPU renders");
    let gm = g.shadows.as_ref().expect("soft shadows ran");
    let rf = &reference
        .shadows
        .as_ref()
        .expect("soft shadows ran")
        .fractions[0];
    let (mut lit, mut umbra, mut bad) = (0, 0, Vec::new());
    for (i, class) in gm.classes.iter().enumerate() {
        let r = rf[i];
        match class {
            Some(ShadowClass::Lit) => {
                lit += 1;
                if r.is_finite() && r != 1.0 {
                    bad.push(format!("pixel {i}: GPU proven lit, CPU samples {r}"));
                }
            }
            Some(ShadowClass::Umbra) => {
                umbra += 1;
                if r.is_finite() && r != 0.0 {
                    bad.push(format!("pixel {i}: GPU proven umbra, CPU samples {r}"));
                }
            }
            _ => {}
        }
    }
    eprintln!("GPU proven lit {lit}, umbra {umbra}");
    assert!(lit > 200, "{lit} proven lit pixels");
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn gpu_adaptive_anti_aliasing_splits_only_border_pixels() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let mut s = scene("beam:2");
    s.settings.aa = AaMode::Iaa {
        max_depth: AaMode::IAA_DEPTH,
        threshold: AaMode::IAA_THRESHOLD,
    };
    let g = gpu_backend::render::render(&gpu, &s, &NoProgress).expect("the GPU renders");
    let beams = g.stats.pass("primary-beams").unwrap();
    assert!(!g.stats.pass("screen-boxes").unwrap().ran);
    let undecided = beams.counter("undecided");
    let parts = g
        .stats
        .pass("primary-rays")
        .unwrap()
        .counter("aa_sub_beams");
    assert!(
        undecided > 0 && undecided < 40 * 40 / 2,
        "{undecided} border pixels"
    );
    // Only the border pixels are split, each in 3 x 3 sub-beams.
    assert_eq!(parts, 9 * undecided);
}
