//! What soft-shadow accuracy costs in time: renders a few scenes with every soft-shadow
//! method and setting, measures the per-pixel visible fraction of the first area light
//! against a many-sample stochastic reference, and writes a markdown report with
//! time-against-error plots.
//!
//! ```text
//! accuracy-cost [SCENE.toml ...] [--width W --height H] [--reference-samples N]
//!               [--out-dir DIR] [--quick]
//! ```
//!
//! For each scene (default: `scenes/soft-shadows.toml` and `scenes/thin-occluder.toml`, at
//! 128 × 96 pixels; about three minutes on two cores):
//!
//! 1. a reference render with `stochastic:N` (`--reference-samples`, default 4096);
//! 2. one render per setting: `stochastic:N` for N in 4..1024 (two with the last-occluder
//!    cache), `beam:n` for n in 2..16, `beam-all:7`, `beam-quadtree:8`,
//!    `minkowski:stochastic:N`, `minkowski:beam:n`, and `beam:7` and `stochastic:64` with
//!    the root finder's epsilon at 1e-3 and 100 times its default and in `f32` precision;
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
//! `--quick` is a smoke run: a 32 × 24 image, a 256-sample reference, fewer settings, and
//! the report in the system's temporary folder unless `--out-dir` is given.

use std::fmt::{self, Write as _};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use beam_trace::root::RootSettings;
use beam_trace::scene::RenderSettings;
use beam_trace::shadow::{Fine, ShadowClass, ShadowSpec, Strategy};
use beam_trace::{Image, NoProgress, Precision, RenderOutput, Scene, render};
use clap::Parser;
use plotters::prelude::*;

/// Soft-shadow accuracy against time, per method and setting.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Scene files (TOML) with at least one area light.
    #[arg(default_values = ["scenes/soft-shadows.toml", "scenes/thin-occluder.toml"])]
    scenes: Vec<PathBuf>,
    /// Image width (default 128; 32 with --quick).
    #[arg(long)]
    width: Option<u32>,
    /// Image height (default 96; 24 with --quick).
    #[arg(long)]
    height: Option<u32>,
    /// Samples of the stochastic reference (default 4096; 256 with --quick).
    #[arg(long)]
    reference_samples: Option<u32>,
    /// Folder of the report (`accuracy.md`) and of its `images/` (default `docs`; the
    /// system's temporary folder with --quick).
    #[arg(long)]
    out_dir: Option<PathBuf>,
    /// Smoke run: tiny images, a small reference and fewer settings.
    #[arg(long)]
    quick: bool,
}

/// The command that reproduces the report.
const COMMAND: &str = "cargo run --release -p examples --bin accuracy-cost";

/// The settings the time ratios are relative to.
const BASELINE: &str = "stochastic:64";

/// The setting whose shadow-class image goes into the report.
const CLASS_IMAGE: &str = "beam:7";

/// Settings whose error maps go into the report, with their image names.
const ERROR_MAPS: [(&str, &str); 2] = [
    ("beam:7", "beam7-error"),
    ("stochastic:64", "stochastic64-error"),
];

/// Saved images are enlarged this many times (nearest neighbour) to be readable.
const ZOOM: u32 = 3;

/// Settings whose root-finder epsilon and precision are varied.
const VARIED: [&str; 2] = ["beam:7", "stochastic:64"];

/// Methods of a full run.
const FULL: &[&str] = &[
    "stochastic:4",
    "stochastic:16",
    "stochastic:64",
    "stochastic:256",
    "stochastic:1024",
    "stochastic:16:cache",
    "stochastic:64:cache",
    "beam:2",
    "beam:3",
    "beam:4",
    "beam:7",
    "beam:8",
    "beam:16",
    "beam-all:7",
    "beam-quadtree:8",
    "minkowski:stochastic:16",
    "minkowski:stochastic:64",
    "minkowski:stochastic:256",
    "minkowski:beam:4",
    "minkowski:beam:7",
    "minkowski:beam:16",
];

/// Methods of a `--quick` run.
const QUICK: &[&str] = &[
    "stochastic:4",
    "stochastic:16",
    "stochastic:64",
    "stochastic:16:cache",
    "beam:2",
    "beam:7",
    "beam-all:7",
    "beam-quadtree:8",
    "minkowski:stochastic:16",
    "minkowski:beam:4",
];

/// Largest errors (RMSE) of the "cheapest setting at each error level" table.
const LEVELS: [f64; 5] = [0.1, 0.05, 0.02, 0.01, 0.005];

