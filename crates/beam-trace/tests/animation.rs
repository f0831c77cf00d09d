//! Animated scene files: formulas of the frame time `t` in numbers, parameters, transforms,
//! lights and surface formulas; each frame is exactly the static file with those numbers.

use beam_trace::scene::Animation;
use beam_trace::{NoProgress, Scene, render};

/// The animated file: a ball whose radius, position and parameter change, a rotating box
/// and a moving point light, plus an area light whose `normal = "y"` stays a string.
fn animated(frames: &str, rate: &str) -> String {
    format!(
        r#"
[animation]
frames = {frames}
rate = {rate}

[camera]
eye = [0.0, 1.0, 5.0]
look_at = [0.0, 0.0, 0.0]
width = "32 + 0*t"
height = 24

[[surfaces]]
formula = "x^2 + y^2 + z^2 - a^2 + 0.01*t"
params = {{ a = "0.6 + 0.05*t" }}
bounds = [[-1, -1, -1], [1, 1, 1]]
transform = {{ translate = ["-0.8 + 0.1*t", 0, 0] }}

[[surfaces]]
formula = "max(abs(x), max(abs(y), abs(z))) - 0.4"
bounds = [[-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]]
transform = {{ translate = [0.9, 0, 0], rotate = ["20*t", "5*t", 0] }}

[[lights]]
type = "point"
position = ["2 + 0.5*t", 3, 4]

[[lights]]
type = "area"
center = [0, 4, "2*sin(t/3)"]
size = 0.5
normal = "y"

[render]
shadows = false
"#
    )
}

/// The same scene written with the numbers of frame `t` (what the animation substitutes).
fn static_frame(t: f64) -> String {
    let n = |v: f64| format!("{v:?}");
    format!(
        r#"
[camera]
eye = [0.0, 1.0, 5.0]
look_at = [0.0, 0.0, 0.0]
width = 32
height = 24

[[surfaces]]
formula = "x^2 + y^2 + z^2 - a^2 + 0.01*t"
params = {{ a = {a}, t = {t} }}
bounds = [[-1, -1, -1], [1, 1, 1]]
transform = {{ translate = [{tx}, 0, 0] }}

[[surfaces]]
formula = "max(abs(x), max(abs(y), abs(z))) - 0.4"
bounds = [[-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]]
transform = {{ translate = [0.9, 0, 0], rotate = [{rx}, {ry}, 0] }}

[[lights]]
type = "point"
position = [{lx}, 3, 4]

[[lights]]
type = "area"
center = [0, 4, {lz}]
size = 0.5
normal = "y"

[render]
shadows = false
"#,
        a = n(0.6 + 0.05 * t),
        t = n(t),
        tx = n(-0.8 + 0.1 * t),
        rx = n(20.0 * t),
        ry = n(5.0 * t),
        lx = n(2.0 + 0.5 * t),
        lz = n(2.0 * (t / 3.0).sin()),
    )
}

#[test]
fn every_frame_is_the_static_file_with_its_numbers() {
    let a = Animation::from_toml(&animated("[0, 3]", "12"), "anim.toml", None)
        .expect("reads")
        .expect("animated");
    assert_eq!(a.frames(), 0..=3);
    assert_eq!(a.rate(), 12.0);
    // The width (an integer field), a, translate x, rotate x and y, light x, light z.
    assert_eq!(a.time_values(), 7);
    let mut images = Vec::new();
    for t in a.frames() {
        let frame = render(&a.scene(t).expect("frame builds"), &NoProgress).expect("renders");
        let alone = Scene::from_toml(&static_frame(t as f64), "frame.toml", None)
            .unwrap_or_else(|e| panic!("{e}"));
        let reference = render(&alone, &NoProgress).expect("renders");
        assert_eq!(frame.image.pixels, reference.image.pixels, "frame {t}");
        assert_eq!(frame.box_classes(), reference.box_classes(), "frame {t}");
        images.push(frame.image.pixels);
    }
    // The frames move.
    assert_ne!(images[0], images[3]);
}

#[test]
fn a_static_load_of_an_animated_file_is_its_first_frame() {
    let text = animated("[2, 5]", "25");
    let first = Scene::from_toml(&text, "anim.toml", None).expect("builds");
    let a = Animation::from_toml(&text, "anim.toml", None)
        .expect("reads")
        .expect("animated");
    let frame = a.scene(2).expect("builds");
    let (x, y) = (
        render(&first, &NoProgress).expect("renders"),
        render(&frame, &NoProgress).expect("renders"),
    );
    assert_eq!(x.image.pixels, y.image.pixels);
}

#[test]
fn static_files_have_no_animation() {
    let text = static_frame(0.0);
    assert!(
        Animation::from_toml(&text, "s.toml", None)
            .expect("reads")
            .is_none()
    );
}

