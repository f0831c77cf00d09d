//! The agreement suite: the same scenes rendered by every backend through the one pipeline
//! (the CPU, and the GPU when an adapter exists: Mesa's lavapipe in CI), checked against
//! the CPU's results by containment, since the GPU evaluates in f32 and the CPU in f64:
//!
//! * no pixel is proven to miss by one backend and proven to hit by another, and where both
//!   prove a hit their `T_final` sections overlap;
//! * no pixel is proven lit by one and proven in the umbra by another;
//! * the images agree on most pixels;
//! * every planned pass ran, with the same passes in the same order.
//!
//! And the GPU's shadow proofs are checked against 256 reliable CPU shadow segments.

use beam_trace::backend::Backend;
use beam_trace::beam::BoxClass;
use beam_trace::scene::{AaMode, PrimaryMode};
use beam_trace::shadow::ShadowClass;
use beam_trace::{Cpu, NoProgress, Pass, RenderOutput, Routing, Scene, render, render_on};
use gpu_backend::{Gpu, GpuBackend};

fn scene(method: &str) -> Scene {
    scene_with(method, "")
}

/// A box given as polygons (a closed triangle mesh) between the ball and the area light,
/// which shades the ball and the floor.
const CUBE: &str = r#"
[[meshes]]
name = "cube"
polygons = [
    [[-0.5, -0.5, -0.5], [-0.5, 0.5, -0.5], [0.5, 0.5, -0.5], [0.5, -0.5, -0.5]],
    [[-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [0.5, 0.5, 0.5], [-0.5, 0.5, 0.5]],
    [[-0.5, -0.5, -0.5], [0.5, -0.5, -0.5], [0.5, -0.5, 0.5], [-0.5, -0.5, 0.5]],
    [[-0.5, 0.5, -0.5], [-0.5, 0.5, 0.5], [0.5, 0.5, 0.5], [0.5, 0.5, -0.5]],
    [[-0.5, -0.5, -0.5], [-0.5, -0.5, 0.5], [-0.5, 0.5, 0.5], [-0.5, 0.5, -0.5]],
    [[0.5, -0.5, -0.5], [0.5, 0.5, -0.5], [0.5, 0.5, 0.5], [0.5, -0.5, 0.5]],
]
transform = { translate = [-1.4, 0.2, 1.2], rotate = [0.0, 30.0, 0.0], scale = 0.7 }
"#;

/// The suite's scene with `extra` (more surfaces or meshes) appended.
fn scene_with(method: &str, extra: &str) -> Scene {
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
{extra}"#
    );
    Scene::from_toml(&text, "gpu.toml", None).unwrap_or_else(|e| panic!("{e}"))
}

/// The backends under test: the CPU, and the GPU where there is one.
fn backends() -> Vec<Box<dyn Backend>> {
    let mut out: Vec<Box<dyn Backend>> = vec![Box::new(Cpu)];
    if let Some(gpu) = Gpu::for_tests() {
        out.push(Box::new(GpuBackend::new(gpu)));
    }
    out
}

/// The scenes of the suite: shadows by several methods, anti-aliasing, per-pixel rays.
fn suite() -> Vec<(String, Scene)> {
    let mut out = Vec::new();
    for method in [
        "beam:4",
        "beam-quadtree:4",
        "minkowski:beam:3",
        "stochastic:16",
        "certified:0.1:64",
        // No refinement: the light's quadrants screened by rejection beams before the
        // segments.
        "certified:1:1024:64",
    ] {
        out.push((method.to_string(), scene(method)));
    }
    let mut iaa = scene("beam:2");
    iaa.settings.aa = Some(AaMode::Iaa {
        max_depth: 2,
        threshold: AaMode::IAA_THRESHOLD,
        limit_rays: AaMode::IAA_LIMIT_RAYS,
    });
    out.push(("iaa".into(), iaa));
    let mut per_pixel = scene("minkowski:stochastic:8");
    per_pixel.settings.primary = PrimaryMode::PerPixel;
    out.push(("per-pixel".into(), per_pixel));
    // A triangle mesh beside the implicit surfaces: the GPU's implicit answers and the
    // host's triangle answers combined.
    for method in ["certified:0.1:64", "stochastic:16"] {
        out.push((format!("mesh, {method}"), scene_with(method, CUBE)));
    }
    let mut mesh_per_pixel = scene_with("beam:3", CUBE);
    mesh_per_pixel.settings.primary = PrimaryMode::PerPixel;
    out.push(("mesh, per-pixel".into(), mesh_per_pixel));
    out
}

