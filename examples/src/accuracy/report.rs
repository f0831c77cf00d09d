//! The markdown report: the tables of runs, the Pareto fronts, the cheapest setting per
//! error level, and the readings drawn from the numbers.

use std::fmt::{self, Write as _};
use std::time::Duration;

use beam_trace::root::RootSettings;

use super::metrics::{Metric, RunResult, SceneReport, cheapest, ms, pareto, percent};
use super::options::{BASELINE, CLASS_IMAGE, ERROR_MAPS, Options};
use super::setting::{Family, VARIED, Variant};

/// The command that reproduces the report.
pub(crate) const COMMAND: &str =
    "cargo run --release -p examples --features plots --bin accuracy-cost";

/// Largest errors (RMSE) of the "cheapest setting at each error level" table.
pub(crate) const LEVELS: [f64; 5] = [0.1, 0.05, 0.02, 0.01, 0.005];

/// The report's table of runs.
pub(crate) fn table(md: &mut String, report: &SceneReport) -> fmt::Result {
    writeln!(
        md,
        "| method | setting | soft shadows (ms) | × {BASELINE} | total (ms) | RMSE | max error | bias | missed shadow | proven lit | proven umbra | largest certified bound width | contradictions | bound violations (> 4σ) |"
    )?;
    writeln!(
        md,
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    )?;
    let base = report.baseline_ms();
    for r in &report.runs {
        writeln!(
            md,
            "| `{}` | {} | {:.1} | {:.2} | {:.1} | {:.5} | {:.4} | {:+.5} | {:.1} % | {:.1} % | {:.1} % | {:.3} | {} | {} |",
            r.setting.spec,
            r.setting.variant_name(),
            r.shadow_ms(),
            r.shadow_ms() / base,
            ms(r.total_time),
            r.errors.rmse,
            r.errors.max,
            r.errors.bias,
            percent(r.errors.missed, r.errors.shadowed),
            percent(r.proofs.lit, r.proofs.shaded),
            percent(r.proofs.umbra, r.proofs.shaded),
            r.proofs.widest_bound,
            r.proofs.contradictions,
            r.proofs.bound_violations,
        )?;
    }
    Ok(())
}

pub(crate) fn describe(r: &RunResult) -> String {
    match r.setting.variant {
        Variant::Default => format!("`{}`", r.setting.spec),
        _ => format!("`{}` ({})", r.setting.spec, r.setting.variant_name()),
    }
}

pub(crate) fn pareto_list(md: &mut String, report: &SceneReport, metric: Metric) -> fmt::Result {
    let front: Vec<String> = pareto(&report.runs, metric)
        .into_iter()
        .map(|i| {
            let r = &report.runs[i];
            format!(
                "{} ({:.1} ms, {:.4})",
                describe(r),
                r.shadow_ms(),
                metric.of(r)
            )
        })
        .collect();
    writeln!(
        md,
        "- Pareto front of time against {} (the scene's epsilon and precision), fastest first: {}.",
        metric.title(),
        front.join(" → ")
    )
}

/// The cheapest run whose RMSE is at most each level.
pub(crate) fn cheapest_per_level(md: &mut String, report: &SceneReport) -> fmt::Result {
    writeln!(
        md,
        "| RMSE at most | cheapest setting | soft shadows (ms) | its RMSE | its max error |"
    )?;
    writeln!(md, "|---:|---|---:|---:|---:|")?;
    for level in LEVELS {
        match cheapest(report, Metric::Rmse, level) {
            Some(r) => writeln!(
                md,
                "| {level} | {} | {:.1} | {:.5} | {:.4} |",
                describe(r),
                r.shadow_ms(),
                r.errors.rmse,
                r.errors.max
            )?,
            None => writeln!(md, "| {level} | none of the settings | | | |")?,
        }
    }
    Ok(())
}

