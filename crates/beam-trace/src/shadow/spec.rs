//! The soft-shadow method of a render, as scene files and the command line name it.

use std::fmt;
use std::str::FromStr;

/// How the beam method spends its sub-beams.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Strategy {
    /// One beam over the whole light first; `n × n` sub-beams only if it is not rejected
    /// (the soft-shadow paper's method).
    Initial,
    /// Always `n × n` sub-beams (the paper's comparison baseline).
    All,
    /// Quadtree subdivision of the light's `n × n` cells: a rejected beam clears all the
    /// cells under it.
    Quadtree,
}

/// What the Minkowski method does in the penumbra it could not decide.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Fine {
    /// `samples` stochastic shadow segments.
    Stochastic {
        /// Samples over the light.
        samples: u32,
    },
    /// `n × n` sub-beams.
    Beams {
        /// Sub-beams per side.
        n: u32,
    },
}

/// The width of a certified bound on a visible fraction, in millionths (so that a spec
/// compares and hashes exactly): `0.05` is `Tolerance(50_000)`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct Tolerance(pub u32);

impl Tolerance {
    /// Millionths per unit.
    pub const SCALE: u32 = 1_000_000;

    /// The width.
    pub fn value(self) -> f64 {
        f64::from(self.0) / f64::from(Self::SCALE)
    }
}

impl fmt::Display for Tolerance {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.value())
    }
}

impl FromStr for Tolerance {
    type Err = String;

    /// A decimal in `(0, 1]` with at most six digits after the point.
    fn from_str(text: &str) -> Result<Self, String> {
        let v: f64 = text
            .parse()
            .map_err(|_| format!("the tolerance must be a number, got '{text}'"))?;
        if !(v > 0.0 && v <= 1.0) {
            return Err(format!(
                "the tolerance must lie in (0, 1] (a width of the visible fraction), got '{text}'"
            ));
        }
        let m = (v * f64::from(Self::SCALE)).round();
        if (m / f64::from(Self::SCALE) - v).abs() > 1e-12 || m < 1.0 {
            return Err(format!(
                "the tolerance takes at most six digits after the point, got '{text}'"
            ));
        }
        Ok(Tolerance(m as u32))
    }
}

/// A soft-shadow method and its settings.
///
/// Written `stochastic:N` (`stochastic:N:cache` with the last-occluder cache), `beam:n`,
/// `beam-all:n`, `beam-quadtree:n`, `minkowski:stochastic:N`, `minkowski:beam:n`,
/// `certified:TOL`, `certified:TOL:BUDGET` or `certified:TOL:BUDGET:SEGMENTS`.
///
/// ```
/// use beam_trace::shadow::{ShadowSpec, Strategy};
/// let s: ShadowSpec = "beam:7".parse()?;
/// assert_eq!(s, ShadowSpec::Beam { n: 7, strategy: Strategy::Initial });
/// assert_eq!(s.to_string(), "beam:7");
/// assert!("beam:0".parse::<ShadowSpec>().is_err());
/// # Ok::<(), String>(())
/// ```
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum ShadowSpec {
    /// Distributed ray tracing over the light.
    Stochastic {
        /// Samples over the light.
        samples: u32,
        /// Whether the object that blocked the last sample is tried first.
        cache: bool,
    },
    /// Interval shadow beams.
    Beam {
        /// Sub-beams per side of the light.
        n: u32,
        /// How sub-beams are spent.
        strategy: Strategy,
    },
    /// Minkowski lit and umbra detection, then `fine` in the penumbra.
    Minkowski {
        /// The method of the undecided points.
        fine: Fine,
    },
    /// The visible fraction proven to lie in a bound, refined to `tolerance`
    /// ([`crate::shadow::certified`]).
    Certified {
        /// Width of the bound at which the refinement stops.
        tolerance: Tolerance,
        /// Largest number of beams per point and light.
        budget: u32,
        /// Stratified segments of the estimate inside the bound, per point and light.
        segments: u32,
    },
    /// The triangles' shadows by the lazy BSP in Plücker space, the implicit surfaces'
    /// by shadow beams over the visible fragments ([`crate::shadow::exact::Exact`]).
    Exact {
        /// Halvings of a visible fragment against the implicit surfaces.
        depth: u32,
        /// Most queries sharing one BSP (1: a tree per query, the method without
        /// coherence).
        group: u32,
        /// The occluders are the meshes' faces (coplanar neighbours merged,
        /// [`crate::mesh::faces`]); `false` (`exact:D:G:triangles`): their triangles.
        faces: bool,
    },
}

