//! Renders a scene on a cluster: one MPI rank per node (or per core), the screen boxes
//! shared among the ranks with the thesis's load balancing, the image assembled on rank 0
//! equal bit for bit to a single process's.
//!
//! ```text
//! mpirun -np 4 render-mpi [SCENE] [--out FILE.png] [--width W --height H] [--threads N]
//!        [--box-threads N]
//!        [--primary MODE] [--shadows METHOD] [--no-balance] [--threshold 2] [--fraction 0.4]
//!        [--unit 64] [--initial equal|rank:R] [--timeout S] [--stats FILE.json]
//!        [--fingerprint] [--quiet]
//! render-mpi --local 4 [...]     four ranks as threads of one process, no MPI
//! render-mpi --single [...]      the plain render of one process (the baseline)
//! ```
//!
//! `SCENE` is a TOML scene file or the name of a catalog surface (the built-in default
//! scene when absent). Rank 0 writes the image and prints the per-pass table and the
//! cluster's report: per rank busy, idle and communication time, requests and donations,
//! and which rank rendered the boxes of which initial part.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use beam_cluster::transport::Mpi;
use beam_cluster::{
    ClusterReport, Fault, Initial, RankOptions, Settings, render_local_with, run_rank,
};
use beam_trace::image::check_writable;
use beam_trace::render::Pipeline;
use beam_trace::scene::PrimaryMode;
use beam_trace::shadow::ShadowSpec;
use beam_trace::{Cpu, NoProgress, Plan, Progress, RenderOutput, Scene, render};
use clap::Parser;
use mpi::Threading;

/// Reliable rendering of implicit surfaces on a cluster (MPI).
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Scene file (TOML) or catalog surface name; the built-in default scene when absent.
    scene: Option<String>,
    /// Output image (written by rank 0).
    #[arg(long, default_value = "render.png")]
    out: PathBuf,
    /// Image width (the scene's when absent).
    #[arg(long)]
    width: Option<u32>,
    /// Image height (the scene's when absent).
    #[arg(long)]
    height: Option<u32>,
    /// Rayon threads per rank (rayon's default when absent).
    #[arg(long)]
    threads: Option<usize>,
    /// Threads per rank that take boxes from its list, each rendering a box at a time on
    /// the rank's rayon threads (the thesis: one per processor).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=256))]
    box_threads: u32,
    /// Primary visibility mode (the scene's when absent).
    #[arg(long)]
    primary: Option<PrimaryMode>,
    /// Soft-shadow method (the scene's when absent).
    #[arg(long)]
    shadows: Option<ShadowSpec>,
    /// Each rank renders its initial part alone (no requests, no donations).
    #[arg(long)]
    no_balance: bool,
    /// A rank asks for boxes when its list holds fewer than this many.
    #[arg(long, default_value_t = 2)]
    threshold: usize,
    /// The share of its boxes a rank gives to one that asks.
    #[arg(long, default_value_t = 0.4)]
    fraction: f64,
    /// Side of the final boxes in pixels, a multiple of the plan's window grid (32 pixels
    /// for the screen boxes, 64 for the octree; the grid itself when absent).
    #[arg(long)]
    unit: Option<u32>,
    /// Where the work starts: `equal` (one part per rank) or `rank:R` (all on rank R).
    #[arg(long, default_value = "equal")]
    initial: String,
    /// Seconds of silence after which a rank is reported dead.
    #[arg(long, default_value_t = 60.0)]
    timeout: f64,
    /// Writes the render's statistics and the cluster's report as JSON (rank 0).
    #[arg(long)]
    stats: Option<PathBuf>,
    /// Prints the render's fingerprint (what must equal a single process's).
    #[arg(long)]
    fingerprint: bool,
    /// Ranks as threads of this process, joined by channels, without MPI.
    #[arg(long, conflicts_with = "single")]
    local: Option<usize>,
    /// The plain render of one process, without the cluster (the baseline).
    #[arg(long)]
    single: bool,
    /// No progress on the terminal.
    #[arg(long)]
    quiet: bool,
    /// Test only: rank R stops dead after rendering N boxes (`R:N`).
    #[arg(long, hide = true)]
    fault: Option<String>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    if args.single || args.local.is_some() {
        return match run_here(&args) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        };
    }
    let Some((universe, threading)) = mpi::initialize_with_threading(Threading::Funneled) else {
        eprintln!("error: MPI could not be initialized");
        return ExitCode::FAILURE;
    };
    let mpi = Mpi::new(universe.world());
    if threading < Threading::Funneled {
        eprintln!("error: the MPI library gives no thread support (MPI_THREAD_FUNNELED needed)");
        mpi.abort(1)
    }
    match run_mpi(&args, &mpi) {
        Ok(()) => {
            // Every rank has finished before any finalizes.
            mpi.barrier();
            ExitCode::SUCCESS
        }
        Err(Failure::Fault) => {
            // A process killed by a signal: no word to the others, no MPI_Finalize.
            std::process::abort()
        }
        Err(Failure::Other(e)) => {
            eprintln!("error: {e}");
            let _ = std::io::stderr().flush();
            mpi.abort(1)
        }
    }
}

