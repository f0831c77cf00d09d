//! The thesis's Tables 7.1 and 7.2 in spirit (section 7.2.6): times, speed-up and
//! efficiency of `render-mpi` under `mpirun` with 1, 2, 4, … ranks, with and without load
//! balancing, against the sequential program (one process, one thread) and the shared-memory
//! render (one process, rayon), then per rank the busy, idle and communication times and
//! the matrix of who rendered which initial part (Fig. 7.4) for the largest run.
//!
//! ```text
//! cluster-tables [--scenes orthocircle,steiner,barth-sextic,weird] [--ranks 1,2,4]
//!                [--size 256] [--sizes weird=128] [--runs 3] [--threads 1]
//!                [--mpirun-args "--hostfile hosts"]
//! ```
//!
//! Each scene is a scene file (`scenes/NAME.toml` when it exists) or a catalog surface.
//! The tables are printed as Markdown; every run's JSON statistics are kept in `--out-dir`.

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use clap::Parser;
use serde_json::Value;

/// Speed-up and efficiency of the cluster renderer (thesis Tables 7.1-7.2).
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Scenes, comma-separated.
    #[arg(long, default_value = "orthocircle,steiner,barth-sextic,weird")]
    scenes: String,
    /// Rank counts, comma-separated.
    #[arg(long, default_value = "1,2,4")]
    ranks: String,
    /// Image side in pixels.
    #[arg(long, default_value_t = 256)]
    size: u32,
    /// Image sides of particular scenes, e.g. `weird=128` (comma-separated).
    #[arg(long, default_value = "")]
    sizes: String,
    /// Runs of each configuration (mean and standard deviation).
    #[arg(long, default_value_t = 3)]
    runs: usize,
    /// Rayon threads per rank.
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Extra arguments for mpirun (e.g. a hostfile), split at spaces.
    #[arg(long, default_value = "")]
    mpirun_args: String,
    /// Where the images and JSON statistics go.
    #[arg(long, default_value = "cluster-tables")]
    out_dir: PathBuf,
}

fn main() -> ExitCode {
    match run(&Args::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `render-mpi`, next to this program.
fn render_mpi() -> Result<PathBuf, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let bin = exe.with_file_name("render-mpi");
    if bin.exists() {
        Ok(bin)
    } else {
        Err(format!(
            "{} not found: build it with `cargo build --release -p beam-cluster --features mpi`",
            bin.display()
        ))
    }
}

/// Mean and standard deviation.
fn stats(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (mean, var.sqrt())
}

/// One configuration: a command and its JSON statistics.
struct Job<'a> {
    scene: &'a str,
    size: u32,
    ranks: Option<usize>,
    balance: bool,
    threads: usize,
}

