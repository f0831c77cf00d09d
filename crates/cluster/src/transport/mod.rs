//! How ranks reach each other: MPI between processes (`Mpi`, feature `mpi`), or channels
//! between threads of one process ([`local_cluster`]) for tests and for machines without
//! MPI. A station calls its transport from one thread only.

mod local;
#[cfg(feature = "mpi")]
mod mpi;

pub use local::{Local, local_cluster};
#[cfg(feature = "mpi")]
pub use mpi::Mpi;

use crate::error::Error;

/// Point-to-point messages between the ranks of a cluster.
pub trait Transport {
    /// This rank's number, `0..size()`.
    fn rank(&self) -> usize;
    /// The number of ranks.
    fn size(&self) -> usize;
    /// Sends `bytes` to rank `to`; returns once the bytes may be reused.
    ///
    /// # Errors
    ///
    /// [`Error::Transport`] when the message cannot be sent.
    fn send(&self, to: usize, bytes: &[u8]) -> Result<(), Error>;
    /// The next message that has arrived, from any rank, with its sender; `None` when none
    /// has.
    ///
    /// # Errors
    ///
    /// [`Error::Transport`] when receiving fails.
    fn try_recv(&self) -> Result<Option<(usize, Vec<u8>)>, Error>;
}
