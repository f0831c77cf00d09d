//! The `render` example on an animated scene file, as a user runs it: one PNG per frame and
//! an animated PNG, and an error naming the field and frame where a formula of `t` fails,
//! before any frame is rendered.

use std::path::PathBuf;
use std::process::{Command, Output};

fn render(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_render"))
        .args(args)
        .output()
        .expect("the example runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("render-anim-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

const SCENE: &str = r#"
[animation]
frames = [3, 5]
rate = 10
[camera]
eye = [0.0, 0.0, 4.0]
look_at = [0.0, 0.0, 0.0]
width = 16
height = 12
[[surfaces]]
formula = "x^2 + y^2 + z^2 - 0.5"
bounds = [[-1, -1, -1], [1, 1, 1]]
transform = { translate = ["0.1*(t - 4)", 0, 0] }
[[lights]]
type = "point"
position = ["RADIUS", 2, 3]
"#;

#[test]
fn an_animation_writes_every_frame_and_an_animated_png() {
    let scene = scratch("anim.toml");
    std::fs::write(&scene, SCENE.replace("RADIUS", "2*t")).unwrap();
    let out = scratch("anim.png");
    let run = render(&[
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    for t in 3..=5 {
        let frame = scratch(&format!("anim-{t:04}.png"));
        assert!(frame.exists(), "{} missing: {stdout}", frame.display());
    }
    assert!(scratch("anim.apng").exists());
    assert!(stdout.contains("3 frame(s)"), "{stdout}");
}

#[test]
fn a_formula_of_t_without_a_value_is_an_error_naming_field_and_frame() {
    let scene = scratch("bad.toml");
    std::fs::write(&scene, SCENE.replace("RADIUS", "sqrt(4 - t)")).unwrap();
    let out = scratch("bad.png");
    let run = render(&[
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(run.status.code(), Some(1));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        err.contains("lights[0].position[0]") && err.contains("t = 5"),
        "{err}"
    );
    // Every frame is checked before the rendering starts: nothing was written.
    assert!(!scratch("bad-0003.png").exists());
    assert!(!scratch("bad.apng").exists());
}

#[test]
fn blocks_of_frames_write_the_frames_rendered_alone() {
    // Translated by 0.1(t − 4): frame 4 is not translated at all, which changes its graph,
    // so the block of three splits and forms a block of two.
    let scene = scratch("blocks.toml");
    std::fs::write(&scene, SCENE.replace("RADIUS", "2*t")).unwrap();
    let (alone, blocks) = (scratch("alone.png"), scratch("blocks.png"));
    for (out, extra) in [(&alone, None), (&blocks, Some("3"))] {
        let mut args = vec![
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ];
        if let Some(n) = extra {
            args.extend(["--block", n]);
        }
        let run = render(&args);
        let stdout = String::from_utf8_lossy(&run.stdout);
        assert!(
            run.status.success(),
            "{stdout}{}",
            String::from_utf8_lossy(&run.stderr)
        );
        if extra.is_some() {
            assert!(stdout.contains("block t = 3 ..= 5"), "{stdout}");
            assert!(stdout.contains("changes form"), "{stdout}");
        }
    }
    for t in 3..=5 {
        let a = std::fs::read(scratch(&format!("alone-{t:04}.png"))).unwrap();
        let b = std::fs::read(scratch(&format!("blocks-{t:04}.png"))).unwrap();
        assert_eq!(a, b, "frame {t} differs");
    }
}
