//! Time per interval operation for interval-core (and, with the `inari` feature, for inari
//! on the same values), with a check that the results agree, printed as markdown tables.
//!
//! ```text
//! cargo run --release -p benches --bin ops_report [-- N]
//! CARGO_TARGET_DIR=target/v3 RUSTFLAGS="-C target-cpu=x86-64-v3" \
//!     cargo run --release -p benches --features inari --bin ops_report [-- N]
//! ```
//!
//! Each workload is `N` (default 1,000,000) seeded random intervals (see the `benches`
//! library); each timing is the best of several passes over the whole vector, written into
//! a pre-allocated output vector through the public operators and methods.

use benches::{Comparison, Domain, N, SEED, binary_operands, intervals};
use interval_core::Interval;
use interval_core::interval::batch;
use std::hint::black_box;
use std::time::{Duration, Instant};

type I = Interval<f64>;

/// Passes timed per measurement: at least `MIN_REPS`, then more while within `BUDGET`.
const MIN_REPS: usize = 3;
const MAX_REPS: usize = 15;
const BUDGET: Duration = Duration::from_millis(1500);

/// The best time of one pass of `f`, in nanoseconds per element.
fn best_ns(n: usize, mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    let mut best = Duration::MAX;
    let mut reps = 0;
    while reps < MIN_REPS || (reps < MAX_REPS && start.elapsed() < BUDGET) {
        let t = Instant::now();
        f();
        best = best.min(t.elapsed());
        reps += 1;
    }
    best.as_secs_f64() * 1e9 / n as f64
}

/// `out[i] = f(xs[i])` through a plain loop.
#[inline(always)]
fn unary<X: Copy>(xs: &[X], out: &mut [X], f: impl Fn(X) -> X) {
    for (x, o) in black_box(xs).iter().zip(out.iter_mut()) {
        *o = f(*x);
    }
    black_box(out);
}

/// `out[i] = f(xs[i], ys[i])` through a plain loop.
#[inline(always)]
fn binary<X: Copy>(xs: &[X], ys: &[X], out: &mut [X], f: impl Fn(X, X) -> X) {
    let (xs, ys) = black_box((xs, ys));
    for ((x, y), o) in xs.iter().zip(ys).zip(out.iter_mut()) {
        *o = f(*x, *y);
    }
    black_box(out);
}

/// Bit-for-bit equality of interval-core results (signs of zero included).
fn bit_identical(a: &[I], b: &[I]) -> (usize, usize) {
    let same = a
        .iter()
        .zip(b)
        .filter(|(x, y)| match (x.bounds(), y.bounds()) {
            (None, None) => true,
            (Some((p, q)), Some((r, s))) => {
                p.to_bits() == r.to_bits() && q.to_bits() == s.to_bits()
            }
            _ => false,
        })
        .count();
    (same, a.len())
}

/// One line of the comparison table.
struct Row {
    op: &'static str,
    tight: bool,
    core_ns: f64,
    inari_ns: Option<f64>,
    cmp: Option<Comparison>,
}

/// The operands of one operation, as interval-core intervals.
struct Case {
    op: &'static str,
    /// Whether both libraries are expected to return the tight result.
    tight: bool,
    xs: Vec<I>,
    ys: Option<Vec<I>>,
}

