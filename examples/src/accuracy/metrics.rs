//! What a render is measured by: its visible fraction's errors against the reference, its
//! proven shadow classes checked against it, and the Pareto fronts of time against error.

use std::path::PathBuf;
use std::time::Duration;

use beam_trace::shadow::ShadowClass;
use beam_trace::{RenderOutput, ShadowMaps};

use super::options::{BASELINE, Reference};
use super::setting::{Setting, Variant, image_name};

/// The visible fraction of a render against the reference.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct Errors {
    /// Root mean square error.
    pub(crate) rmse: f64,
    /// Largest absolute error.
    pub(crate) max: f64,
    /// Mean signed error (negative: darker than the reference).
    pub(crate) bias: f64,
    /// Largest amount by which the fraction exceeds the reference (0 if it never does).
    pub(crate) over: f64,
    /// Pixels where both fractions are finite.
    pub(crate) compared: usize,
    /// Pixels in some shadow in the reference (fraction below 1).
    pub(crate) shadowed: usize,
    /// Of those, pixels the render calls fully lit (fraction 1): shadow it missed.
    pub(crate) missed: usize,
}

/// What a render proved, checked against the reference.
#[derive(Copy, Clone, Debug, Default)]
pub(crate) struct Proofs {
    /// Pixels with a shaded surface.
    pub(crate) shaded: usize,
    /// Pixels proven lit.
    pub(crate) lit: usize,
    /// Pixels proven umbra.
    pub(crate) umbra: usize,
    /// Pixels facing away from the light (no occlusion claimed).
    pub(crate) back_facing: usize,
    /// Proven pixels whose reference fraction says otherwise.
    pub(crate) contradictions: usize,
    /// Pixels whose proven bound misses the reference by more than 4 standard deviations
    /// of the reference's mean (at least `4 / samples`).
    pub(crate) bound_violations: usize,
    /// Widest proven bound `upper − lower` of a pixel.
    pub(crate) widest_bound: f32,
}

/// One render of a scene and how it compares with the reference.
#[derive(Clone, Debug)]
pub(crate) struct RunResult {
    pub(crate) setting: Setting,
    /// Time of the soft-shadow pass.
    pub(crate) shadow_time: Duration,
    /// Time of the whole render.
    pub(crate) total_time: Duration,
    pub(crate) errors: Errors,
    pub(crate) proofs: Proofs,
}

impl RunResult {
    pub(crate) fn shadow_ms(&self) -> f64 {
        ms(self.shadow_time)
    }

    /// Whether the run carries a certificate: its method proves each pixel's visible
    /// fraction within a bound it refines to a tolerance (`certified:TOL`); the report's
    /// "largest certified bound width" says how wide the widest one came out.
    pub(crate) fn certified(&self) -> bool {
        self.setting.spec.method().tolerance() > 0.0
    }
}

/// An error measure the plots and Pareto fronts use.
#[derive(Copy, Clone, Debug)]
pub(crate) enum Metric {
    Rmse,
    MaxError,
}

impl Metric {
    pub(crate) const ALL: [Metric; 2] = [Metric::Rmse, Metric::MaxError];

    pub(crate) fn of(self, r: &RunResult) -> f64 {
        match self {
            Metric::Rmse => r.errors.rmse,
            Metric::MaxError => r.errors.max,
        }
    }

    pub(crate) fn title(self) -> &'static str {
        match self {
            Metric::Rmse => "RMSE",
            Metric::MaxError => "largest error",
        }
    }

    pub(crate) fn file_suffix(self) -> &'static str {
        match self {
            Metric::Rmse => "rmse",
            Metric::MaxError => "max-error",
        }
    }
}

/// Everything measured on one scene.
pub(crate) struct SceneReport {
    /// File stem of the scene, used in image names.
    pub(crate) name: String,
    /// The scene file.
    pub(crate) path: PathBuf,
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) reference: Reference,
    pub(crate) reference_time: Duration,
    pub(crate) runs: Vec<RunResult>,
}

impl SceneReport {
    pub(crate) fn find(&self, spec: &str, variant: Variant) -> Option<&RunResult> {
        self.runs
            .iter()
            .find(|r| r.setting.variant == variant && r.setting.spec.to_string() == spec)
    }

    pub(crate) fn contradictions(&self) -> usize {
        self.runs
            .iter()
            .map(|r| r.proofs.contradictions + r.proofs.bound_violations)
            .sum()
    }

    /// Shadow time of the baseline, or of the reference if the baseline did not run.
    pub(crate) fn baseline_ms(&self) -> f64 {
        self.find(BASELINE, Variant::Default)
            .map_or(ms(self.reference_time), RunResult::shadow_ms)
    }

    pub(crate) fn image(&self, what: &str) -> String {
        image_name(&self.name, what)
    }
}

pub(crate) fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

