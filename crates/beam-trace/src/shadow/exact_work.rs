//! The exact method's work counters (kept apart from the method, which the shadow
//! methods' shared counters include).

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
