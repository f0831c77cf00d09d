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
//! (`pruned`, tracing and simplification included).

use std::hint::black_box;
use std::time::Duration;

use benches::expr::{self, Engine, Engines, FidgetPruneBench, Mode, PruneBench, Samples};
use criterion::{Criterion, Throughput};

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

fn main() {
    let mut c = config().configure_from_args();
    evaluation(&mut c);
    pruning(&mut c);
    c.final_summary();
}
