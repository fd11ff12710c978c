//! How ranks exchange bytes: a [`Transport`] moves f64 buffers between neighbour ranks
//! and performs the few collectives the engine needs. [`Local`] is the single-rank
//! transport (every send reaches the sender itself); MPI lives in `mpi.rs`.

/// Point-to-point exchange and collectives between ranks.
pub trait Transport {
    fn rank(&self) -> usize;
    fn size(&self) -> usize;
    /// Sends `data` to rank `dest` while receiving the buffer rank `src` sends to us.
    fn sendrecv(&self, data: &[f64], dest: usize, src: usize, recv: &mut Received);
    /// Two exchanges at once: sends `data[..split]` to `dest[0]` and `data[split..]` to
    /// `dest[1]` while receiving into `recv` the buffer rank `src[0]` sends us (first
    /// of the two when `src[0] == src[1]`: messages between two ranks keep their order)
    /// followed by the one from `src[1]`; returns where the second begins.
    fn sendrecv2(&self, data: &[f64], split: usize, dest: [usize; 2], src: [usize; 2], recv: &mut Received) -> usize;
    /// Element-wise maximum over ranks, in place.
    fn max(&self, values: &mut [f64]);
    /// The `local` slices of all ranks, concatenated in rank order.
    fn all_gather(&self, local: &[u64]) -> Vec<u64>;
    /// Rank 0 receives every other rank's `local` buffer in rank order, one at a time
    /// (so it never holds more than one rank's share), and hands each to `take`.
    fn gather_to_root(&self, local: &[f64], take: &mut dyn FnMut(&[f64]));
}

/// A receive buffer whose memory only grows: a message overwrites it from the front and
/// reads as a slice of its own length, so a message longer than the last one needs no
/// zeroing of the memory earlier messages wrote.
#[derive(Clone, Debug, Default)]
pub struct Received {
    buf: Vec<f64>,
    len: usize,
}

impl Received {
    /// Room for a message of `n` values after the first `keep` values held (0: the
    /// message replaces them), to be written whole.
    pub fn room(&mut self, keep: usize, n: usize) -> &mut [f64] {
        debug_assert!(keep <= self.len);
        let end = keep + n;
        if self.buf.len() < end {
            self.buf.resize(end, 0.0);
        }
        self.len = end;
        &mut self.buf[keep..end]
    }
}

impl std::ops::Deref for Received {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        &self.buf[..self.len]
    }
}

/// One rank: the world is this process.
#[derive(Clone, Copy, Debug, Default)]
pub struct Local;

impl Transport for Local {
    fn rank(&self) -> usize {
        0
    }
    fn size(&self) -> usize {
        1
    }
    fn sendrecv(&self, data: &[f64], _dest: usize, _src: usize, recv: &mut Received) {
        recv.room(0, data.len()).copy_from_slice(data);
    }
    fn sendrecv2(&self, data: &[f64], split: usize, _dest: [usize; 2], _src: [usize; 2], recv: &mut Received) -> usize {
        recv.room(0, data.len()).copy_from_slice(data);
        split
    }
    fn max(&self, _values: &mut [f64]) {}
    fn all_gather(&self, local: &[u64]) -> Vec<u64> {
        local.to_vec()
    }
    fn gather_to_root(&self, local: &[f64], take: &mut dyn FnMut(&[f64])) {
        take(local);
    }
}
