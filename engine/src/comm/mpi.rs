//! The MPI transport (rsmpi over the system's MPI library; cargo feature `mpi`).

use super::{Received, Transport};
use mpi::collective::SystemOperation;
use mpi::environment::Universe;
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

    /// One message each way: the send is posted, the incoming message is probed for its
    /// length and received, then the send completes (no separate length message).
    fn sendrecv(&self, data: &[f64], dest: usize, src: usize, recv: &mut Received) {
        let dest = self.world.process_at_rank(dest as i32);
        let src = self.world.process_at_rank(src as i32);
        mpi::request::scope(|scope| {
            let sent = dest.immediate_send(scope, data);
            let (message, status) = src.matched_probe();
            let count = status.count(f64::equivalent_datatype()) as usize;
            message.matched_receive_into(recv.room(0, count));
            sent.wait();
        });
    }

    /// Both sends are posted, then each incoming message is probed and received in turn.
    fn sendrecv2(&self, data: &[f64], split: usize, dest: [usize; 2], src: [usize; 2], recv: &mut Received) -> usize {
        let (first, second) = data.split_at(split);
        let mut ends = [0; 2];
        mpi::request::scope(|scope| {
            let sent = [(first, dest[0]), (second, dest[1])].map(|(d, r)| self.world.process_at_rank(r as i32).immediate_send(scope, d));
            let mut len = 0;
            for (end, r) in ends.iter_mut().zip(src) {
                let (message, status) = self.world.process_at_rank(r as i32).matched_probe();
                let count = status.count(f64::equivalent_datatype()) as usize;
                message.matched_receive_into(recv.room(len, count));
                len += count;
                *end = len;
            }
            for s in sent {
                s.wait();
            }
        });
        ends[0]
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
