//! What a distributed render reports besides the image: per rank, where its time went and
//! what it sent (the thesis's 7.2.5 discussion), and which rank rendered the boxes of which
//! initial part (the thesis's Fig. 7.4).

use std::fmt;
use std::time::Duration;

use crate::settings::Settings;
use crate::wire::{ReadError, Reader, Writer};

/// One rank's time and traffic.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct RankStats {
    /// The rank.
    pub rank: usize,
    /// Rendering final boxes (summed over the rank's render threads).
    #[serde(serialize_with = "seconds")]
    pub busy: Duration,
    /// Waiting for a box, with an empty list (summed over the rank's render threads).
    #[serde(serialize_with = "seconds")]
    pub idle: Duration,
    /// Sending, receiving and decoding messages (polls that find no message excluded).
    #[serde(serialize_with = "seconds")]
    pub communication: Duration,
    /// From the start until its last box was rendered.
    #[serde(serialize_with = "seconds")]
    pub last_box: Duration,
    /// Final boxes rendered.
    pub boxes: u64,
    /// Their pixels.
    pub pixels: u64,
    /// Boxes bisected.
    pub splits: u64,
    /// Requests for boxes sent.
    pub requests: u64,
    /// Requests refused by the rank asked.
    pub refusals: u64,
    /// Requests answered with boxes.
    pub donations: u64,
    /// Boxes given away.
    pub boxes_given: u64,
    /// Boxes received from other ranks.
    pub boxes_received: u64,
    /// Messages sent.
    pub messages: u64,
    /// Bytes sent.
    pub bytes: u64,
}

fn seconds<S: serde::Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(d.as_secs_f64())
}

impl RankStats {
    /// Appends the statistics to `w`.
    pub fn write(&self, w: &mut Writer) {
        w.u64(self.rank as u64);
        for d in [self.busy, self.idle, self.communication, self.last_box] {
            w.duration(d);
        }
        for v in self.counts() {
            w.u64(v);
        }
    }

    fn counts(&self) -> [u64; 10] {
        [
            self.boxes,
            self.pixels,
            self.splits,
            self.requests,
            self.refusals,
            self.donations,
            self.boxes_given,
            self.boxes_received,
            self.messages,
            self.bytes,
        ]
    }

    /// Reads what [`RankStats::write`] wrote.
    pub fn read(r: &mut Reader<'_>) -> Result<Self, ReadError> {
        let time = |r: &mut Reader<'_>| r.duration("rank time");
        let count = |r: &mut Reader<'_>| r.u64("rank counter");
        // Fields are read in the order they are written (a struct literal evaluates its
        // fields in source order).
        Ok(Self {
            rank: r.u64("rank")? as usize,
            busy: time(r)?,
            idle: time(r)?,
            communication: time(r)?,
            last_box: time(r)?,
            boxes: count(r)?,
            pixels: count(r)?,
            splits: count(r)?,
            requests: count(r)?,
            refusals: count(r)?,
            donations: count(r)?,
            boxes_given: count(r)?,
            boxes_received: count(r)?,
            messages: count(r)?,
            bytes: count(r)?,
        })
    }
}

/// The cluster's report of one render, made by rank 0.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ClusterReport {
    /// The settings.
    pub settings: Settings,
    /// The side of the final boxes.
    pub unit: u32,
    /// The render threads of each rank (each renders a box at a time).
    pub render_threads: usize,
    /// The rayon threads of each rank (0: rayon's default).
    pub threads: usize,
    /// Wall-clock time of the whole render on rank 0, set-up included.
    #[serde(serialize_with = "seconds")]
    pub wall: Duration,
    /// Wall-clock time of the set-up (the grid) on rank 0.
    #[serde(serialize_with = "seconds")]
    pub setup: Duration,
    /// Every rank's statistics, by rank.
    pub ranks: Vec<RankStats>,
    /// `origins[r][o]`: the final boxes rank `r` rendered that lie in rank `o`'s initial
    /// part.
    pub origins: Vec<Vec<u64>>,
    /// The same in pixels.
    pub origin_pixels: Vec<Vec<u64>>,
}

impl ClusterReport {
    /// Whether some rank rendered boxes of another rank's part.
    pub fn balanced(&self) -> bool {
        self.origins
            .iter()
            .enumerate()
            .any(|(r, row)| row.iter().enumerate().any(|(o, &n)| o != r && n > 0))
    }
}

impl fmt::Display for ClusterReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = &self.settings;
        writeln!(
            f,
            "cluster: {} ranks x {} render threads ({}), balancing {} \
             (request below {} final boxes, donate {:.0} %), final boxes {} px, wall {:.3} s \
             (set-up {:.3} s)",
            self.ranks.len(),
            self.render_threads,
            match self.threads {
                0 => "rayon's default pool".to_string(),
                n => format!("{n} rayon threads"),
            },
            if s.balance { "on" } else { "off" },
            s.threshold,
            s.fraction * 100.0,
            self.unit,
            self.wall.as_secs_f64(),
            self.setup.as_secs_f64()
        )?;
        writeln!(
            f,
            "{:>4} {:>9} {:>9} {:>9} {:>9} {:>6} {:>8} {:>6} {:>6} {:>6} {:>6} {:>6} {:>10}",
            "rank",
            "busy s",
            "idle s",
            "comm s",
            "last s",
            "boxes",
            "pixels",
            "splits",
            "asked",
            "refus.",
            "given",
            "recv.",
            "bytes"
        )?;
        for r in &self.ranks {
            writeln!(
                f,
                "{:>4} {:>9.3} {:>9.3} {:>9.3} {:>9.3} {:>6} {:>8} {:>6} {:>6} {:>6} {:>6} {:>6} {:>10}",
                r.rank,
                r.busy.as_secs_f64(),
                r.idle.as_secs_f64(),
                r.communication.as_secs_f64(),
                r.last_box.as_secs_f64(),
                r.boxes,
                r.pixels,
                r.splits,
                r.requests,
                r.refusals,
                r.boxes_given,
                r.boxes_received,
                r.bytes
            )?;
        }
        write!(f, "boxes rendered (rows) by initial part (columns):")?;
        for (r, row) in self.origins.iter().enumerate() {
            write!(f, "\n{r:>4}")?;
            for n in row {
                write!(f, " {n:>6}")?;
            }
        }
        Ok(())
    }
}
