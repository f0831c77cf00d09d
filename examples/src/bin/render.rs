//! Renders a scene file (or the built-in default scene) with the reliable CPU renderer and
//! prints the effect plan before and the cost of each pass after.
//!
//! ```text
//! render [SCENE] [--out FILE.png] [--width W --height H] [--root-finder NAME]
//!        [--epsilon E] [--aa none|iaa|iaa:D:T:M|ss:N] [--threads N] [--stats FILE.json]
//!        [--primary screen-boxes|screen-rays|per-pixel|octree] [--undecided-depth D]
//!        [--classification FILE.png] [--cost-map FILE.png]
//!        [--shadows stochastic:N|beam:n|beam-all:n|beam-quadtree:n|
//!                   minkowski:stochastic:N|minkowski:beam:n|certified:TOL[:BUDGET[:SEGMENTS]]]
//!        [--shadow-classes FILE.png] [--shadow-fraction PREFIX] [--precision f64|f32|dd]
//! ```
//!
//! `SCENE` is a TOML scene file or the name of a catalog surface.
//!
//! A scene file with an `[animation]` table (`beam_trace::scene::animation`) is rendered
//! frame by frame: `--out anim.png` writes `anim-0000.png`, `anim-0001.png`, … (numbered by
//! the frame time `t`) and `anim.apng`, an animated PNG that plays at the file's rate; each
//! frame's per-pass table is printed, and a summary at the end. The other outputs
//! (`--classification`, `--stats`, …) are for single images.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use beam_trace::blocks::{BlockReport, BlockSettings, Frames, reads_proofs, render_blocks};
use beam_trace::image::{check_writable, write_atomic};
use beam_trace::root::RootMethod;
use beam_trace::scene::{AaMode, Animation, PrimaryMode};
use beam_trace::shadow::ShadowSpec;
use beam_trace::{Precision, Scene, render_on};
use clap::Parser;
use examples::pass_bars::PassBars;
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};

/// Reliable interval ray tracing of implicit surfaces.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Scene file (TOML) or catalog surface name; the built-in default scene when absent.
    scene: Option<String>,
    /// Output image.
    #[arg(long, default_value = "render.png")]
    out: PathBuf,
    /// Image width (keeps the scene's field of view).
    #[arg(long)]
    width: Option<u32>,
    /// Image height.
    #[arg(long)]
    height: Option<u32>,
    /// Root finder (bisection, mitchell, newton, newton-alefeld-hansen, newton-hc4, mrf, mrfro,
    /// mrfro-newton, counter-bisection, point-sampling, sphere-tracing).
    #[arg(long)]
    root_finder: Option<RootMethod>,
    /// Root enclosure width.
    #[arg(long)]
    epsilon: Option<f64>,
    /// Anti-aliasing: none, iaa, iaa:D (depth D), iaa:D:T (and shading-variation threshold
    /// T), iaa:D:T:M (and M × M rays in a part left undecided at depth D, default 2), or
    /// ss:N (N × N rays per pixel). Default: the scene's, else iaa:1:0.1:2 in the
    /// screen-boxes primary mode and none in the others.
    #[arg(long)]
    aa: Option<AaMode>,
    /// Primary visibility: screen-boxes (Undecided pixels resolved by their beams),
    /// screen-rays (9 point rays per Undecided pixel, the thesis's), per-pixel, or octree
    /// (each pixel's first cell of a frustum octree, then rays from there).
    #[arg(long)]
    primary: Option<PrimaryMode>,
    /// Largest subdivision depth of an Undecided pixel's beam in screen-boxes mode (0 to 8),
    /// also the depth limit of the default anti-aliasing (none at 0).
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=8))]
    undecided_depth: Option<u32>,
    /// Rays per pixel in per-pixel mode (a square number).
    #[arg(long)]
    rays_per_pixel: Option<u32>,
    /// Soft-shadow method of area lights: stochastic:N (stochastic:N:cache), beam:n,
    /// beam-all:n, beam-quadtree:n, minkowski:stochastic:N, minkowski:beam:n,
    /// certified:TOL, certified:TOL:BUDGET or certified:TOL:BUDGET:SEGMENTS (the visible
    /// fraction proven to lie in a bound at most TOL wide, with at most BUDGET beams per
    /// point, default 1024, and an estimate inside it from SEGMENTS stratified segments,
    /// default 32), or, for scenes with triangle meshes, exact, exact:D or exact:D:G (the
    /// meshes' shadows by the lazy BSP of seed 003, up to G neighbouring points sharing a
    /// tree, default 64, the implicit surfaces' by beams over the visible fragments halved
    /// up to D times, default 10) and exact:D:G:triangles (the triangles as occluders
    /// rather than the meshes' faces).
    #[arg(long)]
    shadows: Option<ShadowSpec>,
    /// Where the searches run: cpu (the reliable CPU renderer) or gpu (wgpu compute).
    #[arg(long, value_parser = ["cpu", "gpu"], default_value = "cpu")]
    backend: String,
    /// Write the soft-shadow classification image (proven lit green, proven umbra blue,
    /// penumbra orange).
    #[arg(long)]
    shadow_classes: Option<PathBuf>,
    /// Write, per area light `i`, the per-pixel visible fraction and its proven bounds as
    /// PFM files (`PREFIX-light<i>-fraction.pfm`, `-lower.pfm`, `-upper.pfm`) and the bound
    /// width as an image (`PREFIX-light<i>-width.png`: black proven exactly, white unknown).
    #[arg(long)]
    shadow_fraction: Option<String>,
    /// Floating-point format of the interval evaluations of g and g' on rays and beams:
    /// f64 (default), f32 (as a GPU evaluates; sound, wider enclosures) or dd
    /// (double-double; root searches escalate to it by themselves where rounding blocks a
    /// proof).
    #[arg(long)]
    precision: Option<Precision>,
    /// Do not run root searches that rounding keeps open again in a higher precision.
    #[arg(long)]
    no_escalate: bool,
    /// Frames per block of an animation (thesis 6.4): the screen boxes are classified once
    /// per block over its frames' common n-surface, and each frame skips the tests those
    /// proofs decide; every frame stays bit for bit the frame rendered alone. 1 renders
    /// every frame alone; default: the file's `[animation] block`, else 1.
    #[arg(long)]
    block: Option<usize>,
    /// Regular grid resolution (0: no grid).
    #[arg(long)]
    grid: Option<u32>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Write the statistics as JSON.
    #[arg(long)]
    stats: Option<PathBuf>,
    /// Write the screen box classification image.
    #[arg(long)]
    classification: Option<PathBuf>,
    /// Write the per-pixel cost map.
    #[arg(long)]
    cost_map: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// What the command renders: one scene, or the frames of an animated scene file.