/// What a run changes besides the shadow method.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Variant {
    /// The scene's settings.
    Default,
    /// The root finder's epsilon.
    Epsilon(f64),
    /// Single-precision interval evaluation.
    F32,
}

/// A shadow method with a variant of the other settings.
#[derive(Copy, Clone, Debug, PartialEq)]
struct Setting {
    spec: ShadowSpec,
    variant: Variant,
}

impl Setting {
    fn new(spec: ShadowSpec) -> Self {
        Setting {
            spec,
            variant: Variant::Default,
        }
    }

    /// Applies the setting to a scene's render settings.
    fn apply(&self, s: &mut RenderSettings) {
        s.shadow_method = self.spec;
        match self.variant {
            Variant::Default => {}
            Variant::Epsilon(e) => s.root.epsilon = e,
            Variant::F32 => s.precision = Precision::F32,
        }
    }

    /// The variant as the report's "setting" column writes it.
    fn variant_name(&self) -> String {
        match self.variant {
            Variant::Default => "default".into(),
            Variant::Epsilon(e) => format!("epsilon {e:.0e}"),
            Variant::F32 => "f32".into(),
        }
    }

    /// Whether this is `spec` (written as the command line does) with the scene's settings.
    fn is(&self, spec: &str) -> bool {
        self.variant == Variant::Default && self.spec.to_string() == spec
    }

    /// A short label for the plots.
    fn label(&self) -> String {
        let method = match self.spec {
            ShadowSpec::Stochastic { samples, cache } => {
                format!("s{samples}{}", if cache { "c" } else { "" })
            }
            ShadowSpec::Beam { n, strategy } => {
                let s = match strategy {
                    Strategy::Initial => "b",
                    Strategy::All => "ba",
                    Strategy::Quadtree => "bq",
                };
                format!("{s}{n}")
            }
            ShadowSpec::Minkowski {
                fine: Fine::Stochastic { samples },
            } => format!("ms{samples}"),
            ShadowSpec::Minkowski {
                fine: Fine::Beams { n },
            } => format!("mb{n}"),
        };
        match self.variant {
            Variant::Default => method,
            Variant::Epsilon(e) => format!("{method} ε{e:.0e}"),
            Variant::F32 => format!("{method} f32"),
        }
    }

    fn family(&self) -> Family {
        match (self.variant, self.spec) {
            (Variant::Epsilon(_), _) => Family::Epsilon,
            (Variant::F32, _) => Family::F32,
            (_, ShadowSpec::Stochastic { cache: false, .. }) => Family::Stochastic,
            (_, ShadowSpec::Stochastic { cache: true, .. }) => Family::StochasticCache,
            (
                _,
                ShadowSpec::Beam {
                    strategy: Strategy::Initial,
                    ..
                },
            ) => Family::Beam,
            (_, ShadowSpec::Beam { .. }) => Family::BeamOther,
            (
                _,
                ShadowSpec::Minkowski {
                    fine: Fine::Stochastic { .. },
                },
            ) => Family::MinkowskiStochastic,
            (_, ShadowSpec::Minkowski { .. }) => Family::MinkowskiBeam,
        }
    }
}

/// The colour groups of the plots.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Family {
    Stochastic,
    StochasticCache,
    Beam,
    BeamOther,
    MinkowskiStochastic,
    MinkowskiBeam,
    Epsilon,
    F32,
}

impl Family {
    const ALL: [Family; 8] = [
        Family::Stochastic,
        Family::StochasticCache,
        Family::Beam,
        Family::BeamOther,
        Family::MinkowskiStochastic,
        Family::MinkowskiBeam,
        Family::Epsilon,
        Family::F32,
    ];

    fn name(self) -> &'static str {
        match self {
            Family::Stochastic => "stochastic:N",
            Family::StochasticCache => "stochastic:N:cache",
            Family::Beam => "beam:n",
            Family::BeamOther => "beam-all / beam-quadtree",
            Family::MinkowskiStochastic => "minkowski:stochastic:N",
            Family::MinkowskiBeam => "minkowski:beam:n",
            Family::Epsilon => "root epsilon varied",
            Family::F32 => "f32 precision",
        }
    }

    /// Whether the family's visible fraction is a proven lower bound of the true one.
    fn is_lower_bound(self) -> bool {
        matches!(
            self,
            Family::Beam | Family::BeamOther | Family::MinkowskiBeam
        )
    }

    fn color(self) -> RGBColor {
        match self {
            Family::Stochastic => RGBColor(31, 119, 180),
            Family::StochasticCache => RGBColor(23, 190, 207),
            Family::Beam => RGBColor(214, 39, 40),
            Family::BeamOther => RGBColor(255, 127, 14),
            Family::MinkowskiStochastic => RGBColor(44, 160, 44),
            Family::MinkowskiBeam => RGBColor(148, 103, 189),
            Family::Epsilon => RGBColor(140, 86, 75),
            Family::F32 => RGBColor(227, 119, 194),
        }
    }
}

