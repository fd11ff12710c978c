//! Communication between the owners of particles and their ghost copies, over a 3D
//! grid of ranks (LAMMPS's "swaps": per dimension, one exchange with each neighbour).
//!
//! One code path serves every rank count: on a single rank the neighbours are the rank
//! itself and the swaps create the periodic images, so every test exercises the same
//! packing, borders, forward and reverse exchanges that MPI runs use.

mod exact_sum;
#[cfg(feature = "mpi")]
mod mpi;
mod procs;
mod transport;

pub use exact_sum::{exact_column_sums, exact_sums};
#[cfg(feature = "mpi")]
pub use mpi::MpiTransport;
pub use procs::ProcGrid;
pub use transport::{Local, Transport};

use crate::{CellGrid, Domain, Fields, Particles, SweepPairs, Vec3};

/// One exchange of the ghost layer with a neighbour, recorded for forward and reverse
/// communication.
#[derive(Clone, Debug)]
struct Swap {
    dim: usize,
    /// Position shift the sender applies (0 or +-L across the periodic boundary).
    shift: f64,
    dest: usize,
    src: usize,
    /// Local indices sent (owned or ghosts received in earlier swaps).
    send: Vec<u32>,
    recv_start: usize,
    recv_count: usize,
}

/// Owner/ghost exchanges, migration and reductions of one rank.
pub struct Comm {
    t: Box<dyn Transport>,
    pub grid: ProcGrid,
    /// Owned cell range [lo, hi), set at each exchange.
    lo: [i32; 3],
    hi: [i32; 3],
    swaps: Vec<Swap>,
    send: Vec<f64>,
    recv: Vec<f64>,
    written: Vec<bool>,
    /// Particles whose new values go to their ghosts in [`Comm::after_colour`].
    fresh: Vec<bool>,
    /// Per colour, the particles of its sweep pairs (list radius), gathered at the first
    /// colour after each exchange (`members_stale`): they hold every particle it touches.
    members: Vec<Vec<u32>>,
    members_stale: bool,
    /// Per swap, the bit mask of the slots whose ghosts returned their values in the
    /// last reverse exchange (those ghosts hold the values their owners would forward).
    returned: Vec<Vec<f64>>,
    /// Scratch: the slots of a swap that travel, and the particles packed or unpacked.
    slots: Vec<u32>,
    idx: Vec<u32>,
    /// Wall time spent in exchanges and collectives.
    time: std::cell::Cell<std::time::Duration>,
    traffic: Traffic,
}

/// Point-to-point messages this rank sent to other ranks, and their f64 values.
#[derive(Default)]
struct Traffic {
    messages: u64,
    values: u64,
}

impl Traffic {
    /// Sends `send` to `dest` and receives `src`'s buffer into `recv`, counted.
    fn sendrecv(&mut self, t: &dyn Transport, send: &[f64], dest: usize, src: usize, recv: &mut Vec<f64>) {
        if dest != t.rank() {
            self.messages += 1;
            self.values += send.len() as u64;
        }
        t.sendrecv(send, dest, src, recv);
    }
}

impl Comm {
    /// A single-rank communicator.
    pub fn serial() -> Self {
        Self::new(Box::new(Local), [1, 1, 1])
    }

    /// A communicator over `t` with the processor grid `procs` (product = rank count).
    pub fn new(t: Box<dyn Transport>, procs: [usize; 3]) -> Self {
        let grid = ProcGrid::new(procs, t.rank());
        Self {
            t,
            grid,
            lo: [0; 3],
            hi: [0; 3],
            swaps: Vec::new(),
            send: Vec::new(),
            recv: Vec::new(),
            written: Vec::new(),
            fresh: Vec::new(),
            members: Vec::new(),
            members_stale: true,
            returned: Vec::new(),
            slots: Vec::new(),
            idx: Vec::new(),
            time: Default::default(),
            traffic: Traffic::default(),
        }
    }

    /// Wall time spent in communication so far (exchanges, ghosts, collectives).
    pub fn time(&self) -> std::time::Duration {
        self.time.get()
    }

    /// Point-to-point messages sent to other ranks so far, and their bytes.
    pub fn traffic(&self) -> (u64, u64) {
        (self.traffic.messages, 8 * self.traffic.values)
    }

    fn timed<R>(&self, f: impl FnOnce() -> R) -> R {
        let start = std::time::Instant::now();
        let r = f();
        self.time.set(self.time.get() + start.elapsed());
        r
    }

