//! What soft-shadow accuracy costs in time: renders a few scenes with every soft-shadow
//! method and setting, measures the per-pixel visible fraction of the first area light
//! against a many-sample stochastic reference, and writes a markdown report with
//! time-against-error plots.
//!
//! ```text
//! accuracy-cost [SCENE.toml ...] [--width W --height H] [--reference-samples N | --exact-reference]
//!               [--out-dir DIR] [--runs N] [--quick]
//! ```
//!
//! For each scene (default: `scenes/soft-shadows.toml` and `scenes/thin-occluder.toml`, at
//! 128 × 96 pixels; about eight minutes on two cores):
//!
//! 1. a reference render with `stochastic:N` (`--reference-samples`, default 4096), or with
//!    the `exact` method (`--exact-reference`, for scenes whose occluders are meshes);
//! 2. renders of the settings: `stochastic:N` for N in 4..1024 (two with the last-occluder
//!    cache), `beam:n` for n in 2..16, `beam-all:7`, `beam-quadtree:8`,
//!    `minkowski:stochastic:N`, `minkowski:beam:n`, the `certified` settings, and `beam:7`
//!    and `stochastic:64` with the root finder's epsilon at 1e-3 and 100 times its default
//!    and in `f32` precision; each three times (`--runs`), in rounds over all settings so
//!    that a slow spell of the machine slows each alike, its times the medians;
//! 3. per render: the soft-shadow pass time, the total time, the RMSE, the largest error and
//!    the mean signed error (bias) of the visible fraction against the reference, the share
//!    of the reference's shadowed pixels it calls fully lit (missed shadow), the share of
//!    pixels proven lit or umbra, and the contradictions: pixels proven lit whose reference
//!    fraction is below 1, or proven umbra whose reference fraction is above 0.
//!
//! It writes `DIR/accuracy.md` (default `DIR` = `docs`) and, under `DIR/images/`, per scene
//! the reference render, the `beam:7` shadow-class image, the signed-error maps of
//! `beam:7` and `stochastic:64`, and the time-against-RMSE and time-against-largest-error
//! plots with their Pareto fronts (all named `accuracy-*`). Every run is printed as it
//! finishes. The program fails (after writing the report) if any pixel's proven class
//! contradicts the reference.
//!
//! `--quick` is a smoke run: a 32 × 24 image, a 256-sample reference, fewer settings, one
//! render each, and the report in the system's temporary folder unless `--out-dir` is
//! given.

use std::process::ExitCode;

use clap::Parser;
use examples::accuracy::{self, Args};

fn main() -> ExitCode {
    let args = Args::parse();
    match accuracy::run(&args) {
        Ok(0) => ExitCode::SUCCESS,
        Ok(n) => {
            eprintln!("error: {n} proven shadow classes CONTRADICT the reference");
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
