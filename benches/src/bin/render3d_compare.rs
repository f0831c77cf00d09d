//! Times our renderer (`beam_trace::render`, primary visibility only) against fidget's CPU
//! voxel renderer with its VM and its JIT, on the same `.vm` models, image sizes and thread
//! count, and compares their silhouettes (which pixels each says the model covers).
//!
//! ```text
//! cargo run --release -p benches --bin render3d_compare
//! cargo run --release -p benches --bin render3d_compare -- --sizes 512 --runs 1 data/models/csg3d-660.vm
//! cargo run --release -p benches --bin render3d_compare -- --threads 4 --precision f32 other.vm
//! ```
//!
//! Without file arguments it renders the committed 3D models (`data/models/csg3d-*.vm`).
//! Options: `--sizes 512,1024` (square images), `--threads 2` (a rayon pool of that many
//! threads for each renderer), `--runs 3` (the time reported is the best of that many
//! renders; the median is printed beside it), `--distance 100000` (our eye's distance, see
//! below), `--precision f64|f32` (our interval evaluations; fidget's are `f32`), `--primary
//! screen-rays|octree|screen-boxes` (our primary visibility: the screen box structure, the
//! default, or the frustum octree of `beam_trace::frustum`, with one ray per undecided pixel
//! either way; or the renderer's default mode, whose undecided pixels are resolved by their
//! beams: a pixel then counts as covered where the surface has more than half of its
//! weight, instead of where its centre's ray meets it), `--isa baseline|best` (the
//! instruction set of our evaluators' loops, see `interval_core::isa`: the best this CPU
//! has, the default, or the baseline of its architecture), `--warm` (let each of our renders
//! find the tapes compiled by the renders before it: by default the codes kept for equal
//! tapes are forgotten before each of our timed runs, `implicit_expr::jit::forget_shared`,
//! so that every run compiles its tapes as the first render of a process does, as fidget
//! compiles its pruned tapes in every run), `--stats`
//! (print our render's statistics: the time and counters of each pass), `--images DIR`
//! (write `DIR/MODEL-SIZE.png`, the silhouettes compared: white where both renderers hit,
//! red where only ours does, blue where only fidget's JIT does, and our screen box
//! classification `DIR/MODEL-SIZE-boxes.png`).
//!
//! # The views
//!
//! fidget renders the cube `[-1, 1]³` orthographically, looking down `-z`: image column
//! `i` is `x`, image row `j` is `y` from `+1` at the top to `-1` at the bottom, and each
//! pixel is one column of `size` voxels in `z`, the first (nearest) voxel whose centre is
//! inside (`f < 0`) giving the depth. Its sample grid (voxel corners) is shifted by half a
//! voxel onto the voxel centres, so that pixel `(i, j)` samples `x = -1 + (2i + 1) / size`,
//! `y = 1 - (2j + 1) / size`.
//!
//! Ours is a pinhole camera at `(0, 0, D)` (`D = --distance`) looking at the origin with
//! `+y` up and the vertical field of view `2·atan(1 / D)`: the plane `z = 0` fills the
//! image exactly as fidget's square does, and each pixel's one ray goes through its centre,
//! so on that plane both sample the same `(x, y)`. The model is a `vm` surface with bounds
//! `[-1, 1]³`, clipped to them (`clip = true`: where the solid reaches a face of the cube,
//! both renderers see the face), a white material on a black background and no light, so
//! only primary
//! visibility runs (screen boxes, then one ray per pixel centre in undecided boxes:
//! `primary = "screen-rays"`, `rays_per_undecided = 1`; the default primary mode would
//! split undecided pixels' beams and weigh their parts, where fidget takes one sample). At depth `z` our ray is at `(x, y)·(D - z) / D`: a point of the
//! model appears scaled by `D / (D - z)`, at most `1 / (D - 1)` off the orthographic view,
//! that is at most `size / (2 (D - 1))` pixels at the border of the image: 0.003 px at 512
//! and 0.005 px at 1024 for the default `D = 100000` (0.26 and 0.51 px for `D = 1000`, where
//! 0.3 % of the pixels of `csg3d-660` at 512 differ, all on the models' edges; none differ
//! for the default). Silhouettes may also differ where fidget's voxels (`2 / size` apart in
//! depth) step over a part thinner than a voxel, and where a ray grazes the surface.
//!
//! # The octree bound
//!
//! A third column times [`benches::octree::first_hits`] on the same model and pool: fidget's
//! own algorithm (3D tiles of 64, halved front to back, each tile's tape pruned for the
//! tiles inside it) with our outward-rounded intervals, which proves for each pixel's column
//! in which voxel the surface may begin and that none is in front of it, but finds no root.
//! It shows what the subdivision costs with our evaluator, apart from the renderer's beams
//! and root proofs. Its silhouette must hold fidget's (a voxel whose centre fidget finds
//! inside keeps every tile around it from being skipped); the table counts the pixels where
//! fidget's does not lie inside it (0 unless fidget's `f32` rounding puts a centre inside
//! that is not) and the pixels only it covers (its conservative rim).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use beam_trace::{Image, NoProgress, RenderOutput, Scene};
use benches::models::MODELS;
use benches::octree::{FirstHits, first_hits};
use benches::vmgen::op_count;
use fidget::eval::Function;
use fidget::jit::JitFunction;
use fidget::raster::voxel::{EvalConfig, RenderConfig, render};
use fidget::render::{CancelToken, RenderHints, ThreadPool, VoxelSize};
use fidget::shape::Shape;
use fidget::vm::VmFunction;
use interval_core::isa::{self, Isa};

