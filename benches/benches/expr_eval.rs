//! Criterion benchmarks of expression evaluation, ours and fidget's VM side by side on the
//! same expressions, points and boxes (`benches::expr`), then the tape-pruning workload.
//!
//! ```text
//! cargo bench -p benches --bench expr_eval
//! cargo bench -p benches --bench expr_eval -- csg2d          # only the groups matching csg2d
//! EXPR_BENCH_VM=path/a.vm:path/b.vm cargo bench -p benches --bench expr_eval
//! ```
//!
//! Groups are named `mode/expression` (`point-scalar/sphere`, `interval-scalar/csg2d`, ...)
//! with the functions `ours` (`f32` points, `Interval<f32>`: like for like with fidget's
//! `f32`), `ours-f64` and `fidget-vm`; the throughput is one element per evaluation, so
//! criterion reports the time per point or box. fidget has no interval slice evaluator, so
//! the `interval-batch` groups hold ours only. The `prune/...` groups time one pass over
//! the 16 × 16 tiles of `[-1, 1]²`: the samples of every tile with the full tape
//! (`full`), or after tracing the tile's interval evaluation and simplifying the tape
//! (`pruned`, tracing and simplification included). The `ray-beam/...` groups time `g(t)`
//! over a beam of directions, as the renderer's cells and probes call it: 100 ranges along
//! one beam per iteration, each evaluation a call of the tape's compiled code.

use std::hint::black_box;
use std::time::Duration;

use benches::expr::{self, Engine, Engines, FidgetPruneBench, Mode, PruneBench, Samples};
use criterion::{Criterion, Throughput};
use implicit_expr::ray::{RayEvaluator, RayFunction};
use interval_core::Interval;

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
}

/// The `.vm` files named by `EXPR_BENCH_VM` (colon-separated paths), as `(name, text)`.
fn extra_vm() -> Vec<(String, String)> {
    let Ok(paths) = std::env::var("EXPR_BENCH_VM") else {
        return Vec::new();
    };
    paths
        .split(':')
        .filter(|p| !p.is_empty())
        .map(|p| {
            let text = std::fs::read_to_string(p)
                .unwrap_or_else(|e| panic!("EXPR_BENCH_VM: cannot read {p}: {e}"));
            let name = std::path::Path::new(p)
                .file_stem()
                .map_or(p.to_string(), |s| s.to_string_lossy().into_owned());
            (name, text)
        })
        .collect()
}

fn evaluation(c: &mut Criterion) {
    let exprs = expr::expressions(&extra_vm()).expect("benchmark expressions build");
    for e in &exprs {
        let mut en = Engines::new(e);
        for mode in Mode::ALL {
            let mut g = c.benchmark_group(format!("{}/{}", mode.name(), e.name));
            g.throughput(Throughput::Elements(mode.evaluations() as u64));
            for (id, engine) in [
                ("ours", Engine::Ours32),
                ("ours-f64", Engine::Ours64),
                ("fidget-vm", Engine::FidgetVm),
            ] {
                if en.run(engine, mode).is_none() {
                    continue;
                }
                g.bench_function(id, |b| b.iter(|| black_box(en.run(engine, mode))));
            }
            g.finish();
        }
    }
}

fn pruning(c: &mut Criterion) {
    let exprs = expr::expressions(&extra_vm()).expect("benchmark expressions build");
    for e in exprs
        .iter()
        .filter(|e| e.planar && e.tape.choice_count() > 0)
    {
        for samples in [Samples::Points(8), Samples::Boxes(4)] {
            let mut g = c.benchmark_group(format!(
                "prune/{}/{}",
                e.name,
                samples.describe().replace(' ', "-")
            ));
            let mut ours = PruneBench::new(&e.tape, 16, samples);
            g.throughput(Throughput::Elements(ours.evaluations() as u64));
            g.bench_function("full", |b| b.iter(|| black_box(ours.full())));
            g.bench_function("pruned", |b| b.iter(|| black_box(ours.pruned())));
            if let Ok(mut theirs) = e
                .fidget_vm()
                .and_then(|f| FidgetPruneBench::new(&f, 16, samples))
            {
                g.bench_function("fidget-vm-full", |b| b.iter(|| black_box(theirs.full())));
                g.bench_function("fidget-vm-pruned", |b| {
                    b.iter(|| black_box(theirs.pruned()))
                });
            }
            g.finish();
        }
    }
}

/// Formulas of the `ray-beam` groups: a sphere, and a small union and intersection of
/// shapes as the CSG models hold them.
const RAY_FORMULAS: [(&str, &str); 2] = [
    ("sphere", "sqrt(x*x + y*y + z*z) - 1"),
    (
        "csg",
        "max(min(sqrt(x*x + y*y) - 0.5, z - 0.3), min(x - 0.1, max(y + 0.2, sqrt((x - 0.3)^2 + z^2) - 0.4)))",
    ),
];

fn ray_beam(c: &mut Criterion) {
    let iv = |lo: f64, hi: f64| Interval::new(lo, hi).expect("ordered bounds");
    for (name, formula) in RAY_FORMULAS {
        let mut ctx = implicit_expr::Context::new();
        let f = implicit_expr::parse::parse(&mut ctx, formula, &[]).expect("formula parses");
        let rf = RayFunction::new(&ctx, f).expect("ray function builds");
        let mut ev = RayEvaluator::<Interval<f64>>::new(&rf, &[]).expect("no parameters");
        // A beam of directions a pixel or two wide, from a point on the z axis.
        let origin = [iv(0.0, 0.0), iv(0.0, 0.0), iv(5.0, 5.0)];
        ev.set_ray(origin, [iv(0.01, 0.011), iv(-0.02, -0.019), iv(-1.0, -1.0)]);
        let ranges: Vec<Interval<f64>> = (0..100)
            .map(|i| {
                let t = 3.0 + f64::from(i) * 0.02;
                iv(t, t + 0.02)
            })
            .collect();
        let mut g = c.benchmark_group(format!("ray-beam/{name}"));
        g.throughput(Throughput::Elements(ranges.len() as u64));
        g.bench_function("ours-f64", |b| {
            b.iter(|| {
                for &t in &ranges {
                    black_box(ev.g(t));
                }
            })
        });
        g.finish();
    }
}

fn main() {
    let mut c = config().configure_from_args();
    evaluation(&mut c);
    pruning(&mut c);
    ray_beam(&mut c);
    c.final_summary();
}
