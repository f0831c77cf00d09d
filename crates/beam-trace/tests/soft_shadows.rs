//! Soft shadows from area lights, end to end on small images: what the methods prove holds
//! against many stochastic samples, a light of size zero is a point light, shrinking a light
//! converges to the hard shadow, results do not depend on the thread count, and beams catch
//! the shadow of an occluder thinner than the gaps between sparse samples.

use beam_trace::scene::AaMode;
use beam_trace::shadow::{ShadowClass, ShadowSpec};
use beam_trace::{NoProgress, RenderOutput, Scene, ShadowMaps, render};

/// A ball over a floor slab, lit by `light` (TOML of one `[[lights]]` table).
fn scene(size: u32, light: &str, method: &str) -> Scene {
    let text = format!(
        r#"
[camera]
eye = [0.0, 3.0, 6.0]
look_at = [0.0, -0.6, 0.0]
fov = 45.0
width = {size}
height = {size}

[[surfaces]]
name = "ball"
formula = "x^2 + y^2 + z^2 - 1"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]

[[surfaces]]
name = "floor"
formula = "y + 1.2"
bounds = [[-3.0, -1.5, -3.0], [3.0, -1.2, 3.0]]
clip = true

{light}

[render]
shadow_method = "{method}"
"#
    );
    Scene::from_toml(&text, "soft.toml", None).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn square_light(size: f64) -> String {
    format!(
        r#"[[lights]]
type = "area"
center = [-1.0, 4.0, 1.0]
size = {size}
normal = "y""#
    )
}

fn run(scene: &Scene) -> RenderOutput {
    render(scene, &NoProgress).expect("the render succeeds")
}

fn maps(out: &RenderOutput) -> &ShadowMaps {
    out.shadows.as_ref().expect("a soft-shadow pass ran")
}

/// Proven-lit pixels see the whole light and proven-umbra pixels none of it, according to
/// 256 reliable shadow segments per shaded point: the proven classes never contradict the
/// samples (the check `accuracy-cost` makes on larger scenes).
#[test]
fn proven_classes_agree_with_many_samples() {
    let light = square_light(1.5);
    let reference = run(&scene(40, &light, "stochastic:256"));
    let reference = &maps(&reference).fractions[0];
    for method in [
        "beam:4",
        "minkowski:beam:3",
        "minkowski:stochastic:8",
        "beam-quadtree:4",
    ] {
        let out = run(&scene(40, &light, method));
        let m = maps(&out);
        let (mut lit, mut umbra) = (0, 0);
        for (i, class) in m.classes.iter().enumerate() {
            match class {
                Some(ShadowClass::Lit) => {
                    lit += 1;
                    assert_eq!(reference[i], 1.0, "{method}: pixel {i} proven lit");
                }
                Some(ShadowClass::Umbra) => {
                    umbra += 1;
                    assert_eq!(reference[i], 0.0, "{method}: pixel {i} proven umbra");
                }
                _ => {}
            }
        }
        assert!(lit > 200, "{method}: {lit} proven lit pixels");
        if method.starts_with("minkowski") {
            assert!(umbra > 0, "{method}: no proven umbra pixel");
        }
    }
}

/// The visible fractions of a beam method are proven lower bounds: never above the share of
/// free segments by more than the sampling error, and close to it on average.
#[test]
fn beam_fractions_track_the_stochastic_estimate() {
    let light = square_light(1.5);
    let reference = run(&scene(32, &light, "stochastic:1024"));
    let reference = &maps(&reference).fractions[0];
    let out = run(&scene(32, &light, "beam:8"));
    let beam = &maps(&out).fractions[0];
    let (mut sum, mut n) = (0.0, 0);
    for (b, r) in beam.iter().zip(reference) {
        if b.is_finite() && r.is_finite() {
            assert!(*b <= r + 0.1, "beam {b} above the estimate {r}");
            sum += (b - r).abs();
            n += 1;
        }
    }
    assert!(n > 500);
    let mean = sum / n as f32;
    assert!(mean < 0.05, "mean difference {mean}");
}

/// An area light of size zero renders exactly as the point light at its place.
#[test]
fn a_light_of_size_zero_is_a_point_light() {
    let point = r#"[[lights]]
type = "point"
position = [-1.0, 4.0, 1.0]"#;
    let a = run(&scene(24, point, "beam:7"));
    let b = run(&scene(24, &square_light(0.0), "beam:7"));
    assert_eq!(a.image, b.image);
    assert!(b.stats.pass("hard-shadows").unwrap().ran);
    assert!(!b.stats.pass("soft-shadows").unwrap().ran);
    assert!(b.shadows.is_none());
}

/// Scenes with only point lights plan no soft-shadow pass, and scenes with area lights no
/// hard-shadow pass; `shadows = false` runs neither.
#[test]
fn the_plan_runs_soft_shadows_only_for_area_lights() {
    let out = run(&scene(16, &square_light(1.0), "beam:2"));
    assert!(out.stats.pass("soft-shadows").unwrap().ran);
    assert!(!out.stats.pass("hard-shadows").unwrap().ran);
    assert_eq!(out.stats.lights.len(), 1);
    let mut s = scene(16, &square_light(1.0), "beam:2");
    s.settings.shadows = false;
    let out = run(&s);
    assert!(!out.stats.pass("soft-shadows").unwrap().ran);
    assert_eq!(out.stats.pass("soft-shadows").unwrap().total_work(), 0);
}

