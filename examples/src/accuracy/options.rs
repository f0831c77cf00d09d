//! The experiment's command line and the options resolved from it, and the settings the
//! report singles out.

use std::path::PathBuf;

use clap::Parser;

use super::setting::{Setting, settings};

/// Soft-shadow accuracy against time, per method and setting.
#[derive(Parser, Debug)]
#[command(version, about)]
pub struct Args {
    /// Scene files (TOML) with at least one area light.
    #[arg(default_values = ["scenes/soft-shadows.toml", "scenes/thin-occluder.toml"])]
    pub scenes: Vec<PathBuf>,
    /// Image width (default 128; 32 with --quick).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height (default 96; 24 with --quick).
    #[arg(long)]
    pub height: Option<u32>,
    /// Samples of the stochastic reference (default 4096; 256 with --quick).
    #[arg(long)]
    pub reference_samples: Option<u32>,
    /// Folder of the report (`accuracy.md`) and of its `images/` (default `docs`; the
    /// system's temporary folder with --quick).
    #[arg(long)]
    pub out_dir: Option<PathBuf>,
    /// Smoke run: tiny images, a small reference and fewer settings.
    #[arg(long)]
    pub quick: bool,
    /// Only these methods (comma-separated, as `--shadows` writes them), without the
    /// epsilon and precision variants.
    #[arg(long, value_delimiter = ',')]
    pub methods: Option<Vec<String>>,
}

/// The settings the time ratios are relative to.
pub(crate) const BASELINE: &str = "stochastic:64";

/// The setting whose shadow-class image goes into the report.
pub(crate) const CLASS_IMAGE: &str = "beam:7";

/// Settings whose error maps go into the report, with their image names.
pub(crate) const ERROR_MAPS: [(&str, &str); 2] = [
    ("beam:7", "beam7-error"),
    ("stochastic:64", "stochastic64-error"),
];

/// Options resolved from the command line.
pub(crate) struct Options {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) reference_samples: u32,
    pub(crate) out_dir: PathBuf,
    pub(crate) settings: Vec<Setting>,
}

impl Options {
    pub(crate) fn from_args(args: &Args) -> Result<Self, String> {
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
            settings: match &args.methods {
                Some(methods) => methods
                    .iter()
                    .map(|m| m.parse().map(Setting::new))
                    .collect::<Result<_, _>>()?,
                None => settings(args.quick)?,
            },
        })
    }

    pub(crate) fn images(&self) -> PathBuf {
        self.out_dir.join("images")
    }
}