/// What contradicts between `a` and the reference `r`.
fn contradictions(a: &RenderOutput, r: &RenderOutput) -> Vec<String> {
    let mut bad = Vec::new();
    for (i, (x, y)) in a.box_classes().iter().zip(&r.box_classes()).enumerate() {
        match (x, y) {
            (Some(BoxClass::Miss), Some(BoxClass::Hit { .. }))
            | (Some(BoxClass::Hit { .. }), Some(BoxClass::Miss)) => {
                bad.push(format!("pixel {i}: {x:?} against {y:?}"));
            }
            (Some(BoxClass::Hit { t_final: s }), Some(BoxClass::Hit { t_final: t }))
                if s.intersection(*t).is_empty() =>
            {
                bad.push(format!("pixel {i}: T_final {s:?} and {t:?} are disjoint"));
            }
            _ => {}
        }
    }
    if let (Some(sa), Some(sr)) = (&a.shadows, &r.shadows) {
        for (i, (x, y)) in sa.classes.iter().zip(&sr.classes).enumerate() {
            if matches!(
                (x, y),
                (Some(ShadowClass::Lit), Some(ShadowClass::Umbra))
                    | (Some(ShadowClass::Umbra), Some(ShadowClass::Lit))
            ) {
                bad.push(format!("pixel {i}: shadow {x:?} against {y:?}"));
            }
        }
    }
    bad
}

#[test]
fn every_backend_agrees_with_the_cpu() {
    for backend in backends() {
        for (name, s) in suite() {
            let reference = render(&s, &NoProgress).expect("the CPU renders");
            let out = render_on(&s, backend.as_ref(), &NoProgress)
                .unwrap_or_else(|e| panic!("{name} on {}: {e}", backend.name()));
            let who = format!("{name} on {}", backend.name());
            eprintln!("{}", Routing::new(backend.as_ref(), &s, &out.plan));
            for pass in Pass::ALL.into_iter().filter(|&p| p != Pass::Grid) {
                assert_eq!(
                    out.stats.of(pass).map(|p| p.ran),
                    reference.stats.of(pass).map(|p| p.ran),
                    "{who}: pass {pass}"
                );
            }
            let bad = contradictions(&out, &reference);
            assert!(bad.is_empty(), "{who}:\n{}", bad.join("\n"));
            let close = out
                .image
                .pixels
                .iter()
                .zip(&reference.image.pixels)
                .filter(|(a, b)| a.iter().zip(b.iter()).all(|(x, y)| (x - y).abs() <= 0.1))
                .count();
            let share = close as f64 / out.image.pixels.len() as f64;
            eprintln!(
                "{who}: {:.1} % of the pixels agree within 0.1",
                100.0 * share
            );
            assert!(share >= 0.9, "{who}: only {share} of the pixels agree");
        }
    }
}

#[test]
fn the_cpu_backend_through_render_on_is_the_cpu_render() {
    let s = scene("beam:3");
    let a = render(&s, &NoProgress).unwrap();
    let b = render_on(&s, &Cpu, &NoProgress).unwrap();
    assert_eq!(a.image.pixels, b.image.pixels);
    assert_eq!(a.stats.work(), b.stats.work());
}

#[test]
fn the_gpu_routing_names_what_runs_on_the_cpu() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let backend = GpuBackend::new(gpu);
    let mut s = scene("stochastic:8:cache");
    s.settings.aa = Some(AaMode::Iaa {
        max_depth: 2,
        threshold: AaMode::IAA_THRESHOLD,
        limit_rays: AaMode::IAA_LIMIT_RAYS,
    });
    let plan = beam_trace::Plan::for_scene(&s);
    let routing = Routing::new(&backend, &s, &plan).to_string();
    for line in [
        "beams on gpu",
        "shading-variation on the cpu",
        "hit-points on the cpu",
        "soft-shadows on the cpu (the last-occluder cache",
        "normals on the cpu",
    ] {
        assert!(routing.contains(line), "{line}:\n{routing}");
    }
    let out = render_on(&s, &backend, &NoProgress).expect("the GPU renders");
    assert!(out.stats.pass("gpu-compile").is_some_and(|p| p.ran));
}

#[test]
fn a_scene_with_meshes_searches_on_the_gpu_but_for_the_exact_method() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let backend = GpuBackend::new(gpu);
    let s = scene_with("certified:0.1:64", CUBE);
    let plan = beam_trace::Plan::for_scene(&s);
    let routing = Routing::new(&backend, &s, &plan).to_string();
    for line in ["beams on gpu", "segments on gpu", "soft-shadows on gpu"] {
        assert!(routing.contains(line), "{line}:\n{routing}");
    }
    let exact = scene_with("exact", CUBE);
    let plan = beam_trace::Plan::for_scene(&exact);
    let routing = Routing::new(&backend, &exact, &plan).to_string();
    assert!(
        routing.contains("soft-shadows on the cpu (the exact method"),
        "{routing}"
    );
    // The exact method's answers come from the CPU, the rest of the render from the GPU.
    let out = render_on(&exact, &backend, &NoProgress).expect("the GPU renders");
    let reference = render(&exact, &NoProgress).expect("the CPU renders");
    let bad = contradictions(&out, &reference);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn a_scene_with_partial_domains_searches_on_the_cpu() {
    // The kernels have no two-sided test of domain boundaries: beams, roots, segments and
    // soft shadows go back to the CPU, so the proven classes are the CPU's own.
    let Some(gpu) = Gpu::for_tests() else { return };
    let backend = GpuBackend::new(gpu);
    let text = r#"
[camera]
eye = [0.0, 3.0, 6.0]
look_at = [0.0, -0.6, 0.0]
width = 32
height = 32
[[surfaces]]
name = "root"
formula = "z + sqrt(x + 0.5) - 0.6"
bounds = [[-1.5, -1.0, -1.0], [1.5, 1.0, 1.0]]
[[surfaces]]
name = "floor"
formula = "y + 1.2"
bounds = [[-3.0, -1.5, -3.0], [3.0, -1.2, 3.0]]
clip = true
[[lights]]
type = "point"
position = [3.0, 5.0, 2.0]
"#;
    let s = Scene::from_toml(text, "domains.toml", None).unwrap_or_else(|e| panic!("{e}"));
    let plan = beam_trace::Plan::for_scene(&s);
    let routing = Routing::new(&backend, &s, &plan).to_string();
    let why = "on the cpu (the kernels have no two-sided test of domain boundaries)";
    for kind in ["beams", "segments"] {
        assert!(
            routing.contains(&format!("{kind} {why}")),
            "{kind}:\n{routing}"
        );
    }
    let out = render_on(&s, &backend, &NoProgress).expect("the GPU backend renders");
    let reference = render(&s, &NoProgress).expect("the CPU renders");
    assert_eq!(out.box_classes(), reference.box_classes());
}