const USAGE: &str = "usage: render3d_compare [--sizes 512,1024] [--threads 2] [--runs 3] \
[--distance 100000] [--precision f64|f32] [--primary screen-rays|octree|screen-boxes] [--isa baseline|best] \
[--warm] [--stats] [--images DIR] [MODEL.vm ...]";

struct Options {
    sizes: Vec<u32>,
    threads: usize,
    runs: usize,
    distance: f64,
    precision: String,
    primary: String,
    isa: Isa,
    warm: bool,
    stats: bool,
    images: Option<PathBuf>,
    files: Vec<PathBuf>,
}

/// The options, or `None` when only the usage was asked for (and printed).
fn parse_args() -> Result<Option<Options>, String> {
    let mut o = Options {
        sizes: vec![512, 1024],
        threads: 2,
        runs: 3,
        distance: 100_000.0,
        precision: "f64".into(),
        primary: "screen-rays".into(),
        isa: isa::detected(),
        warm: false,
        stats: false,
        images: None,
        files: Vec::new(),
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = |name: &str| args.next().ok_or(format!("{name} needs a value\n{USAGE}"));
        match a.as_str() {
            "--sizes" => {
                let v = value("--sizes")?;
                o.sizes = v
                    .split(',')
                    .map(|s| parse_in(s.trim(), "--sizes", 1, 16384))
                    .collect::<Result<_, _>>()?;
            }
            "--threads" => o.threads = parse_in(&value("--threads")?, "--threads", 1, 1024)?,
            "--runs" => o.runs = parse_in(&value("--runs")?, "--runs", 1, 1000)?,
            "--distance" => {
                let v = value("--distance")?;
                o.distance = v
                    .parse()
                    .ok()
                    .filter(|d: &f64| d.is_finite() && *d >= 10.0 && *d <= 1e6)
                    .ok_or(format!("--distance {v}: a number from 10 to 1e6"))?;
            }
            "--precision" => {
                let v = value("--precision")?;
                if v != "f64" && v != "f32" {
                    return Err(format!("--precision {v}: f64 or f32"));
                }
                o.precision = v;
            }
            "--primary" => {
                let v = value("--primary")?;
                if !["screen-rays", "octree", "screen-boxes"].contains(&v.as_str()) {
                    return Err(format!(
                        "--primary {v}: screen-rays, octree or screen-boxes"
                    ));
                }
                o.primary = v;
            }
            "--isa" => {
                o.isa = match value("--isa")?.as_str() {
                    "baseline" => Isa::Baseline,
                    "best" => isa::detected(),
                    v => return Err(format!("--isa {v}: baseline or best")),
                }
            }
            "--warm" => o.warm = true,
            "--stats" => o.stats = true,
            "--images" => o.images = Some(PathBuf::from(value("--images")?)),
            "-h" | "--help" => {
                println!("{USAGE}");
                return Ok(None);
            }
            s if s.starts_with("--") => return Err(format!("unknown option '{s}'\n{USAGE}")),
            path => o.files.push(PathBuf::from(path)),
        }
    }
    if o.files.is_empty() {
        o.files = MODELS
            .iter()
            .filter(|m| m.three_d)
            .map(|m| m.path())
            .collect();
    }
    Ok(Some(o))
}

