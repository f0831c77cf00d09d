//! Renders a planar implicit region `f(x, y) < 0` to a PNG, reliably: tiles proven inside or
//! outside by interval arithmetic are filled whole, with the tape pruned per tile, and only
//! the pixels that no interval decides are evaluated as points. A command line over the
//! `render2d` crate (see its documentation for why the image equals plain per-pixel
//! evaluation).
//!
//! ```text
//! cargo run --release -p examples --bin render2d -- --formula "x^2 + y^2 - 0.5" --out disc.png
//! cargo run --release -p examples --bin render2d -- --vm data/models/csg2d.vm --out csg2d.png --check --stats
//! ```

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::str::FromStr;
use std::time::Instant;

use clap::{Parser, ValueEnum};
use implicit_expr::{Context, Error, Tape};
use render2d::{Image, Region, Settings};

/// Renders f(x, y) < 0 (inside) by interval subdivision with tape pruning.
#[derive(Parser, Debug)]
#[command(name = "render2d")]
struct Args {
    /// The function as a formula in x and y (z is set by --z), e.g. "x^2 + y^2 - 1".
    #[arg(long, conflicts_with = "vm", required_unless_present = "vm")]
    formula: Option<String>,
    /// The function as a `.vm` file (one SSA operation per line).
    #[arg(long, value_name = "FILE")]
    vm: Option<PathBuf>,
    /// Image width and height in pixels.
    #[arg(long, default_value_t = 1024)]
    size: usize,
    /// The region shown: xmin,xmax,ymin,ymax.
    #[arg(long, default_value = "-1,1,-1,1", value_parser = Region::from_str, allow_hyphen_values = true)]
    region: Region,
    /// The value of z, for functions that use it.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    z: f64,
    /// Output PNG file.
    #[arg(long, default_value = "render2d.png")]
    out: PathBuf,
    /// Precision of the interval and point evaluations.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    precision: Precision,
    /// Tile sizes in pixels, largest first, each dividing the previous one.
    #[arg(long, default_value = "128,32,8", value_delimiter = ',')]
    tiles: Vec<usize>,
    /// Evaluate every tile with the full tape (no pruning).
    #[arg(long)]
    no_prune: bool,
    /// Threads (default: one per core).
    #[arg(long)]
    threads: Option<usize>,
    /// Also classify every pixel by point evaluation of its centre and compare.
    #[arg(long)]
    check: bool,
    /// Print tile counts, tape lengths and the time per stage.
    #[arg(long)]
    stats: bool,
    /// Shade the pixels decided by point evaluation (the band the intervals left open).
    #[arg(long)]
    show_points: bool,
}

/// Working precision.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
enum Precision {
    /// `f32` points and `Interval<f32>`.
    F32,
    /// `f64` points and `Interval<f64>`.
    F64,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> Result<ExitCode, String> {
    let total = Instant::now();
    let (ctx, root) = load(args)?;
    let tape = Tape::new(&ctx, &[root]).map_err(|e| e.to_string())?;
    let loaded = total.elapsed();
    let settings = Settings {
        width: args.size,
        height: args.size,
        region: args.region,
        z: args.z,
        tiles: args.tiles.clone(),
        prune: !args.no_prune,
        timing: args.stats,
    };
    settings.validate().map_err(|e| e.to_string())?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .map_err(|e| e.to_string())?;
    let threads = pool.current_num_threads();

    let start = Instant::now();
    let (image, stats) = pool
        .install(|| match args.precision {
            Precision::F32 => render2d::render::<f32>(&tape, &settings),
            Precision::F64 => render2d::render::<f64>(&tape, &settings),
        })
        .map_err(|e| e.to_string())?;
    let render_time = start.elapsed();

    let mut code = ExitCode::SUCCESS;
    let mut check_line = None;
    if args.check {
        let start = Instant::now();
        let reference = pool
            .install(|| match args.precision {
                Precision::F32 => render2d::render_points::<f32>(&tape, &settings),
                Precision::F64 => render2d::render_points::<f64>(&tape, &settings),
            })
            .map_err(|e| e.to_string())?;
        let differing = render2d::count_differences(&image, &reference);
        check_line = Some(format!(
            "check: per-pixel point evaluation in {:.1} ms; {differing} differing pixels",
            start.elapsed().as_secs_f64() * 1e3
        ));
        if differing != 0 {
            code = ExitCode::from(3);
        }
    }

    let write = Instant::now();
    write_png(&args.out, &image, args.show_points)
        .map_err(|e| format!("cannot write {}: {e}", args.out.display()))?;
    let write_time = write.elapsed();

    println!(
        "{}: {}x{} pixels, tape of {} instructions, {:?} precision, {} threads",
        args.out.display(),
        image.width,
        image.height,
        tape.len(),
        args.precision,
        threads
    );
    if args.stats {
        print!("{}", stats.table(image.width * image.height, threads));
        println!(
            "time: load and compile {:.1} ms, render {:.1} ms, PNG {:.1} ms",
            loaded.as_secs_f64() * 1e3,
            render_time.as_secs_f64() * 1e3,
            write_time.as_secs_f64() * 1e3
        );
    }
    if let Some(line) = check_line {
        println!("{line}");
    }
    println!(
        "render {:.1} ms, total {:.1} ms",
        render_time.as_secs_f64() * 1e3,
        total.elapsed().as_secs_f64() * 1e3
    );
    Ok(code)
}

/// The expression of `--formula` or `--vm`, with errors shown against the input.
fn load(args: &Args) -> Result<(Context, implicit_expr::NodeId), String> {
    let mut ctx = Context::new();
    if let Some(formula) = &args.formula {
        let root = implicit_expr::parse::parse(&mut ctx, formula, &[])
            .map_err(|e| show_error(&e, formula, None))?;
        return Ok((ctx, root));
    }
    let path = args.vm.as_ref().ok_or("give --formula or --vm")?;
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let root = implicit_expr::vm::import_vm(&mut ctx, &text)
        .map_err(|e| show_error(&e, &text, Some(path)))?;
    Ok((ctx, root))
}

/// The error message, followed by the offending line with a caret line under the span.
fn show_error(e: &Error, text: &str, path: Option<&Path>) -> String {
    let span = match e {
        Error::Syntax { span, .. } | Error::Vm { span, .. } => span.clone(),
        _ => return e.to_string(),
    };
    let start = span.start.min(text.len());
    let line_start = text[..start].rfind('\n').map_or(0, |p| p + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |p| start + p);
    let line = &text[line_start..line_end];
    let col = text[line_start..start].chars().count();
    let width = text[start..span.end.clamp(start, line_end)]
        .chars()
        .count()
        .max(1);
    let place = match path {
        Some(p) => format!("{}: ", p.display()),
        None => String::new(),
    };
    format!(
        "{place}{e}\n  {line}\n  {}{}",
        " ".repeat(col),
        "^".repeat(width)
    )
}

/// Writes the image as an RGB PNG, whole or not at all: into a temporary file in the same
/// directory, renamed over `path` once complete.
fn write_png(path: &Path, image: &Image, show_points: bool) -> std::io::Result<()> {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".tmp");
    let tmp = path.with_file_name(name);
    let mut bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut bytes, image.width as u32, image.height as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(std::io::Error::other)?;
        writer
            .write_image_data(&image.to_rgb8(show_points))
            .map_err(std::io::Error::other)?;
        writer.finish().map_err(std::io::Error::other)?;
    }
    let result = std::fs::write(&tmp, &bytes).and_then(|()| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
