//! The runs of the experiment: which settings, the renders of one scene against the
//! reference, and the images they leave (reference, shadow classes, error maps).

use std::path::Path;
use std::time::Duration;

use beam_trace::scene::AaMode;
use beam_trace::{Image, NoProgress, RenderOutput, Scene, render};

use super::metrics::{RunResult, SceneReport, fractions, measure, ms, percent, shadow_time};
use super::options::{CLASS_IMAGE, ERROR_MAPS, Options};
use super::setting::{Setting, image_name};
use crate::report::median;

/// Saved images are enlarged this many times (nearest neighbour) to be readable.
pub(crate) const ZOOM: u32 = 3;

pub(crate) fn render_with(scene: &Scene, setting: &Setting) -> Result<RenderOutput, String> {
    let mut scene = scene.clone();
    setting.apply(&mut scene.settings);
    render(&scene, &NoProgress).map_err(|e| format!("{}: {setting:?}: {e}", scene.name))
}

pub(crate) fn print_run(r: &RunResult) {
    println!(
        "  {:<26} {:<16} {:>10.1} ms  rmse {:.5}  max {:.4}  bias {:+.5}  missed {:>5.1}%  lit {:>5.1}%  umbra {:>5.1}%  widest bound {:.3}  contradictions {}  bound violations {}",
        r.setting.spec.to_string(),
        r.setting.variant_name(),
        r.shadow_ms(),
        r.errors.rmse,
        r.errors.max,
        r.errors.bias,
        percent(r.errors.missed, r.errors.shadowed),
        percent(r.proofs.lit, r.proofs.shaded),
        percent(r.proofs.umbra, r.proofs.shaded),
        r.proofs.widest_bound,
        r.proofs.contradictions,
        r.proofs.bound_violations,
    );
}

pub(crate) fn load_scene(path: &Path, width: u32, height: u32) -> Result<Scene, String> {
    let mut scene = Scene::load(path).map_err(|e| format!("{}: {e}", path.display()))?;
    // One sample per Hit pixel: each pixel's visible fraction is one shading point's,
    // compared point for point with the reference's (anti-aliasing would average it).
    scene.settings.aa.get_or_insert(AaMode::None);
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
    let reference_spec = opts.reference.spec();
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
        reference: opts.reference,
        reference_time,
        runs: Vec::with_capacity(opts.settings.len()),
    };
    let save =
        |image: &Image, what: &str| write_image(image, &opts.images(), &image_name(&name, what));
    save(&reference_out.image, "reference")?;
    for &setting in &opts.settings {
        let out = render_with(&scene, &setting)?;
        let run = measure(setting, &out, &reference, opts.reference)?;
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
    median_times(&scene, opts, &mut report.runs).map(|()| report)
}

/// Renders every setting `opts.runs − 1` more times, in rounds over all settings, and
/// gives each run the medians of its shadow and total times (their first render's
/// errors and proofs stay: every method renders the same fractions each time).
fn median_times(scene: &Scene, opts: &Options, runs: &mut [RunResult]) -> Result<(), String> {
    let mut shadow: Vec<Vec<Duration>> = runs.iter().map(|r| vec![r.shadow_time]).collect();
    let mut total: Vec<Vec<Duration>> = runs.iter().map(|r| vec![r.total_time]).collect();
    for round in 1..opts.runs {
        println!("  timing round {} of {}", round + 1, opts.runs);
        for (k, run) in runs.iter().enumerate() {
            let out = render_with(scene, &run.setting)?;
            shadow[k].push(shadow_time(&out));
            total[k].push(out.stats.total);
        }
    }
    for ((run, shadow), total) in runs.iter_mut().zip(&mut shadow).zip(&mut total) {
        run.shadow_time = median(shadow, Ord::cmp).unwrap_or(run.shadow_time);
        run.total_time = median(total, Ord::cmp).unwrap_or(run.total_time);
    }
    Ok(())
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
