//! The experiments of the exact soft-shadow method (seed 003) in this project's terms:
//! procedural triangle meshes above a floor, horizontal square lights, the visible fraction
//! of the lights at a grid of floor points, computed exactly (lazy Plücker BSP per floor
//! tile, `beam_trace::shadow::exact`) and by stochastic sampling (jittered stratified
//! segments through a BVH) at several sample counts. The exact method gets, per floor tile
//! and light, the triangles in the shaft between the tile and the light, without the
//! ball's faces turned away from the whole light (redundant for a closed mesh).
//!
//! Tables (markdown, `--report FILE` saves them):
//!
//! 1. **Equal time and equal quality**: the exact method's time against stochastic sampling
//!    with 4 to 1024 samples per point, the sampling's RMSE and largest error against the
//!    exact fractions; equal quality is the fewest samples whose RMSE is at most 1/255.
//! 2. **Coherence**: the BSP rebuilt for every query (`reset`), against one tree per tile
//!    grown by its queries.
//! 3. **Light size**: the light's side ×1 to ×10 (area ×1 to ×100).
//! 4. **Light count**: the light split into 1 to 36 lights of the same total area.
//!
//! ```text
//! cargo run --release -p examples --bin exact-shadows -- --triangles 20000 --size 256
//! cargo run --release -p examples --bin exact-shadows -- --size 128 --images out/
//! ```

use std::ops::Range;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use beam_trace::image::Image;
use beam_trace::shadow::Patch;
use beam_trace::shadow::exact::{BspWork, ExactShadows, Plane};
use clap::Parser;
use examples::polygon_scene::{Bvh, SplitMix64, Triangle, facing, lumpy_ball_and_canopy, shaft};
use glam::DVec3;
use rayon::prelude::*;

/// Exact soft shadows of triangle meshes against stochastic sampling.
#[derive(Parser, Debug)]
#[command(name = "exact-shadows")]
struct Args {
    /// Triangles of the procedural scene (a lumpy ball and a canopy of leaves).
    #[arg(long, default_value_t = 20_000)]
    triangles: usize,
    /// Floor points per side (the floor `[-2, 2]²` sampled at cell centres).
    #[arg(long, default_value_t = 256)]
    size: usize,
    /// Floor points per side of a tile (one BSP per tile and light; 4 was the fastest of 1 to
    /// 32 on 1,000 triangles, see docs/shadows.md).
    #[arg(long, default_value_t = 4)]
    tile: usize,
    /// Side of the light (at height 4 above the origin).
    #[arg(long, default_value_t = 1.0)]
    light: f64,
    /// Seed of the scene.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Write the visible-fraction images (exact, stochastic at equal time, their
    /// difference) into this folder.
    #[arg(long)]
    images: Option<PathBuf>,
    /// Also save the report here.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Skip the coherence ablation (its reset variant is the slowest part).
    #[arg(long)]
    no_coherence: bool,
    /// Build each tile's tree without its region (insertions then keep every line from the
    /// light through an occluder, not only those reaching the tile; the same fractions).
    #[arg(long)]
    no_region: bool,
    /// Multipliers of the light's side for the light-size table (area grows with the
    /// square).
    #[arg(long, value_delimiter = ',', default_value = "1,2,5,10")]
    light_scales: Vec<f64>,
    /// Numbers of lights per side for the light-count table (k × k lights).
    #[arg(long, value_delimiter = ',', default_value = "1,2,3,4,6")]
    light_counts: Vec<usize>,
}

/// The floor point of row `r` and column `c` of the `size × size` grid over `[-2, 2]²` (cell
/// centres).
fn floor_point(size: usize, r: usize, c: usize) -> DVec3 {
    let cell = 4.0 / size as f64;
    DVec3::new(
        -2.0 + (c as f64 + 0.5) * cell,
        0.0,
        -2.0 + (r as f64 + 0.5) * cell,
    )
}

/// The floor points (row-major, `size × size`).
fn floor_points(size: usize) -> Vec<DVec3> {
    (0..size * size)
        .map(|i| floor_point(size, i / size, i % size))
        .collect()
}

/// The rows and columns of tile `t` of a `size × size` grid cut into tiles of `tile²`.
fn tile_cells(t: usize, tile: usize, size: usize) -> (Range<usize>, Range<usize>) {
    let tiles = size.div_ceil(tile);
    let (r0, c0) = (t / tiles * tile, t % tiles * tile);
    (r0..(r0 + tile).min(size), c0..(c0 + tile).min(size))
}

/// The lights: the square of side `side` at height 4 split into `k × k` squares.
fn lights(side: f64, k: usize) -> Vec<Patch> {
    let s = side / k as f64;
    (0..k * k)
        .map(|i| {
            let (a, b) = (i / k, i % k);
            let c = DVec3::new(
                -side / 2.0 + (b as f64 + 0.5) * s,
                4.0,
                -side / 2.0 + (a as f64 + 0.5) * s,
            );
            Patch::square(c, s, 1)
        })
        .collect()
}

/// The procedural scene: a closed ball and open leaves.
struct Scene {
    ball: Vec<Triangle>,
    canopy: Vec<Triangle>,
}