enum Failure {
    Fault,
    Other(String),
}

impl From<String> for Failure {
    fn from(e: String) -> Self {
        Failure::Other(e)
    }
}

fn scene_of(args: &Args) -> Result<Scene, String> {
    let mut scene = match &args.scene {
        None => Scene::default_scene(),
        Some(s) if Path::new(s).exists() => Scene::load(Path::new(s)).map_err(|e| e.to_string())?,
        Some(s) if !s.ends_with(".toml") => {
            Scene::catalog(s, 512, 512).map_err(|e| e.to_string())?
        }
        Some(s) => return Err(format!("{s}: no such scene file")),
    };
    if args.width.is_some() || args.height.is_some() {
        let w = args.width.unwrap_or(scene.camera.width());
        let h = args.height.unwrap_or(scene.camera.height());
        if !(1..=16384).contains(&w) || !(1..=16384).contains(&h) {
            return Err("--width and --height must lie in 1..=16384".into());
        }
        scene.camera = scene.camera.resized(w, h).map_err(|e| e.to_string())?;
    }
    if let Some(p) = args.primary {
        scene.settings.primary = p;
    }
    if let Some(m) = args.shadows {
        scene.settings.shadow_method = m;
    }
    Ok(scene)
}

fn settings_of(args: &Args) -> Result<Settings, String> {
    let initial = match args.initial.as_str() {
        "equal" => Initial::Equal,
        s => match s.strip_prefix("rank:").map(str::parse) {
            Some(Ok(r)) => Initial::OnRank(r),
            _ => return Err(format!("--initial {s}: expected `equal` or `rank:R`")),
        },
    };
    if !(args.timeout > 0.0 && args.timeout.is_finite()) {
        return Err("--timeout must be a positive number of seconds".into());
    }
    Ok(Settings {
        balance: !args.no_balance,
        threshold: args.threshold,
        fraction: args.fraction,
        unit: args.unit,
        initial,
        timeout: Duration::from_secs_f64(args.timeout),
        heartbeat: Duration::from_secs_f64((args.timeout / 8.0).min(0.25)),
    })
}

fn fault_of(args: &Args) -> Result<Option<Fault>, String> {
    let Some(f) = &args.fault else {
        return Ok(None);
    };
    let parsed = f
        .split_once(':')
        .and_then(|(r, n)| Some((r.parse().ok()?, n.parse().ok()?)));
    match parsed {
        Some((rank, after)) => Ok(Some(Fault { rank, after })),
        None => Err(format!("--fault {f}: expected R:N")),
    }
}

/// Rank 0's progress: a line per tenth of the pixels.
struct Lines {
    total: AtomicU64,
    done: AtomicU64,
    quiet: bool,
}

impl Progress for Lines {
    fn begin(&self, _pass: &str, total: u64) {
        self.total.store(total, Ordering::Relaxed);
        self.done.store(0, Ordering::Relaxed);
    }