    pub fn rank(&self) -> usize {
        self.t.rank()
    }

    pub fn size(&self) -> usize {
        self.t.size()
    }

    pub fn transport(&self) -> &dyn Transport {
        self.t.as_ref()
    }

    /// Whether a particle created at `r` starts on this rank (before cells exist: the box
    /// split evenly; the first exchange moves it to the owner of its cell).
    pub fn keeps(&self, domain: &Domain, r: Vec3) -> bool {
        let len = domain.len();
        (0..3).all(|d| {
            let p = self.grid.dims[d];
            let k = (((r[d] - domain.lo[d]) / len[d]) * p as f64).floor() as i64;
            k.clamp(0, p as i64 - 1) as usize == self.grid.coords[d]
        })
    }

    /// Whether this rank owns global cell `cell` of a grid of `count` cells per dimension.
    pub fn owns_cell(&self, cell: [i32; 3], count: [usize; 3]) -> bool {
        (0..3).all(|d| {
            let (c, p, n) = (self.grid.coords[d], self.grid.dims[d], count[d]);
            let (lo, hi) = (c * n / p, (c + 1) * n / p);
            (lo..hi).contains(&(cell[d] as usize))
        })
    }

    /// Owned cell range [lo, hi) of this rank on `grid`.
    pub fn owned_cells(&self, grid: &CellGrid) -> ([i32; 3], [i32; 3]) {
        let lo = [0, 1, 2].map(|d| (self.grid.coords[d] * grid.count[d] / self.grid.dims[d]) as i32);
        let hi = [0, 1, 2].map(|d| ((self.grid.coords[d] + 1) * grid.count[d] / self.grid.dims[d]) as i32);
        (lo, hi)
    }

    /// Largest value over ranks.
    pub fn max(&self, x: f64) -> f64 {
        let mut v = [x];
        self.max_each(&mut v);
        v[0]
    }

    /// Element-wise largest values over ranks, in place.
    pub fn max_each(&self, v: &mut [f64]) {
        self.timed(|| self.t.max(v));
    }

    /// Sum of an integer count over ranks.
    pub fn count(&self, n: usize) -> u64 {
        self.timed(|| self.t.all_gather(&[n as u64])).iter().sum()
    }

    /// Whether any rank says yes.
    pub fn any(&self, yes: bool) -> bool {
        self.max(if yes { 1.0 } else { 0.0 }) > 0.0
    }

    /// Wraps owned particles into the box, hands them to the owners of their cells, and
    /// rebuilds the ghost layer: k cells (the grid's reach) on every side of the
    /// sub-domain, which must own at least k cells along each dimension. With
    /// `keep_cells` (a system read from a restart) positions and cells stay as stored,
    /// so the lists come out as they were when the restart was written.
    pub fn exchange(&mut self, store: &mut Particles, domain: &Domain, grid: &CellGrid, keep_cells: bool) {
        let start = std::time::Instant::now();
        store.truncate_ghosts();
        self.members_stale = true;
        (self.lo, self.hi) = self.owned_cells(grid);
        if !keep_cells {
            for i in 0..store.nlocal {
                domain.wrap(&mut store.r[i], &mut store.image[i]);
                store.cell[i] = grid.locate(store.r[i]);
                store.octant[i] = grid.octant(store.cell[i], store.r[i]) as u32;
            }
        }
        self.migrate(store, grid, keep_cells);
        // owned particles in cell order (then by tag): neighbours sit close in memory
        let mut order: Vec<u32> = (0..store.nlocal as u32).collect();
        let key = |i: u32| {
            let c = store.cell[i as usize];
            (c[2], c[1], c[0], store.tag[i as usize])
        };
        order.sort_unstable_by_key(|&i| key(i));
        store.reorder_owned(&order);
        self.borders(store, domain, grid);
        self.time.set(self.time.get() + start.elapsed());
    }