/// Exact fractions (the mean over the lights, weighted by area: equal here), seconds, the
/// summed work and the largest tree.
fn exact(
    tris: &Scene,
    size: usize,
    tile: usize,
    lights: &[Patch],
    (reset, region): (bool, bool),
) -> (Vec<f64>, f64, BspWork) {
    let floor = Plane {
        point: DVec3::ZERO,
        normal: DVec3::Y,
    };
    let tiles = size.div_ceil(tile);
    let cell = 4.0 / size as f64;
    // Per light, the occluders before culling to a tile's shaft.
    let candidates: Vec<Vec<Triangle>> = lights
        .iter()
        .map(|light| {
            let mut v = facing(&tris.ball, light);
            v.extend_from_slice(&tris.canopy);
            v
        })
        .collect();
    let start = Instant::now();
    let per_tile: Vec<(usize, Vec<f64>, BspWork)> = (0..tiles * tiles)
        .into_par_iter()
        .map(|t| {
            let (rows, cols) = tile_cells(t, tile, size);
            let (x0, x1) = (
                -2.0 + cols.start as f64 * cell,
                -2.0 + cols.end as f64 * cell,
            );
            let (z0, z1) = (
                -2.0 + rows.start as f64 * cell,
                -2.0 + rows.end as f64 * cell,
            );
            let mut sums = vec![0.0; rows.len() * cols.len()];
            let mut work = BspWork::default();
            for (li, (light, candidates)) in lights.iter().zip(&candidates).enumerate() {
                let occ = shaft(candidates, x0, x1, z0, z1, light);
                let seed = (t as u64) << 8 | li as u64;
                let mut ex =
                    ExactShadows::new(*light, floor, &occ, seed).expect("a light above the floor");
                if region {
                    ex.set_region(DVec3::new(x0, 0.0, z0), DVec3::new(x1, 0.0, z1))
                        .expect("a tile is a box");
                }
                let points = rows.clone().flat_map(|r| cols.clone().map(move |c| (r, c)));
                for (sum, (r, c)) in sums.iter_mut().zip(points) {
                    if reset {
                        ex.reset();
                    }
                    *sum += ex
                        .visible_fraction(floor_point(size, r, c), Some(DVec3::Y))
                        .expect("on the floor");
                }
                work.add(&ex.work());
            }
            (t, sums, work)
        })
        .collect();
    let seconds = start.elapsed().as_secs_f64();
    let mut out = vec![0.0; size * size];
    let mut work = BspWork::default();
    for (t, sums, w) in per_tile {
        let (rows, cols) = tile_cells(t, tile, size);
        let points = rows.flat_map(|r| cols.clone().map(move |c| (r, c)));
        for (sum, (r, c)) in sums.iter().zip(points) {
            out[r * size + c] = sum / lights.len() as f64;
        }
        work.add(&w);
    }
    (out, seconds, work)
}

