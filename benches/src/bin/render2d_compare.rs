//! Times the 2D renderer of the `render2d` crate (the `render2d` example's) against fidget's
//! 2D rasterizer with its VM and JIT evaluators, on the same `.vm` expressions, image size
//! and thread count, and counts the pixels on which the images differ.
//!
//! ```text
//! cargo run --release -p benches --bin render2d_compare
//! cargo run --release -p benches --bin render2d_compare -- --size 1024 --threads 2 --runs 5 other.vm
//! ```
//!
//! Without file arguments it renders `data/models/csg2d.vm`. Both renderers sample pixel
//! centres of `[-1, 1]²` (fidget's image transform is shifted by half a pixel to match).
//! Ours runs in `f32` (sound intervals, like for like with fidget's `f32`) and `f64`, with
//! the tiles (64, 16, 4) and the example's default tiles (128, 32, 8, fidget's VM tiles); fidget uses
//! its defaults (VM: 128, 32, 8; JIT: 128, 16). Times are the best and the median of
//! `--runs` renders after one warm-up render. Before each of our renders the codes kept for
//! equal tapes are forgotten (`implicit_expr::jit::forget_shared`, outside the time), so
//! that each compiles its tapes as a process's first render does, as fidget compiles its
//! pruned tapes in every render; `--warm` lets them find the tapes compiled before.

use std::process::ExitCode;
use std::time::{Duration, Instant};

use benches::expr::{CSG2D_VM, Expr};
use fidget::eval::Function;
use fidget::jit::JitFunction;
use fidget::raster::pixel::{EvalConfig, RenderConfig, render};
use fidget::render::{CancelToken, RenderHints, ThreadPool};
use fidget::shape::Shape;
use fidget::vm::VmFunction;
use render2d::{Image, Settings};

struct Options {
    size: usize,
    threads: usize,
    runs: usize,
    warm: bool,
    files: Vec<(String, String)>,
}

fn parse_args() -> Result<Options, String> {
    let mut o = Options {
        size: 1024,
        threads: 2,
        runs: 5,
        warm: false,
        files: Vec::new(),
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut num = |name: &str| -> Result<usize, String> {
            let v = args.next().ok_or(format!("{name} needs a value"))?;
            v.parse().map_err(|e| format!("{name} {v}: {e}"))
        };
        match a.as_str() {
            "--size" => o.size = num("--size")?,
            "--threads" => o.threads = num("--threads")?,
            "--runs" => o.runs = num("--runs")?.max(1),
            "--warm" => o.warm = true,
            path => {
                let text = std::fs::read_to_string(path)
                    .map_err(|e| format!("cannot read {path}: {e}"))?;
                let name = std::path::Path::new(path)
                    .file_stem()
                    .map_or(path.to_string(), |s| s.to_string_lossy().into_owned());
                o.files.push((name, text));
            }
        }
    }
    if o.files.is_empty() {
        o.files.push(("csg2d".into(), CSG2D_VM.into()));
    }
    Ok(o)
}

/// Best and median of `runs` timed calls of `f`, after one warm-up call whose result is
/// returned; `before` runs untimed before each call.
fn time<R>(runs: usize, before: impl Fn(), mut f: impl FnMut() -> R) -> (R, Duration, Duration) {
    before();
    let first = f();
    let mut times: Vec<Duration> = (0..runs)
        .map(|_| {
            before();
            let t = Instant::now();
            std::hint::black_box(f());
            t.elapsed()
        })
        .collect();
    times.sort();
    (first, times[0], times[times.len() / 2])
}

/// fidget's render of `f` at `size`², on `pool`; `true` is inside, row by row from the top.
fn fidget_render<F: Function + RenderHints>(
    shape: Shape<F>,
    size: usize,
    pool: &ThreadPool,
) -> Vec<bool> {
    // Shift fidget's sample grid (pixel corners) by half a pixel onto the pixel centres.
    let half = 1.0 / size as f32;
    let cfg = RenderConfig {
        world_to_model: nalgebra::Matrix3::new_translation(&nalgebra::Vector2::new(half, half)),
        ..RenderConfig::from_size((size as u32).into())
    };
    let eval = EvalConfig {
        tile_sizes: None,
        threads: Some(pool),
        cancel: CancelToken::new(),
    };
    let bound = shape.try_into().expect("no variables besides x, y, z");
    let image = render(bound, &cfg, &eval).expect("not cancelled");
    image.iter().map(|p| p.inside()).collect()
}