    /// Moves owned particles to the neighbour towards their cell until none is astray.
    fn migrate(&mut self, store: &mut Particles, grid: &CellGrid, keep_cells: bool) {
        let hops = *self.grid.dims.iter().max().unwrap_or(&1);
        for _ in 0..hops {
            for d in 0..3 {
                if self.grid.dims[d] == 1 {
                    continue;
                }
                let n = grid.count[d] as i32;
                for dir in [-1, 1] {
                    self.send.clear();
                    let mut i = store.nlocal;
                    while i > 0 {
                        i -= 1;
                        let c = store.cell[i][d];
                        if c >= self.lo[d] && c < self.hi[d] {
                            continue;
                        }
                        // the shorter way round the periodic box
                        let down = (self.lo[d] - c).rem_euclid(n);
                        let up = (c - (self.hi[d] - 1)).rem_euclid(n);
                        if (down <= up) == (dir == -1) {
                            store.pack_owned(i, &mut self.send);
                            store.remove_owned(i);
                        }
                    }
                    let (dest, src) = self.grid.neighbours(d, dir);
                    self.traffic.sendrecv(self.t.as_ref(), &self.send, dest, src, &mut self.recv);
                    for rec in self.recv.chunks_exact(store.owned_record()) {
                        store.unpack_owned(rec);
                        if !keep_cells {
                            let i = store.nlocal - 1;
                            store.cell[i] = grid.locate(store.r[i]);
                            store.octant[i] = grid.octant(store.cell[i], store.r[i]) as u32;
                        }
                    }
                }
            }
            let astray = (0..store.nlocal).any(|i| (0..3).any(|d| store.cell[i][d] < self.lo[d] || store.cell[i][d] >= self.hi[d]));
            if !self.any(astray) {
                return;
            }
        }
    }

    /// Builds the ghost layer dimension by dimension (the k outermost owned cell layers
    /// on each side); ghosts received in earlier dimensions travel on, so edges and
    /// corners are covered.
    fn borders(&mut self, store: &mut Particles, domain: &Domain, grid: &CellGrid) {
        self.swaps.clear();
        let len = domain.len();
        let layout = store.ghost_layout();
        for d in 0..3 {
            let n = grid.count[d] as i32;
            for dir in [-1, 1] {
                let k = grid.reach as i32;
                let layer = if dir == -1 { self.lo[d]..self.lo[d] + k } else { self.hi[d] - k..self.hi[d] };
                let edge = if dir == -1 { 0 } else { self.grid.dims[d] - 1 };
                let wraps = self.grid.coords[d] == edge;
                let (shift, cell_shift) = if wraps { (-(dir as f64) * len[d], -dir * n) } else { (0.0, 0) };
                let send: Vec<u32> = (0..store.len() as u32).filter(|&i| layer.contains(&store.cell[i as usize][d])).collect();
                self.send.clear();
                for &i in &send {
                    store.pack_ghost(i as usize, &layout, d, shift, cell_shift, &mut self.send);
                }
                let (dest, src) = self.grid.neighbours(d, dir);
                self.traffic.sendrecv(self.t.as_ref(), &self.send, dest, src, &mut self.recv);
                let recv_start = store.len();
                for rec in self.recv.chunks_exact(layout.width) {
                    store.unpack_ghost(rec);
                }
                let recv_count = store.len() - recv_start;
                self.swaps.push(Swap { dim: d, shift, dest, src, send, recv_start, recv_count });
            }
        }
    }

    /// Copies `fields` from the owners to all their ghosts.
    pub fn forward(&mut self, store: &mut Particles, fields: Fields) {
        let start = std::time::Instant::now();
        let me = self.t.rank();
        for s in &self.swaps {
            if s.dest == me && s.src == me {
                let moves = s.send.iter().enumerate().map(|(k, &i)| (i as usize, s.recv_start + k));
                store.copy_fields(moves, fields, Some((s.dim, s.shift)));
                continue;
            }
            self.send.clear();
            store.pack_fields(&s.send, fields, Some((s.dim, s.shift)), &mut self.send);
            self.traffic.sendrecv(self.t.as_ref(), &self.send, s.dest, s.src, &mut self.recv);
            self.idx.clear();
            self.idx.extend(s.recv_start as u32..(s.recv_start + s.recv_count) as u32);
            store.unpack_fields(&self.idx, fields, &self.recv);
        }
        self.time.set(self.time.get() + start.elapsed());
    }