/// Stochastic fractions with `n × n` jittered stratified segments per point and light.
fn stochastic(bvh: &Bvh, points: &[DVec3], lights: &[Patch], n: usize) -> (Vec<f64>, f64) {
    let start = Instant::now();
    let out: Vec<f64> = points
        .par_iter()
        .enumerate()
        .map(|(i, &x)| {
            // A per-point generator: results do not depend on the thread count.
            let mut rng = SplitMix64::new(
                (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03,
            );
            let mut next = || rng.next_f64();
            let mut free = 0usize;
            for light in lights {
                for a in 0..n {
                    for b in 0..n {
                        let l = light.point(
                            (a as f64 + next()) / n as f64,
                            (b as f64 + next()) / n as f64,
                        );
                        free += usize::from(!bvh.blocked(l, x));
                    }
                }
            }
            free as f64 / (n * n * lights.len()) as f64
        })
        .collect();
    (out, start.elapsed().as_secs_f64())
}

fn errors(a: &[f64], b: &[f64]) -> (f64, f64) {
    let mut sq = 0.0;
    let mut worst: f64 = 0.0;
    for (x, y) in a.iter().zip(b) {
        sq += (x - y) * (x - y);
        worst = worst.max((x - y).abs());
    }
    ((sq / a.len() as f64).sqrt(), worst)
}

fn image(values: &[f64], size: usize, map: impl Fn(f64) -> [f32; 3]) -> Image {
    let mut img = Image::new(size as u32, size as u32, [0.0; 3]);
    for (i, &v) in values.iter().enumerate() {
        img.set((i % size) as u32, (i / size) as u32, map(v));
    }
    img
}

fn run(args: &Args) -> Result<(), String> {
    if args.size == 0 || args.tile == 0 || args.triangles == 0 || args.light <= 0.0 {
        return Err("--size, --tile, --triangles and --light must be positive".into());
    }
    let (ball, canopy) = lumpy_ball_and_canopy(args.triangles, args.seed);
    let all: Vec<Triangle> = ball.iter().chain(&canopy).copied().collect();
    let triangle_count = all.len();
    let tris = Scene { ball, canopy };
    let points = floor_points(args.size);
    let bvh = Bvh::new(all);
    let one = lights(args.light, 1);
    let mut md = format!(
        "# Exact soft shadows against stochastic sampling\n\n{} triangles (lumpy ball and canopy, seed {}), floor {}², tiles of {}², light side {} at height 4, {} threads\n\n",
        triangle_count,
        args.seed,
        args.size,
        args.tile,
        args.light,
        rayon::current_num_threads()
    );
    let region = !args.no_region;
    eprintln!("exact ...");
    let (ex, t_exact, w) = exact(&tris, args.size, args.tile, &one, (false, region));
    eprintln!("  {t_exact:.3} s");
    md += &format!(
        "## Equal time and equal quality\n\nexact: {:.3} s (merges {}, inner nodes {}, splits {}, fragments {}, largest tree {} nodes)\n\n| samples per point | time (s) | time / exact | RMSE | largest error |\n|---:|---:|---:|---:|---:|\n",
        t_exact, w.merges, w.inner_nodes, w.splits, w.fragments, w.peak_nodes
    );
    let mut equal_time: Option<(usize, Vec<f64>)> = None;
    let mut equal_quality = None;
    for n in [2, 4, 8, 16, 32] {
        eprintln!("stochastic {} ...", n * n);
        let (st, t) = stochastic(&bvh, &points, &one, n);
        eprintln!("  {t:.3} s");
        let (rmse, worst) = errors(&st, &ex);
        md += &format!(
            "| {} | {t:.3} | {:.2} | {rmse:.4} | {worst:.3} |\n",
            n * n,
            t / t_exact
        );
        if equal_time.is_none() && t >= t_exact {
            equal_time = Some((n * n, st.clone()));
        }
        if equal_quality.is_none() && rmse <= 1.0 / 255.0 {
            equal_quality = Some((n * n, t / t_exact));
        }
    }
    md += &match equal_quality {
        Some((s, r)) => format!(
            "\nEqual quality (RMSE ≤ 1/255): {s} samples, {r:.1} × the exact method's time.\n"
        ),
        None => "\nEqual quality (RMSE ≤ 1/255) is not reached by 1024 samples.\n".to_string(),
    };
    if let Some(dir) = &args.images {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let grey = |v: f64| [v as f32; 3];
        let save =
            |img: Image, name: &str| img.write_png(&dir.join(name)).map_err(|e| e.to_string());
        save(image(&ex, args.size, grey), "exact.png")?;
        if let Some((s, st)) = &equal_time {
            save(image(st, args.size, grey), &format!("stochastic-{s}.png"))?;
            let diff: Vec<f64> = st.iter().zip(&ex).map(|(a, b)| a - b).collect();
            save(
                image(&diff, args.size, |d| {
                    let m = (d.abs() * 4.0).min(1.0) as f32;
                    if d > 0.0 {
                        [m, 0.0, 0.0]
                    } else {
                        [0.0, 0.0, m]
                    }
                }),
                &format!("difference-{s}.png"),
            )?;
        }
    }
    if !args.no_coherence {
        let small = (args.size / 4).max(args.tile);
        eprintln!("coherence ...");
        let (a, ta, wa) = exact(&tris, small, args.tile, &one, (false, region));
        let (b, tb, wb) = exact(&tris, small, args.tile, &one, (true, region));
        let same = a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-9);
        md += &format!(
            "\n## Coherence\n\nfloor {small}²: one tree per tile {ta:.3} s ({} merges); rebuilt for every query {tb:.3} s ({} merges): {:.1} × slower; same fractions: {same}\n",
            wa.merges,
            wb.merges,
            tb / ta
        );
    }
    md += "\n## Light size\n\n| light side | area | exact (s) | merges | splits | largest tree | stochastic 256 (s) |\n|---:|---:|---:|---:|---:|---:|---:|\n";
    for &scale in &args.light_scales {
        let side = args.light * scale;
        eprintln!("light side {side} ...");
        let l = lights(side, 1);
        let (_, t, w) = exact(&tris, args.size / 2, args.tile, &l, (false, region));
        eprintln!("  exact {t:.3} s");
        let (_, ts) = stochastic(&bvh, &floor_points(args.size / 2), &l, 16);
        md += &format!(
            "| {side} | {:.2} | {t:.3} | {} | {} | {} | {ts:.3} |\n",
            scale * scale,
            w.merges,
            w.splits,
            w.peak_nodes
        );
    }
    md += "\n## Light count (same total area)\n\n| lights | exact (s) | per light (s) | merges |\n|---:|---:|---:|---:|\n";
    for &k in &args.light_counts {
        eprintln!("{} lights ...", k * k);
        let l = lights(args.light, k);
        let (_, t, w) = exact(&tris, args.size / 2, args.tile, &l, (false, region));
        md += &format!(
            "| {} | {t:.3} | {:.4} | {} |\n",
            k * k,
            t / (k * k) as f64,
            w.merges
        );
    }
    examples::report::print_and_save(&md, args.report.as_deref())
}

fn main() -> ExitCode {
    examples::report::exit(run(&Args::parse()))
}
