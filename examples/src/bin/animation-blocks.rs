//! The thesis's animation experiments (section 6.5) in spirit: three animations rendered
//! frame by frame and in blocks of `n` frames, the time per frame and the saving of the
//! blocks, side by side with the thesis's figures.
//!
//! ```text
//! animation-blocks [--frames 100] [--sizes 1,2,5,10] [--width 160] [--height 120]
//!                  [--threads 2] [--max-growth 2] [--adaptive] [--only NAME]
//!                  [--write-scenes DIR]
//!                  [--out FILE]
//! ```
//!
//! The animations (each a scene file written in the code; `--write-scenes DIR` saves them
//! to render with the `render` command):
//!
//! * `orthocircle`: the thesis's orthocircle with `a` and `b` changing, turning about two
//!   axes and drifting sideways (the thesis moves the camera; here the camera is still and
//!   the object moves, which the thesis says is the same);
//! * `spheres`: six spheres moving out from the centre along the axes;
//! * `morph`: chubs turning into McMullen's K3 surface, `(1 − s)·f_chubs + s·f_K3`, turning
//!   about `x` and `y`, its colour changing, under a moving light (the thesis's extreme case).
//!
//! Every block size renders every frame; the frames of each size are compared with those of
//! the first size bit for bit (the table's last column must be 0). The saving is given both
//! ways the thesis's chapters use: `1 − new/old` and `(old − new)/new`.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use beam_trace::backend::cpu::Cpu;
use beam_trace::blocks::{BlockReport, BlockSettings, Frames, render_blocks};
use beam_trace::scene::Animation;
use beam_trace::{Error, NoProgress, Pass, RenderOutput, Scene};
use clap::Parser;

/// Animations rendered frame by frame and in blocks of frames.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Frames of each animation.
    #[arg(long, default_value_t = 100)]
    frames: u32,
    /// Block sizes (the first is the reference the others are compared with).
    #[arg(long, value_delimiter = ',', default_values_t = [1, 2, 5, 10])]
    sizes: Vec<usize>,
    /// Image width.
    #[arg(long, default_value_t = 160)]
    width: u32,
    /// Image height.
    #[arg(long, default_value_t = 120)]
    height: u32,
    /// Worker threads.
    #[arg(long, default_value_t = 2)]
    threads: usize,
    /// Split a block whose n-surface leaves more than this many times its first frame's
    /// open pixels (the thesis's rejection of an n-surface).
    #[arg(long, default_value_t = 2.0)]
    max_growth: f64,
    /// Adaptive block sizes (halved after a block that did not pay, doubled after one that
    /// did, up to the size given), as the render command uses them.
    #[arg(long)]
    adaptive: bool,
    /// Only the animation of this name.
    #[arg(long)]
    only: Option<String>,
    /// Write each animation's scene file to this folder.
    #[arg(long)]
    write_scenes: Option<PathBuf>,
    /// Also write the table (Markdown) to this file.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// The scene file of animation `name` with `frames` frames at `w × h`.
fn scene_file(name: &str, frames: u32, w: u32, h: u32) -> String {
    let last = frames.saturating_sub(1);
    let head = format!(
        "# {name}: written by the animation-blocks report.\n\
         [animation]\nframes = [0, {last}]\nrate = 25\n\n\
         [camera]\neye = [0.0, 1.2, 6.0]\nlook_at = [0.0, 0.0, 0.0]\nfov = 40\n\
         width = {w}\nheight = {h}\n"
    );
    let body = match name {
        "orthocircle" => "\n[[surfaces]]\ncatalog = \"orthocircle\"\n\
             params = { a = \"0.075 + 0.0006*t\", b = \"3 - 0.01*t\" }\n\
             transform = { rotate = [\"5 + 0.9*t\", \"3 + 0.6*t\", 0], \
             translate = [\"-0.3 + 0.006*t\", 0, 0] }\n\
             material = { color = [0.85, 0.55, 0.25], specular = 0.5, shininess = 40.0 }\n\n\
             [[lights]]\ntype = \"point\"\nposition = [3, 5, 4]\n"
            .to_string(),
        "spheres" => {
            let mut s = String::new();
            for (axis, sign) in [
                (0, 1.0),
                (0, -1.0),
                (1, 1.0),
                (1, -1.0),
                (2, 1.0),
                (2, -1.0),
            ] {
                let mut t = ["0".to_string(), "0".to_string(), "0".to_string()];
                t[axis] = format!("\"{sign} * (0.05 + 0.012*t)\"");
                let _ = write!(
                    s,
                    "\n[[surfaces]]\nformula = \"x^2 + y^2 + z^2 - 0.09\"\n\
                     bounds = [[-0.35, -0.35, -0.35], [0.35, 0.35, 0.35]]\n\
                     transform = {{ translate = [{}] }}\n\
                     material = {{ color = [0.3, 0.55, 0.85], specular = 0.5, shininess = 48.0 }}\n",
                    t.join(", ")
                );
            }
            s.push_str("\n[[lights]]\ntype = \"point\"\nposition = [3, 5, 4]\n");
            s
        }
        _ => "\n[[surfaces]]\n\
              formula = \"(1 - s)*(x^4 + y^4 + z^4 - x^2 - y^2 - z^2 + 0.5) + \
              s*((1 + x^2)*(1 + y^2)*(1 + z^2) + 8*x*y*z - 2)\"\n\
              params = { s = \"(t + 0.5) / 100\" }\n\
              bounds = [[-2, -2, -2], [2, 2, 2]]\n\
              transform = { rotate = [\"4 + 1.1*t\", \"2 + 0.8*t\", 0] }\n\
              material = { color = [\"0.9 - 0.004*t\", 0.5, \"0.3 + 0.004*t\"], specular = 0.5, \
              shininess = 40.0 }\n\n\
              [[lights]]\ntype = \"point\"\nposition = [\"4*cos(t/16)\", 5, \"4*sin(t/16)\"]\n"
            .to_string(),
    };
    // One sample per Hit pixel: the blocks' proofs are measured, not the anti-aliasing.
    head + &body + "\n[render]\naa = \"none\"\n"
}

