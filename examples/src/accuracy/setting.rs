//! The settings the experiment runs: a shadow method with a variant of the other render
//! settings, the families the plots group them in, and the lists of a full and a quick run.

use beam_trace::Precision;
use beam_trace::root::RootSettings;
use beam_trace::scene::RenderSettings;
use beam_trace::shadow::{Fine, ShadowSpec, Strategy};

/// The colour groups of the plots.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Family {
    Stochastic,
    StochasticCache,
    Beam,
    BeamOther,
    MinkowskiStochastic,
    MinkowskiBeam,
    Certified,
    Exact,
    Epsilon,
    F32,
}

impl Family {
    pub(crate) const ALL: [Family; 10] = [
        Family::Stochastic,
        Family::StochasticCache,
        Family::Beam,
        Family::BeamOther,
        Family::MinkowskiStochastic,
        Family::MinkowskiBeam,
        Family::Certified,
        Family::Exact,
        Family::Epsilon,
        Family::F32,
    ];

    pub(crate) fn name(self) -> &'static str {
        match self {
            Family::Stochastic => "stochastic:N",
            Family::StochasticCache => "stochastic:N:cache",
            Family::Beam => "beam:n",
            Family::BeamOther => "beam-all / beam-quadtree",
            Family::MinkowskiStochastic => "minkowski:stochastic:N",
            Family::MinkowskiBeam => "minkowski:beam:n",
            Family::Certified => "certified:TOL",
            Family::Exact => "exact",
            Family::Epsilon => "root epsilon varied",
            Family::F32 => "f32 precision",
        }
    }

    /// Whether the family's visible fraction is a proven lower bound of the true one.
    pub(crate) fn is_lower_bound(self) -> bool {
        matches!(
            self,
            Family::Beam | Family::BeamOther | Family::MinkowskiBeam
        )
    }
}

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
    "certified:1:1024:64",
    "certified:1:1024:72",
    "certified:1:1024:80",
    "certified:1:1024:96",
    "certified:1:1024:128",
    "certified:0.9:1024:64",
    "certified:0.7",
    "certified:0.5",
    "certified:0.25",
    "certified:0.1",
    "certified:0.05",
    "certified:0.02",
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
    "certified:0.25",
    "certified:0.05",
    "certified:0.9:1024:64",
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
            // The spec as written, defaults left out: `c0.5`, `c0.9/1024/64`.
            spec @ ShadowSpec::Certified { .. } => {
                let written = spec.to_string();
                let settings = written.trim_start_matches("certified:");
                format!("c{}", settings.replace(':', "/"))
            }
            ShadowSpec::Exact {
                depth,
                group,
                faces: true,
            } if group == ShadowSpec::MAX_EXACT_GROUP => format!("e{depth}"),
            ShadowSpec::Exact {
                depth,
                group,
                faces: true,
            } => format!("e{depth}/{group}"),
            ShadowSpec::Exact { depth, group, .. } => format!("e{depth}/{group}t"),
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
            (_, ShadowSpec::Certified { .. }) => Family::Certified,
            (_, ShadowSpec::Exact { .. }) => Family::Exact,
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
