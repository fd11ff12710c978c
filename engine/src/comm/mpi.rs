//! The MPI transport (rsmpi over the system's MPI library; cargo feature `mpi`).

use super::Transport;
use mpi::collective::SystemOperation;
use mpi::environment::Universe;
use mpi::point_to_point as p2p;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

/// MPI_COMM_WORLD; finalises MPI when dropped.
pub struct MpiTransport {
    world: SimpleCommunicator,
    _universe: Universe,
}

impl MpiTransport {
    /// Initialises MPI; None if it was initialised already.
    pub fn init() -> Option<Self> {
        let universe = mpi::initialize()?;
        let world = universe.world();
        Some(Self { world, _universe: universe })
    }
}

impl Transport for MpiTransport {
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    fn size(&self) -> usize {
        self.world.size() as usize
    }

    fn sendrecv(&self, data: &[f64], dest: usize, src: usize, recv: &mut Vec<f64>) {
        let dest = self.world.process_at_rank(dest as i32);
        let src = self.world.process_at_rank(src as i32);
        let count = data.len() as u64;
        let (incoming, _): (u64, _) = p2p::send_receive(&count, &dest, &src);
        recv.clear();
        recv.resize(incoming as usize, 0.0);
        p2p::send_receive_into(data, &dest, &mut recv[..], &src);
    }

    fn max(&self, values: &mut [f64]) {
        let local = values.to_vec();
        self.world.all_reduce_into(&local[..], values, SystemOperation::max());
    }

    fn gather_to_root(&self, local: &[f64], take: &mut dyn FnMut(&[f64])) {
        if self.rank() == 0 {
            take(local);
            for r in 1..self.size() {
                let (buf, _) = self.world.process_at_rank(r as i32).receive_vec::<f64>();
                take(&buf);
            }
        } else {
            self.world.process_at_rank(0).send(local);
        }
    }

    fn all_gather(&self, local: &[u64]) -> Vec<u64> {
        let mut out = vec![0u64; local.len() * self.size()];
        self.world.all_gather_into(local, &mut out[..]);
        out
    }
}
