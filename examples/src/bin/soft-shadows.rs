//! The soft-shadow papers' experiments, reproduced in one run each.
//!
//! ```text
//! soft-shadows table1 [--size 512] [--sub 7] [--light-fraction 0.1] [--markdown FILE]
//! soft-shadows penumbra [--size 256] [--samples 32] [--markdown FILE]
//! soft-shadows exact [SCENE] [--width 320] [--height 240] [--samples 16,64,256,1024]
//!                    [--sweep-samples 64] [--light-scales 1,2,5,10] [--light-counts 1,2,3,4,6]
//!                    [--light-layout spread|tiled] [--no-sweeps] [--generate TRIANGLES [--stand-in canopy|hall] [--seed S]]
//!                    [--image FILE]
//! ```
//!
//! * `table1`: the reliable soft-shadow paper's Table 1. Orthocircle, Chubs, Kusner-Schmitt
//!   and McMullen, lit by an axis-aligned square light whose area is `--light-fraction` of
//!   the view's area at the surface, with `--sub`² sub-beams: the beam method (one beam over
//!   the light first) against always tracing every sub-beam; also the quadtree subdivision
//!   of the light the paper found slower on its GPU.
//! * `penumbra`: the Minkowski penumbra paper's Tables 1 and 4 in spirit. Minkowski lit and
//!   umbra detection with stochastic sampling in the penumbra against plain stochastic
//!   sampling, with and without the last-occluder cache, on the same catalog scenes and on
//!   `scenes/soft-shadows.toml`, and the speedup as the light grows.
//! * `exact`: the exact-shadow paper's experiments through the renderer on a scene of
//!   polygonal occluders (`scenes/mesh-shadows.toml` by default): equal quality against
//!   stochastic sampling, the coherence ablation, the light size and light count sweeps,
//!   peak memory ([`examples::exact_sweeps`]).
//!
//! Times are wall-clock on this machine with every core; the ratios are what compares with
//! the papers.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use beam_trace::scene::AaMode;
use beam_trace::shadow::ShadowSpec;
use beam_trace::{Light, NoProgress, RenderOutput, Scene, render};
use clap::{Parser, Subcommand};
use examples::soft_scene::{catalog_with_area_light, square_light};

/// Soft-shadow experiments of the beam and Minkowski papers.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    #[command(subcommand)]
    table: Table,
    /// Also write the tables (markdown) to this file.
    #[arg(long, global = true)]
    markdown: Option<PathBuf>,
}

#[derive(Subcommand, Debug)]
enum Table {
    /// The beam paper's Table 1: beam method against always n × n sub-beams.
    Table1 {
        /// Image side in pixels.
        #[arg(long, default_value_t = 512)]
        size: u32,
        /// Sub-beams per side of the light.
        #[arg(long, default_value_t = 7)]
        sub: u32,
        /// Light area as a fraction of the view's area at the surface.
        #[arg(long, default_value_t = 0.1)]
        light_fraction: f64,
    },
    /// The Minkowski paper's Tables 1 and 4: penumbra detection against plain stochastic.
    Penumbra {
        /// Image side in pixels.
        #[arg(long, default_value_t = 256)]
        size: u32,
        /// Stochastic samples per point.
        #[arg(long, default_value_t = 32)]
        samples: u32,
    },
    /// The exact-shadow paper's experiments through the renderer.
    Exact {
        /// The scene file (its occluders polygons, so that the exact method is the
        /// reference).
        #[arg(default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/mesh-shadows.toml"))]
        scene: PathBuf,
        /// Image width in pixels.
        #[arg(long, default_value_t = 320)]
        width: u32,
        /// Image height in pixels.
        #[arg(long, default_value_t = 240)]
        height: u32,
        /// Samples of the stochastic runs of the equal-quality table.
        #[arg(long, value_delimiter = ',', default_value = "16,64,256,1024")]
        samples: Vec<u32>,
        /// Samples of the stochastic runs of the light sweeps.
        #[arg(long, default_value_t = 64)]
        sweep_samples: u32,
        /// Multipliers of each light's side (area times their squares: 10 is 100 times).
        #[arg(long, value_delimiter = ',', default_value = "1,2,5,10")]
        light_scales: Vec<f64>,
        /// Lights per side in place of each area light (6: 36 lights).
        #[arg(long, value_delimiter = ',', default_value = "1,2,3,4,6")]
        light_counts: Vec<u32>,
        /// The lights of the light count table: copies of each light on a grid (the
        /// paper's), or its parts.
        #[arg(long, value_enum, default_value = "spread")]
        light_layout: examples::exact_sweeps::LightLayout,
        /// Leave out the light size and light count tables.
        #[arg(long)]
        no_sweeps: bool,
        /// Instead of the scene file, a generated scene of about this many triangles on a
        /// floor (stand-ins for the paper's models, see `--stand-in`).
        #[arg(long)]
        generate: Option<usize>,
        /// What `--generate` makes: a lumpy ball and canopy (curved, small triangles) or a
        /// furnished hall (planar faces, many parts).
        #[arg(long, value_enum, default_value = "canopy")]
        stand_in: examples::exact_sweeps::StandIn,
        /// Seed of the generated scene.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Also write the exact method's render of the scene to this PNG file.
        #[arg(long)]
        image: Option<std::path::PathBuf>,
    },
}