/// Sentences on the variants: what f32 and the root epsilon change.
pub(crate) fn variants_reading(md: &mut String, report: &SceneReport) -> fmt::Result {
    for spec in VARIED {
        let Some(base) = report.find(spec, Variant::Default) else {
            continue;
        };
        let variants: Vec<String> = report
            .runs
            .iter()
            .filter(|r| r.setting.spec.to_string() == spec && r.setting.variant != Variant::Default)
            .map(|r| {
                format!(
                    "{} takes {:.2}× the time with RMSE {:.5} (default {:.5})",
                    r.setting.variant_name(),
                    r.shadow_ms() / base.shadow_ms(),
                    r.errors.rmse,
                    base.errors.rmse
                )
            })
            .collect();
        if !variants.is_empty() {
            writeln!(md, "- `{spec}`: {}.", variants.join("; "))?;
        }
    }
    Ok(())
}

/// Sentences on the bias of the beam methods against the noise of the stochastic ones.
pub(crate) fn bias_reading(md: &mut String, report: &SceneReport) -> fmt::Result {
    for family in [
        Family::Stochastic,
        Family::Beam,
        Family::BeamOther,
        Family::MinkowskiBeam,
    ] {
        let runs: Vec<&RunResult> = report
            .runs
            .iter()
            .filter(|r| r.setting.family() == family)
            .collect();
        if runs.is_empty() {
            continue;
        }
        let mean = runs.iter().map(|r| r.errors.bias).sum::<f64>() / runs.len() as f64;
        write!(
            md,
            "- `{}` ({} runs): mean signed error {mean:+.5}",
            family.name(),
            runs.len()
        )?;
        if family.is_lower_bound() {
            let over = runs.iter().map(|r| r.errors.over).fold(0.0, f64::max);
            write!(
                md,
                "; its fraction is a proven lower bound, and it exceeds the reference by at most {over:.4}"
            )?;
        }
        writeln!(md, ".")?;
    }
    Ok(())
}

pub(crate) fn scene_section(md: &mut String, report: &SceneReport) -> fmt::Result {
    writeln!(md, "## Scene `{}`\n", report.path.display())?;
    writeln!(
        md,
        "{}×{} pixels; reference `{}` (soft shadows {:.0} ms). Contradictions over all runs: **{}**.\n",
        report.width,
        report.height,
        report.reference,
        ms(report.reference_time),
        report.contradictions()
    )?;
    if let Some(r) = report.runs.first() {
        writeln!(
            md,
            "Errors are over the {} pixels where both fractions are defined; {:.1} % of the shaded pixels face away from the light in every run (class `BackFacing`: no shadow test, no claim, not counted as proven).\n",
            r.errors.compared,
            percent(r.proofs.back_facing, r.proofs.shaded)
        )?;
    }
    writeln!(
        md,
        "| reference render | `{CLASS_IMAGE}` shadow classes | `{}` error | `{}` error |",
        ERROR_MAPS[0].0, ERROR_MAPS[1].0
    )?;
    writeln!(md, "|---|---|---|---|")?;
    writeln!(
        md,
        "| ![reference](images/{}) | ![classes](images/{}) | ![error](images/{}) | ![error](images/{}) |\n",
        report.image("reference"),
        report.image("beam7-classes"),
        report.image(ERROR_MAPS[0].1),
        report.image(ERROR_MAPS[1].1),
    )?;
    writeln!(
        md,
        "Shadow classes: proven lit green, proven umbra blue, penumbra orange, facing away from the light blue-grey. \
         Error maps: white where the visible fraction equals the reference, red where it is darker, blue where it is brighter \
         (intensity `sqrt(|error|)`), near black where no surface is shaded.\n"
    )?;
    table(md, report)?;
    writeln!(md)?;
    for metric in Metric::ALL {
        pareto_list(md, report, metric)?;
    }
    writeln!(md)?;
    for metric in Metric::ALL {
        writeln!(
            md,
            "![time against {}](images/{})\n",
            metric.title(),
            report.image(metric.file_suffix())
        )?;
    }
    writeln!(
        md,
        "Cheapest setting at each error level (the scene's epsilon and precision):\n"
    )?;
    cheapest_per_level(md, report)?;
    writeln!(md)?;
    bias_reading(md, report)?;
    variants_reading(md, report)?;
    writeln!(md)
}

