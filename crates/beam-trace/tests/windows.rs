//! A render cut into windows ([`Pipeline::render`]) and put together again
//! ([`Pipeline::assemble`]) is the render of the whole image, bit for bit: images, classes,
//! coverage, soft-shadow maps and every counter. This is what lets a render be shared among
//! processes (the cluster crate) and still give the image of one process.

use std::path::PathBuf;
use std::time::Instant;

use beam_trace::render::Pipeline;
use beam_trace::scene::PrimaryMode;
use beam_trace::screen::PixelRect;
use beam_trace::window::Window;
use beam_trace::{Cpu, NoProgress, Plan, RenderOutput, Scene, render};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn small(mut scene: Scene, w: u32, h: u32) -> Scene {
    scene.camera = scene.camera.resized(w, h).expect("a valid size");
    scene
}

fn file_scene(name: &str, w: u32, h: u32) -> Scene {
    small(
        Scene::load(&root().join("scenes").join(name)).expect("the scene file loads"),
        w,
        h,
    )
}

/// The windows of `scene`'s image cut at the columns `xs` and rows `ys` (multiples of the
/// window grid).
fn cut(scene: &Scene, xs: &[u32], ys: &[u32]) -> Vec<Window> {
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let edges = |cuts: &[u32], end: u32| {
        let mut e = vec![0];
        e.extend(cuts.iter().copied().filter(|&c| c < end));
        e.push(end);
        e
    };
    let (ex, ey) = (edges(xs, w), edges(ys, h));
    let mut out = Vec::new();
    for y in ey.windows(2) {
        for x in ex.windows(2) {
            let rect = PixelRect {
                x0: x[0],
                y0: y[0],
                x1: x[1],
                y1: y[1],
            };
            out.push(Window::new(rect, w, h).expect("a window of the image"));
        }
    }
    out
}

/// The render of `scene` from its windows `windows`, rendered in reverse order.
fn by_windows(scene: &Scene, windows: &[Window]) -> RenderOutput {
    let start = Instant::now();
    let plan = Plan::for_scene(scene);
    let pipeline = Pipeline::new(scene, &Cpu, &plan).expect("the CPU prepares");
    let pieces = windows
        .iter()
        .rev()
        .map(|w| pipeline.render(w, &NoProgress).expect("the window renders"))
        .collect();
    pipeline
        .assemble(pieces, start)
        .expect("the pieces cover the image")
}

fn assert_same(name: &str, whole: &RenderOutput, parts: &RenderOutput) {
    let bits = |img: &beam_trace::Image| -> Vec<[u32; 3]> {
        img.pixels.iter().map(|p| p.map(f32::to_bits)).collect()
    };
    assert_eq!(
        bits(&whole.image),
        bits(&parts.image),
        "{name}: images differ"
    );
    assert_eq!(
        bits(&whole.classification()),
        bits(&parts.classification()),
        "{name}: classification images differ"
    );
    assert_eq!(
        whole.box_classes(),
        parts.box_classes(),
        "{name}: box classes"
    );
    assert_eq!(whole.stats.work(), parts.stats.work(), "{name}: counters");
    assert_eq!(
        whole.shadows.is_some(),
        parts.shadows.is_some(),
        "{name}: shadow maps"
    );
    assert_eq!(
        whole.fingerprint(),
        parts.fingerprint(),
        "{name}: fingerprints"
    );
}

/// Cuts of the image into windows: in four, in vertical strips, in horizontal strips.
const CUTS: [(&[u32], &[u32]); 3] = [(&[64], &[64]), (&[64, 128], &[]), (&[], &[64])];

fn check(name: &str, scene: &Scene, cuts: &[(&[u32], &[u32])]) {
    let whole = render(scene, &NoProgress).expect("the scene renders");
    for &(xs, ys) in cuts {
        let parts = by_windows(scene, &cut(scene, xs, ys));
        assert_same(&format!("{name} cut at {xs:?} x {ys:?}"), &whole, &parts);
    }
}

