//! Ranks as MPI processes (rsmpi): one message per `send`, received by probing for any
//! source, so a rank never blocks on a peer that has nothing to say.

use mpi::collective::CommunicatorCollectives;
use mpi::point_to_point::{Destination, MatchedReceiveVec, Source};
use mpi::topology::{Communicator, SimpleCommunicator};

use super::traits::Transport;
use crate::error::Error;

/// This process's rank in `MPI_COMM_WORLD`.
pub struct Mpi {
    world: SimpleCommunicator,
}

impl Mpi {
    /// The transport over `world` (from [`mpi::initialize_with_threading`] with at least
    /// `Threading::Funneled`: only the thread that made it calls MPI).
    pub fn new(world: SimpleCommunicator) -> Self {
        Self { world }
    }

    /// Waits until every rank has called it.
    pub fn barrier(&self) {
        self.world.barrier();
    }

    /// Ends every process of the job with `code` (a rank failed: the others must not hang).
    pub fn abort(&self, code: i32) -> ! {
        self.world.abort(code)
    }
}

impl Transport for Mpi {
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    fn size(&self) -> usize {
        self.world.size() as usize
    }

    fn send(&self, to: usize, bytes: &[u8]) -> Result<(), Error> {
        if to >= self.size() {
            return Err(Error::Transport(format!("no rank {to} of {}", self.size())));
        }
        self.world.process_at_rank(to as i32).send(bytes);
        Ok(())
    }

    fn try_recv(&self) -> Result<Option<(usize, Vec<u8>)>, Error> {
        Ok(self
            .world
            .any_process()
            .immediate_matched_probe()
            .map(|probed| {
                let (bytes, status) = probed.matched_receive_vec::<u8>();
                (status.source_rank() as usize, bytes)
            }))
    }
}
