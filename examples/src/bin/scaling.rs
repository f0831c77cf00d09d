//! How the render time grows with the number of objects: scenes of `N` spheres (or catalog
//! surfaces) standing above a floor, lit by one point light, rendered by
//! `beam_trace::render`, with the time of each pass.
//!
//! ```text
//! scaling [--counts 1,10,100,1000,10000] [--width 320] [--height 240] [--threads 2]
//!         [--catalog] [--max-seconds S] [--seed S] [--load-only] [--stats]
//!         [--images DIR] [--write-scenes DIR]
//! ```
//!
//! The objects stand on a square of side 9 on the floor `y = 0`, one in each of `N` cells of
//! a `k × k` grid (`k = ⌈√N⌉`; the cells taken in a seeded order), with a radius of 0.3 to
//! 0.4 cell sides (at most 1.5) and a seeded jitter inside their cell, so that they never
//! overlap, a small gap above the floor. `--catalog` replaces the spheres by the catalog's
//! surfaces in turn, each scaled so that its box's half-diagonal is that radius. Each scene
//! is written as TOML text and read by `Scene::from_toml`, as a scene file would be; the
//! table gives the time to read it, the render's total and each pass that runs. With
//! `--max-seconds S` the counts after a render that took longer than `S` seconds are skipped
//! (and said so); `--load-only` reads the scenes without rendering them; `--stats` prints
//! each render's statistics (the counters of every pass); `--images DIR` writes each image
//! as `DIR/scaling-N.png`, `--write-scenes DIR` each scene as `DIR/scaling-N.toml`.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use beam_trace::{NoProgress, Pass, Plan, Scene};
use clap::Parser;
use implicit_expr::catalog;

/// Render time against the number of objects of a scene.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Numbers of objects, one scene each (rendered in increasing order).
    #[arg(long, value_delimiter = ',', default_values_t = [1, 10, 100, 1000, 10000])]
    counts: Vec<usize>,
    /// Image width.
    #[arg(long, default_value_t = 320)]
    width: u32,
    /// Image height.
    #[arg(long, default_value_t = 240)]
    height: u32,
    /// Worker threads of the render.
    #[arg(long, default_value_t = 2)]
    threads: usize,
    /// Catalog surfaces (all of them in turn) instead of spheres.
    #[arg(long)]
    catalog: bool,
    /// Skip the larger counts once a render takes longer than this many seconds.
    #[arg(long)]
    max_seconds: Option<f64>,
    /// Seed of the placement.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Read the scenes without rendering them (checks that the loader accepts them).
    #[arg(long)]
    load_only: bool,
    /// Print each render's statistics (time and counters of every pass).
    #[arg(long)]
    stats: bool,
    /// Write each image to this folder as scaling-N.png.
    #[arg(long)]
    images: Option<PathBuf>,
    /// Write each scene to this folder as scaling-N.toml (to render it with the `render`
    /// command, of this version or another).
    #[arg(long)]
    write_scenes: Option<PathBuf>,
}

/// Largest number of objects of one scene.
const MAX_COUNT: usize = 100_000;
/// Half the side of the square the objects stand on.
const HALF_SIDE: f64 = 4.5;

