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

/// A soft-shadow method and its settings.
///
/// Written `stochastic:N` (`stochastic:N:cache` with the last-occluder cache), `beam:n`,
/// `beam-all:n`, `beam-quadtree:n`, `minkowski:stochastic:N` or `minkowski:beam:n`.
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
}

impl ShadowSpec {
    /// Largest number of stochastic samples.
    pub const MAX_SAMPLES: u32 = 65_536;
    /// Largest number of sub-beams per side.
    pub const MAX_SIDE: u32 = 64;
}

impl Default for ShadowSpec {
    /// `beam:7`: 49 sub-beams, as in the soft-shadow paper.
    fn default() -> Self {
        ShadowSpec::Beam {
            n: 7,
            strategy: Strategy::Initial,
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
        }
    }
}

const FORMS: &str = "stochastic:N, stochastic:N:cache, beam:n, beam-all:n, beam-quadtree:n, \
                     minkowski:stochastic:N, minkowski:beam:n";

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
        let e = "cone:3".parse::<ShadowSpec>().unwrap_err();
        assert!(e.contains("unknown shadow method 'cone:3'"), "{e}");
        assert!("minkowski:beam:65".parse::<ShadowSpec>().is_err());
    }
}
