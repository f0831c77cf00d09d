//! Compares the root finders of `beam-trace` on the catalog surfaces, as thesis Table 4.1
//! does: primary rays only, one per pixel, every method on the same rays.
//!
//! Each surface is seen from the direction `(1, 0.8, 2.2)` at the distance where the
//! bounding sphere of its box fills the 40° field of view; each ray is clipped to the box
//! (a slab test) and its first root searched in the parameter range inside it. The tables
//! give, per method (rows) and surface (columns), the time of casting all rays in
//! milliseconds (rayon over rows: the time depends on the threads, the results do not),
//! the interval evaluations of `g` and `g'`, the point evaluations, the bisections, the
//! searches escalated to double-double because rounding kept them open (and how many of
//! those ended proven; `--no-escalate` turns escalation off), the hits and the undecided
//! rays. Then every pixel is checked: all reliable methods must agree on
//! hit or miss (undecided answers are counted apart) and their first-root enclosures must
//! overlap once widened by `ε`. Each disagreement is listed, marked as a *contradiction*
//! when the answers cannot both be true (a proven root against "no root", or a proven root
//! lying before another method's first possible root) and as a *possible-root difference*
//! otherwise (one method could not reject a piece that another rejected).
//!
//! ```text
//! cargo run --release -p examples --bin root-finders
//! cargo run --release -p examples --bin root-finders -- --size 300 --surfaces sphere,drop
//! cargo run --release -p examples --bin root-finders -- --epsilon 1e-4 --surfaces all
//! ```

use std::fmt::Write as _;
use std::process::ExitCode;
use std::time::Instant;

use beam_trace::ray::BeamEval;
use beam_trace::root::{
    Escalating, Proof, RootCounters, RootFinder, RootMethod, RootResult, RootSettings,
};
use clap::Parser;
use examples::catalog_view::{CatalogView, TABLE_4_1};
use implicit_expr::catalog;
use rayon::prelude::*;

/// Times the root finders on catalog surfaces and checks that the reliable ones agree.
#[derive(Parser, Debug)]
#[command(name = "root_finders")]
struct Args {
    /// Image width and height in pixels (one primary ray per pixel).
    #[arg(long, default_value_t = 100)]
    size: u32,
    /// Catalog surfaces, comma-separated, or `all` (default: the eight of Table 4.1).
    #[arg(long, value_delimiter = ',')]
    surfaces: Vec<String>,
    /// Root enclosure width ε.
    #[arg(long, default_value_t = RootSettings::default().epsilon)]
    epsilon: f64,
    /// Largest number of subdivisions per ray.
    #[arg(long, default_value_t = RootSettings::default().max_steps)]
    max_steps: u64,
    /// Methods, comma-separated (default: all).
    #[arg(long, value_delimiter = ',')]
    methods: Vec<RootMethod>,
    /// Lipschitz bound of the sphere-tracing baseline.
    #[arg(long, default_value_t = RootSettings::default().lipschitz)]
    lipschitz: f64,
    /// Sampling step of the point-sampling baseline, as a fraction of the ray's range.
    #[arg(long, default_value_t = RootSettings::default().sampling_step)]
    sampling_step: f64,
    /// Do not run searches that end open because of rounding again in double-double.
    #[arg(long)]
    no_escalate: bool,
    /// Most disagreements listed (default: every one).
    #[arg(long, default_value_t = u64::MAX)]
    max_listed: u64,
}

