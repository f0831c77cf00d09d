//! The thesis's Table 5.4 measured here: the screen box structure (beams classify screen
//! boxes; 1 ray per pixel in Hit boxes, 9 in Undecided ones) against classic interval ray
//! casting with 9 rays in every pixel, on the same scenes, in one run.
//!
//! ```text
//! screen-boxes [--size N] [--surfaces orthocircle,blobby,drop] [--root-finder NAME]
//! ```

use std::process::ExitCode;

use beam_trace::root::RootMethod;
use beam_trace::scene::PrimaryMode;
use beam_trace::{NoProgress, RenderOutput, Scene, render};
use clap::Parser;

/// Screen box structure against 9 rays per pixel (thesis Table 5.4).
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Image size (square).
    #[arg(long, default_value_t = 300)]
    size: u32,
    /// Catalog surfaces, comma separated.
    #[arg(long, default_value = "orthocircle,blobby,drop", value_delimiter = ',')]
    surfaces: Vec<String>,
    /// Root finder.
    #[arg(long, default_value = "newton-alefeld-hansen")]
    root_finder: RootMethod,
}

fn counter(out: &RenderOutput, pass: &str, name: &str) -> u64 {
    out.stats.pass(pass).map_or(0, |p| p.counter(name))
}

fn primary_time(out: &RenderOutput) -> f64 {
    ["grid", "screen-boxes", "primary-rays"]
        .iter()
        .filter_map(|p| out.stats.pass(p))
        .map(|p| p.time.as_secs_f64())
        .sum()
}

fn run(args: Args) -> Result<(), String> {
    println!(
        "| surface | boxes: time (s) | boxes: rays | boxes: beams | 9 rays/pixel: time (s) | 9 rays/pixel: rays | time ratio | rays ratio | pixel difference: max | mean |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for name in &args.surfaces {
        let mut scene = Scene::catalog(name, args.size, args.size).map_err(|e| e.to_string())?;
        // Primary visibility only, as in the thesis's comparison.
        scene.settings.shadows = false;
        scene.settings.root_finder = args.root_finder;
        scene.settings.rays_per_undecided = 9;
        let mut classic = scene.clone();
        classic.settings.primary = PrimaryMode::PerPixel;
        classic.settings.rays_per_pixel = 9;
        scene.settings.primary = PrimaryMode::ScreenRays;
        let boxes = render(&scene, &NoProgress).map_err(|e| e.to_string())?;
        let plain = render(&classic, &NoProgress).map_err(|e| e.to_string())?;
        let (tb, tc) = (primary_time(&boxes), primary_time(&plain));
        let (rb, rc) = (
            counter(&boxes, "primary-rays", "rays"),
            counter(&plain, "primary-rays", "rays"),
        );
        let diffs: Vec<f32> = boxes
            .image
            .pixels
            .iter()
            .zip(&plain.image.pixels)
            .map(|(a, b)| (0..3).map(|k| (a[k] - b[k]).abs()).fold(0f32, f32::max))
            .collect();
        let diff = diffs.iter().copied().fold(0f32, f32::max);
        let mean = diffs.iter().sum::<f32>() / diffs.len().max(1) as f32;
        println!(
            "| {name} | {tb:.2} | {rb} | {} | {tc:.2} | {rc} | {:.2}× | {:.2}× | {diff:.3} | {mean:.5} |",
            counter(&boxes, "screen-boxes", "beams"),
            tc / tb,
            rc as f64 / rb.max(1) as f64,
        );
    }
    println!(
        "\nTimes are grid + screen boxes + primary rays on {} thread(s); the thesis (Table 5.4, 300 × 300) reports 2.4×, 3.1× and 3.0× less time for orthocircle, blob and drop.",
        rayon::current_num_threads()
    );
    Ok(())
}

fn main() -> ExitCode {
    examples::report::exit(run(Args::parse()))
}
