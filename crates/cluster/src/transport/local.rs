//! Ranks as threads of one process, joined by channels.

use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};

use super::traits::Transport;
use crate::error::Error;

/// One rank of a cluster of threads ([`local_cluster`]).
pub struct Local {
    rank: usize,
    peers: Vec<Sender<(usize, Vec<u8>)>>,
    inbox: Receiver<(usize, Vec<u8>)>,
}

/// The ranks of a cluster of `ranks` threads: move each into its own thread.
pub fn local_cluster(ranks: usize) -> Vec<Local> {
    let (peers, inboxes): (Vec<_>, Vec<_>) = (0..ranks).map(|_| channel()).unzip();
    inboxes
        .into_iter()
        .enumerate()
        .map(|(rank, inbox)| Local {
            rank,
            peers: peers.clone(),
            inbox,
        })
        .collect()
}

impl Transport for Local {
    fn rank(&self) -> usize {
        self.rank
    }

    fn size(&self) -> usize {
        self.peers.len()
    }

    fn send(&self, to: usize, bytes: &[u8]) -> Result<(), Error> {
        let peer = self
            .peers
            .get(to)
            .ok_or_else(|| Error::Transport(format!("no rank {to} of {}", self.peers.len())))?;
        // A rank that has finished has dropped its inbox: what it would get is moot.
        let _ = peer.send((self.rank, bytes.to_vec()));
        Ok(())
    }

    fn try_recv(&self) -> Result<Option<(usize, Vec<u8>)>, Error> {
        match self.inbox.try_recv() {
            Ok(m) => Ok(Some(m)),
            Err(TryRecvError::Empty | TryRecvError::Disconnected) => Ok(None),
        }
    }
}