/// The visible fraction of a render against the reference.
#[derive(Copy, Clone, Debug, Default)]
struct Errors {
    /// Root mean square error.
    rmse: f64,
    /// Largest absolute error.
    max: f64,
    /// Mean signed error (negative: darker than the reference).
    bias: f64,
    /// Largest amount by which the fraction exceeds the reference (0 if it never does).
    over: f64,
    /// Pixels where both fractions are finite.
    compared: usize,
    /// Pixels in some shadow in the reference (fraction below 1).
    shadowed: usize,
    /// Of those, pixels the render calls fully lit (fraction 1): shadow it missed.
    missed: usize,
}

/// What a render proved, checked against the reference.
#[derive(Copy, Clone, Debug, Default)]
struct Proofs {
    /// Pixels with a shaded surface.
    shaded: usize,
    /// Pixels proven lit.
    lit: usize,
    /// Pixels proven umbra.
    umbra: usize,
    /// Pixels facing away from the light (no occlusion claimed).
    back_facing: usize,
    /// Proven pixels whose reference fraction says otherwise.
    contradictions: usize,
}

/// One render of a scene and how it compares with the reference.
#[derive(Clone, Debug)]
struct RunResult {
    setting: Setting,
    /// Time of the soft-shadow pass.
    shadow_time: Duration,
    /// Time of the whole render.
    total_time: Duration,
    errors: Errors,
    proofs: Proofs,
}

impl RunResult {
    fn shadow_ms(&self) -> f64 {
        ms(self.shadow_time)
    }
}

/// An error measure the plots and Pareto fronts use.
#[derive(Copy, Clone, Debug)]
enum Metric {
    Rmse,
    MaxError,
}

impl Metric {
    const ALL: [Metric; 2] = [Metric::Rmse, Metric::MaxError];

    fn of(self, r: &RunResult) -> f64 {
        match self {
            Metric::Rmse => r.errors.rmse,
            Metric::MaxError => r.errors.max,
        }
    }

    fn title(self) -> &'static str {
        match self {
            Metric::Rmse => "RMSE",
            Metric::MaxError => "largest error",
        }
    }

    fn file_suffix(self) -> &'static str {
        match self {
            Metric::Rmse => "rmse",
            Metric::MaxError => "max-error",
        }
    }
}

/// Everything measured on one scene.
struct SceneReport {
    /// File stem of the scene, used in image names.
    name: String,
    /// The scene file.
    path: PathBuf,
    width: u32,
    height: u32,
    reference_samples: u32,
    reference_time: Duration,
    runs: Vec<RunResult>,
}

impl SceneReport {
    fn find(&self, spec: &str, variant: Variant) -> Option<&RunResult> {
        self.runs
            .iter()
            .find(|r| r.setting.variant == variant && r.setting.spec.to_string() == spec)
    }

    fn contradictions(&self) -> usize {
        self.runs.iter().map(|r| r.proofs.contradictions).sum()
    }

    /// Shadow time of the baseline, or of the reference if the baseline did not run.
    fn baseline_ms(&self) -> f64 {
        self.find(BASELINE, Variant::Default)
            .map_or(ms(self.reference_time), RunResult::shadow_ms)
    }

    fn image(&self, what: &str) -> String {
        image_name(&self.name, what)
    }
}