#[test]
fn open_roots_that_rounding_dominates_escalate_on_the_cpu() {
    // The unit sphere with terms of 1e11 that cancel: in f32 (and f64) every ray stays
    // open; the backend sends those rays to the CPU, which escalates to double-double.
    let Some(gpu) = Gpu::for_tests() else { return };
    let backend = GpuBackend::new(gpu);
    let text = r#"
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov = 40.0
width = 16
height = 16
[[surfaces]]
formula = "(x + 1e11)^2 - 2e11*x - 1e22 + y^2 + z^2 - 1"
bounds = [[-1.25, -1.25, -1.25], [1.25, 1.25, 1.25]]
[render]
primary = "screen-rays"
rays_per_undecided = 1
"#;
    let s = Scene::from_toml(text, "cancel.toml", None).unwrap_or_else(|e| panic!("{e}"));
    let out = render_on(&s, &backend, &NoProgress).expect("the GPU backend renders");
    let reference = render(&s, &NoProgress).expect("the CPU renders");
    let (gpu_rays, cpu_rays) = (
        out.stats.pass("primary-rays").unwrap(),
        reference.stats.pass("primary-rays").unwrap(),
    );
    assert!(gpu_rays.counter("escalated") > 0);
    assert_eq!(gpu_rays.counter("hits"), cpu_rays.counter("hits"));
    assert_eq!(gpu_rays.counter("possible"), 0);
    assert_eq!(gpu_rays.counter("undecided"), 0);
}

#[test]
fn undecided_beams_that_cancellation_keeps_open_escalate_on_the_cpu() {
    // The same sphere in the default primary mode: the kernels' screen boxes stay undecided
    // where the large terms cancel; the backend sends those beams to the CPU, which
    // classifies them in double-double with the centred form, as the CPU backend does.
    let Some(gpu) = Gpu::for_tests() else { return };
    let backend = GpuBackend::new(gpu);
    let text = |escalate: bool| {
        format!(
            r#"
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov = 40.0
width = 32
height = 32
[[surfaces]]
formula = "(x + 1e11)^2 - 2e11*x - 1e22 + y^2 + z^2 - 1"
bounds = [[-1.25, -1.25, -1.25], [1.25, 1.25, 1.25]]
[render]
escalate = {escalate}
"#
        )
    };
    let scene = |escalate| {
        Scene::from_toml(&text(escalate), "cancel.toml", None).unwrap_or_else(|e| panic!("{e}"))
    };
    let undecided = |out: &beam_trace::RenderOutput| {
        out.stats
            .pass("screen-boxes")
            .unwrap()
            .counter("undecided_pixels")
    };
    let out = render_on(&scene(true), &backend, &NoProgress).expect("the GPU backend renders");
    let open = render_on(&scene(false), &backend, &NoProgress).expect("the GPU backend renders");
    let cpu = render(&scene(true), &NoProgress).expect("the CPU renders");
    let boxes = out.stats.pass("screen-boxes").unwrap();
    assert!(boxes.counter("escalated_resolved") > 0);
    // Without escalation only the beams that miss the bounds are decided.
    assert!(
        undecided(&open) >= 4 * undecided(&out),
        "GPU {} undecided pixels, {} without escalation",
        undecided(&out),
        undecided(&open)
    );
    assert!(
        undecided(&out) <= 2 * undecided(&cpu).max(32),
        "GPU {} undecided pixels, CPU {}",
        undecided(&out),
        undecided(&cpu)
    );
}

#[test]
fn gpu_shadow_proofs_agree_with_many_cpu_samples() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let g =
        render_on(&scene("beam:4"), &GpuBackend::new(gpu), &NoProgress).expect("the GPU renders");
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