/// An integer in `lo..=hi`.
fn parse_in<T: std::str::FromStr + PartialOrd + std::fmt::Display>(
    s: &str,
    name: &str,
    lo: T,
    hi: T,
) -> Result<T, String> {
    s.parse()
        .ok()
        .filter(|v| *v >= lo && *v <= hi)
        .ok_or(format!("{name} {s}: an integer from {lo} to {hi}"))
}

/// The best and the median of `runs` timed calls of `f`, and the result of the best.
fn time<R>(
    runs: usize,
    mut f: impl FnMut() -> Result<(R, Duration), String>,
) -> Result<(R, Duration, Duration), String> {
    let mut best: Option<(R, Duration)> = None;
    let mut times = Vec::with_capacity(runs);
    for _ in 0..runs {
        let (r, t) = f()?;
        times.push(t);
        if best.as_ref().is_none_or(|(_, b)| t < *b) {
            best = Some((r, t));
        }
    }
    times.sort();
    let (r, b) = best.ok_or("no run")?;
    Ok((r, b, times[times.len() / 2]))
}

/// fidget's voxel render of `shape` at `size`³ on `pool`: for each pixel, row by row from
/// the top, whether a voxel of its column is inside.
fn fidget_render<F: Function + RenderHints>(
    shape: &Shape<F>,
    size: u32,
    pool: &ThreadPool,
) -> Result<(Vec<bool>, Duration), String> {
    // Shift the sample grid (voxel corners) by half a voxel onto the voxel centres.
    let half = 1.0 / size as f32;
    let cfg = RenderConfig {
        image_size: VoxelSize::new(size, size, size),
        world_to_model: nalgebra::Matrix4::new_translation(&nalgebra::Vector3::new(
            half, half, half,
        )),
    };
    let eval = EvalConfig {
        tile_sizes: None,
        threads: Some(pool),
        cancel: CancelToken::new(),
    };
    let t = std::time::Instant::now();
    let bound = shape
        .clone()
        .try_into()
        .map_err(|_| "the model has variables besides x, y, z".to_string())?;
    let image = render(bound, &cfg, &eval).ok_or("fidget's render was cancelled")?;
    let elapsed = t.elapsed();
    Ok((image.iter().map(|p| p.depth > 0).collect(), elapsed))
}

/// `s` as a TOML basic string.
fn toml_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Our scene of the model at `path`: see the module documentation.
fn scene(path: &Path, size: u32, o: &Options) -> Result<Scene, String> {
    let d = o.distance;
    let fov = 2.0 * (1.0 / d).atan().to_degrees();
    let text = format!(
        "background = [0.0, 0.0, 0.0]\n\
         [camera]\n\
         eye = [0.0, 0.0, {d:?}]\n\
         look_at = [0.0, 0.0, 0.0]\n\
         up = [0.0, 1.0, 0.0]\n\
         fov = {fov:?}\n\
         width = {size}\n\
         height = {size}\n\
         [[surfaces]]\n\
         name = \"model\"\n\
         vm = {}\n\
         bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]\n\
         clip = true\n\
         material = {{ color = [1.0, 1.0, 1.0] }}\n\
         [render]\n\
         primary = \"{}\"\n\
         aa = \"none\"\n\
         rays_per_undecided = 1\n\
         precision = \"{}\"\n",
        toml_string(&path.to_string_lossy()),
        o.primary,
        o.precision
    );
    Scene::from_toml(&text, "render3d_compare", None).map_err(|e| e.to_string())
}

