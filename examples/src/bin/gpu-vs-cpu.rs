//! GPU against CPU render time for catalog surfaces, with and without soft shadows.
//!
//! ```text
//! gpu-vs-cpu [--sizes 512,1024] [--surfaces sphere,orthocircle,chubs] [--markdown FILE]
//! ```
//!
//! Each surface is rendered at each size by both backends: without soft shadows (the
//! catalog's point light, hard shadows) and with them (a square area light of 0.1 of the
//! view's area, the beam method with 7 × 7 sub-beams, as in the reliable soft-shadow
//! paper). The table gives the wall-clock time of each render, the GPU's own time (its
//! dispatches and read-backs) and the CPU/GPU ratio, with the adapter's name. On a software
//! adapter (lavapipe) this measures correctness more than speed.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use beam_trace::scene::AaMode;
use beam_trace::shadow::ShadowSpec;
use beam_trace::{NoProgress, Scene, render, render_on};
use clap::Parser;
use examples::soft_scene::catalog_with_area_light;
use gpu_backend::{Gpu, GpuBackend};

/// GPU against CPU render time.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Image sides, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "512,1024")]
    sizes: Vec<u32>,
    /// Catalog surfaces, comma separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "sphere,orthocircle,chubs"
    )]
    surfaces: Vec<String>,
    /// Also write the table (markdown) to this file.
    #[arg(long)]
    markdown: Option<PathBuf>,
}

/// Seconds of a CPU and a GPU render of `scene`, and the GPU's set-up (compiling its
/// kernels).
fn time_both(gpu: &GpuBackend, scene: &Scene) -> Result<(f64, f64, f64), String> {
    let t = Instant::now();
    render(scene, &NoProgress).map_err(|e| e.to_string())?;
    let cpu = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let out = render_on(scene, gpu, &NoProgress).map_err(|e| e.to_string())?;
    let wall = t.elapsed().as_secs_f64();
    let own = out
        .stats
        .pass("gpu-compile")
        .map_or(0.0, |p| p.time.as_secs_f64());
    Ok((cpu, wall, own))
}

fn run(args: Args) -> Result<(), String> {
    let gpu = GpuBackend::new(Gpu::new().map_err(|e| e.to_string())?);
    let mut md = String::new();
    let _ = writeln!(
        md,
        "Adapter: **{}**; CPU: {} thread(s). Seconds per render (wall clock; the GPU time includes compiling its kernel).\n",
        gpu.gpu().name(),
        rayon::current_num_threads()
    );
    let _ = writeln!(
        md,
        "| surface | size | soft shadows | CPU (s) | GPU (s) | GPU set-up (s) | CPU / GPU |"
    );
    let _ = writeln!(md, "|---|---:|---|---:|---:|---:|---:|");
    eprintln!("adapter: {}", gpu.gpu().name());
    for name in &args.surfaces {
        for &size in &args.sizes {
            let mut hard = Scene::catalog(name, size, size).map_err(|e| e.to_string())?;
            let mut soft = catalog_with_area_light(name, size, 0.1)?;
            // The backends' queries are compared, one sample per Hit pixel (interval
            // anti-aliasing judges its pixels on the CPU whatever the backend).
            hard.settings.aa = Some(AaMode::None);
            soft.settings.aa = Some(AaMode::None);
            soft.settings.shadow_method = "beam:7".parse::<ShadowSpec>()?;
            for (label, scene) in [("no", &hard), ("beam:7", &soft)] {
                let (cpu, gpu_wall, gpu_own) = time_both(&gpu, scene)?;
                let row = format!(
                    "| {name} | {size} | {label} | {cpu:.2} | {gpu_wall:.2} | {gpu_own:.2} | {:.2} |",
                    cpu / gpu_wall
                );
                eprintln!("{row}");
                let _ = writeln!(md, "{row}");
            }
        }
    }
    examples::report::print_and_save(&md, args.markdown.as_deref())
}

fn main() -> ExitCode {
    examples::report::exit(run(Args::parse()))
}
