//! Counters and times of a render, per tile level and in total.

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
    /// Time in interval evaluation, summed over threads (with [`Settings::timing`](crate::Settings::timing)).
    pub interval_time: Duration,
    /// Time in tape pruning, summed over threads (with [`Settings::timing`](crate::Settings::timing)).
    pub prune_time: Duration,
    /// Time in point evaluation, summed over threads (with [`Settings::timing`](crate::Settings::timing)).
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
}