/// Our render of `scene` on `pool`: the covered pixels, row by row from the top.
fn ours_render(
    scene: &Scene,
    pool: &rayon::ThreadPool,
) -> Result<((Vec<bool>, RenderOutput), Duration), String> {
    let t = std::time::Instant::now();
    let out = pool
        .install(|| beam_trace::render(scene, &NoProgress))
        .map_err(|e| e.to_string())?;
    let elapsed = t.elapsed();
    let hits = out.image.pixels.iter().map(|p| p[0] > 0.5).collect();
    Ok(((hits, out), elapsed))
}

/// The octree bound of `tape` at `size` on `pool` ([`first_hits`]).
fn octree_bound(
    tape: &implicit_expr::Tape,
    size: u32,
    pool: &rayon::ThreadPool,
) -> Result<(FirstHits, Duration), String> {
    let t = std::time::Instant::now();
    let bound = pool.install(|| first_hits(tape, size as usize))?;
    Ok((bound, t.elapsed()))
}

/// The silhouettes compared: white where both hit, red where only `ours` does, blue where
/// only `theirs` does, black where neither does.
fn comparison_image(size: u32, ours: &[bool], theirs: &[bool]) -> Image {
    let pixels = ours
        .iter()
        .zip(theirs)
        .map(|(&a, &b)| match (a, b) {
            (true, true) => [1.0; 3],
            (true, false) => [1.0, 0.1, 0.1],
            (false, true) => [0.2, 0.4, 1.0],
            (false, false) => [0.0; 3],
        })
        .collect();
    Image {
        width: size,
        height: size,
        pixels,
    }
}

/// Pixels where `a` and `b` differ.
fn differing(a: &[bool], b: &[bool]) -> usize {
    a.iter().zip(b).filter(|(x, y)| x != y).count()
}

/// The time of each pass that ran, `name s` separated by commas.
fn pass_times(out: &RenderOutput) -> String {
    out.stats
        .passes
        .iter()
        .filter(|p| p.ran)
        .map(|p| format!("{} {:.3}", p.name, p.time.as_secs_f64()))
        .collect::<Vec<_>>()
        .join(", ")
}

fn main() -> ExitCode {
    benches::exit(run())
}