pub(crate) const INTRO: &str = "\
What soft-shadow accuracy costs in time. Each scene is rendered once with a many-sample \
stochastic reference and once per soft-shadow method and setting; the per-pixel visible \
fraction of the area light is compared with the reference over the pixels where both are \
defined. *RMSE* and *max error* are the root mean square and the largest absolute error of \
that fraction, *bias* its mean signed error (negative: darker than the reference). *Missed \
shadow* is the share of the pixels in some shadow in the reference (fraction below 1) that \
the method calls fully lit. *Proven \
lit* and *proven umbra* are the shares of shaded pixels whose class was proven. A \
*contradiction* is a pixel proven lit whose reference fraction is below 1, or proven umbra \
whose reference fraction is above 0; there must be none, and the program fails if there \
is one.

The reference is itself an estimate: a stochastic error of order `1/sqrt(N)` per pixel \
remains in it, so errors much below that level measure the reference as much as the method.

Every render here takes one sample per Hit pixel (`aa = \"none\"`), so that a pixel's \
fraction is one shading point's. What anti-aliasing accuracy costs in time (every primary \
and anti-aliasing mode against 16 × 16 rays per pixel over the edge pixels, with the \
Pareto front) is the sibling report [`anti-aliasing.md`](anti-aliasing.md), made by \
`aa-cost`.";

