//! The render pipeline end to end on small images: the effect plan (skipped passes cost
//! nothing), independence of the thread count, the classification image, and image output.

use std::path::{Path, PathBuf};

use beam_trace::image::check_writable;
use beam_trace::{Image, NoProgress, RenderOutput, RenderStats, Scene, render};

/// Colours of the classification image (before the darkening of box outlines).
const MISS_BLUE: [f32; 3] = [0.1, 0.25, 0.8];
const HIT_RED: [f32; 3] = [0.85, 0.15, 0.1];

/// A unit sphere over a floor slab (so that the sphere casts a shadow), seen from the front;
/// `lights` is written as the TOML of the lights, `render` as the body of `[render]`.
fn scene_toml(size: u32, lights: &str, render: &str) -> String {
    format!(
        r#"
background = [0.1, 0.2, 0.3]

[camera]
eye = [0.0, 1.0, 6.0]
look_at = [0.0, 0.0, 0.0]
fov = 40.0
width = {size}
height = {size}

[[surfaces]]
name = "ball"
formula = "x^2 + y^2 + z^2 - 1"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
material = {{ color = [0.9, 0.4, 0.2] }}

[[surfaces]]
name = "floor"
formula = "y + 1.2"
bounds = [[-3.0, -1.5, -3.0], [3.0, -1.2, 3.0]]
clip = true

{lights}

[render]
{render}
"#
    )
}

const ONE_LIGHT: &str = r#"
[[lights]]
type = "point"
position = [-3.0, 6.0, 4.0]
"#;

