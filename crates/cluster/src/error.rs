//! The crate's error type: every variant names the rank or the message at fault.

/// Errors of a distributed render.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The render itself failed (a backend, a bad window).
    #[error(transparent)]
    Render(#[from] beam_trace::Error),
    /// A rank sent nothing for longer than the settings' timeout: it died or hangs.
    #[error("rank {rank} sent nothing for {seconds:.1} s (timeout): it died or hangs")]
    Silent {
        /// The silent rank.
        rank: usize,
        /// How long it has been silent.
        seconds: f64,
    },
    /// Another rank failed and said why.
    #[error("rank {rank} failed: {message}")]
    Failed {
        /// The rank that failed.
        rank: usize,
        /// Its error.
        message: String,
    },
    /// A message could not be decoded.
    #[error("message from rank {from}: {message}")]
    Message {
        /// The sender.
        from: usize,
        /// What is wrong with it.
        message: String,
    },
    /// The transport failed.
    #[error("transport: {0}")]
    Transport(String),
    /// A setting is out of range.
    #[error("setting {name}: {message}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// What is wrong.
        message: String,
    },
}
