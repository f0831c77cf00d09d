//! The CPU output guard: the images, classification images, coverage, shadow maps and work
//! counters of the default scene, every scene file of `scenes/`, the main render modes and
//! unlit renders, compared bit for bit with the values recorded in
//! `tests/data/cpu_guard.txt`.
//!
//! A change that alters any of them must say why in its commit and record them again:
//!
//! ```sh
//! BEAM_TRACE_RECORD_GUARD=1 cargo test -p beam-trace --test cpu_guard
//! ```
//!
//! Times (and the cost map, which shows them) are not compared.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use beam_trace::{NoProgress, RenderOutput, Scene, render};

/// Side of the guarded renders (small, so that the guard runs in seconds).
const WIDTH: u32 = 64;
const HEIGHT: u32 = 48;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn guard_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cpu_guard.txt")
}

/// FNV-1a over 64 bits.
#[derive(Copy, Clone)]
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(mut self, b: &[u8]) -> Self {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
        self
    }
    fn f32s(self, v: impl IntoIterator<Item = f32>) -> Self {
        v.into_iter()
            .fold(self, |h, x| h.bytes(&x.to_bits().to_le_bytes()))
    }
}

fn pixels_hash(img: &beam_trace::Image) -> u64 {
    Fnv::new()
        .bytes(&img.width.to_le_bytes())
        .bytes(&img.height.to_le_bytes())
        .f32s(img.pixels.iter().flatten().copied())
        .0
}

/// One line: the case name and the hashes of what it produced.
fn digest(name: &str, out: &RenderOutput) -> String {
    let mut counters = String::new();
    for (pass, ran, cs) in out.stats.work() {
        let _ = write!(counters, "{pass}:{ran}");
        for (n, v) in cs {
            let _ = write!(counters, " {n}={v}");
        }
        counters.push(';');
    }
    let shadows = out.shadows.as_ref().map_or(0, |s| {
        let classes = format!("{:?}", s.classes);
        s.fractions
            .iter()
            .fold(Fnv::new().bytes(classes.as_bytes()), |h, f| {
                h.f32s(f.iter().copied())
            })
            .bytes(&pixels_hash(&s.image).to_le_bytes())
            .0
    });
    let coverage = Fnv::new()
        .f32s(out.coverage.iter().flat_map(|c| [c.proven, c.possible]))
        .0;
    format!(
        "{name} image={:016x} classification={:016x} coverage={coverage:016x} shadows={:016x} \
         counters={:016x}",
        pixels_hash(&out.image),
        pixels_hash(&out.classification()),
        shadows,
        Fnv::new().bytes(counters.as_bytes()).0,
    )
}

fn small(mut scene: Scene) -> Scene {
    scene.camera = scene.camera.resized(WIDTH, HEIGHT).expect("a valid size");
    scene
}

fn file_scene(name: &str) -> Scene {
    small(Scene::load(&root().join("scenes").join(name)).expect("the scene file loads"))
}

/// Every guarded case: a name and its scene.
fn cases() -> Vec<(String, Scene)> {
    let mut out = vec![("builtin-default".to_string(), small(Scene::default_scene()))];
    let mut files: Vec<String> = std::fs::read_dir(root().join("scenes"))
        .expect("scenes/ is readable")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    files.sort();
    for f in files {
        out.push((f.clone(), file_scene(&f)));
    }
    let mut variant = |name: &str, file: &str, edit: &dyn Fn(&mut Scene)| {
        let mut s = file_scene(file);
        edit(&mut s);
        out.push((name.to_string(), s));
    };
    variant("default+none", "default.toml", &|s| {
        s.settings.aa = Some(beam_trace::scene::AaMode::None);
    });
    variant("default+iaa", "default.toml", &|s| {
        s.settings.aa = Some("iaa".parse().unwrap());
    });
    variant("default+ss:2", "default.toml", &|s| {
        s.settings.aa = Some("ss:2".parse().unwrap());
    });
    variant("default+per-pixel", "default.toml", &|s| {
        s.settings.primary = beam_trace::scene::PrimaryMode::PerPixel;
    });
    variant("default+f32", "default.toml", &|s| {
        s.settings.precision = "f32".parse().unwrap();
    });
    variant("default+no-grid", "default.toml", &|s| {
        s.settings.grid_resolution = 0;
    });
    for finder in [
        "mitchell",
        "newton",
        "mrfro",
        "counter-bisection",
        "sphere-tracing",
    ] {
        variant(&format!("csg+{finder}"), "csg.toml", &|s| {
            s.settings.root_finder = finder.parse().unwrap();
        });
    }
    for method in [
        "stochastic:16",
        "stochastic:16:cache",
        "beam:4",
        "beam-all:4",
        "beam-quadtree:4",
        "minkowski:stochastic:16",
        "minkowski:beam:4",
    ] {
        variant(
            &format!("soft-shadows+{method}"),
            "soft-shadows.toml",
            &|s| {
                s.settings.shadow_method = method.parse().unwrap();
            },
        );
    }
    // Unlit: each pixel's colour and coverage resolved in the primary-rays pass, for one
    // colour (hits known from the boxes) and several (each hit's object searched).
    for (file, modes) in [
        ("default.toml", ["octree", "screen-rays", "per-pixel"]),
        ("gallery.toml", ["octree", "screen-rays", "per-pixel"]),
    ] {
        for mode in modes {
            variant(&format!("{file}+unlit+{mode}"), file, &|s| {
                s.lights.clear();
                s.settings.aa = Some(beam_trace::scene::AaMode::None);
                s.settings.primary = match mode {
                    "octree" => beam_trace::scene::PrimaryMode::Octree,
                    "screen-rays" => beam_trace::scene::PrimaryMode::ScreenRays,
                    _ => beam_trace::scene::PrimaryMode::PerPixel,
                };
            });
        }
    }
    variant("soft-shadows+iaa", "soft-shadows.toml", &|s| {
        s.settings.aa = Some("iaa".parse().unwrap());
    });
    out
}

#[test]
fn cpu_output_matches_the_recorded_guard() {
    let lines: Vec<String> = cases()
        .iter()
        .map(|(name, scene)| {
            let out = render(scene, &NoProgress).expect("the render succeeds");
            digest(name, &out)
        })
        .collect();
    let text = lines.join("\n") + "\n";
    if std::env::var_os("BEAM_TRACE_RECORD_GUARD").is_some() {
        std::fs::create_dir_all(guard_file().parent().unwrap()).unwrap();
        std::fs::write(guard_file(), &text).expect("the guard file is writable");
        return;
    }
    let recorded = std::fs::read_to_string(guard_file()).expect("tests/data/cpu_guard.txt");
    let differ: Vec<String> = recorded
        .lines()
        .zip(&lines)
        .filter(|(a, b)| a != b)
        .map(|(a, b)| format!("  recorded {a}\n  now      {b}"))
        .collect();
    assert_eq!(
        recorded.lines().count(),
        lines.len(),
        "the guard's cases changed: record again with a stated reason"
    );
    assert!(
        differ.is_empty(),
        "the CPU output changed:\n{}",
        differ.join("\n")
    );
}