#[test]
fn errors_name_the_field_and_the_frame() {
    let err = |text: &str| match Animation::from_toml(text, "anim.toml", None) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("accepted:\n{text}"),
    };
    let e = err(&animated("[3, 1]", "25"));
    assert!(
        e.contains("animation.frames") && e.contains("[3, 1]"),
        "{e}"
    );
    let e = err(&animated("[0, 3]", "0"));
    assert!(e.contains("animation.rate"), "{e}");
    let e = err(&animated("[0, 3]", "25").replace("[animation]", "[animation]\nspeed = 2"));
    assert!(e.contains("speed"), "{e}");
    // A formula of t without a value at the first frame.
    let e = err(&animated("[1, 3]", "25").replace("\"2 + 0.5*t\"", "\"1 / (t - 1)\""));
    assert!(
        e.contains("lights[0].position[0]") && e.contains("t = 1"),
        "{e}"
    );
    // Or at a later frame: reported when that frame is built.
    let a = Animation::from_toml(
        &animated("[0, 3]", "25").replace("\"2 + 0.5*t\"", "\"sqrt(1 - t)\""),
        "anim.toml",
        None,
    )
    .expect("reads")
    .expect("animated");
    assert!(a.scene(1).is_ok());
    let e = a.scene(2).map(|_| ()).unwrap_err().to_string();
    assert!(
        e.contains("lights[0].position[0]") && e.contains("t = 2"),
        "{e}"
    );
}

#[test]
fn the_animated_png_holds_every_frame_at_the_rate() {
    use beam_trace::Image;
    let frames: Vec<Image> = (0..3)
        .map(|k| Image::new(4, 3, [0.2 * k as f32, 0.5, 1.0]))
        .collect();
    let dir = std::env::temp_dir().join(format!("apng-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let path = dir.join("anim.apng");
    beam_trace::image::write_apng(&frames, 12.5, &path).expect("writes");
    // A whole rate is exact (1/12 s), another to the thousandth (1/12.5 s = 80 ms).
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(&path).expect("opens"),
    ));
    let mut reader = decoder.read_info().expect("a PNG");
    let control = reader.info().animation_control.expect("animated");
    assert_eq!((control.num_frames, control.num_plays), (3, 0));
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    for (k, frame) in frames.iter().enumerate() {
        reader.next_frame(&mut buf).expect("a frame");
        let fc = reader.info().frame_control.expect("frame control");
        assert_eq!((fc.delay_num, fc.delay_den), (80, 1000), "frame {k}");
        assert_eq!(&buf[..3], &frame.to_rgb8()[..3], "frame {k}");
    }
    // A whole rate is exact.
    beam_trace::image::write_apng(&frames, 12.0, &path).expect("writes");
    let reader = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(&path).expect("opens"),
    ))
    .read_info()
    .expect("a PNG");
    let fc = reader.info().frame_control.expect("frame control");
    assert_eq!((fc.delay_num, fc.delay_den), (1, 12));
    // Frames of different sizes, no frame or no rate are refused, naming the file.
    let mixed = [Image::new(4, 3, [0.0; 3]), Image::new(3, 4, [0.0; 3])];
    let e = beam_trace::image::write_apng(&mixed, 12.0, &path).unwrap_err();
    assert!(e.to_string().contains("anim.apng"), "{e}");
    assert!(beam_trace::image::write_apng(&[], 12.0, &path).is_err());
    assert!(beam_trace::image::write_apng(&frames, 0.0, &path).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn formulas_undefined_at_some_times_and_parameters_named_like_keys_are_read() {
    // `1/(2t − 1)` has no value at t = 1/2, between frames; a parameter called `op` (a key
    // of CSG tables elsewhere) is still a parameter.
    let text = r#"
[animation]
frames = [1, 2]
[camera]
eye = [0.0, 0.0, 4.0]
look_at = [0.0, 0.0, 0.0]
width = 8
height = 6
[[surfaces]]
formula = "x^2 + y^2 + z^2 - op"
params = { op = "0.25 + 1/(2*t - 1)" }
bounds = [[-2, -2, -2], [2, 2, 2]]
"#;
    let a = Animation::from_toml(text, "anim.toml", None)
        .expect("reads")
        .expect("animated");
    assert_eq!(a.time_values(), 1);
    for t in a.frames() {
        a.scene(t).unwrap_or_else(|e| panic!("frame {t}: {e}"));
    }
    // A typo leaves a string where a number is needed: the error names the field.
    let e = Scene::from_toml(
        &text.replace("0.25 + 1/(2*t - 1)", "0.25 + sinn(t)"),
        "anim.toml",
        None,
    )
    .map(|_| ())
    .unwrap_err()
    .to_string();
    assert!(e.contains("params.op"), "{e}");
    // Frame ranges beyond ±1e9 (or the integer range) are refused, not overflowed.
    for frames in ["[-9223372036854775808, 0]", "[0, 2000000000]"] {
        let bad = text.replace("[1, 2]", frames);
        let e = Animation::from_toml(&bad, "anim.toml", None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("animation.frames"), "{e}");
    }
}
