//! The runs of the experiment: which settings, the renders of one scene against the
//! reference, and the images they leave (reference, shadow classes, error maps).

use std::path::Path;
use std::time::Duration;

use beam_trace::root::RootSettings;
use beam_trace::scene::RenderSettings;
use beam_trace::shadow::{Fine, ShadowSpec, Strategy};
use beam_trace::{Image, NoProgress, Precision, RenderOutput, Scene, render};

use super::metrics::{RunResult, SceneReport, measure, ms, percent};
use super::plots::Family;
use super::{CLASS_IMAGE, ERROR_MAPS, Options};

/// Saved images are enlarged this many times (nearest neighbour) to be readable.
pub(crate) const ZOOM: u32 = 3;

/// Settings whose root-finder epsilon and precision are varied.
pub(crate) const VARIED: [&str; 2] = ["beam:7", "stochastic:64"];

/// Methods of a full run.
pub(crate) const FULL: &[&str] = &[
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
pub(crate) const QUICK: &[&str] = &[
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

/// What a run changes besides the shadow method.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) enum Variant {
    /// The scene's settings.
    Default,
    /// The root finder's epsilon.
    Epsilon(f64),
    /// Single-precision interval evaluation.
    F32,
}

/// A shadow method with a variant of the other settings.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(crate) struct Setting {
    pub(crate) spec: ShadowSpec,
    pub(crate) variant: Variant,
}

impl Setting {
    pub(crate) fn new(spec: ShadowSpec) -> Self {
        Setting {
            spec,
            variant: Variant::Default,
        }
    }

    /// Applies the setting to a scene's render settings.
    pub(crate) fn apply(&self, s: &mut RenderSettings) {
        s.shadow_method = self.spec;
        match self.variant {
            Variant::Default => {}
            Variant::Epsilon(e) => s.root.epsilon = e,
            Variant::F32 => s.precision = Precision::F32,
        }
    }

    /// The variant as the report's "setting" column writes it.
    pub(crate) fn variant_name(&self) -> String {
        match self.variant {
            Variant::Default => "default".into(),
            Variant::Epsilon(e) => format!("epsilon {e:.0e}"),
            Variant::F32 => "f32".into(),
        }
    }

    /// Whether this is `spec` (written as the command line does) with the scene's settings.
    pub(crate) fn is(&self, spec: &str) -> bool {
        self.variant == Variant::Default && self.spec.to_string() == spec
    }

    /// A short label for the plots.
    pub(crate) fn label(&self) -> String {
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

    pub(crate) fn family(&self) -> Family {
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

/// The file name of an image of the report.
pub(crate) fn image_name(scene: &str, what: &str) -> String {
    format!("accuracy-{scene}-{what}.png")
}

/// The settings of a run: every method, then the epsilon and precision variants.
pub(crate) fn settings(quick: bool) -> Result<Vec<Setting>, String> {
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

pub(crate) fn render_with(scene: &Scene, setting: &Setting) -> Result<RenderOutput, String> {
    let mut scene = scene.clone();
    setting.apply(&mut scene.settings);
    render(&scene, &NoProgress).map_err(|e| format!("{}: {setting:?}: {e}", scene.name))
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

pub(crate) fn print_run(r: &RunResult) {
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

pub(crate) fn load_scene(path: &Path, width: u32, height: u32) -> Result<Scene, String> {
    let mut scene = Scene::load(path).map_err(|e| format!("{}: {e}", path.display()))?;
    scene.camera = scene
        .camera
        .resized(width, height)
        .map_err(|e| e.to_string())?;
    Ok(scene)
}

pub(crate) fn scene_name(path: &Path) -> String {
    path.file_stem()
        .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned())
}

/// Renders the reference and every setting of one scene, writing its images.
pub(crate) fn run_scene(path: &Path, opts: &Options) -> Result<SceneReport, String> {
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
pub(crate) fn error_map(out: &RenderOutput, reference: &[f32]) -> Result<Image, String> {
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
pub(crate) fn zoom(image: &Image, k: u32) -> Image {
    let mut big = Image::new(image.width * k, image.height * k, [0.0; 3]);
    for y in 0..big.height {
        for x in 0..big.width {
            big.set(x, y, image.get(x / k, y / k));
        }
    }
    big
}

pub(crate) fn write_image(image: &Image, dir: &Path, file: &str) -> Result<(), String> {
    zoom(image, ZOOM)
        .write_png(&dir.join(file))
        .map_err(|e| e.to_string())
}
