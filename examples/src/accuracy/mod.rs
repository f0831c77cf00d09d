//! What soft-shadow accuracy costs in time: the experiment of the `accuracy-cost` example.
//!
//! A few scenes are rendered with every soft-shadow method and setting; the per-pixel
//! visible fraction of the first area light is measured against a many-sample stochastic
//! reference, and a markdown report with time-against-error plots is written. The parts:
//!
//! * [`options`]: the command line and the options resolved from it;
//! * [`setting`]: the settings run (a method and a variant) and their families;
//! * [`experiment`]: the renders of one scene and the images they leave;
//! * [`metrics`]: errors and proofs of a render against the reference, Pareto fronts;
//! * [`plots`]: time against error per method family, with the Pareto fronts;
//! * [`report`]: the markdown report.
//!
//! [`Args`] is the command line and [`run`] the whole experiment.

pub mod experiment;
pub mod metrics;
pub mod options;
pub mod plots;
pub mod report;
pub mod setting;

pub use options::Args;

use std::time::{Duration, Instant};

use experiment::run_scene;
use metrics::{Metric, SceneReport};
use options::Options;
use plots::plot;
use report::markdown;

pub(crate) fn write_report(
    reports: &[SceneReport],
    opts: &Options,
    elapsed: Duration,
) -> Result<(), String> {
    for report in reports {
        for metric in Metric::ALL {
            plot(
                report,
                metric,
                &opts.images().join(report.image(metric.file_suffix())),
            )?;
        }
    }
    let path = opts.out_dir.join("accuracy.md");
    std::fs::write(&path, markdown(reports, opts, elapsed))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// Runs the whole experiment: every scene of `args`, then the report and its plots.
///
/// Returns the number of proven shadow classes that contradict the reference (0 when all
/// hold), or a message naming what failed.
pub fn run(args: &Args) -> Result<usize, String> {
    let start = Instant::now();
    let opts = Options::from_args(args)?;
    std::fs::create_dir_all(opts.images())
        .map_err(|e| format!("{}: {e}", opts.images().display()))?;
    let reports = args
        .scenes
        .iter()
        .map(|p| run_scene(p, &opts))
        .collect::<Result<Vec<_>, _>>()?;
    let elapsed = start.elapsed();
    write_report(&reports, &opts, elapsed)?;
    for r in &reports {
        println!("{}: CONTRADICTIONS {}", r.name, r.contradictions());
    }
    println!("whole run: {:.1} s", elapsed.as_secs_f64());
    Ok(reports.iter().map(SceneReport::contradictions).sum())
}
