//! The settings of a distributed render: the thesis's load balancing (7.2.4) and its
//! parameters, and the failure detection it lacked.

use std::time::Duration;

use crate::error::Error;

/// The least default side of the final boxes, in pixels.
pub const DEFAULT_UNIT: u32 = 32;

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
    /// A rank asks for boxes when its list holds fewer than this many final boxes (the
    /// thesis: 2 boxes; a box not yet bisected counts for the final boxes it holds).
    pub threshold: usize,
    /// The share of its final boxes a rank gives to one that asks (the thesis: 40 % of its
    /// boxes).
    pub fraction: f64,
    /// The side of the final boxes, rendered as one window: a multiple of the pipeline's
    /// window grid (`beam_trace::window::window_grid`: 32 pixels for the screen boxes, 64
    /// for the frustum octree, 1 for per-pixel rays); `None`: the grid's side, at least
    /// [`DEFAULT_UNIT`]. Larger boxes are bisected first.
    pub unit: Option<u32>,
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
    /// boxes of one cell of the window grid; a rank silent for 60 s is reported dead.
    fn default() -> Self {
        Self {
            balance: true,
            threshold: 2,
            fraction: 0.4,
            unit: None,
            initial: Initial::Equal,
            timeout: Duration::from_secs(60),
            heartbeat: Duration::from_millis(250),
        }
    }
}

impl Settings {
    /// The side of the final boxes on a window grid of side `grid`: the setting, else the
    /// grid's side but at least 32 pixels (a box of one pixel per message would cost more
    /// to send than to render).
    pub fn unit(&self, grid: u32) -> u32 {
        self.unit.unwrap_or(grid.max(DEFAULT_UNIT))
    }

    /// Checks the settings for a cluster of `ranks` ranks rendering windows on a grid of
    /// side `grid`.
    ///
    /// # Errors
    ///
    /// [`Error::Setting`] naming the first setting out of range.
    pub fn check(&self, ranks: usize, grid: u32) -> Result<(), Error> {
        let bad = |name, message: String| Err(Error::Setting { name, message });
        if !(self.fraction > 0.0 && self.fraction <= 1.0) {
            return bad("fraction", format!("{} is not in (0, 1]", self.fraction));
        }
        if self.threshold == 0 {
            return bad("threshold", "must be at least 1 box".into());
        }
        let unit = self.unit(grid);
        if unit == 0 || !unit.is_multiple_of(grid) {
            return bad(
                "unit",
                format!("{unit} is not a positive multiple of the window grid, {grid} pixels"),
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
