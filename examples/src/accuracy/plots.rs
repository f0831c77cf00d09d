//! Plots of shadow time against error, one colour per method family, with the Pareto
//! front; the points that carry a certificate (a method that proves each pixel's fraction
//! within a bound refined to a tolerance) are framed by a square.

use std::path::Path;

use plotters::prelude::*;

use super::metrics::{Metric, RunResult, SceneReport, pareto};
use super::setting::Family;

/// Smallest value a log axis shows (an error of exactly 0 is drawn there).
pub(crate) const LOG_FLOOR: f64 = 1e-5;

pub(crate) fn log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
        let v = v.max(LOG_FLOOR);
        (lo.min(v), hi.max(v))
    });
    if lo > hi {
        (LOG_FLOOR, 1.0)
    } else {
        (lo / 1.6, hi * 1.6)
    }
}

/// Plots shadow time against `metric` for one scene, by family, with the Pareto front.
pub(crate) fn plot(report: &SceneReport, metric: Metric, path: &Path) -> Result<(), String> {
    draw_plot(report, metric, path).map_err(|e| format!("{}: {e}", path.display()))
}

pub(crate) fn draw_plot(
    report: &SceneReport,
    metric: Metric,
    path: &Path,
) -> Result<(), Box<dyn std::error::Error>> {
    let runs = &report.runs;
    let point = |r: &RunResult| (r.shadow_ms(), metric.of(r).max(LOG_FLOOR));
    let (x0, x1) = log_range(runs.iter().map(RunResult::shadow_ms));
    let (y0, y1) = log_range(runs.iter().map(|r| metric.of(r)));
    let root = BitMapBackend::new(path, (1100, 640)).into_drawing_area();
    root.fill(&WHITE)?;
    let (plot_area, legend_area) = root.split_horizontally(860);
    let mut chart = ChartBuilder::on(&plot_area)
        .caption(
            format!(
                "{}: soft-shadow time against {} ({}x{}, reference {})",
                report.name,
                metric.title(),
                report.width,
                report.height,
                report.reference
            ),
            ("sans-serif", 19),
        )
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("soft-shadow pass time (ms, log)")
        .y_desc(format!("{} of the visible fraction (log)", metric.title()))
        .x_label_formatter(&|v| round_label(*v, false))
        .y_label_formatter(&|v| round_label(*v, true))
        .draw()?;
    let front: Vec<(f64, f64)> = pareto(runs, metric)
        .into_iter()
        .map(|i| point(&runs[i]))
        .collect();
    chart.draw_series(LineSeries::new(front.clone(), BLACK.stroke_width(2)))?;
    chart.draw_series(
        front
            .iter()
            .map(|&p| Circle::new(p, 9, BLACK.stroke_width(2))),
    )?;
    // A square around each point that carries a certificate.
    chart.draw_series(runs.iter().filter(|r| r.certified()).map(|r| {
        EmptyElement::at(point(r)) + Rectangle::new([(-13, -13), (13, 13)], BLACK.stroke_width(1))
    }))?;
    chart.draw_series(runs.iter().enumerate().map(|(i, r)| {
        // Alternate the label above and below the point so that neighbours overlap less.
        let dy = if i % 2 == 0 { -16 } else { 4 };
        EmptyElement::at(point(r))
            + Circle::new((0, 0), 5, color(r.setting.family()).filled())
            + Text::new(r.setting.label(), (7, dy), ("sans-serif", 12))
    }))?;
    draw_legend(&legend_area, runs)?;
    root.present()?;
    Ok(())
}

/// A log-axis tick label at 1, 2 and 5 times a power of ten, none elsewhere.
pub(crate) fn round_label(v: f64, scientific: bool) -> String {
    let mantissa = v / 10f64.powf(v.log10().floor());
    if ![1.0, 2.0, 5.0].iter().any(|m| (mantissa - m).abs() < 1e-6) {
        return String::new();
    }
    if scientific {
        format!("{v:.0e}")
    } else if v >= 1.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.3}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    }
}

/// The families present in `runs` and the Pareto-front marker, in a panel beside the plot.
pub(crate) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    runs: &[RunResult],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let font = ("sans-serif", 15);
    let mut y = 70;
    area.draw(&(EmptyElement::at((20, y)) + Circle::new((0, 0), 9, BLACK.stroke_width(2))))?;
    area.draw(&Text::new("Pareto front", (40, y - 8), font))?;
    area.draw(&Text::new("(default settings)", (40, y + 10), font))?;
    y += 18;
    if runs.iter().any(RunResult::certified) {
        y += 34;
        area.draw(&Rectangle::new(
            [(12, y - 8), (28, y + 8)],
            BLACK.stroke_width(1),
        ))?;
        area.draw(&Text::new("certificate: each pixel", (40, y - 8), font))?;
        area.draw(&Text::new("proven within a bound", (40, y + 10), font))?;
        y += 18;
    }
    for family in Family::ALL {
        if !runs.iter().any(|r| r.setting.family() == family) {
            continue;
        }
        y += 26;
        area.draw(&Circle::new((20, y), 5, color(family).filled()))?;
        area.draw(&Text::new(family.name(), (40, y - 8), font))?;
    }
    Ok(())
}

fn color(family: Family) -> RGBColor {
    match family {
        Family::Stochastic => RGBColor(31, 119, 180),
        Family::StochasticCache => RGBColor(23, 190, 207),
        Family::Beam => RGBColor(214, 39, 40),
        Family::BeamOther => RGBColor(255, 127, 14),
        Family::MinkowskiStochastic => RGBColor(44, 160, 44),
        Family::MinkowskiBeam => RGBColor(148, 103, 189),
        Family::Certified => RGBColor(0, 0, 0),
        Family::Exact => RGBColor(188, 189, 34),
        Family::Epsilon => RGBColor(140, 86, 75),
        Family::F32 => RGBColor(227, 119, 194),
    }
}