/// The file name of an image of the report.
fn image_name(scene: &str, what: &str) -> String {
    format!("accuracy-{scene}-{what}.png")
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// The settings of a run: every method, then the epsilon and precision variants.
fn settings(quick: bool) -> Result<Vec<Setting>, String> {
    let methods = if quick { QUICK } else { FULL };
    let mut out = methods
        .iter()
        .map(|s| s.parse().map(Setting::new))
        .collect::<Result<Vec<_>, _>>()?;
    let epsilon = RootSettings::default().epsilon;
    for spec in VARIED {
        let spec: ShadowSpec = spec.parse()?;
        for variant in [
            Variant::Epsilon(epsilon * 1e-3),
            Variant::Epsilon(epsilon * 100.0),
            Variant::F32,
        ] {
            out.push(Setting { spec, variant });
        }
    }
    Ok(out)
}

fn render_with(scene: &Scene, setting: &Setting) -> Result<RenderOutput, String> {
    let mut scene = scene.clone();
    setting.apply(&mut scene.settings);
    render(&scene, &NoProgress).map_err(|e| format!("{}: {setting:?}: {e}", scene.name))
}

/// Time of the soft-shadow pass of a render.
fn shadow_time(out: &RenderOutput) -> Duration {
    out.stats
        .pass("soft-shadows")
        .map_or(Duration::ZERO, |p| p.time)
}

/// The visible fraction of the first area light, per pixel.
fn fractions(out: &RenderOutput) -> Result<&[f32], String> {
    out.shadows
        .as_ref()
        .and_then(|m| m.fractions.first())
        .map(Vec::as_slice)
        .ok_or_else(|| "the render has no soft-shadow maps (no area light?)".to_string())
}

fn compare(fraction: &[f32], reference: &[f32]) -> Errors {
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

fn check_proofs(classes: &[Option<ShadowClass>], reference: &[f32]) -> Proofs {
    let mut p = Proofs::default();
    for (class, &r) in classes.iter().zip(reference) {
        let Some(class) = class else { continue };
        p.shaded += 1;
        let contradicted = match class {
            ShadowClass::Lit => {
                p.lit += 1;
                r.is_finite() && r < 1.0
            }
            ShadowClass::Umbra => {
                p.umbra += 1;
                r.is_finite() && r > 0.0
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

fn measure(setting: Setting, out: &RenderOutput, reference: &[f32]) -> Result<RunResult, String> {
    let maps = out.shadows.as_ref().ok_or("no soft-shadow maps")?;
    Ok(RunResult {
        setting,
        shadow_time: shadow_time(out),
        total_time: out.stats.total,
        errors: compare(fractions(out)?, reference),
        proofs: check_proofs(&maps.classes, reference),
    })
}

fn percent(part: usize, whole: usize) -> f64 {
    100.0 * part as f64 / whole.max(1) as f64
}

fn print_run(r: &RunResult) {
    println!(
        "  {:<26} {:<16} {:>10.1} ms  rmse {:.5}  max {:.4}  bias {:+.5}  missed {:>5.1}%  lit {:>5.1}%  umbra {:>5.1}%  contradictions {}",
        r.setting.spec.to_string(),
        r.setting.variant_name(),
        r.shadow_ms(),
        r.errors.rmse,
        r.errors.max,
        r.errors.bias,
        percent(r.errors.missed, r.errors.shadowed),
        percent(r.proofs.lit, r.proofs.shaded),
        percent(r.proofs.umbra, r.proofs.shaded),
        r.proofs.contradictions,
    );
}

fn load_scene(path: &Path, width: u32, height: u32) -> Result<Scene, String> {
    let mut scene = Scene::load(path).map_err(|e| format!("{}: {e}", path.display()))?;
    scene.camera = scene
        .camera
        .resized(width, height)
        .map_err(|e| e.to_string())?;
    Ok(scene)
}

fn scene_name(path: &Path) -> String {
    path.file_stem()
        .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned())
}

/// Options resolved from the command line.
struct Options {
    width: u32,
    height: u32,
    reference_samples: u32,
    out_dir: PathBuf,
    settings: Vec<Setting>,
}

impl Options {
    fn from_args(args: &Args) -> Result<Self, String> {
        let (w, h, n) = if args.quick {
            (32, 24, 256)
        } else {
            (128, 96, 4096)
        };
        let width = args.width.unwrap_or(w);
        let height = args.height.unwrap_or(h);
        if !(1..=4096).contains(&width) || !(1..=4096).contains(&height) {
            return Err("--width and --height must lie in 1..=4096".into());
        }
        let out_dir = args.out_dir.clone().unwrap_or_else(|| {
            if args.quick {
                std::env::temp_dir().join("accuracy-cost")
            } else {
                PathBuf::from("docs")
            }
        });
        Ok(Options {
            width,
            height,
            reference_samples: args.reference_samples.unwrap_or(n),
            out_dir,
            settings: settings(args.quick)?,
        })
    }

    fn images(&self) -> PathBuf {
        self.out_dir.join("images")
    }
}

/// Renders the reference and every setting of one scene, writing its images.
fn run_scene(path: &Path, opts: &Options) -> Result<SceneReport, String> {
    let scene = load_scene(path, opts.width, opts.height)?;
    let name = scene_name(path);
    let reference_spec = ShadowSpec::Stochastic {
        samples: opts.reference_samples,
        cache: false,
    };
    println!(
        "{}: {}x{}, reference {reference_spec} ...",
        path.display(),
        opts.width,
        opts.height
    );
    let reference_out = render_with(&scene, &Setting::new(reference_spec))?;
    let reference = fractions(&reference_out)?.to_vec();
    let reference_time = shadow_time(&reference_out);
    println!("  reference: {:.1} ms", ms(reference_time));
    let mut report = SceneReport {
        name: name.clone(),
        path: path.to_path_buf(),
        width: opts.width,
        height: opts.height,
        reference_samples: opts.reference_samples,
        reference_time,
        runs: Vec::with_capacity(opts.settings.len()),
    };
    let save =
        |image: &Image, what: &str| write_image(image, &opts.images(), &image_name(&name, what));
    save(&reference_out.image, "reference")?;
    for &setting in &opts.settings {
        let out = render_with(&scene, &setting)?;
        let run = measure(setting, &out, &reference)?;
        print_run(&run);
        if setting.is(CLASS_IMAGE)
            && let Some(maps) = &out.shadows
        {
            save(&maps.image, "beam7-classes")?;
        }
        for (spec, what) in ERROR_MAPS {
            if setting.is(spec) {
                save(&error_map(&out, &reference)?, what)?;
            }
        }
        report.runs.push(run);
    }
    Ok(report)
}

/// The signed error of a render's visible fraction: white where exact, red where darker
/// than the reference, blue where brighter (intensity `sqrt(|error|)`), near black where
/// either fraction is undefined.
fn error_map(out: &RenderOutput, reference: &[f32]) -> Result<Image, String> {
    let pixels = fractions(out)?
        .iter()
        .zip(reference)
        .map(|(&f, &r)| {
            let e = f - r;
            if !e.is_finite() {
                return [0.05; 3];
            }
            let a = 1.0 - e.abs().min(1.0).sqrt();
            if e < 0.0 { [1.0, a, a] } else { [a, a, 1.0] }
        })
        .collect();
    Ok(Image {
        width: out.image.width,
        height: out.image.height,
        pixels,
    })
}

/// The image enlarged `k` times (nearest neighbour).
fn zoom(image: &Image, k: u32) -> Image {
    let mut big = Image::new(image.width * k, image.height * k, [0.0; 3]);
    for y in 0..big.height {
        for x in 0..big.width {
            big.set(x, y, image.get(x / k, y / k));
        }
    }
    big
}

fn write_image(image: &Image, dir: &Path, file: &str) -> Result<(), String> {
    zoom(image, ZOOM)
        .write_png(&dir.join(file))
        .map_err(|e| e.to_string())
}

/// Indices of the runs on the Pareto front of `metric` (no other run with the scene's
/// settings both faster and more accurate), fastest first. Only runs with the scene's
/// settings compete: a variant of the root epsilon or precision gives the same errors as
/// its default, so its place on a front would be timing noise.
fn pareto(runs: &[RunResult], metric: Metric) -> Vec<usize> {
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

/// Smallest value a log axis shows (an error of exactly 0 is drawn there).
const LOG_FLOOR: f64 = 1e-5;

fn log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
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
fn plot(report: &SceneReport, metric: Metric, path: &Path) -> Result<(), String> {
    draw_plot(report, metric, path).map_err(|e| format!("{}: {e}", path.display()))
}

fn draw_plot(
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
                "{}: soft-shadow time against {} ({}x{}, reference stochastic:{})",
                report.name,
                metric.title(),
                report.width,
                report.height,
                report.reference_samples
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
    chart.draw_series(runs.iter().enumerate().map(|(i, r)| {
        // Alternate the label above and below the point so that neighbours overlap less.
        let dy = if i % 2 == 0 { -16 } else { 4 };
        EmptyElement::at(point(r))
            + Circle::new((0, 0), 5, r.setting.family().color().filled())
            + Text::new(r.setting.label(), (7, dy), ("sans-serif", 12))
    }))?;
    draw_legend(&legend_area, runs)?;
    root.present()?;
    Ok(())
}

/// A log-axis tick label at 1, 2 and 5 times a power of ten, none elsewhere.
fn round_label(v: f64, scientific: bool) -> String {
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
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    runs: &[RunResult],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let font = ("sans-serif", 15);
    let mut y = 70;
    area.draw(&(EmptyElement::at((20, y)) + Circle::new((0, 0), 9, BLACK.stroke_width(2))))?;
    area.draw(&Text::new("Pareto front", (40, y - 8), font))?;
    area.draw(&Text::new("(default settings)", (40, y + 10), font))?;
    y += 18;
    for family in Family::ALL {
        if !runs.iter().any(|r| r.setting.family() == family) {
            continue;
        }
        y += 26;
        area.draw(&Circle::new((20, y), 5, family.color().filled()))?;
        area.draw(&Text::new(family.name(), (40, y - 8), font))?;
    }
    Ok(())
}

/// The report's table of runs.
fn table(md: &mut String, report: &SceneReport) -> fmt::Result {
    writeln!(
        md,
        "| method | setting | soft shadows (ms) | × {BASELINE} | total (ms) | RMSE | max error | bias | missed shadow | proven lit | proven umbra | contradictions |"
    )?;
    writeln!(
        md,
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    )?;
    let base = report.baseline_ms();
    for r in &report.runs {
        writeln!(
            md,
            "| `{}` | {} | {:.1} | {:.2} | {:.1} | {:.5} | {:.4} | {:+.5} | {:.1} % | {:.1} % | {:.1} % | {} |",
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
            r.proofs.contradictions,
        )?;
    }
    Ok(())
}

fn describe(r: &RunResult) -> String {
    match r.setting.variant {
        Variant::Default => format!("`{}`", r.setting.spec),
        _ => format!("`{}` ({})", r.setting.spec, r.setting.variant_name()),
    }
}

fn pareto_list(md: &mut String, report: &SceneReport, metric: Metric) -> fmt::Result {
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
fn cheapest_per_level(md: &mut String, report: &SceneReport) -> fmt::Result {
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
fn variants_reading(md: &mut String, report: &SceneReport) -> fmt::Result {
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
fn bias_reading(md: &mut String, report: &SceneReport) -> fmt::Result {
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

fn scene_section(md: &mut String, report: &SceneReport) -> fmt::Result {
    writeln!(md, "## Scene `{}`\n", report.path.display())?;
    writeln!(
        md,
        "{}×{} pixels; reference `stochastic:{}` (soft shadows {:.0} ms). Contradictions over all runs: **{}**.\n",
        report.width,
        report.height,
        report.reference_samples,
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

const INTRO: &str = "\
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
remains in it, so errors much below that level measure the reference as much as the method.";

const READING: &str = "\
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
- **Proofs.** Only the beam methods prove lit points (their first beam over the whole \
light) and only the Minkowski methods prove umbra; the stochastic method proves nothing, \
its fraction is an estimate.";

/// The cheapest run with the scene's settings whose `metric` is at most `level`.
fn cheapest(report: &SceneReport, metric: Metric, level: f64) -> Option<&RunResult> {
    report
        .runs
        .iter()
        .filter(|r| r.setting.variant == Variant::Default && metric.of(r) <= level)
        .min_by(|a, b| a.shadow_time.cmp(&b.shadow_time))
}

/// The data-driven part of the reading: cheapest settings, the variants' cost, the
/// contradictions.
fn summary(md: &mut String, reports: &[SceneReport]) -> fmt::Result {
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
fn variant_summary(
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
fn markdown(reports: &[SceneReport], opts: &Options, elapsed: Duration) -> String {
    let mut md = String::new();
    let mut write = || -> fmt::Result {
        writeln!(md, "# Soft-shadow accuracy against cost\n")?;
        writeln!(md, "{INTRO}\n")?;
        writeln!(
            md,
            "Reproduce with `{COMMAND}` (options: `--width`, `--height`, `--reference-samples`, `--out-dir`, `--quick`; scene files as arguments). \
             This report: {}×{} pixels, reference `stochastic:{}`, {} settings per scene; the whole run took {:.0} s.\n",
            opts.width,
            opts.height,
            opts.reference_samples,
            opts.settings.len(),
            elapsed.as_secs_f64()
        )?;
        writeln!(
            md,
            "Times come from one run on one machine, with every render using all its cores; \
             absolute times will differ elsewhere, the ratios (column `× {BASELINE}`) are what matter.\n"
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

fn write_report(reports: &[SceneReport], opts: &Options, elapsed: Duration) -> Result<(), String> {
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

fn run(args: &Args) -> Result<usize, String> {
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

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
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