    /// After colour `colour` of a sweep wrote `fields` of the particles of its pairs: the
    /// ghosts written return their values to their owners, then every particle the colour
    /// may have touched (owned and in its pairs, or reached by a returning ghost) forwards
    /// its values to its ghosts, but not to the ghosts that returned them (they hold
    /// them). Ghosts of particles outside the colour's pairs keep theirs, which are
    /// current, so they do not travel (particles of its pairs whose partners all lay
    /// beyond the cutoff forward values unchanged: marking from the colour's list costs a
    /// pass per list build, not per step). On one rank every swap is a copy, and all
    /// ghosts are copied (marking costs more than it saves).
    pub fn after_colour(&mut self, store: &mut Particles, sweep: &SweepPairs, colour: usize, fields: Fields) {
        let start = std::time::Instant::now();
        let me = self.t.rank();
        let remote = self.swaps.iter().any(|s| s.dest != me || s.src != me);
        self.fresh.clear();
        if remote {
            if self.members_stale {
                self.gather_members(store.len(), sweep);
            }
            self.fresh.resize(store.len(), false);
            for &k in &self.members[colour] {
                self.fresh[k as usize] = true;
            }
        }
        self.reverse(store, &sweep.ghost_writes[colour], fields);
        self.time.set(self.time.get() + start.elapsed());
        if remote {
            self.forward_fresh(store, fields);
        } else {
            self.forward(store, fields);
        }
    }

    /// [`Comm::after_colour`] without its forward: the ghosts written return their values
    /// to their owners, whose ghosts keep the old ones until a [`Comm::forward`] of
    /// `fields` (the last colour of a sweep, when nothing reads them before).
    pub fn reverse_colour(&mut self, store: &mut Particles, sweep: &SweepPairs, colour: usize, fields: Fields) {
        let start = std::time::Instant::now();
        self.fresh.clear();
        self.reverse(store, &sweep.ghost_writes[colour], fields);
        self.time.set(self.time.get() + start.elapsed());
    }

    /// `members`: the particles of each colour's pairs, each once.
    fn gather_members(&mut self, len: usize, sweep: &SweepPairs) {
        let seen = &mut self.slots;
        seen.clear();
        seen.resize(len, u32::MAX);
        self.members.resize_with(sweep.colours(), Vec::new);
        for (c, members) in self.members.iter_mut().enumerate() {
            members.clear();
            for &k in sweep.colour(c).iter().flatten() {
                if seen[k as usize] != c as u32 {
                    seen[k as usize] = c as u32;
                    members.push(k);
                }
            }
        }
        self.members_stale = false;
    }

    /// Copies `fields` of the listed ghosts back to their owners (values, not deltas; a
    /// message leads with one bit per ghost of the swap saying whether its record
    /// follows, kept in `returned`), marking the owners reached in `fresh` (when it is in
    /// use). Within one colour of the sweep each particle has exactly one writer, so only
    /// the ghosts written travel back, hop by hop through the swaps in reverse order.
    fn reverse(&mut self, store: &mut Particles, ghosts: &[u32], fields: Fields) {
        let fields = fields.without(Fields::POSITION);
        self.written.clear();
        self.written.resize(store.len(), false);
        for &g in ghosts {
            self.written[g as usize] = true;
        }
        self.returned.resize_with(self.swaps.len(), Vec::new);
        let me = self.t.rank();
        for (n, s) in self.swaps.iter().enumerate().rev() {
            if s.dest == me && s.src == me {
                let written = &self.written;
                let moves = (0..s.recv_count).filter(|&k| written[s.recv_start + k]).map(|k| (s.recv_start + k, s.send[k] as usize));
                store.copy_fields(moves, fields, None);
                // the owners reached may be ghosts that travel on in later swaps (the
                // sources, ghosts of this swap, lie above every destination)
                for k in 0..s.recv_count {
                    let i = s.send[k] as usize;
                    if self.written[s.recv_start + k] {
                        self.written[i] |= i >= store.nlocal;
                        if let Some(f) = self.fresh.get_mut(i) {
                            *f = true;
                        }
                    }
                }
                continue;
            }
            self.slots.clear();
            self.slots.extend((0..s.recv_count as u32).filter(|&k| self.written[s.recv_start + k as usize]));
            self.idx.clear();
            self.idx.extend(self.slots.iter().map(|&k| s.recv_start as u32 + k));
            lead_with_mask(&mut self.send, s.recv_count, &self.slots);
            store.pack_fields(&self.idx, fields, None, &mut self.send);
            self.traffic.sendrecv(self.t.as_ref(), &self.send, s.src, s.dest, &mut self.recv);
            let records = masked_slots(&self.recv, s.send.len(), &mut self.slots);
            self.returned[n].clear();
            self.returned[n].extend_from_slice(&self.recv[..self.recv.len() - records.len()]);
            self.idx.clear();
            self.idx.extend(self.slots.iter().map(|&k| s.send[k as usize]));
            store.unpack_fields(&self.idx, fields, records);
            for &i in &self.idx {
                let i = i as usize;
                self.written[i] |= i >= store.nlocal;
                if let Some(f) = self.fresh.get_mut(i) {
                    *f = true;
                }
            }
        }
    }