fn scene(size: u32, lights: &str, render: &str) -> Scene {
    let text = scene_toml(size, lights, render);
    Scene::from_toml(&text, "test.toml", None).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn run(scene: &Scene) -> RenderOutput {
    render(scene, &NoProgress).expect("the render succeeds")
}

/// Asserts that the passes `ran` ran and did work, and the passes `skipped` did not run
/// and count nothing.
fn assert_passes(stats: &RenderStats, ran: &[&str], skipped: &[&str]) {
    for name in ran {
        let p = stats
            .pass(name)
            .unwrap_or_else(|| panic!("no pass {name}:\n{stats}"));
        assert!(p.ran, "{name} should run:\n{stats}");
        assert!(p.total_work() > 0, "{name} should count work:\n{stats}");
    }
    for name in skipped {
        let p = stats
            .pass(name)
            .unwrap_or_else(|| panic!("no pass {name}:\n{stats}"));
        assert!(!p.ran, "{name} should be skipped:\n{stats}");
        assert_eq!(p.total_work(), 0, "{name} should count nothing:\n{stats}");
        assert!(p.time.is_zero(), "{name} should take no time:\n{stats}");
    }
}

#[test]
fn every_pass_is_reported_in_order() {
    let out = run(&scene(16, ONE_LIGHT, ""));
    let names: Vec<&str> = out.stats.passes.iter().map(|p| p.name.as_str()).collect();
    let expected: Vec<&str> = beam_trace::Pass::ALL.iter().map(|p| p.name()).collect();
    assert_eq!(names, expected);
    for pass in beam_trace::Pass::ALL {
        assert_eq!(
            out.plan.runs(pass),
            out.stats.of(pass).unwrap().ran,
            "{pass}"
        );
    }
}

#[test]
fn plan_without_lights_skips_normals_shadows_and_shading() {
    let out = run(&scene(16, "", ""));
    assert_passes(
        &out.stats,
        &["grid", "screen-boxes", "pixel-beams"],
        &["primary-rays", "normals", "hard-shadows", "shading"],
    );
    // Flat colour: hit pixels have the material's colour.
    let c = out.image.get(8, 8);
    assert_eq!(c, [0.9, 0.4, 0.2]);
}

#[test]
fn plan_with_lights_runs_normals_shadows_and_shading() {
    let out = run(&scene(16, ONE_LIGHT, ""));
    assert_passes(
        &out.stats,
        &[
            "grid",
            "screen-boxes",
            "pixel-beams",
            "normals",
            "hard-shadows",
            "shading",
        ],
        &["primary-rays"],
    );
    let shadows = out.stats.pass("hard-shadows").unwrap();
    assert!(shadows.counter("segments") > 0);
    assert_eq!(
        shadows.counter("segments"),
        shadows.counter("lit")
            + shadows.counter("occluded")
            + shadows.counter("undecided")
            + shadows.counter("back_facing")
    );
    // The sphere stands between the light and part of the floor.
    assert!(shadows.counter("occluded") > 0, "{}", out.stats);
    assert!(shadows.counter("lit") > 0, "{}", out.stats);
}

#[test]
fn plan_with_shadows_off_runs_no_shadow_rays() {
    let out = run(&scene(16, ONE_LIGHT, "shadows = false"));
    assert_passes(
        &out.stats,
        &["normals", "shading"],
        &["hard-shadows", "primary-rays"],
    );
    assert_eq!(out.plan.hard_shadow_lights, 0);
}

#[test]
fn plan_for_aa_modes() {
    let none = run(&scene(16, "", "aa = \"none\""));
    assert_passes(
        &none.stats,
        &["screen-boxes", "pixel-beams"],
        &["primary-rays"],
    );
    let thesis = run(&scene(16, "", "primary = \"screen-rays\""));
    assert_passes(
        &thesis.stats,
        &["screen-boxes", "primary-rays"],
        &["pixel-beams"],
    );

    let iaa = run(&scene(16, "", "aa = \"iaa\""));
    assert_passes(
        &iaa.stats,
        &["screen-boxes", "pixel-beams"],
        &["primary-rays"],
    );
    // IAA starts from the screen boxes: more sub-pixel beams, and their variation judged.
    let beams = |o: &RenderOutput| o.stats.pass("pixel-beams").unwrap().counter("beams");
    assert!(beams(&iaa) >= beams(&none), "{}\n{}", iaa.stats, none.stats);

    let ss = run(&scene(16, "", "aa = \"ss:2\""));
    assert_passes(
        &ss.stats,
        &["primary-rays"],
        &["pixel-beams", "screen-boxes"],
    );
    assert_eq!(
        ss.stats.pass("primary-rays").unwrap().counter("rays"),
        16 * 16 * 4
    );
}

#[test]
fn plan_per_pixel_runs_no_screen_boxes() {
    let out = run(&scene(
        16,
        "",
        "primary = \"per-pixel\"\nrays_per_pixel = 4",
    ));
    assert_passes(
        &out.stats,
        &["primary-rays"],
        &["screen-boxes", "pixel-beams"],
    );
    assert_eq!(
        out.stats.pass("primary-rays").unwrap().counter("rays"),
        16 * 16 * 4
    );
}

#[test]
fn plan_without_grid() {
    let with = run(&scene(16, "", ""));
    assert_passes(&with.stats, &["grid"], &[]);
    let without = run(&scene(16, "", "grid = 0"));
    assert_passes(&without.stats, &["screen-boxes", "pixel-beams"], &["grid"]);
    assert_eq!(without.plan.grid, None);
    // The grid only speeds the search up: the same pixels are background.
    let bg = |o: &RenderOutput| -> Vec<bool> {
        o.image
            .pixels
            .iter()
            .map(|&p| p == [0.1, 0.2, 0.3])
            .collect()
    };
    let (a, b) = (bg(&with), bg(&without));
    let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert!(
        differ <= 2,
        "{differ} pixels differ with and without the grid"
    );
}

/// Renders `scene` on a pool of `threads` threads.
fn run_on(threads: usize, scene: &Scene) -> RenderOutput {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| run(scene))
}

fn assert_thread_independent(scene: &Scene) {
    let one = run_on(1, scene);
    let two = run_on(2, scene);
    // Bit-identical: compare the bits, not the values.
    let bits =
        |img: &Image| -> Vec<[u32; 3]> { img.pixels.iter().map(|p| p.map(f32::to_bits)).collect() };
    assert_eq!(bits(&one.image), bits(&two.image), "images differ");
    assert_eq!(
        bits(&one.classification()),
        bits(&two.classification()),
        "classification images differ"
    );
    assert_eq!(one.stats.work(), two.stats.work(), "work counters differ");
    assert_eq!(one.plan, two.plan);
}

#[test]
fn thread_count_does_not_change_the_result() {
    // Screen boxes, shadows.
    assert_thread_independent(&scene(24, ONE_LIGHT, ""));
    // Interval anti-aliasing, shadows.
    assert_thread_independent(&scene(16, ONE_LIGHT, "aa = \"iaa\""));
    // Per-pixel supersampling, shadows.
    assert_thread_independent(&scene(16, ONE_LIGHT, "aa = \"ss:2\""));
    // Per-pixel primary rays, no grid.
    assert_thread_independent(&scene(16, ONE_LIGHT, "primary = \"per-pixel\"\ngrid = 0"));
}