/// As the light shrinks to a point, the soft-shadow image converges to the hard-shadow one.
#[test]
fn shrinking_the_light_converges_to_the_hard_shadow() {
    let point = r#"[[lights]]
type = "point"
position = [-1.0, 4.0, 1.0]"#;
    // Without anti-aliasing, so that both images take their samples at the same points
    // (interval anti-aliasing splits pixels where a hard shadow's edge may cross them).
    let plain = |lights: &str, method: &str| {
        let mut s = scene(32, lights, method);
        s.settings.aa = Some(AaMode::None);
        run(&s)
    };
    let hard = plain(point, "beam:4");
    let mut previous = f32::INFINITY;
    for size in [1.6, 0.4, 0.1, 0.005] {
        for method in ["beam:4", "stochastic:16"] {
            let soft = plain(&square_light(size), method);
            let differing = hard
                .image
                .pixels
                .iter()
                .zip(&soft.image.pixels)
                .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| (x - y).abs() > 0.02))
                .count() as f32
                / hard.image.pixels.len() as f32;
            if method == "beam:4" {
                assert!(
                    differing <= previous + 1e-3,
                    "size {size}: {differing} > {previous}"
                );
                previous = differing;
            }
            if size < 0.01 {
                assert!(
                    differing < 0.01,
                    "{method} size {size}: {differing} of the pixels differ"
                );
            }
        }
    }
}

/// Images and every counter are the same with 1 and 2 worker threads, for every method.
#[test]
fn results_do_not_depend_on_the_thread_count() {
    for method in [
        "stochastic:8",
        "stochastic:8:cache",
        "beam:3",
        "beam-all:2",
        "beam-quadtree:4",
        "minkowski:stochastic:8",
        "minkowski:beam:3",
    ] {
        let s = scene(20, &square_light(1.5), method);
        let outs: Vec<RenderOutput> = [1, 2]
            .iter()
            .map(|&k| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(k)
                    .build()
                    .unwrap()
                    .install(|| run(&s))
            })
            .collect();
        assert_eq!(outs[0].image, outs[1].image, "{method}");
        assert_eq!(outs[0].stats.work(), outs[1].stats.work(), "{method}");
        assert_eq!(maps(&outs[0]).classes, maps(&outs[1]).classes, "{method}");
    }
}

/// A rod 2·10⁻³ wide above the floor: shadow beams see its shadow (every sub-beam it crosses
/// counts as occluded), while 4 stochastic segments per point pass between it almost
/// everywhere (thesis Fig. 5.24 a-b).
#[test]
fn beams_catch_the_shadow_of_a_thin_occluder() {
    let text = |method: &str| {
        format!(
            r#"
[camera]
eye = [0.0, 3.0, 0.01]
look_at = [0.0, -1.0, 0.0]
fov = 50.0
width = 48
height = 48

[[surfaces]]
name = "rod"
formula = "y^2 + z^2 - 1e-6"
bounds = [[-1.5, -0.01, -0.01], [1.5, 0.01, 0.01]]
clip = true

[[surfaces]]
name = "floor"
formula = "y + 1"
bounds = [[-3.0, -1.5, -3.0], [3.0, -1.0, 3.0]]
clip = true

[[lights]]
type = "area"
center = [0.0, 2.0, 0.0]
size = 0.5
normal = "y"

[render]
shadow_method = "{method}"
"#
        )
    };
    let shadowed = |method: &str| {
        let s = Scene::from_toml(&text(method), "rod.toml", None).unwrap();
        let out = run(&s);
        out.stats.lights[0].counter("pixels_in_shadow")
    };
    let beams = shadowed("beam:4");
    let samples = shadowed("stochastic:4");
    assert!(beams >= 40, "beams found {beams} shadowed pixels");
    assert!(
        samples * 4 < beams,
        "stochastic {samples} against beams {beams}"
    );
}

/// The method names parse back to the same settings.
#[test]
fn methods_parse_from_their_names() {
    for s in [
        "stochastic:32",
        "beam:7",
        "minkowski:beam:7",
        "minkowski:stochastic:32",
    ] {
        assert_eq!(s.parse::<ShadowSpec>().unwrap().to_string(), s);
    }
}

/// Both forms of area light load: an axis-aligned square and a parallelogram, with the
/// intensity scaling the colour; every `.toml` under `scenes/` with an area light loads.
#[test]
fn area_lights_load_from_both_forms() {
    use beam_trace::Light;
    use glam::DVec3;
    let text = r#"
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
[[surfaces]]
catalog = "sphere"
[[lights]]
type = "area"
center = [1.0, 4.0, 0.0]
size = 2.0
normal = "y"
intensity = 0.5
[[lights]]
type = "area"
corner = [0.0, 3.0, 0.0]
edge_u = [1.0, 0.0, 0.5]
edge_v = [0.0, 0.5, 1.0]
"#;
    let s = Scene::from_toml(text, "two.toml", None).unwrap();
    let Light::Area(a) = s.lights[0] else {
        panic!("an area light")
    };
    assert_eq!(a.patch.center(), DVec3::new(1.0, 4.0, 0.0));
    assert_eq!(a.patch.area(), 4.0);
    assert_eq!(a.patch.edge_u.y, 0.0);
    assert_eq!(a.color, [0.5; 3]);
    let Light::Area(b) = s.lights[1] else {
        panic!("an area light")
    };
    assert_eq!(b.patch.edge_v, DVec3::new(0.0, 0.5, 1.0));
    let out = run(&Scene {
        camera: s.camera.resized(12, 12).unwrap(),
        ..s
    });
    assert_eq!(out.stats.lights.len(), 2);
}