fn differing(ours: &Image, theirs: &[bool]) -> usize {
    render2d::count_differences(ours, theirs)
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() -> ExitCode {
    benches::exit(run())
}

fn run() -> Result<(), String> {
    let o = parse_args()?;
    let ours_pool = rayon::ThreadPoolBuilder::new()
        .num_threads(o.threads)
        .build()
        .map_err(|e| e.to_string())?;
    let fidget_pool = ThreadPool::Custom(
        rayon::ThreadPoolBuilder::new()
            .num_threads(o.threads)
            .build()
            .map_err(|e| e.to_string())?,
    );
    println!(
        "{}x{} pixels over [-1, 1]², {} threads for every renderer, best / median of {} runs; {}\n",
        o.size,
        o.size,
        o.threads,
        o.runs,
        if o.warm {
            "our renders find the tapes compiled by the renders before them"
        } else {
            "each of our renders compiles its tapes afresh"
        }
    );
    for (name, text) in &o.files {
        let e = Expr::from_vm(name, text).map_err(|err| format!("{name}: {err}"))?;
        let (fctx, froot) = e
            .fidget
            .as_ref()
            .map_err(|err| format!("{name}: fidget: {err}"))?;
        let vm = Shape::<VmFunction>::new(fctx, *froot).map_err(|err| err.to_string())?;
        let jit = Shape::<JitFunction>::new(fctx, *froot).map_err(|err| err.to_string())?;
        println!(
            "## {name}: our tape {} instructions, fidget VM tape {}\n",
            e.tape.len(),
            vm.inner().size()
        );
        println!(
            "| renderer | tiles | best ms | median ms | best / fidget VM | pixels differing from ours f64 |"
        );
        println!("|---|---|---:|---:|---:|---:|");

        let ours = |tiles: &[usize], f32: bool| {
            let s = Settings {
                tiles: tiles.to_vec(),
                ..Settings::square(o.size)
            };
            let cold = || {
                if !o.warm {
                    implicit_expr::jit::forget_shared();
                }
            };
            time(o.runs, cold, || {
                ours_pool.install(|| {
                    if f32 {
                        render2d::render::<f32>(&e.tape, &s)
                    } else {
                        render2d::render::<f64>(&e.tape, &s)
                    }
                    .expect("valid settings")
                    .0
                })
            })
        };
        let (vm_img, vm_best, vm_med) = time(
            o.runs,
            || {},
            || fidget_render(vm.clone(), o.size, &fidget_pool),
        );
        let (jit_img, jit_best, jit_med) = time(
            o.runs,
            || {},
            || fidget_render(jit.clone(), o.size, &fidget_pool),
        );
        let (ref64, r64_best, r64_med) = ours(&[64, 16, 4], false);
        let reference: Vec<bool> = ref64.pixels.iter().map(|p| p.is_inside()).collect();
        let rows: Vec<(String, String, Duration, Duration, usize)> = vec![
            ("ours f64".into(), "64, 16, 4".into(), r64_best, r64_med, 0),
            {
                let (img, b, m) = ours(&[64, 16, 4], true);
                (
                    "ours f32".into(),
                    "64, 16, 4".into(),
                    b,
                    m,
                    differing(&img, &reference),
                )
            },
            {
                let (img, b, m) = ours(&[128, 32, 8], true);
                (
                    "ours f32".into(),
                    "128, 32, 8".into(),
                    b,
                    m,
                    differing(&img, &reference),
                )
            },
            {
                let (img, b, m) = ours(&[128, 32, 8], false);
                (
                    "ours f64".into(),
                    "128, 32, 8".into(),
                    b,
                    m,
                    differing(&img, &reference),
                )
            },
            (
                "fidget VM".into(),
                "128, 32, 8".into(),
                vm_best,
                vm_med,
                differing(&ref64, &vm_img),
            ),
            (
                "fidget JIT".into(),
                "128, 16".into(),
                jit_best,
                jit_med,
                differing(&ref64, &jit_img),
            ),
        ];
        for (who, tiles, best, med, diff) in rows {
            println!(
                "| {who} | {tiles} | {:.1} | {:.1} | {:.2} | {diff} |",
                ms(best),
                ms(med),
                best.as_secs_f64() / vm_best.as_secs_f64()
            );
        }
        println!();
    }
    Ok(())
}
