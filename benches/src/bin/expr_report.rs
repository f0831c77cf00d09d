//! Times our expression evaluators against fidget's VM (and JIT) in one run, on the same
//! expressions, points and boxes (`benches::expr`), and prints markdown tables: time per
//! evaluation, time per tape instruction and the ratio ours / fidget VM for point and
//! interval evaluation, one at a time and in batches; then the tape-pruning workload (full
//! tape against trace + simplify + pruned tape on the tiles of `[-1, 1]²`) on the planar
//! expressions.
//!
//! ```text
//! cargo run --release -p benches --bin expr_report
//! cargo run --release -p benches --bin expr_report -- extra.vm ...   # more .vm files
//! CARGO_TARGET_DIR=target/v3 RUSTFLAGS="-C target-cpu=x86-64-v3" \
//!     cargo run --release -p benches --bin expr_report
//! ```
//!
//! Each cell is the best of seven samples, each sample enough passes over the workload to
//! last about 20 ms (one pass: 4096 points or 1024 boxes); passes longer than 0.2 s get
//! three samples of one pass.

use std::hint::black_box;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use benches::expr::{self, Engine, Engines, FidgetPruneBench, Mode, PruneBench, Samples};

/// Best time of one call of `f`, in seconds: seven samples of about 20 ms each (three
/// samples of one call when a call takes longer than 0.2 s).
fn best(mut f: impl FnMut() -> f64) -> f64 {
    black_box(f());
    let start = Instant::now();
    black_box(f());
    let once = start.elapsed().max(Duration::from_nanos(1));
    let reps = (Duration::from_millis(20).as_secs_f64() / once.as_secs_f64())
        .ceil()
        .max(1.0) as usize;
    let samples = if once > Duration::from_millis(200) {
        3
    } else {
        7
    };
    (0..samples)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                black_box(f());
            }
            t.elapsed().as_secs_f64() / reps as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() -> ExitCode {
    benches::exit(run())
}

fn run() -> Result<(), String> {
    let mut extra = Vec::new();
    for path in std::env::args().skip(1) {
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("cannot read {path}: {e}"))?;
        let name = std::path::Path::new(&path)
            .file_stem()
            .map_or(path.clone(), |s| s.to_string_lossy().into_owned());
        extra.push((name, text));
    }
    let exprs = expr::expressions(&extra).map_err(|e| e.to_string())?;
    println!(
        "Workloads: {} points, {} boxes per pass (seeded); single thread; best of 7 samples.\n",
        expr::N_POINTS,
        expr::N_BOXES
    );
    println!("| expression | our tape | fidget VM tape | fidget |");
    println!("|---|---:|---:|---|");
    let mut engines: Vec<(String, Engines)> = Vec::new();
    for e in &exprs {
        let en = Engines::new(e);
        let status = match (&en.vm, &en.jit) {
            (Ok(_), Ok(_)) => "VM and JIT".to_string(),
            (Err(m), _) | (_, Err(m)) => format!("n/a: {m}"),
        };
        println!(
            "| {} | {} | {} | {status} |",
            e.name,
            en.ours_len,
            en.vm_len.map_or("-".into(), |n| n.to_string())
        );
        engines.push((e.name.clone(), en));
    }
    println!();
    for mode in Mode::ALL {
        println!("### {}\n", mode.name());
        println!(
            "| expression | ours f32 ns | ours f64 ns | fidget VM ns | fidget JIT ns | ours f32 / VM | ours f64 / VM | ours f32 ns/instr | VM ns/instr |"
        );
        println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
        for (name, en) in engines.iter_mut() {
            let per_eval = mode.evaluations() as f64;
            let mut ns = |engine: Engine| -> Option<f64> {
                en.run(engine, mode)?;
                Some(best(|| en.run(engine, mode).unwrap_or(0.0)) / per_eval * 1e9)
            };
            let o32 = ns(Engine::Ours32);
            let o64 = ns(Engine::Ours64);
            let vm = ns(Engine::FidgetVm);
            let jit = ns(Engine::FidgetJit);
            let cell = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.1}"));
            let ratio = |a: Option<f64>, b: Option<f64>| match (a, b) {
                (Some(a), Some(b)) => format!("{:.2}", a / b),
                _ => "n/a".to_string(),
            };
            let per_instr = |v: Option<f64>, len: Option<usize>| match (v, len) {
                (Some(v), Some(n)) if n > 0 => format!("{:.2}", v / n as f64),
                _ => "n/a".to_string(),
            };
            println!(
                "| {name} | {} | {} | {} | {} | {} | {} | {} | {} |",
                cell(o32),
                cell(o64),
                cell(vm),
                cell(jit),
                ratio(o32, vm),
                ratio(o64, vm),
                per_instr(o32, Some(en.ours_len)),
                per_instr(vm, en.vm_len),
            );
        }
        println!();
    }
    if engines.iter().any(|(_, en)| en.vm.is_ok()) {
        println!("(fidget has no interval slice evaluator: its interval-batch cells are n/a.)\n");
    }

    println!(
        "### tape pruning: 16 x 16 tiles of [-1, 1]² (64-pixel tiles of a 1024² image), f32\n"
    );
    println!(
        "| expression | per tile | full tape ms | pruned ms (trace + simplify + eval) | of which trace + simplify ms | speed-up | mean pruned tape | fidget VM full ms | fidget VM pruned ms | fidget speed-up | fidget mean pruned tape |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for e in exprs
        .iter()
        .filter(|e| e.planar && e.tape.choice_count() > 0)
    {
        for samples in [Samples::Points(8), Samples::Points(64), Samples::Boxes(4)] {
            let mut ours = PruneBench::new(&e.tape, 16, samples);
            let full = best(|| ours.full());
            let pruned = best(|| ours.pruned());
            ours.pruned();
            let mean_len = ours.mean_pruned_len();
            let overhead = best(|| ours.trace_and_simplify() as f64);
            let theirs = e
                .fidget_vm()
                .and_then(|f| FidgetPruneBench::new(&f, 16, samples))
                .map(|mut b| {
                    let full = best(|| b.full());
                    let pruned = best(|| b.pruned());
                    b.pruned();
                    (full, pruned, b.mean_pruned_len())
                });
            let (tf, tp, ts, tl) = match theirs {
                Ok((f, p, l)) => (
                    format!("{:.2}", f * 1e3),
                    format!("{:.2}", p * 1e3),
                    format!("{:.1}x", f / p),
                    format!("{l:.0}"),
                ),
                Err(_) => ("n/a".into(), "n/a".into(), "n/a".into(), "n/a".into()),
            };
            println!(
                "| {} | {} | {:.2} | {:.2} | {:.2} | {:.1}x | {:.0} | {tf} | {tp} | {ts} | {tl} |",
                e.name,
                samples.describe(),
                full * 1e3,
                pruned * 1e3,
                overhead * 1e3,
                full / pruned,
                mean_len
            );
        }
    }
    Ok(())
}
