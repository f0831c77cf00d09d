//! The exact method's work counters and phase times (kept apart from the method, which
//! the shadow methods' shared counters include).

use std::time::Duration;

/// What the BSP did, for the per-light table.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct BspWork {
    /// Queries answered.
    pub queries: u64,
    /// Leaves expanded (an occluder turned into its chain of edges).
    pub merges: u64,
    /// Inner nodes created.
    pub inner_nodes: u64,
    /// Fragments split by a query plane.
    pub splits: u64,
    /// Visible fragments emitted.
    pub fragments: u64,
    /// Query points on an edge's line (the fragment sent to the positive side).
    pub degenerate: u64,
    /// The most nodes alive at once.
    pub peak_nodes: u64,
}

impl BspWork {
    /// Adds `other`'s counts to these (the peak is the larger one).
    pub fn add(&mut self, other: &BspWork) {
        self.queries += other.queries;
        self.merges += other.merges;
        self.inner_nodes += other.inner_nodes;
        self.splits += other.splits;
        self.fragments += other.fragments;
        self.degenerate += other.degenerate;
        self.peak_nodes = self.peak_nodes.max(other.peak_nodes);
    }
}

/// Thread time the exact method spent in each phase of the seed's per-light table (not
/// compared between runs: it is a time).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct ExactTimes {
    /// Shaft culling: the triangles that may shade a group, and the points' own shafts.
    pub shaft: Duration,
    /// Setting up the groups' trees: clipping the occluders, the stabbing signs.
    pub init: Duration,
    /// The queries: growing the trees and collecting the visible fragments.
    pub queries: Duration,
    /// The implicit occluders' beams and segments over the fragments (and the sampled
    /// estimate of points in the light's own plane).
    pub implicit: Duration,
}

impl ExactTimes {
    /// Adds `other`'s times to these.
    pub fn add(&mut self, other: &ExactTimes) {
        self.shaft += other.shaft;
        self.init += other.init;
        self.queries += other.queries;
        self.implicit += other.implicit;
    }

    /// The phases by name, in the order they run.
    pub fn phases(&self) -> [(&'static str, Duration); 4] {
        [
            ("shaft culling", self.shaft),
            ("bsp init", self.init),
            ("bsp queries", self.queries),
            ("implicit occluders", self.implicit),
        ]
    }
}
