//! Criterion benchmarks of interval operations: interval-core, and with the `inari` feature
//! inari on the same values in the same group; then the batch operations against the scalar
//! loop.
//!
//! ```text
//! cargo bench -p benches --bench interval_ops
//! CARGO_TARGET_DIR=target/v3 RUSTFLAGS="-C target-cpu=x86-64-v3" \
//!     cargo bench -p benches --features inari --bench interval_ops
//! ```
//!
//! Every benchmark writes `f(x[i], y[i])` for a whole workload into a pre-allocated output
//! vector through the public operators and methods; the throughput is one element per
//! interval, so criterion reports the time per operation. The arithmetic workloads hold
//! [`N`] intervals; the elementary functions (whose inari versions go through MPFR and take
//! microseconds) use the first [`N_ELEMENTARY`] intervals of theirs, to keep the whole run
//! to a few minutes.

use benches::{Domain, N, SEED, binary_operands, intervals};
use criterion::measurement::WallTime;
use criterion::{Bencher, BenchmarkGroup, Criterion, Throughput};
use interval_core::Interval;
use interval_core::interval::batch;
use std::hint::black_box;
use std::time::Duration;

type I = Interval<f64>;

/// Intervals per elementary-function workload.
const N_ELEMENTARY: usize = 100_000;

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
}

/// Times `out[i] = f(xs[i])`.
fn unary<X: Copy>(b: &mut Bencher, xs: &[X], f: impl Fn(X) -> X) {
    let mut out = xs.to_vec();
    b.iter(|| {
        for (x, o) in black_box(xs).iter().zip(out.iter_mut()) {
            *o = f(*x);
        }
        black_box(&mut out);
    });
}

/// Times `out[i] = f(xs[i], ys[i])`.
fn binary<X: Copy>(b: &mut Bencher, xs: &[X], ys: &[X], f: impl Fn(X, X) -> X) {
    let mut out = xs.to_vec();
    b.iter(|| {
        let (xs, ys) = black_box((xs, ys));
        for ((x, y), o) in xs.iter().zip(ys).zip(out.iter_mut()) {
            *o = f(*x, *y);
        }
        black_box(&mut out);
    });
}

fn group<'a>(c: &'a mut Criterion, name: &str, n: usize) -> BenchmarkGroup<'a, WallTime> {
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(n as u64));
    g
}

/// One group per operation, interval-core and inari side by side.
fn operations(c: &mut Criterion) {
    let (xs, ys) = binary_operands(N);
    let positive = intervals(Domain::Positive, N, SEED);
    let exp_args = intervals(Domain::Exp, N_ELEMENTARY, SEED);
    let sin_args = intervals(Domain::Sin, N_ELEMENTARY, SEED);
    let pown_args = &xs[..N_ELEMENTARY];
    #[cfg(feature = "inari")]
    let (jx, jy, jpos, jexp, jsin) = (
        benches::to_inari(&xs),
        benches::to_inari(&ys),
        benches::to_inari(&positive),
        benches::to_inari(&exp_args),
        benches::to_inari(&sin_args),
    );

    macro_rules! binary_group {
        ($name:literal, $op:tt) => {{
            let mut g = group(c, $name, N);
            g.bench_function("interval-core", |b| binary(b, &xs, &ys, |x, y| x $op y));
            #[cfg(feature = "inari")]
            g.bench_function("inari", |b| binary(b, &jx, &jy, |x, y| x $op y));
            g.finish();
        }};
    }
    binary_group!("add", +);
    binary_group!("mul", *);
    binary_group!("div", /);

    let mut g = group(c, "sqrt", N);
    g.bench_function("interval-core", |b| unary(b, &positive, I::sqrt));
    #[cfg(feature = "inari")]
    g.bench_function("inari", |b| unary(b, &jpos, inari::Interval::sqrt));
    g.finish();

    let mut g = group(c, "exp", N_ELEMENTARY);
    g.bench_function("interval-core", |b| unary(b, &exp_args, I::exp));
    #[cfg(feature = "inari")]
    g.bench_function("inari", |b| unary(b, &jexp, inari::Interval::exp));
    g.finish();

    let mut g = group(c, "sin", N_ELEMENTARY);
    g.bench_function("interval-core", |b| unary(b, &sin_args, I::sin));
    #[cfg(feature = "inari")]
    g.bench_function("inari", |b| unary(b, &jsin, inari::Interval::sin));
    g.finish();

    let mut g = group(c, "pown3", N_ELEMENTARY);
    g.bench_function("interval-core", |b| unary(b, pown_args, |x| x.pown(3)));
    #[cfg(feature = "inari")]
    g.bench_function("inari", |b| unary(b, &jx[..N_ELEMENTARY], |x| x.powi(3)));
    g.finish();
}

/// Batch operations against the scalar loop over the same operator.
fn batches(c: &mut Criterion) {
    let (xs, ys) = binary_operands(N);
    let positive = intervals(Domain::Positive, N, SEED);
    // A macro rather than a table of function pointers, so that the scalar loop inlines the
    // operator as user code would.
    macro_rules! batch_group {
        ($name:literal, $op:tt, $batch:path) => {{
            let mut g = group(c, $name, N);
            g.bench_function("scalar loop", |b| binary(b, &xs, &ys, |x, y| x $op y));
            g.bench_function("batch", |b| {
                let mut out = vec![I::EMPTY; N];
                b.iter(|| {
                    let (xs, ys) = black_box((&xs[..], &ys[..]));
                    $batch(xs, ys, &mut out).expect("equal lengths");
                    black_box(&mut out);
                });
            });
            g.finish();
        }};
    }
    batch_group!("batch_add", +, batch::add);
    batch_group!("batch_mul", *, batch::mul);
    batch_group!("batch_div", /, batch::div);

    let mut g = group(c, "batch_sqrt", N);
    g.bench_function("scalar loop", |b| unary(b, &positive, I::sqrt));
    g.bench_function("batch", |b| {
        let mut out = vec![I::EMPTY; N];
        b.iter(|| {
            batch::sqrt(black_box(&positive[..]), &mut out).expect("equal lengths");
            black_box(&mut out);
        });
    });
    g.finish();
}

fn main() {
    let mut c = config().configure_from_args();
    operations(&mut c);
    batches(&mut c);
    c.final_summary();
}
