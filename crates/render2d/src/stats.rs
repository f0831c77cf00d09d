//! Counters and times of a render, per tile level and in total.

use std::fmt::Write;
use std::time::Duration;

/// What happened at one level of tiles.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LevelStats {
    /// Tile size of the level in pixels.
    pub size: usize,
    /// Tiles evaluated in interval arithmetic.
    pub tiles: u64,
    /// Tiles proven inside.
    pub inside: u64,
    /// Tiles proven outside.
    pub outside: u64,
    /// Sum of the lengths of the tapes evaluated at this level.
    pub tape_len_sum: u64,
    /// Shortest tape evaluated at this level.
    pub tape_len_min: usize,
    /// Longest tape evaluated at this level.
    pub tape_len_max: usize,
}

impl LevelStats {
    /// Mean length of the tapes evaluated at this level.
    pub fn tape_len_mean(&self) -> f64 {
        if self.tiles == 0 {
            0.0
        } else {
            self.tape_len_sum as f64 / self.tiles as f64
        }
    }

    /// Counts a tile of this level evaluated with a tape of `len` instructions.
    pub(crate) fn add_tape(&mut self, len: usize) {
        if self.tiles == 0 || len < self.tape_len_min {
            self.tape_len_min = len;
        }
        self.tape_len_max = self.tape_len_max.max(len);
        self.tape_len_sum += len as u64;
        self.tiles += 1;
    }

    /// Adds the counts of `o`, a part of the same level.
    fn merge(&mut self, o: &LevelStats) {
        if o.tiles > 0 {
            if self.tiles == 0 || o.tape_len_min < self.tape_len_min {
                self.tape_len_min = o.tape_len_min;
            }
            self.tape_len_max = self.tape_len_max.max(o.tape_len_max);
        }
        self.tiles += o.tiles;
        self.inside += o.inside;
        self.outside += o.outside;
        self.tape_len_sum += o.tape_len_sum;
    }
}

/// Counters and times of a [`render`](crate::render).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    /// One entry per tile level, largest tiles first.
    pub levels: Vec<LevelStats>,
    /// Pixels classified by point evaluation.
    pub point_pixels: u64,
    /// Point batches evaluated (one per undecided smallest tile).
    pub point_batches: u64,
    /// Sum over point batches of the length of the tape they used.
    pub point_tape_len_sum: u64,
    /// Tapes pruned (`simplify` calls that returned a shorter tape).
    pub pruned_tapes: u64,
    /// Time in interval evaluation, summed over threads (with
    /// [`Settings::timing`](crate::Settings::timing)).
    pub interval_time: Duration,
    /// Time in tape pruning, summed over threads (with
    /// [`Settings::timing`](crate::Settings::timing)).
    pub prune_time: Duration,
    /// Time in point evaluation, summed over threads (with
    /// [`Settings::timing`](crate::Settings::timing)).
    pub point_time: Duration,
}

impl Stats {
    /// Zero counts for the tile sizes `tiles`.
    pub(crate) fn new(tiles: &[usize]) -> Self {
        Self {
            levels: tiles
                .iter()
                .map(|&size| LevelStats {
                    size,
                    ..LevelStats::default()
                })
                .collect(),
            ..Self::default()
        }
    }

    /// Adds the counts and times of `o`, made with the same tile sizes.
    pub(crate) fn merge(&mut self, o: &Stats) {
        for (a, b) in self.levels.iter_mut().zip(&o.levels) {
            a.merge(b);
        }
        self.point_pixels += o.point_pixels;
        self.point_batches += o.point_batches;
        self.point_tape_len_sum += o.point_tape_len_sum;
        self.pruned_tapes += o.pruned_tapes;
        self.interval_time += o.interval_time;
        self.prune_time += o.prune_time;
        self.point_time += o.point_time;
    }

    /// Mean length of the tapes used by the point batches.
    pub fn point_tape_len_mean(&self) -> f64 {
        if self.point_batches == 0 {
            0.0
        } else {
            self.point_tape_len_sum as f64 / self.point_batches as f64
        }
    }

    /// The counters as a text table, one line per tile level, then the pixels classified by
    /// point evaluation (out of `pixels`, the image's), the pruned tapes and the stage times
    /// (summed over `threads` threads); every line ends with a newline. The `--stats`
    /// output of the `render2d` example.
    pub fn table(&self, pixels: usize, threads: usize) -> String {
        let mut s = String::new();
        // Writing to a `String` cannot fail.
        let _ = self.write_table(&mut s, pixels, threads);
        s
    }

    /// Writes [`Stats::table`] into `out`.
    fn write_table(&self, out: &mut String, pixels: usize, threads: usize) -> std::fmt::Result {
        writeln!(
            out,
            "level  tile  evaluated   inside  outside  split  tape len min/mean/max"
        )?;
        for (k, l) in self.levels.iter().enumerate() {
            let split = l.tiles - l.inside - l.outside;
            writeln!(
                out,
                "{k:>5} {:>5} {:>10} {:>8} {:>8} {:>6}  {}/{:.0}/{}",
                l.size,
                l.tiles,
                l.inside,
                l.outside,
                split,
                l.tape_len_min,
                l.tape_len_mean(),
                l.tape_len_max
            )?;
        }
        writeln!(
            out,
            "pixels by point evaluation: {} of {} ({:.2} %), in {} batches, mean tape length {:.0}",
            self.point_pixels,
            pixels,
            100.0 * self.point_pixels as f64 / pixels as f64,
            self.point_batches,
            self.point_tape_len_mean()
        )?;
        writeln!(out, "pruned tapes built: {}", self.pruned_tapes)?;
        writeln!(
            out,
            "stage times summed over {threads} threads: interval {:.1} ms, pruning {:.1} ms, points {:.1} ms",
            self.interval_time.as_secs_f64() * 1e3,
            self.prune_time.as_secs_f64() * 1e3,
            self.point_time.as_secs_f64() * 1e3
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merge_keeps_extremes_and_table_shows_them() {
        let mut a = Stats::new(&[8, 2]);
        let mut b = Stats::new(&[8, 2]);
        a.levels[0].add_tape(10);
        b.levels[0].add_tape(4);
        b.levels[0].add_tape(7);
        b.levels[0].inside = 1;
        b.point_pixels = 4;
        b.point_batches = 1;
        b.point_tape_len_sum = 3;
        a.merge(&b);
        let l = &a.levels[0];
        assert_eq!((l.tiles, l.tape_len_min, l.tape_len_max), (3, 4, 10));
        assert_eq!(
            a.levels[1],
            LevelStats {
                size: 2,
                ..LevelStats::default()
            }
        );
        let table = a.table(16, 2);
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines.len(), 6);
        assert_eq!(
            lines[1],
            "    0     8          3        1        0      2  4/7/10"
        );
        assert_eq!(
            lines[2],
            "    1     2          0        0        0      0  0/0/0"
        );
        assert!(
            lines[3].starts_with("pixels by point evaluation: 4 of 16 (25.00 %), in 1 batches")
        );
        assert!(table.ends_with(" ms\n"));
    }
}