enum Source {
    Still(Box<Scene>),
    Frames(Animation),
}

fn source(args: &Args) -> Result<Source, String> {
    let scene = match &args.scene {
        None => Scene::default_scene(),
        Some(s) if Path::new(s).exists() => {
            let path = Path::new(s);
            if let Some(a) = Animation::load(path).map_err(|e| e.to_string())? {
                return Ok(Source::Frames(a));
            }
            Scene::load(path).map_err(|e| e.to_string())?
        }
        Some(s) if !s.ends_with(".toml") => {
            Scene::catalog(s, 512, 512).map_err(|e| e.to_string())?
        }
        Some(s) => return Err(format!("{s}: no such scene file")),
    };
    Ok(Source::Still(Box::new(scene)))
}

/// `scene` with the command line's settings applied.
fn apply(args: &Args, mut scene: Scene) -> Result<Scene, String> {
    if args.width.is_some() || args.height.is_some() {
        let w = args.width.unwrap_or(scene.camera.width());
        let h = args.height.unwrap_or(scene.camera.height());
        if !(1..=16384).contains(&w) || !(1..=16384).contains(&h) {
            return Err("--width and --height must lie in 1..=16384".into());
        }
        scene.camera = scene.camera.resized(w, h).map_err(|e| e.to_string())?;
    }
    let s = &mut scene.settings;
    if let Some(m) = args.root_finder {
        s.root_finder = m;
    }
    if let Some(e) = args.epsilon {
        if !(e > 0.0 && e.is_finite()) {
            return Err("--epsilon must be positive".into());
        }
        s.root.epsilon = e;
    }
    if let Some(aa) = args.aa {
        s.aa = Some(aa);
    }
    if let Some(p) = args.primary {
        s.primary = p;
    }
    if let Some(d) = args.undecided_depth {
        s.undecided_depth = d;
    }
    if let Some(n) = args.rays_per_pixel {
        let k = (n as f64).sqrt().round() as u32;
        if n == 0 || k * k != n || n > 256 {
            return Err("--rays-per-pixel must be a square number from 1 to 256".into());
        }
        s.rays_per_pixel = n;
    }
    if let Some(m) = args.shadows {
        s.shadow_method = m;
    }
    if args.no_escalate {
        s.root.escalate = false;
    }
    if let Some(p) = args.precision {
        s.precision = p;
    }
    if let Some(g) = args.grid {
        if g > beam_trace::scene::MAX_GRID_RESOLUTION {
            return Err(format!(
                "--grid must be at most {}",
                beam_trace::scene::MAX_GRID_RESOLUTION
            ));
        }
        s.grid_resolution = g;
        s.grid_auto = false;
    }
    Ok(scene)
}

