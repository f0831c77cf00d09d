//! What anti-aliasing accuracy costs in time: renders a scene (default: the built-in
//! default scene at 160 × 120) with every primary mode and anti-aliasing setting, and
//! measures each image against a reference of 16 × 16 stratified rays per pixel over the
//! edge pixels: those where the reference differs from one central ray per pixel by more
//! than one 8-bit level in some channel (silhouettes, creases, shadow boundaries).
//!
//! ```text
//! aa-cost [SCENE.toml] [--width W --height H] [--reference N] [--modes M,M,...] [--out FILE.md]
//!         [--images DIR] [--runs N]
//! ```
//!
//! `--modes` measures only the anti-aliasing modes listed (as the render command's `--aa`
//! takes them: `none`, `ss:N`, `iaa:D:T:M`, ...; `screen-rays` for the thesis's 9 point
//! rays), after the render without anti-aliasing (`none`, screen boxes), which every ratio
//! refers to.
//!
//! Each time is the median of `--runs` renders (default 3), taken in rounds over all modes.
//!
//! `--images DIR` writes the reference, each mode's image and a map of its error over the
//! edge pixels into `DIR`, to see where each mode's error lies.
//!
//! Prints (and with `--out` writes) a markdown table: per mode the render time, the time
//! ratio to `none`, the RMSE and the largest error over the edge pixels (the
//! largest channel difference per pixel), and whether the mode is on the Pareto front of
//! time against RMSE.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use beam_trace::scene::{AaMode, PrimaryMode};
use beam_trace::{Image, NoProgress, Scene, render};
use clap::Parser;
use examples::report::median;

/// Anti-aliasing modes: time against edge error.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// A scene file (default: the built-in default scene).
    scene: Option<PathBuf>,
    /// Image width.
    #[arg(long, default_value_t = 160)]
    width: u32,
    /// Image height.
    #[arg(long, default_value_t = 120)]
    height: u32,
    /// Rays per pixel side of the reference (N × N stratified rays).
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(2..=16))]
    reference: u32,
    /// Only these modes after `none` (comma-separated, as `--aa` takes them, or
    /// `screen-rays`); all of the built-in list when absent.
    #[arg(long, value_delimiter = ',')]
    modes: Vec<String>,
    /// Where to write the report too.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Renders per mode: each time reported is the median of this many, taken in rounds
    /// over all modes so that a slow spell of the machine slows every mode alike.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=99))]
    runs: u32,
    /// A directory to write images into: the reference, each mode's image and its error
    /// over the edge pixels (`<mode>-error.png`, 8 times the largest channel difference,
    /// white at 1/8 or more; the other pixels dark blue).
    #[arg(long)]
    images: Option<PathBuf>,
}

/// `none`, then the modes `names` (see [`Args::modes`]).
fn chosen(names: &[String]) -> Result<Vec<(String, PrimaryMode, AaMode)>, String> {
    let (name, primary, aa) = modes()[0];
    let mut out = vec![(name.to_string(), primary, aa)];
    for name in names {
        let (primary, aa) = if name == "screen-rays" {
            (PrimaryMode::ScreenRays, AaMode::None)
        } else {
            let aa = name
                .parse::<AaMode>()
                .map_err(|e| format!("--modes {name}: {e}"))?;
            (PrimaryMode::ScreenBoxes, aa)
        };
        out.push((name.clone(), primary, aa));
    }
    Ok(out)
}

/// The modes measured: a name, the primary mode and the anti-aliasing mode; the first,
/// `none`, is the one every ratio refers to.
fn modes() -> Vec<(&'static str, PrimaryMode, AaMode)> {
    let iaa = |d, t, m| AaMode::Iaa {
        max_depth: d,
        threshold: t,
        limit_rays: m,
    };
    vec![
        (
            "none (screen-boxes)",
            PrimaryMode::ScreenBoxes,
            AaMode::None,
        ),
        (
            "screen-rays (9 rays)",
            PrimaryMode::ScreenRays,
            AaMode::None,
        ),
        ("ss:1", PrimaryMode::ScreenBoxes, AaMode::Supersample(1)),
        ("ss:2", PrimaryMode::ScreenBoxes, AaMode::Supersample(2)),
        ("ss:3", PrimaryMode::ScreenBoxes, AaMode::Supersample(3)),
        ("ss:4", PrimaryMode::ScreenBoxes, AaMode::Supersample(4)),
        ("iaa:1:0.1:1", PrimaryMode::ScreenBoxes, iaa(1, 0.1, 1)),
        ("iaa:2:0.1:1", PrimaryMode::ScreenBoxes, iaa(2, 0.1, 1)),
        ("iaa:4:0.1:1", PrimaryMode::ScreenBoxes, iaa(4, 0.1, 1)),
        (
            "iaa:1:0.1:2 (default)",
            PrimaryMode::ScreenBoxes,
            AaMode::DEFAULT,
        ),
        ("iaa:2:0.1:2", PrimaryMode::ScreenBoxes, iaa(2, 0.1, 2)),
        ("iaa:3:0.1:2", PrimaryMode::ScreenBoxes, iaa(3, 0.1, 2)),
        ("iaa:4:0.1:2", PrimaryMode::ScreenBoxes, iaa(4, 0.1, 2)),
        ("iaa:1:0.1:4", PrimaryMode::ScreenBoxes, iaa(1, 0.1, 4)),
        ("iaa:2:0.1:4", PrimaryMode::ScreenBoxes, iaa(2, 0.1, 4)),
        ("iaa:3:0.1:4", PrimaryMode::ScreenBoxes, iaa(3, 0.1, 4)),
        ("iaa:2:0.5:2", PrimaryMode::ScreenBoxes, iaa(2, 0.5, 2)),
    ]
}

