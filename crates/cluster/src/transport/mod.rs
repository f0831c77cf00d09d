//! How ranks reach each other: MPI between processes (`Mpi`, feature `mpi`), or channels
//! between threads of one process ([`local_cluster`]) for tests and for machines without
//! MPI. A station calls its transport from one thread only.

mod local;
#[cfg(feature = "mpi")]
mod mpi;
mod traits;

pub use local::{Local, local_cluster};
#[cfg(feature = "mpi")]
pub use mpi::Mpi;
pub use traits::Transport;
