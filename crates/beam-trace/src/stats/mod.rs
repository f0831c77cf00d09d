//! Per-pass statistics: time and work counters, printed as a table and saved as JSON.

use std::fmt;
use std::time::Duration;

pub mod counters;

pub use counters::Counters;

use crate::plan::Pass;

/// Time and counters of one pass of the render.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct PassStats {
    /// Name of the pass.
    pub name: String,
    /// Whether the plan ran it.
    pub ran: bool,
    /// Wall-clock time (excluded from comparisons between runs).
    #[serde(serialize_with = "seconds")]
    pub time: Duration,
    /// Work counters, in a fixed order.
    pub counters: Vec<(String, u64)>,
    /// Thread time of the pass's phases where it reports them (the exact soft-shadow
    /// method's shaft culling, BSP set-up and queries), summed over the threads; like
    /// [`PassStats::time`], excluded from comparisons between runs.
    #[serde(serialize_with = "phase_seconds")]
    pub phases: Vec<(String, Duration)>,
}

fn phase_seconds<S: serde::Serializer>(
    phases: &[(String, Duration)],
    s: S,
) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    let mut map = s.serialize_map(Some(phases.len()))?;
    for (name, t) in phases {
        map.serialize_entry(name, &t.as_secs_f64())?;
    }
    map.end()
}

fn seconds<S: serde::Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(d.as_secs_f64())
}

impl PassStats {
    /// A pass that did not run: zero time, zero counters.
    pub fn skipped(name: &str) -> Self {
        Self {
            name: name.into(),
            ..Self::default()
        }
    }

    /// A pass that ran, with its counters in order.
    pub fn new(name: &str, time: Duration, counters: &[(&str, u64)]) -> Self {
        Self {
            name: name.into(),
            ran: true,
            time,
            counters: counters.iter().map(|(n, v)| (n.to_string(), *v)).collect(),
            phases: Vec::new(),
        }
    }

    /// The same with the thread time of its phases, in order (those of zero time left
    /// out: a phase the pass did not enter).
    pub fn with_phases(mut self, phases: &[(&str, Duration)]) -> Self {
        self.phases = phases
            .iter()
            .filter(|(_, t)| !t.is_zero())
            .map(|(n, t)| (n.to_string(), *t))
            .collect();
        self
    }

    /// A pass of the pipeline that ran, with its named counters.
    pub fn of(pass: Pass, time: Duration, counters: &impl Counters) -> Self {
        Self::new(pass.name(), time, &counters.list())
    }

    /// The counter `name` (0 when absent).
    pub fn counter(&self, name: &str) -> u64 {
        self.counters
            .iter()
            .find(|(n, _)| n == name)
            .map_or(0, |(_, v)| *v)
    }

    /// Sum of every counter.
    pub fn total_work(&self) -> u64 {
        self.counters.iter().map(|(_, v)| v).sum()
    }
}

/// The work of one pass: its name, whether it ran, its counters.
pub type PassWork = (String, bool, Vec<(String, u64)>);

/// Statistics of a whole render.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct RenderStats {
    /// Passes, in the order they ran.
    pub passes: Vec<PassStats>,
    /// Per area light, the soft-shadow pass's time and counters (the soft-shadow paper's
    /// Table 1: pixels in shadow, initial beams occluded, sub-beams or rays traced).
    pub lights: Vec<PassStats>,
    /// Total wall-clock time.
    #[serde(serialize_with = "seconds")]
    pub total: Duration,
}

impl RenderStats {
    /// The pass called `name`.
    pub fn pass(&self, name: &str) -> Option<&PassStats> {
        self.passes.iter().find(|p| p.name == name)
    }

    /// The statistics of the pipeline's pass `pass`.
    pub fn of(&self, pass: Pass) -> Option<&PassStats> {
        self.pass(pass.name())
    }

    /// The statistics without the times: what must not depend on the thread count.
    pub fn work(&self) -> Vec<PassWork> {
        self.passes
            .iter()
            .chain(&self.lights)
            .map(|p| (p.name.clone(), p.ran, p.counters.clone()))
            .collect()
    }
}

impl fmt::Display for RenderStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{:<16} {:>10}  counters", "pass", "time (ms)")?;
        for p in &self.passes {
            let time = if p.ran {
                format!("{:.1}", p.time.as_secs_f64() * 1e3)
            } else {
                "skipped".to_string()
            };
            let counters: Vec<String> =
                p.counters.iter().map(|(n, v)| format!("{n}={v}")).collect();
            writeln!(f, "{:<16} {:>10}  {}", p.name, time, counters.join(" "))?;
        }
        write!(
            f,
            "{:<16} {:>10.1}",
            "total",
            self.total.as_secs_f64() * 1e3
        )?;
        if !self.lights.is_empty() {
            write!(f, "\nsoft shadows per area light:")?;
            for l in &self.lights {
                let counters: Vec<String> =
                    l.counters.iter().map(|(n, v)| format!("{n}={v}")).collect();
                write!(
                    f,
                    "\n  {}: {:.1} ms  {}",
                    l.name,
                    l.time.as_secs_f64() * 1e3,
                    counters.join(" ")
                )?;
                if !l.phases.is_empty() {
                    let phases: Vec<String> = l
                        .phases
                        .iter()
                        .map(|(n, t)| format!("{n} {:.1}", t.as_secs_f64() * 1e3))
                        .collect();
                    write!(f, "\n    thread ms: {}", phases.join(", "))?;
                }
            }
        }
        Ok(())
    }
}