fn run(args: Args) -> Result<(), String> {
    if let Some(n) = args.threads {
        if n == 0 {
            return Err("--threads must be at least 1".into());
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .map_err(|e| e.to_string())?;
    }
    let scene = match source(&args)? {
        Source::Still(scene) => apply(&args, *scene)?,
        Source::Frames(animation) => return run_animation(&args, &animation),
    };
    // Report unwritable outputs before the work starts.
    for p in [
        Some(&args.out),
        args.stats.as_ref(),
        args.classification.as_ref(),
        args.cost_map.as_ref(),
        args.shadow_classes.as_ref(),
    ]
    .into_iter()
    .flatten()
    {
        check_writable(p).map_err(|e| format!("cannot write output: {e}"))?;
    }
    if let Some(prefix) = &args.shadow_fraction {
        check_writable(&shadow_file(prefix, 0, "width.png"))
            .map_err(|e| format!("cannot write output: {e}"))?;
    }
    println!(
        "scene {}: {} × {} pixels, {} surface(s), {} light(s), {} thread(s)",
        scene.name,
        scene.camera.width(),
        scene.camera.height(),
        scene.geometry.leaves().len(),
        scene.lights.len(),
        rayon::current_num_threads()
    );
    let bar = PassBars::new(args.quiet);
    let backend = backend(&args)?;
    let plan = beam_trace::Plan::for_scene(&scene);
    print!("{plan}");
    print!(
        "{}",
        beam_trace::Routing::new(backend.as_ref(), &scene, &plan)
    );
    let out = render_on(&scene, backend.as_ref(), &bar).map_err(|e| e.to_string())?;
    out.image.write_png(&args.out).map_err(|e| e.to_string())?;
    println!("{}", out.stats);
    println!("wrote {}", args.out.display());
    if let Some(p) = &args.classification {
        out.classification()
            .write_png(p)
            .map_err(|e| e.to_string())?;
        println!("wrote {}", p.display());
    }
    if let Some(p) = &args.cost_map {
        out.cost_map().write_png(p).map_err(|e| e.to_string())?;
        println!("wrote {}", p.display());
    }
    if let Some(p) = &args.shadow_classes {
        let maps = out.shadows.as_ref().ok_or_else(|| {
            "--shadow-classes: the scene has no area light with shadows on, so no soft-shadow \
             pass ran"
                .to_string()
        })?;
        maps.image.write_png(p).map_err(|e| e.to_string())?;
        println!("wrote {}", p.display());
    }
    if let Some(prefix) = &args.shadow_fraction {
        write_shadow_fractions(&out, prefix)?;
    }
    if let Some(p) = &args.stats {
        let json = serde_json::to_string_pretty(&out.stats).map_err(|e| e.to_string())?;
        write_atomic(p, |f| std::io::Write::write_all(f, json.as_bytes()))
            .map_err(|e| e.to_string())?;
        println!("wrote {}", p.display());
    }
    Ok(())
}

/// The backend `--backend` names.
fn backend(args: &Args) -> Result<Box<dyn beam_trace::Backend>, String> {
    Ok(if args.backend == "gpu" {
        let gpu = gpu_backend::Gpu::new().map_err(|e| e.to_string())?;
        println!("GPU adapter: {}", gpu.name());
        Box::new(gpu_backend::GpuBackend::new(gpu))
    } else {
        Box::new(beam_trace::Cpu)
    })
}

/// `PATH` with `-SUFFIX.EXT` in place of its extension (`anim.png` → `anim-0007.png`).
fn sibling(path: &Path, suffix: &str, ext: &str) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "render".into());
    path.with_file_name(format!("{stem}{suffix}.{ext}"))
}