/// The answers of one method on one surface.
struct Run {
    results: Vec<RootResult>,
    counters: RootCounters,
    ms: f64,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("root_finders: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> Result<(), Box<dyn std::error::Error>> {
    if args.size == 0 {
        return Err("--size must be at least 1".into());
    }
    if args.epsilon.is_nan() || args.epsilon < 0.0 {
        return Err("--epsilon must be a number ≥ 0".into());
    }
    let names: Vec<&'static str> = match args.surfaces.as_slice() {
        [] => TABLE_4_1.to_vec(),
        [all] if all == "all" => {
            let mut v = TABLE_4_1.to_vec();
            v.extend(catalog::names().filter(|n| !TABLE_4_1.contains(n)));
            v
        }
        list => list
            .iter()
            .map(|n| catalog::get(n).map(|s| s.name))
            .collect::<Result<_, _>>()?,
    };
    let methods: Vec<RootMethod> = if args.methods.is_empty() {
        RootMethod::ALL.to_vec()
    } else {
        args.methods.clone()
    };
    let settings = RootSettings {
        epsilon: args.epsilon,
        max_steps: args.max_steps,
        sampling_step: args.sampling_step,
        lipschitz: args.lipschitz,
        escalate: !args.no_escalate,
        ..RootSettings::default()
    };
    let setups: Vec<CatalogView> = names
        .iter()
        .map(|n| CatalogView::new(n, args.size))
        .collect::<Result<_, _>>()?;

    // runs[s][m]: surface s, method m.
    let mut runs: Vec<Vec<Run>> = Vec::new();
    for s in &setups {
        let mut row = Vec::new();
        for &m in &methods {
            row.push(cast(s, m, &settings));
        }
        runs.push(row);
    }

    let rays = u64::from(args.size) * u64::from(args.size);
    println!(
        "Root finders on {} × {} primary rays per surface (ε = {:e}, max {} steps, {} threads)\n",
        args.size,
        args.size,
        settings.epsilon,
        settings.max_steps,
        rayon::current_num_threads()
    );
    let cols: Vec<&str> = setups.iter().map(|s| s.name).collect();
    let table = |title: &str, cell: &dyn Fn(&Run) -> String| {
        print_table(title, &cols, &methods, &runs, cell);
    };
    table("Time (ms)", &|r| format!("{:.1}", r.ms));
    table("Interval evaluations of g", &|r| {
        r.counters.g_evals.to_string()
    });
    table("Interval evaluations of g' (with g)", &|r| {
        r.counters.dg_evals.to_string()
    });
    table("Point evaluations of g", &|r| {
        r.counters.point_evals.to_string()
    });
    table("Bisections", &|r| r.counters.bisections.to_string());
    table("Escalated to double-double (resolved there)", &|r| {
        format!(
            "{} ({})",
            r.counters.escalated, r.counters.escalated_resolved
        )
    });
    table(&format!("Hits (of {rays} rays)"), &|r| {
        r.results
            .iter()
            .filter(|x| matches!(x, RootResult::Root { .. }))
            .count()
            .to_string()
    });
    table("Undecided rays", &|r| {
        r.results
            .iter()
            .filter(|x| matches!(x, RootResult::Undecided { .. }))
            .count()
            .to_string()
    });

    agreement(
        &setups,
        &methods,
        &runs,
        &settings,
        args.size,
        args.max_listed,
    );
    Ok(())
}

/// Casts one ray per pixel of `s` with method `m`: the answers in row-major order, the
/// summed counters and the wall time.
fn cast(s: &CatalogView, m: RootMethod, settings: &RootSettings) -> Run {
    let finder = Escalating::new(m.finder());
    let (w, h) = (s.camera.width(), s.camera.height());
    let start = Instant::now();
    let rows: Vec<(Vec<RootResult>, RootCounters)> = (0..h)
        .into_par_iter()
        .map_init(
            || BeamEval::new(s.geometry.ray_function()),
            |ev, j| {
                let mut counters = RootCounters::default();
                let row = (0..w)
                    .map(|i| {
                        let (ray, t) = s.ray(i, j);
                        match t {
                            None => RootResult::NoRoot,
                            Some(t) => {
                                ev.set_ray(&ray);
                                finder.first_root(ev, t, settings, &mut counters)
                            }
                        }
                    })
                    .collect();
                (row, counters)
            },
        )
        .collect();
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let mut counters = RootCounters::default();
    let mut results = Vec::with_capacity((w * h) as usize);
    for (row, c) in rows {
        results.extend(row);
        counters.add(&c);
    }
    Run {
        results,
        counters,
        ms,
    }
}