/// The fractional part of `i · a`: a Weyl sequence, evenly spread in `[0, 1)`.
fn weyl(i: u64, a: f64) -> f64 {
    (i as f64 * a).fract()
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// The TOML text of the scene of `n` objects.
fn scene_text(args: &Args, n: usize) -> String {
    let mut t = String::new();
    let _ = write!(
        t,
        "background = [0.08, 0.09, 0.12]\n\
         ambient = 0.15\n\n\
         [camera]\n\
         eye = [0.0, 6.5, 10.5]\n\
         look_at = [0.0, 0.0, 0.0]\n\
         fov = 45.0\n\
         width = {}\n\
         height = {}\n\n\
         [[lights]]\n\
         type = \"point\"\n\
         position = [-4.0, 9.0, 6.0]\n\n\
         [[surfaces]]\n\
         name = \"floor\"\n\
         formula = \"y\"\n\
         bounds = [[-6.0, -0.5, -6.0], [6.0, 0.0, 6.0]]\n\
         clip = true\n\
         material = {{ color = [0.7, 0.7, 0.68], specular = 0.05, shininess = 8.0 }}\n",
        args.width, args.height
    );
    let k = (n as f64).sqrt().ceil() as usize;
    let cells = k * k;
    let cell = 2.0 * HALF_SIDE / k as f64;
    // The cells in a seeded order: i -> (offset + i · step) mod k², with step coprime to k².
    let mut step = ((cells as f64 * 0.618_034) as usize).max(1);
    while gcd(step, cells) != 1 {
        step += 1;
    }
    let offset = (args.seed as usize) % cells;
    let shapes = catalog::all();
    for i in 0..n {
        let c = (offset + i * step) % cells;
        let s = args.seed.wrapping_mul(7919).wrapping_add(i as u64 + 1);
        let r = ((0.3 + 0.1 * weyl(s, 0.754_877_666)) * cell).min(1.5);
        let jitter = |a: f64| (2.0 * weyl(s, a) - 1.0) * (0.5 * cell - r);
        let x = -HALF_SIDE + ((c % k) as f64 + 0.5) * cell + jitter(0.569_840_291);
        let z = -HALF_SIDE + ((c / k) as f64 + 0.5) * cell + jitter(0.362_437_958);
        let y = r * 1.02;
        let hue = weyl(s, 0.618_034);
        let color = [0.35 + 0.5 * hue, 0.45, 0.85 - 0.5 * hue];
        let _ = write!(
            t,
            "\n[[surfaces]]\nname = \"o{i}\"\nmaterial = {{ color = [{:.3}, {:.3}, {:.3}], specular = 0.4, shininess = 32.0 }}\n",
            color[0], color[1], color[2]
        );
        if args.catalog {
            let shape = &shapes[i % shapes.len()];
            let (lo, hi) = shape.bounds;
            let mid: [f64; 3] = std::array::from_fn(|j| 0.5 * (lo[j] + hi[j]));
            let half_diagonal = (0..3)
                .map(|j| (0.5 * (hi[j] - lo[j])).powi(2))
                .sum::<f64>()
                .sqrt();
            let scale = r / half_diagonal;
            let _ = write!(
                t,
                "catalog = \"{}\"\ntransform = {{ scale = {scale:?}, translate = [{:?}, {:?}, {:?}] }}\n",
                shape.name,
                x - scale * mid[0],
                y - scale * mid[1],
                z - scale * mid[2]
            );
        } else {
            let _ = write!(
                t,
                "formula = \"x^2 + y^2 + z^2 - r^2\"\nparams = {{ r = {r:?} }}\n\
                 bounds = [[{m:?}, {m:?}, {m:?}], [{b:?}, {b:?}, {b:?}]]\n\
                 transform = {{ translate = [{x:?}, {y:?}, {z:?}] }}\n",
                b = 1.01 * r,
                m = -1.01 * r
            );
        }
    }
    // One sample per Hit pixel: how the passes grow with `N`, without the anti-aliasing.
    t.push_str("\n[render]\naa = \"none\"\n");
    t
}

fn seconds(d: Duration) -> String {
    format!("{:.3}", d.as_secs_f64())
}

fn run(mut args: Args) -> Result<(), String> {
    if args.counts.is_empty() || args.counts.iter().any(|&n| n == 0 || n > MAX_COUNT) {
        return Err(format!(
            "--counts: numbers of objects from 1 to {MAX_COUNT}"
        ));
    }
    if !(1..=16384).contains(&args.width) || !(1..=16384).contains(&args.height) {
        return Err("--width and --height must lie in 1..=16384".into());
    }
    if args.threads == 0 {
        return Err("--threads must be at least 1".into());
    }
    if let Some(s) = args.max_seconds
        && !(s > 0.0 && s.is_finite())
    {
        return Err("--max-seconds must be a positive number".into());
    }
    args.counts.sort_unstable();
    args.counts.dedup();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()
        .map_err(|e| format!("cannot start the thread pool: {e}"))?;
    let what = if args.catalog {
        "catalog surfaces in turn"
    } else {
        "spheres"
    };
    println!(
        "N {what} above a floor, one point light, {} × {} pixels, {} threads, seed {}\n",
        args.width, args.height, args.threads, args.seed
    );
    // The passes that run: the same plan for every N (same settings, one light).
    let mut passes: Vec<Pass> = Vec::new();
    let mut over_budget: Option<(usize, f64)> = None;
    for &n in &args.counts {
        if let Some((m, s)) = over_budget {
            println!(
                "\nskipped N = {n}: the render of N = {m} took {s:.1} s, more than --max-seconds"
            );
            continue;
        }
        let text = scene_text(&args, n);
        if let Some(dir) = &args.write_scenes {
            let p = dir.join(format!("scaling-{n}.toml"));
            std::fs::write(&p, &text).map_err(|e| format!("cannot write {}: {e}", p.display()))?;
        }
        let t = Instant::now();
        let scene = Scene::from_toml(&text, &format!("scaling-{n}"), None)
            .map_err(|e| format!("the scene of {n} objects: {e}"))?;
        let load = t.elapsed();
        if passes.is_empty() {
            let plan = Plan::for_scene(&scene);
            passes = Pass::ALL.into_iter().filter(|&p| plan.runs(p)).collect();
            let names: Vec<&str> = passes.iter().map(|p| p.name()).collect();
            let header = if args.load_only {
                "| N | surfaces | scene read s |".to_string()
            } else {
                format!(
                    "| N | surfaces | scene read s | render s | {} s |",
                    names.join(" s | ")
                )
            };
            println!("{header}");
            let columns = header.matches('|').count() - 1;
            println!("|{}", "---:|".repeat(columns));
        }
        let surfaces = scene.geometry.leaves().len();
        if args.load_only {
            println!("| {n} | {surfaces} | {} |", seconds(load));
            continue;
        }
        let out = pool
            .install(|| beam_trace::render(&scene, &NoProgress))
            .map_err(|e| format!("the render of {n} objects: {e}"))?;
        let cells: Vec<String> = passes
            .iter()
            .map(|&p| out.stats.of(p).map_or("-".into(), |s| seconds(s.time)))
            .collect();
        println!(
            "| {n} | {surfaces} | {} | {} | {} |",
            seconds(load),
            seconds(out.stats.total),
            cells.join(" | ")
        );
        if args.stats {
            println!("\n```text\n{}\n```\n", out.stats);
        }
        if let Some(dir) = &args.images {
            let p = dir.join(format!("scaling-{n}.png"));
            out.image
                .write_png(&p)
                .map_err(|e| format!("cannot write {}: {e}", p.display()))?;
        }
        let total = out.stats.total.as_secs_f64();
        if args.max_seconds.is_some_and(|max| total > max) {
            over_budget = Some((n, total));
        }
    }
    Ok(())
}

fn main() -> std::process::ExitCode {
    examples::report::exit(run(Args::parse()))
}
