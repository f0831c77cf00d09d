//! The transport trait: what a rank needs from the link between ranks.

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