impl ShadowSpec {
    /// Largest number of stochastic samples.
    pub const MAX_SAMPLES: u32 = 65_536;
    /// Largest number of sub-beams per side.
    pub const MAX_SIDE: u32 = 64;
    /// Beams per point and light of `certified:TOL` without a budget.
    pub const DEFAULT_BUDGET: u32 = 1024;
    /// Largest budget of beams per point and light.
    pub const MAX_BUDGET: u32 = 1 << 20;
    /// Largest number of halvings of `exact:D`.
    pub const MAX_EXACT_DEPTH: u32 = 24;
    /// Halvings of `exact` without a depth. On `scenes/meshes.toml` at 96 × 72 (an
    /// implicit torus among the occluders), against `stochastic:4096`: RMSE 0.00091 with
    /// 8 halvings, 0.00056 with 9, 0.00038 with 10 and 0.00028 with 12, for 1.09, 1.14,
    /// 1.49 and 3.08 s of the soft-shadow pass (`stochastic:64`: 0.0056).
    pub const DEFAULT_EXACT_DEPTH: u32 = 10;
    /// Largest group of `exact:D:G`, and its default: the runs of neighbouring queries
    /// that the renderer hands to a method together (the samples of an 8 × 8 tile of
    /// pixels, one sample each).
    pub const MAX_EXACT_GROUP: u32 = 64;
    /// Segments of `certified:TOL`'s estimate without a count
    /// ([`ESTIMATE_SEGMENTS`](crate::shadow::certified::ESTIMATE_SEGMENTS)).
    pub const DEFAULT_SEGMENTS: u32 = crate::shadow::certified::ESTIMATE_SEGMENTS;
}

impl Default for ShadowSpec {
    /// `certified:1:1024:64`: the whole light's beam proves a point lit or in umbra, the
    /// light's quadrants are screened, and 64 stratified segments estimate the rest inside
    /// the proven bound. On `scenes/soft-shadows.toml` at 128 × 96 (`docs/accuracy.md`) its
    /// RMSE is 0.0049 at 0.40 of `stochastic:64`'s time (0.0052), where `beam:7` (the
    /// soft-shadow paper's 49 sub-beams, the default before) has 0.189 at 0.74; on
    /// `scenes/thin-occluder.toml` 0.0026 at 0.16 against `beam:7`'s 0.057 at 0.12.
    fn default() -> Self {
        ShadowSpec::Certified {
            tolerance: Tolerance(Tolerance::SCALE),
            budget: Self::DEFAULT_BUDGET,
            segments: 64,
        }
    }
}

impl fmt::Display for ShadowSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ShadowSpec::Stochastic { samples, cache } => {
                write!(
                    f,
                    "stochastic:{samples}{}",
                    if cache { ":cache" } else { "" }
                )
            }
            ShadowSpec::Beam { n, strategy } => {
                let name = match strategy {
                    Strategy::Initial => "beam",
                    Strategy::All => "beam-all",
                    Strategy::Quadtree => "beam-quadtree",
                };
                write!(f, "{name}:{n}")
            }
            ShadowSpec::Minkowski {
                fine: Fine::Stochastic { samples },
            } => write!(f, "minkowski:stochastic:{samples}"),
            ShadowSpec::Minkowski {
                fine: Fine::Beams { n },
            } => write!(f, "minkowski:beam:{n}"),
            ShadowSpec::Certified {
                tolerance,
                budget,
                segments,
            } => {
                if segments != ShadowSpec::DEFAULT_SEGMENTS {
                    write!(f, "certified:{tolerance}:{budget}:{segments}")
                } else if budget != ShadowSpec::DEFAULT_BUDGET {
                    write!(f, "certified:{tolerance}:{budget}")
                } else {
                    write!(f, "certified:{tolerance}")
                }
            }
            ShadowSpec::Exact {
                depth,
                group,
                faces,
            } => {
                if !faces {
                    write!(f, "exact:{depth}:{group}:triangles")
                } else if group != ShadowSpec::MAX_EXACT_GROUP {
                    write!(f, "exact:{depth}:{group}")
                } else if depth != ShadowSpec::DEFAULT_EXACT_DEPTH {
                    write!(f, "exact:{depth}")
                } else {
                    write!(f, "exact")
                }
            }
        }
    }
}

const FORMS: &str = "stochastic:N, stochastic:N:cache, beam:n, beam-all:n, beam-quadtree:n, \
                     minkowski:stochastic:N, minkowski:beam:n, certified:TOL, \
                     certified:TOL:BUDGET, certified:TOL:BUDGET:SEGMENTS, exact, exact:D, exact:D:G, exact:D:G:triangles";

fn count(s: &str, text: &str, what: &str, max: u32) -> Result<u32, String> {
    match text.parse::<u32>() {
        Ok(v) if (1..=max).contains(&v) => Ok(v),
        _ => Err(format!(
            "'{s}': the {what} must be an integer from 1 to {max}, got '{text}'"
        )),
    }
}