    /// Copies `fields` from the particles marked in `fresh` to their ghosts, which are
    /// marked in turn (they travel on in later swaps), except to the ghosts that returned
    /// their values through the same swap in [`Comm::reverse`]. A message leads with one
    /// bit per ghost of the swap saying whether its record follows.
    fn forward_fresh(&mut self, store: &mut Particles, fields: Fields) {
        let start = std::time::Instant::now();
        let me = self.t.rank();
        for (n, s) in self.swaps.iter().enumerate() {
            let fresh = &mut self.fresh;
            if s.dest == me && s.src == me {
                // every ghost copied (unchanged values are the same bits), the marks passed on
                for (k, &i) in s.send.iter().enumerate() {
                    fresh[s.recv_start + k] = fresh[i as usize];
                }
                let moves = s.send.iter().enumerate().map(|(k, &i)| (i as usize, s.recv_start + k));
                store.copy_fields(moves, fields, Some((s.dim, s.shift)));
                continue;
            }
            let returned = &self.returned[n];
            let back = |k: usize| returned.get(k / 64).is_some_and(|w| w.to_bits() >> (k % 64) & 1 == 1);
            self.slots.clear();
            self.slots.extend((0..s.send.len() as u32).filter(|&k| fresh[s.send[k as usize] as usize] && !back(k as usize)));
            self.idx.clear();
            self.idx.extend(self.slots.iter().map(|&k| s.send[k as usize]));
            lead_with_mask(&mut self.send, s.send.len(), &self.slots);
            store.pack_fields(&self.idx, fields, Some((s.dim, s.shift)), &mut self.send);
            self.traffic.sendrecv(self.t.as_ref(), &self.send, s.dest, s.src, &mut self.recv);
            let records = masked_slots(&self.recv, s.recv_count, &mut self.slots);
            self.idx.clear();
            self.idx.extend(self.slots.iter().map(|&k| s.recv_start as u32 + k));
            store.unpack_fields(&self.idx, fields, records);
            for &g in &self.idx {
                fresh[g as usize] = true;
            }
        }
        self.time.set(self.time.get() + start.elapsed());
    }
}

/// Starts message `buf` with one bit per record slot 0..n, set for the slots `travel`
/// (ascending) whose records follow.
fn lead_with_mask(buf: &mut Vec<f64>, n: usize, travel: &[u32]) {
    buf.clear();
    buf.resize(n.div_ceil(64), 0.0);
    for &k in travel {
        let w = &mut buf[k as usize / 64];
        *w = f64::from_bits(w.to_bits() | 1 << (k % 64));
    }
}

/// The slots of a [`lead_with_mask`] message of n slots that travelled, ascending, into
/// `slots`; returns the records that follow the mask.
fn masked_slots<'a>(msg: &'a [f64], n: usize, slots: &mut Vec<u32>) -> &'a [f64] {
    let (mask, records) = msg.split_at(n.div_ceil(64));
    slots.clear();
    for (w, word) in mask.iter().enumerate() {
        let mut bits = word.to_bits();
        while bits != 0 {
            slots.push((64 * w) as u32 + bits.trailing_zeros());
            bits &= bits - 1;
        }
    }
    records
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masks_carry_the_travelling_slots_and_their_records() {
        for n in [0, 1, 63, 64, 65, 200] {
            let travel: Vec<u32> = (0..n as u32).filter(|k| k % 3 == 0 || k % 7 == 1).collect();
            let mut msg = Vec::new();
            lead_with_mask(&mut msg, n, &travel);
            assert_eq!(msg.len(), n.div_ceil(64));
            msg.extend(travel.iter().map(|&k| k as f64 + 0.5));
            let mut slots = vec![7];
            let records = masked_slots(&msg, n, &mut slots);
            assert_eq!(slots, travel);
            assert_eq!(records, travel.iter().map(|&k| k as f64 + 0.5).collect::<Vec<_>>());
        }
    }
}