/// The frames of one render: scenes built on demand, images hashed, times summed.
struct Run<'a> {
    animation: &'a Animation,
    times: Vec<i64>,
    hashes: Vec<u64>,
    grid: Duration,
    /// Non-empty grid cells of each frame.
    cells: Vec<u64>,
    reports: Vec<BlockReport>,
}

impl Frames for Run<'_> {
    fn scene(&mut self, k: usize) -> Result<Scene, Error> {
        self.animation.scene(self.times[k])
    }

    fn done(&mut self, _k: usize, out: RenderOutput) -> Result<(), Error> {
        let grid = out.stats.of(Pass::Grid);
        self.grid += grid.map_or(Duration::ZERO, |p| p.time);
        self.cells.push(grid.map_or(0, |p| p.counter("non_empty")));
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for x in out.image.pixels.iter().flatten() {
            for b in x.to_bits().to_le_bytes() {
                h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
            }
        }
        self.hashes.push(h);
        Ok(())
    }

    fn block(&mut self, report: &BlockReport) {
        self.reports.push(report.clone());
    }
}

/// A block's own grid pass.
fn grid_of(r: &BlockReport) -> Option<&beam_trace::stats::PassStats> {
    r.passes.iter().find(|p| p.name == Pass::Grid.name())
}

/// One row: an animation rendered with one block size.
struct Row {
    name: String,
    size: usize,
    time: Duration,
    grid: Duration,
    blocks: usize,
    splits: usize,
    pass_time: Duration,
    /// Time of the blocks' grids.
    block_grid: Duration,
    /// Mean over the blocks of their grid's non-empty cells over their first frame's.
    cell_growth: Option<f64>,
    cost: u64,
    saved: u64,
    differing: usize,
}

fn render(
    name: &str,
    animation: &Animation,
    size: usize,
    args: &Args,
) -> Result<(Row, Vec<u64>), String> {
    let mut run = Run {
        animation,
        times: animation.frames().collect(),
        hashes: Vec::new(),
        grid: Duration::ZERO,
        cells: Vec::new(),
        reports: Vec::new(),
    };
    let settings = BlockSettings {
        size,
        max_growth: args.max_growth,
        adaptive: args.adaptive,
    };
    let count = run.times.len();
    let start = Instant::now();
    render_blocks(count, &mut run, settings, &Cpu, &NoProgress).map_err(|e| e.to_string())?;
    let time = start.elapsed();
    let formed: Vec<&BlockReport> = run.reports.iter().filter(|r| r.formed()).collect();
    let ratios: Vec<f64> = formed
        .iter()
        .filter_map(|r| {
            let block = grid_of(r)?.counter("non_empty") as f64;
            let frame = *run.cells.get(r.first)? as f64;
            (frame > 0.0).then_some(block / frame)
        })
        .collect();
    let row = Row {
        name: name.to_string(),
        size,
        time,
        grid: run.grid,
        blocks: formed.len(),
        splits: run.reports.iter().filter(|r| r.split.is_some()).count(),
        pass_time: formed.iter().map(|r| r.time).sum(),
        block_grid: formed
            .iter()
            .filter_map(|r| grid_of(r).map(|p| p.time))
            .sum(),
        cell_growth: (!ratios.is_empty()).then(|| ratios.iter().sum::<f64>() / ratios.len() as f64),
        cost: formed.iter().map(|r| r.cost).sum(),
        saved: run.reports.iter().map(|r| r.saved).sum(),
        differing: 0,
    };
    Ok((row, run.hashes))
}

