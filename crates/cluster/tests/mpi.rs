//! The render-mpi program under `mpirun` on this machine (feature `mpi`): 1, 2 and 4 ranks
//! give the image and counters of the single-process render bit for bit (its fingerprint);
//! ranks that start with no work end with work done; a rank that dies mid-render ends the
//! job with an error within a bounded time.
#![cfg(feature = "mpi")]

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use beam_trace::{NoProgress, Scene, render};

const BIN: &str = env!("CARGO_BIN_EXE_render-mpi");

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn out_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("beam-cluster-mpi-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).expect("a temporary directory");
    d
}

/// `mpirun` with the flags a CI container needs (root, more ranks than cores) and no core
/// binding (each rank runs threads).
fn mpirun(ranks: usize) -> Command {
    let mut c = Command::new("mpirun");
    c.args([
        "--allow-run-as-root",
        "--oversubscribe",
        "--bind-to",
        "none",
        "-np",
    ])
    .arg(ranks.to_string())
    .arg(BIN);
    c
}

/// Runs `cmd` for at most `limit`, returning its status and output.
fn run_bounded(mut cmd: Command, limit: Duration) -> (Option<i32>, String, Duration) {
    let t0 = Instant::now();
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("mpirun starts (is Open MPI installed?)");
    loop {
        if let Some(_status) = child.try_wait().expect("waits") {
            let out = child.wait_with_output().expect("output");
            let text = format!(
                "{}{}",
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
            return (out.status.code(), text, t0.elapsed());
        }
        if t0.elapsed() > limit {
            let _ = child.kill();
            let out = child.wait_with_output().expect("output");
            panic!(
                "still running after {limit:?}: {}{}",
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

fn fingerprint_of(text: &str) -> String {
    text.lines()
        .find_map(|l| l.strip_prefix("fingerprint: "))
        .unwrap_or_else(|| panic!("no fingerprint in:\n{text}"))
        .trim()
        .to_string()
}

/// The scene arguments and the scene they give.
fn cases() -> Vec<(Vec<String>, Scene)> {
    let size = |mut s: Scene| {
        s.camera = s.camera.resized(200, 140).expect("a size");
        s
    };
    let soft = root().join("scenes/soft-shadows.toml");
    let mut soft_scene = size(Scene::load(&soft).expect("loads"));
    soft_scene.settings.shadow_method = "stochastic:8".parse().expect("a method");
    vec![
        (Vec::new(), size(Scene::default_scene())),
        (
            vec![
                soft.display().to_string(),
                "--shadows".into(),
                "stochastic:8".into(),
            ],
            soft_scene,
        ),
    ]
}

#[test]
fn one_two_and_four_ranks_render_the_single_process_image() {
    let dir = out_dir("same");
    for (k, (args, scene)) in cases().into_iter().enumerate() {
        let alone = format!(
            "{:016x}",
            render(&scene, &NoProgress).expect("renders").fingerprint()
        );
        for ranks in [1, 2, 4] {
            let mut cmd = mpirun(ranks);
            cmd.args(&args)
                .args([
                    "--width",
                    "200",
                    "--height",
                    "140",
                    "--fingerprint",
                    "--quiet",
                ])
                .arg("--out")
                .arg(dir.join(format!("case{k}-{ranks}.png")));
            if ranks == 2 {
                // Two render threads per rank, taking boxes concurrently.
                cmd.args(["--box-threads", "2"]);
            }
            let (code, text, _) = run_bounded(cmd, Duration::from_secs(600));
            assert_eq!(code, Some(0), "{text}");
            assert_eq!(
                fingerprint_of(&text),
                alone,
                "case {k}, {ranks} ranks:\n{text}"
            );
        }
    }
}

#[test]
fn ranks_without_work_at_the_start_end_with_work_done() {
    let dir = out_dir("balance");
    let stats = dir.join("stats.json");
    let mut cmd = mpirun(4);
    cmd.args([
        "--width",
        "256",
        "--height",
        "192",
        "--initial",
        "rank:0",
        "--quiet",
    ])
    .arg("--stats")
    .arg(&stats)
    .arg("--out")
    .arg(dir.join("balance.png"));
    let (code, text, _) = run_bounded(cmd, Duration::from_secs(600));
    assert_eq!(code, Some(0), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).expect("stats written"))
            .expect("JSON");
    let ranks = json["cluster"]["ranks"].as_array().expect("ranks");
    assert_eq!(ranks.len(), 4);
    for r in ranks {
        assert!(r["boxes"].as_u64().expect("boxes") > 0, "{text}");
    }
    for r in &ranks[1..] {
        assert!(
            r["boxes_received"].as_u64().expect("received") > 0,
            "{text}"
        );
    }
}

#[test]
fn a_rank_killed_mid_render_ends_the_job_with_an_error() {
    let dir = out_dir("fault");
    let out = dir.join("fault.png");
    let mut cmd = mpirun(3);
    cmd.args([
        "--width",
        "256",
        "--height",
        "192",
        "--timeout",
        "5",
        "--quiet",
    ])
    .args(["--fault", "1:1"])
    .arg("--out")
    .arg(&out);
    let (code, text, took) = run_bounded(cmd, Duration::from_secs(120));
    assert_ne!(code, Some(0), "the job must fail:\n{text}");
    assert!(took < Duration::from_secs(120));
    assert!(!Path::new(&out).exists(), "no image from a failed render");
}