/// Prints one table: methods as rows, surfaces as columns, in blocks of at most 8 columns.
fn print_table(
    title: &str,
    cols: &[&str],
    methods: &[RootMethod],
    runs: &[Vec<Run>],
    cell: &dyn Fn(&Run) -> String,
) {
    println!("{title}");
    let first = methods
        .iter()
        .map(|m| m.name().len())
        .max()
        .unwrap_or(6)
        .max(6);
    for block in (0..cols.len()).collect::<Vec<_>>().chunks(8) {
        let cells: Vec<Vec<String>> = methods
            .iter()
            .enumerate()
            .map(|(mi, _)| block.iter().map(|&s| cell(&runs[s][mi])).collect())
            .collect();
        let widths: Vec<usize> = block
            .iter()
            .enumerate()
            .map(|(k, &s)| {
                cells
                    .iter()
                    .map(|r| r[k].len())
                    .chain([cols[s].len()])
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let mut line = format!("{:first$}", "method");
        for (k, &s) in block.iter().enumerate() {
            let _ = write!(line, "  {:>w$}", cols[s], w = widths[k]);
        }
        println!("{line}");
        for (mi, m) in methods.iter().enumerate() {
            let mut line = format!("{:first$}", m.name());
            for (k, c) in cells[mi].iter().enumerate() {
                let _ = write!(line, "  {:>w$}", c, w = widths[k]);
            }
            println!("{line}");
        }
    }
    println!();
}

/// A short text for one answer.
fn show(r: &RootResult) -> String {
    match r {
        RootResult::Root { t, proof } => {
            let p = match proof {
                Proof::Unique => "unique",
                Proof::Exists => "exists",
                Proof::Possible => "possible",
            };
            format!("hit [{:.9}, {:.9}] {p}", t.inf(), t.sup())
        }
        RootResult::NoRoot => "miss".into(),
        RootResult::Undecided { t } => format!("undecided from {:.9}", t.inf()),
    }
}

/// Whether the answers `a` and `b` of two reliable methods cannot both be true: a proven
/// root against "no root", or a proven root ending before the other's first possible root
/// (which claims that nothing before it is a root).
fn contradict(a: &RootResult, b: &RootResult) -> bool {
    let proven = |r: &RootResult| match *r {
        RootResult::Root { t, proof } if proof != Proof::Possible => Some(t),
        _ => None,
    };
    let start = |r: &RootResult| match *r {
        RootResult::Root { t, .. } | RootResult::Undecided { t } => t.inf(),
        RootResult::NoRoot => f64::INFINITY,
    };
    let one = |x: &RootResult, y: &RootResult| proven(x).is_some_and(|t| t.sup() < start(y));
    one(a, b) || one(b, a)
}

/// Whether two decided answers agree: both misses, or both hits whose enclosures overlap
/// once widened by `eps`.
fn agree(a: &RootResult, b: &RootResult, eps: f64) -> bool {
    match (a, b) {
        (RootResult::NoRoot, RootResult::NoRoot) => true,
        (RootResult::Root { t: x, .. }, RootResult::Root { t: y, .. }) => {
            x.inf() - eps <= y.sup() + eps && y.inf() - eps <= x.sup() + eps
        }
        _ => false,
    }
}

/// Checks every pixel: the reliable methods' answers must agree on hit or miss and their
/// enclosures overlap when widened by ε. Lists the disagreements (one line each, methods
/// with identical answers grouped; at most `max_listed`), counts per method how often it
/// is the odd one out (disagreeing with most of the others), and compares the baselines
/// with the reliable methods' common answer.
fn agreement(
    setups: &[CatalogView],
    methods: &[RootMethod],
    runs: &[Vec<Run>],
    settings: &RootSettings,
    size: u32,
    max_listed: u64,
) {
    let reliable: Vec<usize> = (0..methods.len())
        .filter(|&k| methods[k].finder().is_reliable())
        .collect();
    let baselines: Vec<usize> = (0..methods.len())
        .filter(|&k| !methods[k].finder().is_reliable())
        .collect();
    let eps = settings.epsilon;
    let mut pixels = 0u64;
    let mut disagree = 0u64;
    let mut contradictions = 0u64;
    let mut undecided = vec![0u64; methods.len()];
    let mut odd = vec![0u64; methods.len()];
    // Per baseline: pixels where the reliable methods agree and the baseline's hit/miss
    // differs (missed hits, false hits).
    let mut baseline_diff = vec![(0u64, 0u64); methods.len()];
    let mut lines = Vec::new();
    for (si, s) in setups.iter().enumerate() {
        for p in 0..(size as usize * size as usize) {
            pixels += 1;
            let answers: Vec<(usize, &RootResult)> = reliable
                .iter()
                .map(|&k| (k, &runs[si][k].results[p]))
                .collect();
            let decided: Vec<(usize, &RootResult)> = answers
                .iter()
                .copied()
                .filter(|(_, r)| !matches!(r, RootResult::Undecided { .. }))
                .collect();
            for &(k, r) in &answers {
                if matches!(r, RootResult::Undecided { .. }) {
                    undecided[k] += 1;
                }
            }
            // Disagreements of each decided method with the others.
            let against: Vec<usize> = decided
                .iter()
                .map(|(_, a)| decided.iter().filter(|(_, b)| !agree(a, b, eps)).count())
                .collect();
            let contra = answers
                .iter()
                .enumerate()
                .any(|(i, (_, a))| answers[i + 1..].iter().any(|(_, b)| contradict(a, b)));
            if against.iter().all(|&n| n == 0) && !contra {
                if let Some(&(_, common)) = decided.first() {
                    let hit = matches!(common, RootResult::Root { .. });
                    for &k in &baselines {
                        match (
                            hit,
                            matches!(runs[si][k].results[p], RootResult::Root { .. }),
                        ) {
                            (true, false) => baseline_diff[k].0 += 1,
                            (false, true) => baseline_diff[k].1 += 1,
                            _ => {}
                        }
                    }
                }
                continue;
            }
            disagree += 1;
            contradictions += u64::from(contra);
            for (d, &(k, _)) in decided.iter().enumerate() {
                if 2 * against[d] > decided.len() - 1 {
                    odd[k] += 1;
                }
            }
            if (lines.len() as u64) < max_listed {
                let kind = if contra {
                    "CONTRADICTION"
                } else {
                    "possible-root difference"
                };
                // Methods with identical answers, grouped.
                let mut groups: Vec<(String, Vec<&str>)> = Vec::new();
                for &(k, r) in &answers {
                    let text = show(r);
                    match groups.iter_mut().find(|(t, _)| *t == text) {
                        Some((_, names)) => names.push(methods[k].name()),
                        None => groups.push((text, vec![methods[k].name()])),
                    }
                }
                let groups: Vec<String> = groups
                    .into_iter()
                    .map(|(text, names)| format!("{}: {text}", names.join(", ")))
                    .collect();
                let (x, y) = (p % size as usize, p / size as usize);
                lines.push(format!(
                    "  {} ({x}, {y}) {kind}: {}",
                    s.name,
                    groups.join("; ")
                ));
            }
        }
    }
    println!("Agreement of the reliable methods");
    if disagree == 0 {
        println!("  all reliable methods agree on {pixels} pixels");
    } else {
        println!(
            "  {disagree} of {pixels} pixels disagree ({contradictions} contradictions, {} \
             possible-root differences)",
            disagree - contradictions
        );
        for &k in &reliable {
            if odd[k] > 0 {
                println!(
                    "  {}: the odd one out on {} pixels",
                    methods[k].name(),
                    odd[k]
                );
            }
        }
        for l in &lines {
            println!("{l}");
        }
        if disagree > lines.len() as u64 {
            println!(
                "  ... {} more (raise --max-listed to see them)",
                disagree - lines.len() as u64
            );
        }
    }
    for &k in &reliable {
        if undecided[k] > 0 {
            println!("  {}: {} undecided rays", methods[k].name(), undecided[k]);
        }
    }
    for &k in &baselines {
        let (missed, false_hits) = baseline_diff[k];
        println!(
            "  baseline {}: {missed} hits missed, {false_hits} false hits (against the reliable \
             methods' common answer)",
            methods[k].name()
        );
    }
}