fn run(args: Args) -> Result<(), String> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.max(1))
        .build_global()
        .map_err(|e| e.to_string())?;
    if args.frames == 0 || args.sizes.is_empty() {
        return Err("give at least one frame and one block size".into());
    }
    let names: Vec<&str> = ["orthocircle", "spheres", "morph"]
        .into_iter()
        .filter(|n| args.only.as_deref().is_none_or(|o| o == *n))
        .collect();
    if names.is_empty() {
        return Err(format!(
            "--only: no animation '{}' (orthocircle, spheres, morph)",
            args.only.as_deref().unwrap_or_default()
        ));
    }
    let mut table = String::new();
    let _ = writeln!(
        table,
        "{} frames of {} × {}, {} thread(s); blocks split where the frames differ in form or \
         the n-surface leaves more than {}x the open pixels of its first frame{}.\n",
        args.frames,
        args.width,
        args.height,
        args.threads,
        args.max_growth,
        if args.adaptive {
            "; adaptive block sizes (n the largest)"
        } else {
            ""
        }
    );
    let _ = writeln!(
        table,
        "| animation | n | blocks | splits | total s | ms per frame | grid ms per frame | \
         grid ms per block | non-empty cells, block / frame | block passes s | \
         saving 1 − new/old | (old − new)/new | rejection tests spared | \
         block pass evaluations | frames differing from n = {} |",
        args.sizes[0]
    );
    let _ = writeln!(
        table,
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for name in names {
        let text = scene_file(name, args.frames, args.width, args.height);
        if let Some(dir) = &args.write_scenes {
            let p = dir.join(format!("{name}.toml"));
            std::fs::write(&p, &text).map_err(|e| format!("{}: {e}", p.display()))?;
            println!("wrote {}", p.display());
        }
        let animation = Animation::from_toml(&text, name, None)
            .map_err(|e| e.to_string())?
            .ok_or("not an animation")?;
        let mut reference: Option<(Duration, Vec<u64>)> = None;
        for &size in &args.sizes {
            let (mut row, hashes) = render(name, &animation, size.max(1), &args)?;
            let (old, saving) = match &reference {
                None => {
                    reference = Some((row.time, hashes));
                    (row.time, None)
                }
                Some((old, ref_hashes)) => {
                    row.differing = hashes
                        .iter()
                        .zip(ref_hashes)
                        .filter(|(a, b)| a != b)
                        .count();
                    (*old, Some(()))
                }
            };
            let frames = f64::from(args.frames);
            let (o, n) = (old.as_secs_f64(), row.time.as_secs_f64());
            let (a, b) = match saving {
                None => ("—".to_string(), "—".to_string()),
                Some(()) => (
                    format!("{:+.1} %", 100.0 * (1.0 - n / o)),
                    format!("{:+.1} %", 100.0 * (o - n) / n),
                ),
            };
            let (block_grid, cells) = if row.blocks == 0 {
                ("—".to_string(), "—".to_string())
            } else {
                (
                    format!(
                        "{:.2}",
                        1e3 * row.block_grid.as_secs_f64() / row.blocks as f64
                    ),
                    row.cell_growth.map_or("—".into(), |g| format!("{g:.2}")),
                )
            };
            let line = format!(
                "| {} | {} | {} | {} | {:.2} | {:.1} | {:.2} | {block_grid} | {cells} | {:.2} | \
                 {a} | {b} | {} | {} | {} |",
                row.name,
                row.size,
                row.blocks,
                row.splits,
                n,
                1e3 * n / frames,
                1e3 * row.grid.as_secs_f64() / frames,
                row.pass_time.as_secs_f64(),
                row.saved,
                row.cost,
                row.differing
            );
            println!("{line}");
            let _ = writeln!(table, "{line}");
            if row.differing > 0 {
                return Err(format!(
                    "{name}: {} frame(s) of blocks of {size} differ from the reference",
                    row.differing
                ));
            }
        }
    }
    let _ = writeln!(
        table,
        "\nThe thesis (section 6.5, n = 5, 100 frames): orthocircle 40–54 %, spheres 32–66 %, \
         the morph 10 %."
    );
    examples::report::print_and_save(&table, args.out.as_deref())
}

fn main() -> std::process::ExitCode {
    examples::report::exit(run(Args::parse()))
}