fn load(path: Option<&Path>, w: u32, h: u32) -> Result<Scene, String> {
    let mut s = match path {
        Some(p) => Scene::load(p).map_err(|e| e.to_string())?,
        None => Scene::default_scene(),
    };
    s.camera = s.camera.resized(w, h).map_err(|e| e.to_string())?;
    Ok(s)
}

/// Renders `scene` with `primary` and `aa`: the image and the wall time in seconds.
fn timed(scene: &Scene, primary: PrimaryMode, aa: AaMode) -> Result<(Image, f64), String> {
    let mut s = scene.clone();
    s.settings.primary = primary;
    s.settings.aa = Some(aa);
    let t0 = Instant::now();
    let out = render(&s, &NoProgress).map_err(|e| e.to_string())?;
    Ok((out.image, t0.elapsed().as_secs_f64()))
}

/// `name` made safe as a file name: characters other than letters, digits and `-` become `_`.
fn file_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The error map of `errors` over the pixels `edges` of an image of the reference's size:
/// grey levels of 8 times the error (white from 1/8 on), the other pixels dark blue.
fn error_image(reference: &Image, errors: &[f64], edges: &[usize]) -> Image {
    let mut img = Image::new(reference.width, reference.height, [0.0, 0.0, 0.15]);
    for &i in edges {
        let v = (8.0 * errors[i]).min(1.0) as f32;
        img.pixels[i] = [v; 3];
    }
    img
}

/// Writes `img` as `dir/name.png`.
fn save(img: &Image, dir: &Path, name: &str) -> Result<(), String> {
    let path = dir.join(format!("{name}.png"));
    img.write_png(&path)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// The largest channel difference of each pixel.
fn errors(a: &Image, b: &Image) -> Vec<f64> {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| {
            (0..3)
                .map(|k| f64::from((p[k] - q[k]).abs()))
                .fold(0.0, f64::max)
        })
        .collect()
}

fn run(args: &Args) -> Result<(), String> {
    let scene = load(args.scene.as_deref(), args.width, args.height)?;
    let modes = if args.modes.is_empty() {
        modes()
            .into_iter()
            .map(|(n, p, a)| (n.to_string(), p, a))
            .collect()
    } else {
        chosen(&args.modes)?
    };
    eprintln!(
        "reference: {n} × {n} rays per pixel at {} × {}",
        args.width,
        args.height,
        n = args.reference
    );
    let (reference, t_ref) = timed(
        &scene,
        PrimaryMode::ScreenBoxes,
        AaMode::Supersample(args.reference),
    )?;
    let (central, _) = timed(&scene, PrimaryMode::ScreenBoxes, AaMode::Supersample(1))?;
    let edges: Vec<usize> = errors(&reference, &central)
        .iter()
        .enumerate()
        .filter(|(_, e)| **e > 1.0 / 255.0)
        .map(|(i, _)| i)
        .collect();
    if edges.is_empty() {
        return Err("the scene has no edge pixels: nothing to anti-alias".into());
    }
    if let Some(dir) = &args.images {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        save(&reference, dir, "reference")?;
    }
    // One render before the timed ones, so that the first mode timed is not also the
    // first to fault in the renderer's memory.
    timed(&scene, modes[0].1, modes[0].2)?;
    let mut rows = Vec::new();
    let mut times: Vec<Vec<f64>> = Vec::new();
    for (name, primary, aa) in &modes {
        let (img, t) = timed(&scene, *primary, *aa)?;
        times.push(vec![t]);
        let e = errors(&img, &reference);
        let on_edges: Vec<f64> = edges.iter().map(|&i| e[i]).collect();
        let rmse = (on_edges.iter().map(|x| x * x).sum::<f64>() / on_edges.len() as f64).sqrt();
        let max = on_edges.iter().copied().fold(0.0, f64::max);
        if let Some(dir) = &args.images {
            let stem = file_name(name);
            save(&img, dir, &stem)?;
            save(
                &error_image(&reference, &e, &edges),
                dir,
                &format!("{stem}-error"),
            )?;
        }
        eprintln!("{name}: {t:.3} s, edge RMSE {rmse:.4}, max {max:.3}");
        rows.push((name.clone(), t, rmse, max));
    }
    for round in 1..args.runs {
        eprintln!("timing round {} of {}", round + 1, args.runs);
        for ((_, primary, aa), t) in modes.iter().zip(&mut times) {
            t.push(timed(&scene, *primary, *aa)?.1);
        }
    }
    for (row, t) in rows.iter_mut().zip(&mut times) {
        row.1 = median(t, f64::total_cmp).unwrap_or(row.1);
    }
    let base = rows[0].1;
    let mut md = format!(
        "Scene `{}` at {} × {}; reference {n} × {n} stratified rays per pixel ({t_ref:.1} s); {} edge pixels (reference and one central ray differ by more than 1/255); times are medians of {} runs.\n\n\
         | mode | time (s) | time / none | edge RMSE | edge max error | Pareto |\n|---|---:|---:|---:|---:|:---:|\n",
        scene.name,
        args.width,
        args.height,
        edges.len(),
        args.runs,
        n = args.reference
    );
    for (name, t, rmse, max) in &rows {
        let (t, rmse, max) = (*t, *rmse, *max);
        let dominated = rows
            .iter()
            .any(|&(_, t2, r2, _)| t2 <= t && r2 <= rmse && (t2 < t || r2 < rmse));
        md += &format!(
            "| {name} | {t:.3} | {:.2} | {rmse:.4} | {max:.3} | {} |\n",
            t / base,
            if dominated { "" } else { "yes" }
        );
    }
    examples::report::print_and_save(&md, args.out.as_deref())
}

fn main() -> ExitCode {
    examples::report::exit(run(&Args::parse()))
}