fn fmt_count(c: usize) -> String {
    let s = c.to_string();
    let mut out = String::new();
    for (i, ch) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

fn describe(row: &Row) -> String {
    match row.cmp {
        None => "n/a".to_string(),
        Some(c) if c.identical == c.total => format!("yes ({})", fmt_count(c.total)),
        Some(c) => {
            let mut parts = vec![format!("{} identical", fmt_count(c.identical))];
            if c.first_wider > 0 {
                parts.push(format!("{} core wider", fmt_count(c.first_wider)));
            }
            if c.second_wider > 0 {
                parts.push(format!("{} inari wider", fmt_count(c.second_wider)));
            }
            if c.incomparable > 0 {
                parts.push(format!("{} INCOMPARABLE", fmt_count(c.incomparable)));
            }
            let verdict = if c.incomparable > 0 || (row.tight && c.identical != c.total) {
                "NO"
            } else {
                "contained"
            };
            format!("{verdict}: {}", parts.join(", "))
        }
    }
}

/// Evaluates `op` with interval-core.
fn core_op(case: &Case, out: &mut [I]) {
    let xs = &case.xs[..];
    match (case.op, case.ys.as_deref()) {
        ("add", Some(ys)) => binary(xs, ys, out, |x, y| x + y),
        ("sub", Some(ys)) => binary(xs, ys, out, |x, y| x - y),
        ("mul", Some(ys)) => binary(xs, ys, out, |x, y| x * y),
        ("div", Some(ys)) => binary(xs, ys, out, |x, y| x / y),
        ("sqr", None) => unary(xs, out, I::sqr),
        ("sqrt", None) => unary(xs, out, I::sqrt),
        ("pown(3)", None) => unary(xs, out, |x| x.pown(3)),
        ("exp", None) => unary(xs, out, I::exp),
        ("ln", None) => unary(xs, out, I::ln),
        ("sin", None) => unary(xs, out, I::sin),
        ("cos", None) => unary(xs, out, I::cos),
        _ => unreachable!("unknown operation {}", case.op),
    }
}

/// Evaluates `op` with inari on the converted operands.
#[cfg(feature = "inari")]
fn inari_op(
    op: &str,
    xs: &[inari::Interval],
    ys: Option<&[inari::Interval]>,
    out: &mut [inari::Interval],
) {
    use inari::Interval as J;
    match (op, ys) {
        ("add", Some(ys)) => binary(xs, ys, out, |x, y| x + y),
        ("sub", Some(ys)) => binary(xs, ys, out, |x, y| x - y),
        ("mul", Some(ys)) => binary(xs, ys, out, |x, y| x * y),
        ("div", Some(ys)) => binary(xs, ys, out, |x, y| x / y),
        ("sqr", None) => unary(xs, out, J::sqr),
        ("sqrt", None) => unary(xs, out, J::sqrt),
        ("pown(3)", None) => unary(xs, out, |x| x.powi(3)),
        ("exp", None) => unary(xs, out, J::exp),
        ("ln", None) => unary(xs, out, J::ln),
        ("sin", None) => unary(xs, out, J::sin),
        ("cos", None) => unary(xs, out, J::cos),
        _ => unreachable!("unknown operation {op}"),
    }
}

/// Times inari on `case` and compares with interval-core's results `ours`.
#[cfg(feature = "inari")]
fn inari_row(case: &Case, ours: &[I]) -> (Option<f64>, Option<Comparison>) {
    let xs = benches::to_inari(&case.xs);
    let ys = case.ys.as_deref().map(benches::to_inari);
    let mut out = vec![inari::Interval::EMPTY; xs.len()];
    let ns = best_ns(xs.len(), || inari_op(case.op, &xs, ys.as_deref(), &mut out));
    let cmp = benches::compare(ours, &out);
    if cmp.identical != cmp.total && (case.tight || cmp.incomparable > 0) {
        let mut shown = 0;
        for (i, (a, b)) in ours.iter().zip(&out).enumerate() {
            let b_bounds = (!b.is_empty()).then(|| (b.inf(), b.sup()));
            if a.bounds() != b_bounds && shown < 5 {
                let y = case.ys.as_ref().map(|ys| format!(", {:?}", ys[i].bounds()));
                println!(
                    "  mismatch {}: x = {:?}{}: core {:?}, inari {:?}",
                    case.op,
                    case.xs[i].bounds(),
                    y.unwrap_or_default(),
                    a.bounds(),
                    b_bounds
                );
                shown += 1;
            }
        }
    }
    (Some(ns), Some(cmp))
}

#[cfg(not(feature = "inari"))]
fn inari_row(_: &Case, _: &[I]) -> (Option<f64>, Option<Comparison>) {
    (None, None)
}

fn main() {
    let n = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("N must be a number"))
        .unwrap_or(N);
    let (xs, ys) = binary_operands(n);
    let positive = intervals(Domain::Positive, n, SEED);
    let exp_args = intervals(Domain::Exp, n, SEED);
    let sin_args = intervals(Domain::Sin, n, SEED);

    println!(
        "intervals per workload: {n}; target features: fma = {}, avx2 = {}, avx512f = {}; \
         inari comparison: {}\n",
        cfg!(target_feature = "fma"),
        cfg!(target_feature = "avx2"),
        cfg!(target_feature = "avx512f"),
        cfg!(feature = "inari"),
    );

    let case = |op, tight, xs: &Vec<I>, ys: Option<&Vec<I>>| Case {
        op,
        tight,
        xs: xs.clone(),
        ys: ys.cloned(),
    };
    let cases = [
        case("add", true, &xs, Some(&ys)),
        case("sub", true, &xs, Some(&ys)),
        case("mul", true, &xs, Some(&ys)),
        case("div", true, &xs, Some(&ys)),
        case("sqr", true, &xs, None),
        case("sqrt", true, &positive, None),
        case("pown(3)", false, &xs, None),
        case("exp", false, &exp_args, None),
        case("ln", false, &positive, None),
        case("sin", false, &sin_args, None),
        case("cos", false, &sin_args, None),
    ];

    let mut out = vec![I::EMPTY; n];
    let mut rows = Vec::new();
    for c in &cases {
        let core_ns = best_ns(n, || core_op(c, &mut out));
        let (inari_ns, cmp) = inari_row(c, &out);
        rows.push(Row {
            op: c.op,
            tight: c.tight,
            core_ns,
            inari_ns,
            cmp,
        });
    }

    println!();
    if cfg!(feature = "inari") {
        println!(
            "| operation | interval-core ns/op | inari ns/op | ratio (core/inari) | results identical? |"
        );
        println!("|---|---:|---:|---:|---|");
    } else {
        println!("| operation | interval-core ns/op |");
        println!("|---|---:|");
    }
    for r in &rows {
        let name = format!("{}{}", r.op, if r.tight { " (tight)" } else { "" });
        match r.inari_ns {
            Some(t) => println!(
                "| {name} | {:.2} | {t:.2} | {:.2} | {} |",
                r.core_ns,
                r.core_ns / t,
                describe(r)
            ),
            None => println!("| {name} | {:.2} |", r.core_ns),
        }
    }

    // Batch operations against the scalar loop over the same operators.
    type Batch2 = fn(&[I], &[I], &mut [I]) -> Result<(), interval_core::IntervalError>;
    type Batch1 = fn(&[I], &mut [I]) -> Result<(), interval_core::IntervalError>;
    let batch2: [(&str, Batch2); 4] = [
        ("add", batch::add),
        ("sub", batch::sub),
        ("mul", batch::mul),
        ("div", batch::div),
    ];
    let batch1: [(&str, &[I], Batch1); 2] =
        [("sqr", &xs, batch::sqr), ("sqrt", &positive, batch::sqrt)];
    println!();
    println!("| batch operation | scalar loop ns/op | batch ns/op | speed-up | bit-identical? |");
    println!("|---|---:|---:|---:|---|");
    let mut reference = vec![I::EMPTY; n];
    for (name, f) in batch2 {
        let c = cases.iter().find(|c| c.op == name).expect("case exists");
        let scalar = best_ns(n, || core_op(c, &mut reference));
        let fast = best_ns(n, || {
            let (a, b) = black_box((&xs[..], &ys[..]));
            f(a, b, &mut out).expect("equal lengths");
            black_box(&mut out);
        });
        let (same, total) = bit_identical(&out, &reference);
        println!(
            "| batch::{name} | {scalar:.2} | {fast:.2} | {:.1}x | {} |",
            scalar / fast,
            if same == total {
                "yes".to_string()
            } else {
                format!("NO ({} differ)", total - same)
            }
        );
    }
    for (name, args, f) in batch1 {
        let c = cases.iter().find(|c| c.op == name).expect("case exists");
        let scalar = best_ns(n, || core_op(c, &mut reference));
        let fast = best_ns(n, || {
            f(black_box(args), &mut out).expect("equal lengths");
            black_box(&mut out);
        });
        let (same, total) = bit_identical(&out, &reference);
        println!(
            "| batch::{name} | {scalar:.2} | {fast:.2} | {:.1}x | {} |",
            scalar / fast,
            if same == total {
                "yes".to_string()
            } else {
                format!("NO ({} differ)", total - same)
            }
        );
    }
}