/// Renders every frame of `animation`: numbered PNG files and an animated PNG.
fn run_animation(args: &Args, animation: &Animation) -> Result<(), String> {
    for (given, name) in [
        (args.stats.is_some(), "--stats"),
        (args.classification.is_some(), "--classification"),
        (args.cost_map.is_some(), "--cost-map"),
        (args.shadow_classes.is_some(), "--shadow-classes"),
        (args.shadow_fraction.is_some(), "--shadow-fraction"),
    ] {
        if given {
            return Err(format!(
                "{name} writes the outputs of one image; an animation writes its frames \
                 (render a frame alone from a static copy of the file for it)"
            ));
        }
    }
    let frames = animation.frames();
    let count = frames.end() - frames.start() + 1;
    // Numbered by t: `-0007`, `-m0003` for t = −3 (names sort by t from −9999 to 9999).
    let frame_file = |t: i64| {
        let number = if t < 0 {
            format!("-m{:04}", t.unsigned_abs())
        } else {
            format!("-{t:04}")
        };
        sibling(&args.out, &number, "png")
    };
    let apng = sibling(&args.out, "", "apng");
    for p in [frame_file(*frames.start()), apng.clone()] {
        check_writable(&p).map_err(|e| format!("cannot write output: {e}"))?;
    }
    println!(
        "animation: {count} frame(s), t = {} ..= {}, {} frame(s) per second, {} value(s) \
         written as formulas of t, {} thread(s)",
        frames.start(),
        frames.end(),
        animation.rate(),
        animation.time_values(),
        rayon::current_num_threads()
    );
    // Every frame's scene is checked before any is rendered: a formula of `t` without a
    // value, or frames of different sizes, are reported before the work starts.
    let mut size = None;
    // The first frame's scene, kept for the plan printed before the frames.
    let mut first_scene = None;
    for t in frames.clone() {
        let scene = apply(args, animation.scene(t).map_err(|e| e.to_string())?)?;
        let s = (scene.camera.width(), scene.camera.height());
        match size {
            None => {
                size = Some(s);
                first_scene = Some(scene);
            }
            Some(first) if first != s => {
                return Err(format!(
                    "frame t = {t} is {} × {} pixels, frame t = {} is {} × {}: the frames of \
                     an animation must have one size",
                    s.0,
                    s.1,
                    frames.start(),
                    first.0,
                    first.1
                ));
            }
            _ => {}
        }
    }
    let (width, height) = size.unwrap_or((0, 0));
    let backend = backend(args)?;
    // A bar of the frames, with each frame's pass bars below it.
    let multi = MultiProgress::new();
    let frames_bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        let b = multi.add(ProgressBar::new(count as u64));
        b.set_style(
            ProgressStyle::with_template(
                "{prefix:>13} [{bar:40}] {pos}/{len} {elapsed} (eta {eta})",
            )
            .expect("valid template")
            .progress_chars("=> "),
        );
        b.set_prefix("frames");
        b
    };
    let bar = PassBars::below(multi.clone(), args.quiet);
    let start = std::time::Instant::now();
    let blocks = BlockSettings {
        size: args.block.unwrap_or(animation.block()).max(1),
        ..BlockSettings::default()
    };
    if blocks.size > 1 && !reads_proofs(backend.as_ref()) {
        println!(
            "blocks: the {} backend's beams do not read a block's proofs: every frame is \
             rendered alone",
            backend.name()
        );
    } else if blocks.size > 1 {
        println!(
            "blocks: up to {} frame(s), split where the frames differ in form or the \
             n-surface leaves more than {:.1}x the pixels of its first frame open",
            blocks.size, blocks.max_growth
        );
    }
    // Printed above the bars, which stay at the bottom.
    let say = |text: String| {
        if args.quiet {
            println!("{text}");
        } else {
            multi.suspend(|| println!("{text}"));
        }
    };
    let first_t = *frames.start();
    let mut sink = FrameSink {
        args,
        animation,
        first: first_t,
        count: count as usize,
        file: &frame_file,
        say: &say,
        bar: &frames_bar,
        // Kept as 8-bit RGB for the animated file: a quarter of the memory of the images.
        images: Vec::new(),
        slowest: (0.0, first_t),
        started: std::time::Instant::now(),
    };
    if let Some(first) = first_scene {
        let plan = beam_trace::Plan::for_scene(&first);
        print!("{plan}");
        print!(
            "{}",
            beam_trace::Routing::new(backend.as_ref(), &first, &plan)
        );
    }
    let reports = render_blocks(count as usize, &mut sink, blocks, backend.as_ref(), &bar)
        .map_err(|e| e.to_string())?;
    let (images, slowest) = (sink.images, sink.slowest);
    if blocks.size > 1 {
        let (saved, cost) = reports
            .iter()
            .fold((0, 0), |(s, c), r| (s + r.saved, c + r.cost));
        let formed = reports.iter().filter(|r| r.formed()).count();
        println!(
            "blocks: {formed} formed, {} split; their passes made {cost} interval evaluations \
             and spared the frames {saved} rejection tests",
            reports.iter().filter(|r| r.split.is_some()).count()
        );
    }
    frames_bar.finish_and_clear();
    beam_trace::image::write_apng_rgb8(width, height, &images, animation.rate(), &apng)
        .map_err(|e| e.to_string())?;
    let total = start.elapsed().as_secs_f64();
    println!(
        "{count} frame(s) in {total:.3} s ({:.3} s per frame, the slowest t = {} in {:.3} s); \
         wrote {}",
        total / count as f64,
        slowest.1,
        slowest.0,
        apng.display()
    );
    Ok(())
}