    fn advance(&self, n: u64) {
        let total = self.total.load(Ordering::Relaxed).max(1);
        let before = self.done.fetch_add(n, Ordering::Relaxed);
        let (a, b) = (before * 10 / total, (before + n) * 10 / total);
        if b > a && !self.quiet {
            eprintln!("  {} % of the pixels rendered", b * 10);
        }
    }
}

fn run_mpi(args: &Args, mpi: &Mpi) -> Result<(), Failure> {
    use beam_cluster::transport::Transport;
    let scene = scene_of(args)?;
    let settings = settings_of(args)?;
    let fault = fault_of(args)?;
    let rank = mpi.rank();
    if rank == 0 {
        check_outputs(args)?;
        println!(
            "scene {}: {} x {} pixels on {} ranks",
            scene.name,
            scene.camera.width(),
            scene.camera.height(),
            mpi.size()
        );
    }
    // From here on, as the single-process render's total.
    let started = Instant::now();
    let plan = Plan::for_scene(&scene);
    let pipeline = Pipeline::new(&scene, &Cpu, &plan).map_err(|e| e.to_string())?;
    let progress = Lines {
        total: AtomicU64::new(0),
        done: AtomicU64::new(0),
        quiet: args.quiet,
    };
    let options = RankOptions {
        render_threads: args.box_threads as usize,
        threads: args.threads.unwrap_or(0),
        progress: &progress,
        fault,
        started,
    };
    match run_rank(mpi, &pipeline, &settings, &options) {
        Ok(Some(g)) => write_outputs(args, &g.output, Some(&g.report)).map_err(Failure::Other),
        Ok(None) => Ok(()),
        Err(beam_cluster::Error::Failed { message, .. })
            if message == beam_cluster::station::FAULT_MESSAGE =>
        {
            Err(Failure::Fault)
        }
        Err(e) => Err(Failure::Other(format!("rank {rank}: {e}"))),
    }
}

fn run_here(args: &Args) -> Result<(), String> {
    let scene = scene_of(args)?;
    check_outputs(args)?;
    if args.single {
        if let Some(n) = args.threads {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n.max(1))
                .build_global()
                .map_err(|e| e.to_string())?;
        }
        println!(
            "scene {}: {} x {} pixels, one process",
            scene.name,
            scene.camera.width(),
            scene.camera.height()
        );
        let out = render(&scene, &NoProgress).map_err(|e| e.to_string())?;
        return write_outputs(args, &out, None);
    }
    let ranks = args.local.unwrap_or(1);
    let settings = settings_of(args)?;
    let fault = fault_of(args)?;
    let threads = args.threads.unwrap_or(0);
    println!(
        "scene {}: {} x {} pixels on {ranks} ranks (threads of one process)",
        scene.name,
        scene.camera.width(),
        scene.camera.height()
    );
    let render_threads = args.box_threads as usize;
    let (out, report) = render_local_with(&scene, ranks, &settings, &|_| RankOptions {
        render_threads,
        threads,
        fault,
        ..RankOptions::default()
    })
    .map_err(|e| e.to_string())?;
    write_outputs(args, &out, Some(&report))
}

fn check_outputs(args: &Args) -> Result<(), String> {
    for p in [Some(&args.out), args.stats.as_ref()].into_iter().flatten() {
        check_writable(p).map_err(|e| format!("cannot write output: {e}"))?;
    }
    Ok(())
}

fn write_outputs(
    args: &Args,
    out: &RenderOutput,
    report: Option<&ClusterReport>,
) -> Result<(), String> {
    out.image.write_png(&args.out).map_err(|e| e.to_string())?;
    println!("{}", out.stats);
    if let Some(r) = report {
        println!("{r}");
    }
    if args.fingerprint {
        println!("fingerprint: {:016x}", out.fingerprint());
    }
    if let Some(path) = &args.stats {
        let json = serde_json::json!({
            "render": out.stats,
            "cluster": report,
            "fingerprint": format!("{:016x}", out.fingerprint()),
        });
        let text = serde_json::to_string_pretty(&json).map_err(|e| e.to_string())?;
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    println!("wrote {}", args.out.display());
    Ok(())
}