/// The surfaces of the beam paper's experiments.
const SURFACES: [&str; 4] = ["orthocircle", "chubs", "kusner-schmitt", "mcmullen-k3"];

/// A row of the beam paper's Table 1: surface, pixels in shadow, initial beams occluded,
/// time and beams of the beam method, time and beams with 49 sub-beams always, % time saved.
type PaperRow = (&'static str, u64, u64, f64, u64, f64, u64, u32);

/// The paper's Table 1, on a GPU of 2009.
const PAPER_TABLE1: [PaperRow; 4] = [
    (
        "Orthocircle",
        13_328,
        14_961,
        1.66,
        719_859,
        4.08,
        7_101_962,
        59,
    ),
    (
        "Chubs", 21_932, 27_357, 3.82, 1_340_493, 6.57, 7_343_091, 42,
    ),
    (
        "Kusner-Schmitt",
        22_374,
        44_979,
        5.65,
        2_203_971,
        9.44,
        7_395_374,
        40,
    ),
    (
        "McMullen", 55_231, 73_386, 6.84, 4_085_914, 11.06, 8_749_244, 38,
    ),
];

fn render_with(scene: &Scene, method: ShadowSpec) -> Result<RenderOutput, String> {
    let mut s = scene.clone();
    s.settings.shadow_method = method;
    render(&s, &NoProgress).map_err(|e| e.to_string())
}

/// Seconds of a pass.
fn secs(out: &RenderOutput, pass: &str) -> f64 {
    out.stats.pass(pass).map_or(0.0, |p| p.time.as_secs_f64())
}

fn soft(out: &RenderOutput, counter: &str) -> u64 {
    out.stats.lights.first().map_or(0, |l| l.counter(counter))
}

fn table1(size: u32, sub: u32, fraction: f64) -> Result<String, String> {
    let beam =
        |strategy: &str| -> Result<ShadowSpec, String> { format!("{strategy}:{sub}").parse() };
    let mut md = String::new();
    let _ = writeln!(
        md,
        "Beam method (`beam:{sub}`) against always {n} sub-beams (`beam-all:{sub}`) and the quadtree \
         (`beam-quadtree:{sub}`), {size} × {size}, light area {fraction} of the view:\n",
        n = sub * sub
    );
    let _ = writeln!(
        md,
        "| surface | primary (s) | pixels in shadow | initial beams occluded | beam: time (s) | beam: sub-beams | all: time (s) | all: sub-beams | % time saved | quadtree: time (s) | quadtree / beam |"
    );
    let _ = writeln!(
        md,
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for name in SURFACES {
        let scene = catalog_with_area_light(name, size, fraction)?;
        let a = render_with(&scene, beam("beam")?)?;
        let b = render_with(&scene, beam("beam-all")?)?;
        let q = render_with(&scene, beam("beam-quadtree")?)?;
        let (ta, tb, tq) = (
            secs(&a, "soft-shadows"),
            secs(&b, "soft-shadows"),
            secs(&q, "soft-shadows"),
        );
        let row = format!(
            "| {name} | {:.2} | {} | {} | {ta:.2} | {} | {tb:.2} | {} | {:.0}% | {tq:.2} | {:.2} |",
            secs(&a, "screen-boxes") + secs(&a, "primary-rays"),
            soft(&a, "pixels_in_shadow"),
            soft(&a, "initial_beams_occluded"),
            soft(&a, "sub_beams"),
            soft(&b, "sub_beams"),
            100.0 * (1.0 - ta / tb),
            tq / ta,
        );
        eprintln!("{row}");
        let _ = writeln!(md, "{row}");
    }
    let _ = writeln!(
        md,
        "\nThe paper (512 × 512, 49 sub-beams, GPU):\n\n| surface | pixels in shadow | initial beams occluded | beam: time (s) | beam: beams | all: time (s) | all: beams | % time saved |\n|---|---:|---:|---:|---:|---:|---:|---:|"
    );
    for (n, px, occ, t, beams, t49, b49, saved) in PAPER_TABLE1 {
        let _ = writeln!(
            md,
            "| {n} | {px} | {occ} | {t} | {beams} | {t49} | {b49} | {saved}% |"
        );
    }
    Ok(md)
}

fn penumbra(size: u32, samples: u32) -> Result<String, String> {
    let plain: ShadowSpec = format!("stochastic:{samples}").parse()?;
    let cached: ShadowSpec = format!("stochastic:{samples}:cache").parse()?;
    let mink: ShadowSpec = format!("minkowski:stochastic:{samples}").parse()?;
    let mut md = String::new();
    let _ = writeln!(
        md,
        "Plain stochastic sampling (`{plain}`, and `{cached}` with the last-occluder cache) against \
         Minkowski lit and umbra detection with the same sampling in the penumbra (`{mink}`), \
         {size} × {size}; times of the soft-shadow pass:\n"
    );
    let _ = writeln!(
        md,
        "| scene | stochastic (s) | shadow rays | cached (s) | Minkowski (s) | shadow rays | proven lit | proven umbra | speedup |"
    );
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut scenes: Vec<(String, Scene)> = Vec::new();
    for name in SURFACES {
        scenes.push((name.to_string(), catalog_with_area_light(name, size, 0.1)?));
    }
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/soft-shadows.toml");
    let mut ss = Scene::load(std::path::Path::new(file)).map_err(|e| e.to_string())?;
    ss.camera = ss
        .camera
        .resized(size, size * 3 / 4)
        .map_err(|e| e.to_string())?;
    scenes.push(("soft-shadows.toml".to_string(), ss.clone()));
    // One sample per Hit pixel, as in the paper's tables: the soft-shadow methods, not the
    // anti-aliasing, are measured.
    for (_, scene) in &mut scenes {
        scene.settings.aa = Some(AaMode::None);
    }
    for (name, scene) in &scenes {
        let p = render_with(scene, plain)?;
        let c = render_with(scene, cached)?;
        let m = render_with(scene, mink)?;
        let (tp, tc, tm) = (
            secs(&p, "soft-shadows"),
            secs(&c, "soft-shadows"),
            secs(&m, "soft-shadows"),
        );
        let row = format!(
            "| {name} | {tp:.2} | {} | {tc:.2} | {tm:.2} | {} | {} | {} | {:.2}× |",
            soft(&p, "rays"),
            soft(&m, "rays"),
            soft(&m, "lit_pixels"),
            soft(&m, "umbra_pixels"),
            tp / tm
        );
        eprintln!("{row}");
        let _ = writeln!(md, "{row}");
    }
    // Table 4: the light grows from small to large (side relative to the ball's radius).
    let Light::Area(base) = ss.lights[0] else {
        return Err("scenes/soft-shadows.toml has no area light first".into());
    };
    let _ = writeln!(
        md,
        "\nThe light of `soft-shadows.toml` growing (side as a multiple of the ball's radius, 0.8):\n\n| light side | stochastic (s) | Minkowski (s) | speedup |\n|---:|---:|---:|---:|"
    );
    for side in [0.1, 0.4, 1.6, 3.2] {
        let mut s = ss.clone();
        s.lights = vec![square_light(base.patch.center(), side)];
        let tp = secs(&render_with(&s, plain)?, "soft-shadows");
        let tm = secs(&render_with(&s, mink)?, "soft-shadows");
        let row = format!(
            "| {side} ({:.2}×) | {tp:.2} | {tm:.2} | {:.2}× |",
            side / 0.8,
            tp / tm
        );
        eprintln!("{row}");
        let _ = writeln!(md, "{row}");
    }
    let _ = writeln!(
        md,
        "\nThe paper (d = 32 rays, SPARC 1990s): about 2× overall (Table 1: 12.05 → 5.22 s, \
         64.21 → 25.39 s, 32.35 → 10.54 s, 8.25 → 4.95 s, 37.47 → 24.02 s) and 1.76× to 7.83× \
         as the light shrinks from the largest sphere's size to the smallest's (Table 4)."
    );
    Ok(md)
}

fn run(args: Args) -> Result<(), String> {
    eprintln!("{} thread(s)", rayon::current_num_threads());
    let md = match args.table {
        Table::Table1 {
            size,
            sub,
            light_fraction,
        } => table1(size, sub, light_fraction)?,
        Table::Penumbra { size, samples } => penumbra(size, samples)?,
        Table::Exact {
            scene,
            width,
            height,
            samples,
            sweep_samples,
            light_scales,
            light_counts,
            light_layout,
            no_sweeps,
            generate,
            stand_in,
            seed,
            image,
        } => examples::exact_sweeps::report(
            &scene,
            generate.map(|n| (stand_in, n, seed)),
            &examples::exact_sweeps::Options {
                size: (width, height),
                samples,
                sweep_samples,
                light_scales: if no_sweeps { Vec::new() } else { light_scales },
                light_counts: if no_sweeps { Vec::new() } else { light_counts },
                light_layout,
                image,
            },
        )?,
    };
    examples::report::print_and_save(&md, args.markdown.as_deref())
}

fn main() -> ExitCode {
    examples::report::exit(run(Args::parse()))
}