/// The frames of an animation for [`render_blocks`]: each frame's scene, and its output
/// written as it comes.
struct FrameSink<'a> {
    args: &'a Args,
    animation: &'a Animation,
    /// `t` of the first frame; frame `k` is `first + k`.
    first: i64,
    count: usize,
    file: &'a dyn Fn(i64) -> PathBuf,
    say: &'a dyn Fn(String),
    bar: &'a ProgressBar,
    images: Vec<Vec<u8>>,
    slowest: (f64, i64),
    started: std::time::Instant,
}

impl Frames for FrameSink<'_> {
    fn scene(&mut self, k: usize) -> Result<Scene, beam_trace::Error> {
        let scene = self.animation.scene(self.first + k as i64)?;
        apply(self.args, scene).map_err(|message| beam_trace::Error::Setting {
            name: "command line".into(),
            message,
        })
    }

    fn done(&mut self, k: usize, out: beam_trace::RenderOutput) -> Result<(), beam_trace::Error> {
        let t = self.first + k as i64;
        // A frame's time includes its share of its block's pass (counted in its first frame).
        let seconds = self.started.elapsed().as_secs_f64();
        if seconds > self.slowest.0 {
            self.slowest = (seconds, t);
        }
        let file = (self.file)(t);
        out.image.write_png(&file)?;
        (self.say)(format!(
            "frame t = {t} ({}/{}): {seconds:.3} s, wrote {}\n{}",
            self.images.len() + 1,
            self.count,
            file.display(),
            out.stats
        ));
        self.bar.inc(1);
        self.images.push(out.image.to_rgb8());
        self.started = std::time::Instant::now();
        Ok(())
    }

    fn block(&mut self, report: &BlockReport) {
        (self.say)(block_line(report, self.first));
    }
}

/// What a block did: its frames, its own passes, and whether it was split.
fn block_line(r: &BlockReport, first: i64) -> String {
    let t = |k: usize| first + k as i64;
    let mut line = format!(
        "block t = {} ..= {}: ",
        t(r.first),
        t(r.first + r.frames - 1)
    );
    if !r.formed() {
        line.push_str("no common n-surface");
    } else {
        let _ = write!(
            line,
            "{:.3} s, {} piece(s) of {} beam(s) proven root-free, n-surface {:.2}x its first \
             frame's open pixels",
            r.time.as_secs_f64(),
            r.proven.0,
            r.proven.1,
            r.growth
        );
        for p in &r.passes {
            let counters: Vec<String> =
                p.counters.iter().map(|(n, v)| format!("{n}={v}")).collect();
            let _ = write!(
                line,
                "\n  {:<13} {:>8.1} ms  {}",
                p.name,
                p.time.as_secs_f64() * 1e3,
                counters.join(" ")
            );
        }
    }
    if let Some(why) = &r.split {
        let _ = write!(line, "\n  split: {why}");
    }
    line
}

/// The file of area light `light`'s map `what` under `prefix`.
fn shadow_file(prefix: &str, light: usize, what: &str) -> PathBuf {
    PathBuf::from(format!("{prefix}-light{light}-{what}"))
}

/// `--shadow-fraction`: each area light's fraction and bound maps and bound-width image.
fn write_shadow_fractions(out: &beam_trace::RenderOutput, prefix: &str) -> Result<(), String> {
    let maps = out.shadows.as_ref().ok_or_else(|| {
        "--shadow-fraction: the scene has no area light with shadows on, so no soft-shadow pass \
         ran"
        .to_string()
    })?;
    for light in 0..maps.fractions.len() {
        let [fraction, lower, upper] = maps.light_maps(light).ok_or("no such light")?;
        for (map, what) in [
            (fraction, "fraction.pfm"),
            (lower, "lower.pfm"),
            (upper, "upper.pfm"),
        ] {
            let p = shadow_file(prefix, light, what);
            map.write_pfm(&p).map_err(|e| e.to_string())?;
            println!("wrote {}", p.display());
        }
        let p = shadow_file(prefix, light, "width.png");
        let image = maps.bound_width_image(light).ok_or("no such light")?;
        image.write_png(&p).map_err(|e| e.to_string())?;
        println!("wrote {}", p.display());
    }
    Ok(())
}

fn main() -> ExitCode {
    examples::report::exit(run(Args::parse()))
}