impl FromStr for ShadowSpec {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let parts: Vec<&str> = s.split(':').collect();
        let samples = |t: &str| count(s, t, "number of samples", ShadowSpec::MAX_SAMPLES);
        let side = |t: &str| count(s, t, "number of sub-beams per side", ShadowSpec::MAX_SIDE);
        let tolerance = |t: &str| t.parse::<Tolerance>().map_err(|e| format!("'{s}': {e}"));
        let halvings = |d: &str| match d.parse::<u32>() {
            Ok(depth) if depth <= ShadowSpec::MAX_EXACT_DEPTH => Ok(depth),
            _ => Err(format!(
                "'{s}': the number of halvings must be an integer from 0 to {}, got '{d}'",
                ShadowSpec::MAX_EXACT_DEPTH
            )),
        };
        let beam = |strategy, n: &str| {
            Ok(ShadowSpec::Beam {
                n: side(n)?,
                strategy,
            })
        };
        match parts.as_slice() {
            ["stochastic", n] => Ok(ShadowSpec::Stochastic {
                samples: samples(n)?,
                cache: false,
            }),
            ["stochastic", n, "cache"] => Ok(ShadowSpec::Stochastic {
                samples: samples(n)?,
                cache: true,
            }),
            ["beam", n] => beam(Strategy::Initial, n),
            ["beam-all", n] => beam(Strategy::All, n),
            ["beam-quadtree", n] => beam(Strategy::Quadtree, n),
            ["minkowski", "stochastic", n] => Ok(ShadowSpec::Minkowski {
                fine: Fine::Stochastic {
                    samples: samples(n)?,
                },
            }),
            ["minkowski", "beam", n] => Ok(ShadowSpec::Minkowski {
                fine: Fine::Beams { n: side(n)? },
            }),
            ["certified", tol] => Ok(ShadowSpec::Certified {
                tolerance: tolerance(tol)?,
                budget: ShadowSpec::DEFAULT_BUDGET,
                segments: ShadowSpec::DEFAULT_SEGMENTS,
            }),
            ["certified", tol, budget] => Ok(ShadowSpec::Certified {
                tolerance: tolerance(tol)?,
                budget: count(s, budget, "budget of beams", ShadowSpec::MAX_BUDGET)?,
                segments: ShadowSpec::DEFAULT_SEGMENTS,
            }),
            ["certified", tol, budget, segments] => Ok(ShadowSpec::Certified {
                tolerance: tolerance(tol)?,
                budget: count(s, budget, "budget of beams", ShadowSpec::MAX_BUDGET)?,
                segments: count(
                    s,
                    segments,
                    "number of estimate segments",
                    ShadowSpec::MAX_SAMPLES,
                )?,
            }),
            ["exact"] => Ok(ShadowSpec::Exact {
                depth: ShadowSpec::DEFAULT_EXACT_DEPTH,
                group: ShadowSpec::MAX_EXACT_GROUP,
                faces: true,
            }),
            ["exact", d] => Ok(ShadowSpec::Exact {
                depth: halvings(d)?,
                group: ShadowSpec::MAX_EXACT_GROUP,
                faces: true,
            }),
            ["exact", d, g, rest @ ..] if rest.is_empty() || rest == ["triangles"] => {
                Ok(ShadowSpec::Exact {
                    depth: halvings(d)?,
                    group: count(s, g, "largest group", ShadowSpec::MAX_EXACT_GROUP)?,
                    faces: rest.is_empty(),
                })
            }
            _ => Err(format!("unknown shadow method '{s}' (one of: {FORMS})")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_round_trips() {
        for s in [
            "stochastic:32",
            "stochastic:4:cache",
            "beam:7",
            "beam-all:7",
            "beam-quadtree:8",
            "minkowski:stochastic:32",
            "minkowski:beam:4",
            "certified:0.05",
            "certified:0.001:64",
            "certified:1",
            "certified:0.9:1024:64",
            "certified:0.5:16:8",
            "exact",
            "exact:3",
            "exact:8:1",
            "exact:8:64:triangles",
        ] {
            let spec: ShadowSpec = s.parse().unwrap();
            assert_eq!(spec.to_string(), s);
            assert_eq!(spec.method().name(), s);
        }
    }

    #[test]
    fn bad_forms_say_what_is_wrong() {
        let e = "beam:x".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("sub-beams per side"), "{e}");
        let e = "stochastic:0".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("number of samples"), "{e}");
        let e = "exact:8:65".parse::<ShadowSpec>().unwrap_err();
        assert!(
            e.contains("largest group must be an integer from 1 to 64"),
            "{e}"
        );
        assert!("exact:8:0".parse::<ShadowSpec>().is_err());
        let e = "cone:3".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("unknown shadow method 'cone:3'"), "{e}");
        assert!("minkowski:beam:65".parse::<ShadowSpec>().is_err());
        let e = "certified:0".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("(0, 1]"), "{e}");
        let e = "certified:0.0000001".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("six digits"), "{e}");
        let e = "certified:0.05:0".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("budget of beams"), "{e}");
        let e = "certified:0.05:64:0".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("number of estimate segments"), "{e}");
        let e = "exact:25".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("number of halvings"), "{e}");
        let e = "certified:x".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("'certified:x'") && e.contains("a number"), "{e}");
        assert_eq!(
            "certified:0.05:1024"
                .parse::<ShadowSpec>()
                .unwrap()
                .to_string(),
            "certified:0.05"
        );
    }
}