/// What a pixel of the classification image says: the base colour or the darkened outline.
fn class_colour(c: [f32; 3]) -> &'static str {
    let is = |base: [f32; 3]| c == base || c == base.map(|v| v * 0.6);
    if is(MISS_BLUE) {
        "miss"
    } else if is(HIT_RED) {
        "hit"
    } else if is([0.95, 0.85, 0.1]) {
        "undecided"
    } else if c == [0.5; 3] {
        "none"
    } else {
        "unknown"
    }
}

#[test]
fn classification_of_a_sphere() {
    let text = r#"
background = [0.05, 0.1, 0.15]
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov = 40.0
width = 32
height = 32
[[surfaces]]
catalog = "sphere"
"#;
    let scene = Scene::from_toml(text, "sphere.toml", None).unwrap();
    let out = run(&scene);
    let cls = out.classification();
    assert_eq!((cls.width, cls.height), (32, 32));
    // Corners are far from the sphere (it covers the middle ~ 17 pixels).
    for (x, y) in [(0, 0), (31, 0), (0, 31), (31, 31), (2, 16)] {
        assert_eq!(class_colour(cls.get(x, y)), "miss", "pixel ({x}, {y})");
        assert_eq!(out.image.get(x, y), scene.background, "pixel ({x}, {y})");
    }
    // The centre looks straight at the sphere.
    for (x, y) in [(15, 15), (16, 16), (15, 16), (16, 15)] {
        assert_eq!(class_colour(cls.get(x, y)), "hit", "pixel ({x}, {y})");
        assert_ne!(out.image.get(x, y), scene.background, "pixel ({x}, {y})");
    }
    // Every pixel is classified by some beam, and every proven miss is background.
    let mut counts = std::collections::BTreeMap::new();
    for y in 0..32 {
        for x in 0..32 {
            let c = class_colour(cls.get(x, y));
            assert_ne!(c, "unknown");
            assert_ne!(c, "none");
            *counts.entry(c).or_insert(0u64) += 1;
            if c == "miss" {
                assert_eq!(out.image.get(x, y), scene.background);
            }
        }
    }
    // The counters agree with the image.
    let sb = out.stats.pass("screen-boxes").unwrap();
    assert_eq!(sb.counter("miss_pixels"), counts["miss"]);
    assert_eq!(sb.counter("hit_pixels"), counts["hit"]);
    assert_eq!(
        sb.counter("undecided_pixels"),
        counts.get("undecided").copied().unwrap_or(0)
    );
    // The cost map has the image's size.
    assert_eq!(out.cost_map().pixels.len(), 32 * 32);
}

/// A fresh, empty folder for this test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "beam-trace-render-test-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn decode_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut reader = png::Decoder::new(file).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

#[test]
fn png_output() {
    let dir = temp_dir("png");
    let out = run(&scene(16, ONE_LIGHT, ""));
    let path = dir.join("image.png");
    check_writable(&path).unwrap();
    assert!(!path.exists(), "the probe is removed again");
    out.image.write_png(&path).unwrap();
    let (w, h, bytes) = decode_png(&path);
    assert_eq!((w, h), (16, 16));
    assert_eq!(bytes, out.image.to_rgb8());
    // Only the image is left in the folder (no temporary file).
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("image.png")]);
    // Writing again replaces the file.
    let grey = Image::new(3, 2, [0.5; 3]);
    grey.write_png(&path).unwrap();
    let (w, h, bytes) = decode_png(&path);
    assert_eq!((w, h), (3, 2));
    assert!(bytes.iter().all(|&b| b == grey.to_rgb8()[0]));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn png_output_to_a_missing_folder_fails_and_leaves_no_file() {
    let dir = temp_dir("missing");
    let missing = dir.join("no-such-folder");
    let path = missing.join("image.png");
    let img = Image::new(4, 4, [0.2, 0.4, 0.6]);
    let err = img.write_png(&path).unwrap_err();
    assert!(
        matches!(&err, beam_trace::Error::Io { path: p, .. } if p == &path),
        "{err:?}"
    );
    assert!(err.to_string().contains("image.png"), "{err}");
    assert!(!path.exists());
    assert!(!missing.exists());
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);

    // check_writable refuses a missing folder and a folder given as the file.
    let err = check_writable(&path).unwrap_err();
    assert!(matches!(err, beam_trace::Error::Io { .. }), "{err:?}");
    assert!(!missing.exists());
    let err = check_writable(&dir).unwrap_err();
    assert!(err.to_string().contains("folder"), "{err}");
    assert!(dir.is_dir());
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    // Writing an image over a folder fails too, and leaves the folder alone.
    assert!(img.write_png(&dir).is_err());
    assert!(dir.is_dir());
    std::fs::remove_dir_all(&dir).unwrap();
}