fn run() -> Result<(), String> {
    let Some(o) = parse_args()? else {
        return Ok(());
    };
    let isa = isa::set_limit(o.isa);
    let pool = |what: &str| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(o.threads)
            .build()
            .map_err(|e| format!("cannot start the {what} thread pool: {e}"))
    };
    let ours_pool = pool("renderer's")?;
    let fidget_pool = ThreadPool::Custom(pool("fidget")?);
    // Every model read (and the scenes checked) before the first render.
    let mut models = Vec::new();
    for path in &o.files {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let abs = path
            .canonicalize()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let name = path.file_stem().map_or_else(
            || path.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        );
        let (ctx, root) = fidget::Context::from_text(text.as_bytes())
            .map_err(|e| format!("{}: fidget: {e}", path.display()))?;
        let vm = Shape::<VmFunction>::new(&ctx, root).map_err(|e| format!("{name}: {e}"))?;
        let jit = Shape::<JitFunction>::new(&ctx, root).map_err(|e| format!("{name}: {e}"))?;
        scene(&abs, 1, &o).map_err(|e| format!("{name}: {e}"))?;
        let mut ours_ctx = implicit_expr::Context::new();
        let ours_root = implicit_expr::vm::import_vm(&mut ours_ctx, &text)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let tape = implicit_expr::Tape::new(&ours_ctx, &[ours_root])
            .map_err(|e| format!("{}: {e}", path.display()))?;
        models.push((name, abs, op_count(&text), vm, jit, tape));
    }
    let d = o.distance;
    println!(
        "fidget: orthographic voxel render of [-1, 1]³ along -z, one column of `size` voxels per pixel, \
         samples at voxel centres; VM and JIT, default 3D tiles.\n\
         ours: beam_trace::render, eye (0, 0, {d}) looking at the origin, up +y, fov 2·atan(1/{d}) = {:.5}°, \
         one ray per pixel centre, no light (primary visibility only), {} intervals, evaluator loops for {}; \
         at depth z the view is scaled by {d}/({d} - z), at most {:.4} px off at the border of a {}² image.\n\
         {} threads for each renderer; times: best of {} runs (median in brackets); {}.\n",
        2.0 * (1.0 / d).atan().to_degrees(),
        o.precision,
        isa.name(),
        *o.sizes.iter().max().unwrap_or(&0) as f64 / (2.0 * (d - 1.0)),
        o.sizes.iter().max().unwrap_or(&0),
        o.threads,
        o.runs,
        if o.warm {
            "our runs find the tapes compiled by the runs before them"
        } else {
            "each of our runs compiles its tapes afresh"
        }
    );
    println!(
        "| model | ops | size | fidget VM s | fidget JIT s | ours s | ours / JIT | silhouette: ours vs JIT | VM vs JIT px | octree bound s | octree / JIT | JIT outside the bound px | bound only px | ours per pass (s) |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    for (name, abs, ops, vm, jit, tape) in &models {
        for &size in &o.sizes {
            let scene = scene(abs, size, &o).map_err(|e| format!("{name}: {e}"))?;
            let (vm_hits, vm_best, vm_med) =
                time(o.runs, || fidget_render(vm, size, &fidget_pool))?;
            let (jit_hits, jit_best, jit_med) =
                time(o.runs, || fidget_render(jit, size, &fidget_pool))?;
            // Each of our runs compiles its tapes afresh unless `--warm` (outside the time).
            let cold = || {
                if !o.warm {
                    implicit_expr::jit::forget_shared();
                }
            };
            let ((our_hits, out), our_best, our_med) = time(o.runs, || {
                cold();
                ours_render(&scene, &ours_pool)
            })?;
            let octree = time(o.runs, || {
                cold();
                octree_bound(tape, size, &ours_pool)
            });
            let octree_cells = match &octree {
                Ok((bound, best, med)) => {
                    let covered = bound.covered();
                    let outside = jit_hits.iter().zip(&covered).filter(|&(&j, &b)| j && !b);
                    let only = jit_hits.iter().zip(&covered).filter(|&(&j, &b)| !j && b);
                    format!(
                        "{:.3} ({:.3}) | {:.2} | {} | {}",
                        best.as_secs_f64(),
                        med.as_secs_f64(),
                        best.as_secs_f64() / jit_best.as_secs_f64(),
                        outside.count(),
                        only.count()
                    )
                }
                Err(e) => format!("n/a ({e}) | | | "),
            };
            let n = (size as usize).pow(2);
            let diff = differing(&our_hits, &jit_hits);
            println!(
                "| {name} | {ops} | {size} | {:.3} ({:.3}) | {:.3} ({:.3}) | {:.3} ({:.3}) | {:.2} | {:.3} % ({diff} px) | {} | {octree_cells} | {} |",
                vm_best.as_secs_f64(),
                vm_med.as_secs_f64(),
                jit_best.as_secs_f64(),
                jit_med.as_secs_f64(),
                our_best.as_secs_f64(),
                our_med.as_secs_f64(),
                our_best.as_secs_f64() / jit_best.as_secs_f64(),
                100.0 * diff as f64 / n as f64,
                differing(&vm_hits, &jit_hits),
                pass_times(&out),
            );
            if o.stats {
                if let Ok((bound, _, _)) = &octree {
                    println!(
                        "\noctree bound: {} interval evaluations, {} tapes pruned",
                        bound.evals, bound.prunes
                    );
                }
                println!("\n```text\n{}\n```\n", out.stats);
            }
            if let Some(dir) = &o.images {
                let write = |file: String, image: &Image| {
                    let p = dir.join(file);
                    image
                        .write_png(&p)
                        .map_err(|e| format!("cannot write {}: {e}", p.display()))
                };
                write(
                    format!("{name}-{size}.png"),
                    &comparison_image(size, &our_hits, &jit_hits),
                )?;
                write(format!("{name}-{size}-boxes.png"), &out.classification())?;
            }
        }
    }
    Ok(())
}