#[test]
fn the_default_scene_from_windows_is_the_whole_render() {
    check("default", &small(Scene::default_scene(), 150, 100), &CUTS);
}

#[test]
fn soft_shadows_from_windows_are_the_whole_render() {
    let mut scene = file_scene("soft-shadows.toml", 100, 72);
    check("the file's method", &scene, &CUTS[..1]);
    // Stochastic seeds and certified bounds (their width counters are not sums).
    for method in ["beam:7", "stochastic:16", "certified:0.1"] {
        scene.settings.shadow_method = method.parse().expect("a shadow method");
        check(method, &scene, &CUTS[..1]);
    }
    // Thin rods, whose thin beams stop trying the mean-value form after a few tries that
    // decide nothing: each point keeps its own record, so a window's points are answered
    // as in the whole render.
    let mut thin = file_scene("thin-occluder.toml", 100, 72);
    thin.settings.shadow_method = "certified:0.1".parse().expect("a shadow method");
    check("thin rods, certified:0.1", &thin, &CUTS[..1]);
}

#[test]
fn every_primary_mode_from_windows_is_the_whole_render() {
    for mode in [
        PrimaryMode::Octree,
        PrimaryMode::ScreenRays,
        PrimaryMode::PerPixel,
    ] {
        let mut scene = file_scene("csg.toml", 140, 80);
        scene.settings.primary = mode;
        check(&format!("csg {mode:?}"), &scene, &CUTS);
    }
}

#[test]
fn windows_follow_the_plans_grid() {
    // The screen boxes start from tiles of 32 pixels: windows cut at 32 are whole-render
    // windows too; the frustum octree's tiles are 64 pixels, and a cut at 32 is refused.
    let mut scene = file_scene("csg.toml", 100, 70);
    let cuts: [(&[u32], &[u32]); 1] = [(&[32, 96], &[32])];
    check("csg screen boxes at 32", &scene, &cuts);
    scene.settings.primary = PrimaryMode::Octree;
    {
        let plan = Plan::for_scene(&scene);
        let pipeline = Pipeline::new(&scene, &Cpu, &plan).expect("the CPU prepares");
        assert_eq!(pipeline.grid(), 64);
        let e = pipeline
            .render(&cut(&scene, &[32], &[])[0], &NoProgress)
            .expect_err("off the octree's grid")
            .to_string();
        assert!(e.contains("multiples of 64"), "{e}");
    }
    // Per-pixel rays start from no tiles: any window.
    scene.settings.primary = PrimaryMode::PerPixel;
    let cuts: [(&[u32], &[u32]); 1] = [(&[7, 50], &[33])];
    check("csg per pixel at any column", &scene, &cuts);
}

#[test]
fn pieces_that_miss_or_repeat_a_pixel_are_refused() {
    let scene = small(Scene::default_scene(), 100, 70);
    let plan = Plan::for_scene(&scene);
    let pipeline = Pipeline::new(&scene, &Cpu, &plan).expect("the CPU prepares");
    let windows = cut(&scene, &[64], &[]);
    let piece = |w: &Window| pipeline.render(w, &NoProgress).expect("renders");
    let missing = pipeline
        .assemble(vec![piece(&windows[0])], Instant::now())
        .unwrap_err()
        .to_string();
    assert!(
        missing.contains("pixel (64, 0) is in no piece"),
        "{missing}"
    );
    let twice = pipeline
        .assemble(
            vec![piece(&windows[0]), piece(&windows[1]), piece(&windows[0])],
            Instant::now(),
        )
        .unwrap_err()
        .to_string();
    assert!(twice.contains("in two pieces"), "{twice}");
    // A window of another image size.
    let other = Window::full(60, 60);
    let e = pipeline
        .render(&other, &NoProgress)
        .expect_err("refused")
        .to_string();
    assert!(e.contains("60 x 60"), "{e}");
}