pub(crate) const READING: &str = "\
- **Noise against bias.** The stochastic methods are unbiased but noisy: their RMSE falls \
roughly as `1/sqrt(N)` while their time grows as `N`. The beam methods have no noise but a \
bias: their fraction is the share of sub-beams *proven* free, a proven lower bound, so a \
sub-beam that is neither proven free nor proven blocked counts as occluded. Their fraction \
is too small wherever a sub-beam grazes an occluder or the interval enclosure over the \
sub-beam is too wide to reject it (red in the `beam:7` error maps; where no sub-beam of a \
point is rejected its fraction is 0 whatever the light it sees), and that error falls \
slowly with `n` while the cost grows as `n²`. `beam-all` and `beam-quadtree` give the same \
kind of answer at another cost. The Minkowski methods first prove lit and umbra points, \
then run their fine method on the rest, so they give the fine method's answer (the same \
fraction for the same `N` or `n`) at a lower cost wherever much is proven lit.
- **Thin occluders.** A thin occluder blocks a strip of the light much narrower than a \
stochastic stratum: a sample either misses it (an error of the strip's share) or hits it \
(an error of `1/N`), so sparse sampling leaves a large largest error at a small RMSE, and \
misses some of the shadow altogether (column *missed shadow*). Every sub-beam that touches \
it counts as wholly blocked, which draws the shadow as discrete bands; a beam method never \
misses a shadow, since a fraction of 1 from it is a proof.
- **Proofs.** The beam, Minkowski and certified methods prove lit points (their first beam \
over the whole light); the Minkowski and certified methods also prove umbra, and the \
certified method bounds every point's fraction (column *largest certified bound width*) \
with an unbiased estimate inside the bound; the stochastic method proves nothing, its \
fraction is an estimate.";

/// The data-driven part of the reading: cheapest settings, the variants' cost, the
/// contradictions.
pub(crate) fn summary(md: &mut String, reports: &[SceneReport]) -> fmt::Result {
    for report in reports {
        let picks: Vec<String> = [
            (Metric::Rmse, 0.05),
            (Metric::Rmse, 0.01),
            (Metric::MaxError, 0.1),
        ]
        .into_iter()
        .map(|(metric, level)| {
            let pick = cheapest(report, metric, level).map_or("none".into(), |r| {
                format!(
                    "{} ({:.0} ms, {:.2}× `{BASELINE}`)",
                    describe(r),
                    r.shadow_ms(),
                    r.shadow_ms() / report.baseline_ms()
                )
            });
            format!("{} ≤ {level}: {pick}", metric.title())
        })
        .collect();
        writeln!(
            md,
            "- **`{}`, cheapest setting** at {}.",
            report.name,
            picks.join("; ")
        )?;
    }
    for (variant, title) in [
        (Variant::F32, "`f32` precision"),
        (
            Variant::Epsilon(RootSettings::default().epsilon * 1e-3),
            "epsilon 1e-3 × default",
        ),
        (
            Variant::Epsilon(RootSettings::default().epsilon * 100.0),
            "epsilon 100 × default",
        ),
    ] {
        variant_summary(md, reports, variant, title)?;
    }
    let total: usize = reports.iter().map(SceneReport::contradictions).sum();
    writeln!(
        md,
        "- **Contradictions: {total}.** {}",
        if total == 0 {
            "No proven lit or umbra pixel of any run disagrees with the reference."
        } else {
            "Some proven classes disagree with the reference: a soundness bug to investigate."
        }
    )
}

/// One bullet on a variant: its time relative to the same method with the scene's
/// settings, and how much its RMSE moved.
pub(crate) fn variant_summary(
    md: &mut String,
    reports: &[SceneReport],
    variant: Variant,
    title: &str,
) -> fmt::Result {
    let mut parts = Vec::new();
    let mut rmse_change = 0.0f64;
    for report in reports {
        for spec in VARIED {
            if let (Some(v), Some(base)) = (
                report.find(spec, variant),
                report.find(spec, Variant::Default),
            ) {
                parts.push(format!(
                    "`{spec}` on `{}` {:.2}×",
                    report.name,
                    v.shadow_ms() / base.shadow_ms()
                ));
                rmse_change = rmse_change.max((v.errors.rmse - base.errors.rmse).abs());
            }
        }
    }
    if parts.is_empty() {
        return Ok(());
    }
    writeln!(
        md,
        "- **{title}**, soft-shadow time against the default: {}; the RMSE changes by at most {}.",
        parts.join(", "),
        if rmse_change == 0.0 {
            "0".to_string()
        } else {
            format!("{rmse_change:.1e}")
        }
    )
}

/// The whole report.
pub(crate) fn markdown(reports: &[SceneReport], opts: &Options, elapsed: Duration) -> String {
    let mut md = String::new();
    let mut write = || -> fmt::Result {
        writeln!(md, "# Soft-shadow accuracy against cost\n")?;
        writeln!(md, "{INTRO}\n")?;
        writeln!(
            md,
            "Reproduce with `{COMMAND}` (options: `--width`, `--height`, `--reference-samples` or `--exact-reference`, `--out-dir`, `--runs`, `--quick`; scene files as arguments). \
             This report: {}×{} pixels, reference `{}`, {} settings per scene; the whole run took {:.0} s.\n",
            opts.width,
            opts.height,
            opts.reference,
            opts.settings.len(),
            elapsed.as_secs_f64()
        )?;
        writeln!(
            md,
            "Each time is the median of {} renders on one machine, taken in rounds over all settings \
             so that a slow spell of the machine slows every setting alike, with every render using all its cores; \
             absolute times will differ elsewhere, the ratios (column `× {BASELINE}`) are what matter.\n",
            opts.runs
        )?;
        writeln!(md, "## Reading\n\n{READING}")?;
        summary(&mut md, reports)?;
        writeln!(md)?;
        for r in reports {
            scene_section(&mut md, r)?;
        }
        Ok(())
    };
    write().expect("formatting into a String cannot fail");
    md
}