pub(crate) fn compare(fraction: &[f32], reference: &[f32]) -> Errors {
    let (mut sum_sq, mut sum, mut max, mut over) = (0.0, 0.0, 0.0f64, 0.0f64);
    let (mut compared, mut shadowed, mut missed) = (0, 0, 0);
    for (&f, &r) in fraction.iter().zip(reference) {
        if f.is_finite() && r.is_finite() {
            let e = f as f64 - r as f64;
            sum_sq += e * e;
            sum += e;
            max = max.max(e.abs());
            over = over.max(e);
            if r < 1.0 {
                shadowed += 1;
                missed += usize::from(f == 1.0);
            }
            compared += 1;
        }
    }
    let n = compared.max(1) as f64;
    Errors {
        rmse: (sum_sq / n).sqrt(),
        max,
        bias: sum / n,
        over,
        compared,
        shadowed,
        missed,
    }
}

pub(crate) fn check_proofs(
    classes: &[Option<ShadowClass>],
    reference: &[f32],
    of: Reference,
) -> Proofs {
    let tolerance = of.rounding() as f32;
    let mut p = Proofs::default();
    for (class, &r) in classes.iter().zip(reference) {
        let Some(class) = class else { continue };
        p.shaded += 1;
        let contradicted = match class {
            ShadowClass::Lit => {
                p.lit += 1;
                r.is_finite() && r < 1.0 - tolerance
            }
            ShadowClass::Umbra => {
                p.umbra += 1;
                r.is_finite() && r > tolerance
            }
            ShadowClass::BackFacing => {
                p.back_facing += 1;
                false
            }
            ShadowClass::Penumbra => false,
        };
        p.contradictions += usize::from(contradicted);
    }
    p
}

/// Checks each pixel's proven bound against the reference fractions `reference` of the
/// render `of`.
fn check_bounds(maps: &ShadowMaps, reference: &[f32], of: Reference, p: &mut Proofs) {
    let (Some(lower), Some(upper)) = (maps.lower.first(), maps.upper.first()) else {
        return;
    };
    for ((&lo, &hi), &r) in lower.iter().zip(upper).zip(reference) {
        if !(lo.is_finite() && hi.is_finite() && r.is_finite()) {
            continue;
        }
        p.widest_bound = p.widest_bound.max(hi - lo);
        let r = f64::from(r);
        let slack = of.slack(r);
        if f64::from(lo) > r + slack || f64::from(hi) < r - slack {
            p.bound_violations += 1;
        }
    }
}

pub(crate) fn measure(
    setting: Setting,
    out: &RenderOutput,
    reference: &[f32],
    of: Reference,
) -> Result<RunResult, String> {
    let maps = out.shadows.as_ref().ok_or("no soft-shadow maps")?;
    let mut proofs = check_proofs(&maps.classes, reference, of);
    check_bounds(maps, reference, of, &mut proofs);
    Ok(RunResult {
        setting,
        shadow_time: shadow_time(out),
        total_time: out.stats.total,
        errors: compare(fractions(out)?, reference),
        proofs,
    })
}

pub(crate) fn percent(part: usize, whole: usize) -> f64 {
    100.0 * part as f64 / whole.max(1) as f64
}

/// Indices of the runs on the Pareto front of `metric` (no other run with the scene's
/// settings both faster and more accurate), fastest first. Only runs with the scene's
/// settings compete: a variant of the root epsilon or precision gives the same errors as
/// its default, so its place on a front would be timing noise.
pub(crate) fn pareto(runs: &[RunResult], metric: Metric) -> Vec<usize> {
    let mut order: Vec<usize> = (0..runs.len())
        .filter(|&i| runs[i].setting.variant == Variant::Default)
        .collect();
    order.sort_by(|&a, &b| {
        runs[a]
            .shadow_time
            .cmp(&runs[b].shadow_time)
            .then(metric.of(&runs[a]).total_cmp(&metric.of(&runs[b])))
    });
    let mut best = f64::INFINITY;
    order
        .into_iter()
        .filter(|&i| {
            let e = metric.of(&runs[i]);
            let on_front = e < best;
            best = best.min(e);
            on_front
        })
        .collect()
}

/// The cheapest run with the scene's settings whose `metric` is at most `level`.
pub(crate) fn cheapest(report: &SceneReport, metric: Metric, level: f64) -> Option<&RunResult> {
    report
        .runs
        .iter()
        .filter(|r| r.setting.variant == Variant::Default && metric.of(r) <= level)
        .min_by(|a, b| a.shadow_time.cmp(&b.shadow_time))
}

/// Time of the soft-shadow pass of a render.
pub(crate) fn shadow_time(out: &RenderOutput) -> Duration {
    out.stats
        .pass("soft-shadows")
        .map_or(Duration::ZERO, |p| p.time)
}

/// The visible fraction of the first area light, per pixel.
pub(crate) fn fractions(out: &RenderOutput) -> Result<&[f32], String> {
    out.shadows
        .as_ref()
        .and_then(|m| m.fractions.first())
        .map(Vec::as_slice)
        .ok_or_else(|| "the render has no soft-shadow maps (no area light?)".to_string())
}
