//! The settings of a distributed render: the thesis's load balancing (7.2.4) and its
//! parameters, and the failure detection it lacked.

use std::time::Duration;

use beam_trace::window::WINDOW_ALIGN;

use crate::error::Error;

/// Where the work starts.
#[derive(Copy, Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Initial {
    /// The screen cut into as many equal parts as ranks, one each (the thesis: four
    /// quadrants, upper left to the first workstation, lower right to the last).
    Equal,
    /// The whole screen on one rank, the others starting with nothing (what load balancing
    /// must fix).
    OnRank(usize),
}

/// How the ranks share the screen boxes.
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub struct Settings {
    /// Whether a rank that runs short asks the others for boxes (else each renders its
    /// initial part alone: the thesis's Fig. 7.3).
    pub balance: bool,
    /// A rank asks for boxes when its list holds fewer than this many (the thesis: 2).
    pub threshold: usize,
    /// The share of its boxes a rank gives to one that asks (the thesis: 40 %).
    pub fraction: f64,
    /// The side of the final boxes, rendered as one window: a multiple of
    /// [`WINDOW_ALIGN`] (larger boxes are bisected first).
    pub unit: u32,
    /// Where the work starts.
    pub initial: Initial,
    /// Silence after which a rank is reported dead.
    #[serde(serialize_with = "seconds")]
    pub timeout: Duration,
    /// How often a rank tells the others it is alive.
    #[serde(serialize_with = "seconds")]
    pub heartbeat: Duration,
}

fn seconds<S: serde::Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(d.as_secs_f64())
}

impl Default for Settings {
    /// The thesis's settings: balancing on, a request below 2 boxes, 40 % donated; final
    /// boxes of one window (64 pixels); a rank silent for 60 s is reported dead.
    fn default() -> Self {
        Self {
            balance: true,
            threshold: 2,
            fraction: 0.4,
            unit: WINDOW_ALIGN,
            initial: Initial::Equal,
            timeout: Duration::from_secs(60),
            heartbeat: Duration::from_millis(250),
        }
    }
}

impl Settings {
    /// Checks the settings for a cluster of `ranks` ranks.
    ///
    /// # Errors
    ///
    /// [`Error::Setting`] naming the first setting out of range.
    pub fn check(&self, ranks: usize) -> Result<(), Error> {
        let bad = |name, message: String| Err(Error::Setting { name, message });
        if !(self.fraction > 0.0 && self.fraction <= 1.0) {
            return bad("fraction", format!("{} is not in (0, 1]", self.fraction));
        }
        if self.threshold == 0 {
            return bad("threshold", "must be at least 1 box".into());
        }
        if self.unit == 0 || !self.unit.is_multiple_of(WINDOW_ALIGN) {
            return bad(
                "unit",
                format!("{} is not a positive multiple of {WINDOW_ALIGN}", self.unit),
            );
        }
        if let Initial::OnRank(r) = self.initial
            && r >= ranks
        {
            return bad("initial", format!("rank {r} of {ranks} ranks"));
        }
        if self.heartbeat.is_zero() || self.timeout <= self.heartbeat * 2 {
            return bad(
                "timeout",
                format!(
                    "{:?} must exceed twice the heartbeat ({:?})",
                    self.timeout, self.heartbeat
                ),
            );
        }
        Ok(())
    }
}
