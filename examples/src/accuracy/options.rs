//! The experiment's command line and the options resolved from it, and the settings the
//! report singles out.

use std::path::PathBuf;

use beam_trace::shadow::ShadowSpec;
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
    /// Measure against the `exact` method instead of sampling: for scenes whose occluders
    /// are triangle meshes, where its fractions are exact up to rounding (with implicit
    /// occluders its pieces left open are estimated by segments).
    #[arg(long, conflicts_with = "reference_samples")]
    pub exact_reference: bool,
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
    /// Renders per setting (default 3; 1 with --quick): each time reported is the median
    /// of this many, taken in rounds over all settings so that a slow spell of the machine
    /// slows every setting alike.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=99))]
    pub runs: Option<u32>,
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

/// The render every setting is measured against.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Reference {
    /// `stochastic:N`.
    Stochastic(u32),
    /// `exact` (its default refinement against implicit occluders).
    Exact,
}

impl Reference {
    /// The method of the reference render.
    pub(crate) fn spec(self) -> ShadowSpec {
        match self {
            Reference::Stochastic(samples) => ShadowSpec::Stochastic {
                samples,
                cache: false,
            },
            Reference::Exact => ShadowSpec::Exact {
                depth: ShadowSpec::DEFAULT_EXACT_DEPTH,
                group: ShadowSpec::MAX_EXACT_GROUP,
                faces: true,
            },
        }
    }

    /// How far a proven bound may miss the reference fraction `r` before it counts as a
    /// violation: 4 standard deviations of a stochastic reference's mean (at least `4 /
    /// N`), or for the exact reference `1e-6` (its fractions are `f32`).
    pub(crate) fn slack(self, r: f64) -> f64 {
        match self {
            Reference::Stochastic(samples) => {
                let n = f64::from(samples);
                4.0 * (r * (1.0 - r) / n).sqrt().max(1.0 / n)
            }
            Reference::Exact => Self::EXACT_ROUNDING,
        }
    }

    /// How far the reference's fraction may lie from a true 0 or 1 by rounding alone (0 for
    /// sampling, whose fractions are counts).
    pub(crate) fn rounding(self) -> f64 {
        match self {
            Reference::Stochastic(_) => 0.0,
            Reference::Exact => Self::EXACT_ROUNDING,
        }
    }

    /// The rounding of the exact method's `f32` fractions (sums of fragment areas).
    const EXACT_ROUNDING: f64 = 1e-6;
}

impl std::fmt::Display for Reference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.spec())
    }
}

/// Options resolved from the command line.
pub(crate) struct Options {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) reference: Reference,
    pub(crate) out_dir: PathBuf,
    pub(crate) settings: Vec<Setting>,
    /// Renders per setting whose median times are reported.
    pub(crate) runs: u32,
}

impl Options {
    pub(crate) fn from_args(args: &Args) -> Result<Self, String> {
        let (w, h, n, runs) = if args.quick {
            (32, 24, 256, 1)
        } else {
            (128, 96, 4096, 3)
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
            reference: if args.exact_reference {
                Reference::Exact
            } else {
                Reference::Stochastic(args.reference_samples.unwrap_or(n))
            },
            out_dir,
            settings: match &args.methods {
                Some(methods) => methods
                    .iter()
                    .map(|m| m.parse().map(Setting::new))
                    .collect::<Result<_, _>>()?,
                None => settings(args.quick)?,
            },
            runs: args.runs.unwrap_or(runs),
        })
    }

    pub(crate) fn images(&self) -> PathBuf {
        self.out_dir.join("images")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn references_name_their_method_and_their_slack() {
        let s = Reference::Stochastic(4096);
        assert_eq!(s.to_string(), "stochastic:4096");
        // 4 standard deviations of a mean of 4096 samples at 1/2, and at least 4/N.
        assert!((s.slack(0.5) - 4.0 * (0.25f64 / 4096.0).sqrt()).abs() < 1e-15);
        assert_eq!(s.slack(1.0), 4.0 / 4096.0);
        assert_eq!(s.rounding(), 0.0);
        let e = Reference::Exact;
        assert_eq!(e.to_string(), "exact");
        assert_eq!(e.slack(0.5), 1e-6);
        assert_eq!(e.rounding(), 1e-6);
    }

    #[test]
    fn times_are_medians_of_three_renders_unless_told() {
        let runs = |args: &[&str]| {
            let args =
                Args::parse_from(std::iter::once("accuracy-cost").chain(args.iter().copied()));
            Options::from_args(&args).unwrap().runs
        };
        assert_eq!(runs(&[]), 3);
        assert_eq!(runs(&["--quick"]), 1);
        assert_eq!(runs(&["--quick", "--runs", "5"]), 5);
        assert!(Args::try_parse_from(["accuracy-cost", "--runs", "0"]).is_err());
    }

    #[test]
    fn the_exact_reference_is_chosen_by_its_flag() {
        let args = Args::parse_from(["accuracy-cost", "--exact-reference", "--quick"]);
        assert_eq!(
            Options::from_args(&args).unwrap().reference,
            Reference::Exact
        );
        let args = Args::parse_from(["accuracy-cost", "--reference-samples", "64"]);
        let opts = Options::from_args(&args).unwrap();
        assert_eq!(opts.reference, Reference::Stochastic(64));
        assert!(
            Args::try_parse_from([
                "accuracy-cost",
                "--exact-reference",
                "--reference-samples",
                "64"
            ])
            .is_err()
        );
    }
}
