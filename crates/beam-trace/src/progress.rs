//! Progress of long passes (the render binary shows a progress bar).

/// Reports progress of long passes.
pub trait Progress: Sync {
    /// A pass with `total` units of work begins.
    fn begin(&self, pass: &str, total: u64) {
        let _ = (pass, total);
    }
    /// `n` more units are done.
    fn advance(&self, n: u64) {
        let _ = n;
    }
    /// The pass is over.
    fn end(&self) {}
}

/// Progress that shows nothing.
#[derive(Copy, Clone, Debug, Default)]
pub struct NoProgress;

impl Progress for NoProgress {}