impl Job<'_> {
    fn label(&self) -> String {
        match self.ranks {
            None => format!("single-{}t", self.threads),
            Some(p) => format!("{p}r-{}", if self.balance { "lb" } else { "nolb" }),
        }
    }

    fn run(&self, args: &Args, bin: &Path, k: usize) -> Result<Value, String> {
        let name = Path::new(self.scene)
            .file_stem()
            .map_or(self.scene.to_string(), |s| s.to_string_lossy().into_owned());
        let stem = args.out_dir.join(format!("{name}-{}-{k}", self.label()));
        let json = stem.with_extension("json");
        let mut cmd = match self.ranks {
            None => {
                let mut c = Command::new(bin);
                c.arg("--single");
                c
            }
            Some(p) => {
                let mut c = Command::new("mpirun");
                c.args([
                    "--allow-run-as-root",
                    "--oversubscribe",
                    "--bind-to",
                    "none",
                ]);
                c.args(args.mpirun_args.split_whitespace());
                c.arg("-np").arg(p.to_string()).arg(bin);
                if !self.balance {
                    c.arg("--no-balance");
                }
                c
            }
        };
        cmd.arg(self.scene)
            .args(["--width", &self.size.to_string()])
            .args(["--height", &self.size.to_string()])
            .args(["--threads", &self.threads.to_string(), "--quiet"])
            .arg("--out")
            .arg(stem.with_extension("png"))
            .arg("--stats")
            .arg(&json);
        let out = cmd
            .output()
            .map_err(|e| format!("{:?}: {e}", cmd.get_program()))?;
        if !out.status.success() {
            return Err(format!(
                "{} {}: {}{}",
                self.scene,
                self.label(),
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        let text =
            std::fs::read_to_string(&json).map_err(|e| format!("{}: {e}", json.display()))?;
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", json.display()))
    }
}

fn seconds(v: &Value) -> f64 {
    v.as_f64().unwrap_or(f64::NAN)
}

fn run(args: &Args) -> Result<(), String> {
    let bin = render_mpi()?;
    std::fs::create_dir_all(&args.out_dir).map_err(|e| e.to_string())?;
    let ranks: Vec<usize> = args
        .ranks
        .split(',')
        .map(|r| r.trim().parse().map_err(|_| format!("--ranks: {r}")))
        .collect::<Result<_, _>>()?;
    let mut sizes = std::collections::HashMap::new();
    for kv in args.sizes.split(',').filter(|s| !s.is_empty()) {
        let (k, v) = kv.split_once('=').ok_or(format!("--sizes: {kv}"))?;
        sizes.insert(
            k.to_string(),
            v.parse::<u32>().map_err(|_| format!("--sizes: {kv}"))?,
        );
    }
    let runs = args.runs.max(1);
    let mut table = String::from(
        "| scene | size | one process, 1 thread s | one process, rayon s | ranks | balancing | time s | S_p | E_p % |\n\
         |---|---:|---:|---:|---:|---|---:|---:|---:|\n",
    );
    let mut details = String::new();
    for name in args.scenes.split(',').map(str::trim) {
        let file = format!("scenes/{name}.toml");
        let scene = if Path::new(&file).exists() {
            file.as_str()
        } else {
            name
        };
        let size = sizes.get(name).copied().unwrap_or(args.size);
        let job = |ranks, balance, threads| Job {
            scene,
            size,
            ranks,
            balance,
            threads,
        };
        let measure = |j: Job| -> Result<(Vec<f64>, Value), String> {
            let mut times = Vec::new();
            let mut last = Value::Null;
            for k in 0..runs {
                let v = j.run(args, &bin, k)?;
                times.push(seconds(&v["render"]["total"]));
                last = v;
            }
            eprintln!("{name} {}: {:?}", j.label(), times);
            Ok((times, last))
        };
        let (t1, _) = measure(job(None, true, 1))?;
        let (tr, _) = measure(job(None, true, args.threads.max(2)))?;
        let (t1m, t1s) = stats(&t1);
        let (trm, trs) = stats(&tr);
        for &p in &ranks {
            for balance in [true, false] {
                if p == 1 && !balance {
                    continue;
                }
                let (tp, last) = measure(job(Some(p), balance, args.threads))?;
                let (m, s) = stats(&tp);
                let speedup = t1m / m;
                table.push_str(&format!(
                    "| {name} | {size} | {t1m:.2} ± {t1s:.2} | {trm:.2} ± {trs:.2} | {p} | {} | {m:.2} ± {s:.2} | {speedup:.2} | {:.1} |\n",
                    if balance { "on" } else { "off" },
                    100.0 * speedup / (p * args.threads) as f64
                ));
                if p == *ranks.iter().max().expect("a rank count") {
                    details.push_str(&rank_details(name, balance, &last));
                }
            }
        }
    }
    println!("{table}");
    println!("{details}");
    Ok(())
}

/// Per rank busy, idle and communication time, and the origin matrix, of one run.
fn rank_details(scene: &str, balance: bool, v: &Value) -> String {
    let c = &v["cluster"];
    let mut s = format!(
        "\n{scene}, balancing {}: per rank (last run)\n\n\
         | rank | busy s | idle s | comm. s | last box s | boxes | asked | refused | given | received | bytes sent |\n\
         |---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
        if balance { "on" } else { "off" }
    );
    for r in c["ranks"].as_array().into_iter().flatten() {
        let n = |k: &str| r[k].as_u64().unwrap_or(0);
        s.push_str(&format!(
            "| {} | {:.3} | {:.3} | {:.3} | {:.3} | {} | {} | {} | {} | {} | {} |\n",
            n("rank"),
            seconds(&r["busy"]),
            seconds(&r["idle"]),
            seconds(&r["communication"]),
            seconds(&r["last_box"]),
            n("boxes"),
            n("requests"),
            n("refusals"),
            n("boxes_given"),
            n("boxes_received"),
            n("bytes")
        ));
    }
    let origins = c["origins"].as_array().cloned().unwrap_or_default();
    s.push_str(
        "\nboxes rendered by rank (rows) from each rank's initial part (columns)\n\n| rank |",
    );
    for o in 0..origins.len() {
        s.push_str(&format!(" part {o} |"));
    }
    s.push_str(&format!("\n|---:|{}\n", "---:|".repeat(origins.len())));
    for (r, row) in origins.iter().enumerate() {
        s.push_str(&format!("| {r} |"));
        for n in row.as_array().into_iter().flatten() {
            s.push_str(&format!(" {} |", n.as_u64().unwrap_or(0)));
        }
        s.push('\n');
    }
    s
}
