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
pub use transport::{Local, Received, Transport};

use crate::{CellGrid, Domain, Fields, Particles, SweepPairs, Vec3};

/// One exchange of the ghost layer with a neighbour, recorded for forward and reverse
/// communication.
#[derive(Clone, Debug)]
struct Swap {
    dim: usize,
    /// Whether the ghosts it creates lie above the receiver's sub-domain along `dim`
    /// (it sends the lowest cell layers down). The sweep reads and writes only the
    /// ghosts made by such swaps alone: its blocks C + {0..k}^3 start at owned cells C.
    upper: bool,
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
    recv: Received,
    written: Vec<bool>,
    /// Ghosts below the sub-domain along some dimension (made by a swap that is not
    /// `upper`, or sent on from such a ghost): no sweep colour reads them.
    lower: Vec<bool>,
    /// Particles whose new values go to their ghosts in [`Comm::after_colour`].
    fresh: Vec<bool>,
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

/// Point-to-point messages this rank sent to other ranks, their f64 values, and the
/// rounds they travelled in (one or two exchanges at once: a rank waits once a round).
#[derive(Default)]
struct Traffic {
    messages: u64,
    values: u64,
    rounds: u64,
}

/// What a forward exchange sends: every ghost's record, or those of the particles a
/// sweep colour may have changed ([`Comm::after_colour`]).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Travel {
    Every,
    Fresh,
}

impl Traffic {
    /// Sends `send` to `dest` and receives `src`'s buffer into `recv`, counted.
    fn sendrecv(&mut self, t: &dyn Transport, send: &[f64], dest: usize, src: usize, recv: &mut Received) {
        if dest != t.rank() {
            self.messages += 1;
            self.values += send.len() as u64;
            self.rounds += 1;
        }
        t.sendrecv(send, dest, src, recv);
    }

    /// [`Transport::sendrecv2`], counted.
    fn sendrecv2(&mut self, t: &dyn Transport, send: &[f64], split: usize, dest: [usize; 2], src: [usize; 2], recv: &mut Received) -> usize {
        for (d, part) in dest.into_iter().zip([&send[..split], &send[split..]]) {
            if d != t.rank() {
                self.messages += 1;
                self.values += part.len() as u64;
            }
        }
        self.rounds += dest.iter().any(|&d| d != t.rank()) as u64;
        t.sendrecv2(send, split, dest, src, recv)
    }

    /// One round of one or two exchanges, each a (dest, src) route: `send[..split]` goes
    /// the `first` route, the rest the `second`; returns where the second part of `recv`
    /// begins.
    fn round(&mut self, t: &dyn Transport, send: &[f64], split: usize, first: (usize, usize), second: Option<(usize, usize)>, recv: &mut Received) -> usize {
        match second {
            None => {
                self.sendrecv(t, send, first.0, first.1, recv);
                recv.len()
            }
            Some((d1, s1)) => self.sendrecv2(t, send, split, [first.0, d1], [first.1, s1], recv),
        }
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
            recv: Received::default(),
            written: Vec::new(),
            lower: Vec::new(),
            fresh: Vec::new(),
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

    /// Point-to-point messages sent to other ranks so far, their bytes, and the rounds
    /// they travelled in.
    pub fn traffic(&self) -> (u64, u64, u64) {
        (self.traffic.messages, 8 * self.traffic.values, self.traffic.rounds)
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

    /// The ranks, given back (for a new box on them: LAMMPS's `clear`).
    pub fn into_transport(self) -> Box<dyn Transport> {
        self.t
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
        let mut keyed: Vec<(u128, u32)> = (0..store.nlocal).map(|i| (order_key(store.cell[i], store.tag[i]), i as u32)).collect();
        keyed.sort_unstable_by_key(|&(key, _)| key);
        let order: Vec<u32> = keyed.iter().map(|&(_, i)| i).collect();
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
                store.unpack_ghosts(&self.recv, layout.width);
                let recv_count = store.len() - recv_start;
                self.swaps.push(Swap { dim: d, upper: dir == -1, shift, dest, src, send, recv_start, recv_count });
            }
        }
        let lo = self.lo;
        self.lower.clear();
        self.lower.extend(store.cell.iter().map(|c| (0..3).any(|d| c[d] < lo[d])));
    }

    /// Copies `fields` from the owners to all their ghosts.
    pub fn forward(&mut self, store: &mut Particles, fields: Fields) {
        let start = std::time::Instant::now();
        self.forward_rounds(store, fields, true, 0, Travel::Every);
        self.time.set(self.time.get() + start.elapsed());
    }

    /// The swaps that travel in one round from remote swap `n` on: with `lower`, the two
    /// of its dimension (neither sends a ghost the other receives: the layers they send
    /// lie inside the sub-domain along it), else swap `n` alone.
    fn together(&self, n: usize, lower: bool) -> std::ops::Range<usize> {
        let pair = lower && self.swaps[n].upper && self.swaps.get(n + 1).is_some_and(|s| s.dim == self.swaps[n].dim);
        n..n + 1 + pair as usize
    }

    /// The (dest, src) of swap `n`'s forward exchange.
    fn route(&self, n: usize) -> (usize, usize) {
        (self.swaps[n].dest, self.swaps[n].src)
    }

    /// After colour `colour` of a sweep wrote `fields` of the particles of its pairs: the
    /// ghosts written return their values to their owners, then every particle the colour
    /// may have touched (owned and in its pairs, or reached by a returning ghost) forwards
    /// its values to its ghosts above the sub-domain (the only ones a colour reads or
    /// writes), but not to the ghosts that returned them (they hold them). Ghosts of
    /// particles outside the colour's pairs keep theirs, which are current, so they do not
    /// travel (particles of its pairs whose partners all lay beyond the cutoff forward
    /// values unchanged: the list build marks them, [`SweepPairs::members`]). The ghosts
    /// below the sub-domain (`lower`) are brought up to date after the last colour only,
    /// all of them: after a sweep every ghost holds its owner's values, and no message
    /// travels through the swaps that make them between colours.
    /// When the first swap (along x, the last of the reverse and the first of the
    /// forward) goes to another rank, its two exchanges travel as one ([`Comm::merged`]).
    /// On one rank every swap is a copy, and all ghosts above (after the last colour: all
    /// ghosts) are copied (marking costs more than it saves).
    pub fn after_colour(&mut self, store: &mut Particles, sweep: &SweepPairs, colour: usize, fields: Fields) {
        let start = std::time::Instant::now();
        let last = colour + 1 == sweep.colours();
        let me = self.t.rank();
        let remote = self.swaps.iter().any(|s| s.dest != me || s.src != me);
        if !remote {
            self.fresh.clear();
            self.reverse(store, &sweep.ghost_writes[colour], fields, 0);
            self.forward_rounds(store, fields, last, 0, Travel::Every);
            self.time.set(self.time.get() + start.elapsed());
            return;
        }
        self.fresh.clear();
        self.fresh.extend_from_slice(&sweep.members[colour]);
        let merge = self.swaps.first().is_some_and(|s| s.upper && (s.dest != me || s.src != me));
        self.reverse(store, &sweep.ghost_writes[colour], fields, merge as usize);
        if merge {
            self.merged(store, fields, last);
        }
        self.forward_rounds(store, fields, last, merge as usize, Travel::Fresh);
        self.time.set(self.time.get() + start.elapsed());
    }

    /// [`Comm::after_colour`] without its forward: the ghosts written return their values
    /// to their owners, whose ghosts keep the old ones (those below the sub-domain: the
    /// ones from before the sweep) until a [`Comm::forward`] of `fields` (the last colour
    /// of a sweep, when nothing reads them before).
    pub fn reverse_colour(&mut self, store: &mut Particles, sweep: &SweepPairs, colour: usize, fields: Fields) {
        let start = std::time::Instant::now();
        self.fresh.clear();
        self.reverse(store, &sweep.ghost_writes[colour], fields, 0);
        self.time.set(self.time.get() + start.elapsed());
    }

    /// Copies `fields` of the listed ghosts back to their owners (values, not deltas; a
    /// message leads with one bit per ghost of the swap saying whether its record
    /// follows, kept in `returned`), marking the owners reached in `fresh` (when it is in
    /// use), through the swaps from the last down to swap `first`. Within one colour of
    /// the sweep each particle has exactly one writer, so only the ghosts written travel
    /// back, hop by hop through the swaps in reverse order; the ghosts written lie above
    /// the sub-domain, so nothing travels through the swaps that are not `upper`, and no
    /// message is sent there.
    fn reverse(&mut self, store: &mut Particles, ghosts: &[u32], fields: Fields, first: usize) {
        let fields = fields.without(Fields::POSITION);
        self.written.clear();
        self.written.resize(store.len(), false);
        for &g in ghosts {
            debug_assert!(!self.lower[g as usize], "a sweep colour wrote a ghost below the sub-domain");
            self.written[g as usize] = true;
        }
        self.returned.resize_with(self.swaps.len(), Vec::new);
        let me = self.t.rank();
        for n in (first..self.swaps.len()).rev() {
            let s = &self.swaps[n];
            if !s.upper {
                continue;
            }
            if s.dest == me && s.src == me {
                let written = &self.written;
                let moves = (0..s.recv_count).filter(|&k| written[s.recv_start + k]).map(|k| (s.recv_start + k, s.send[k] as usize));
                store.copy_fields(moves, fields);
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
            let (dest, src) = (s.dest, s.src);
            self.send.clear();
            self.pack_reverse(store, n, fields);
            self.traffic.sendrecv(self.t.as_ref(), &self.send, src, dest, &mut self.recv);
            self.unpack_reverse(store, n, fields, 0..self.recv.len());
        }
    }

    /// Swap 0's reverse and forward exchanges after a colour as one round: its forward
    /// sends the owned particles marked in `fresh` before its reverse, and the owners its
    /// reverse reaches returned their values through it, so they are not among them
    /// (each particle has one writer a colour).
    fn merged(&mut self, store: &mut Particles, fields: Fields, lower: bool) {
        let reverse_fields = fields.without(Fields::POSITION);
        let (dest, src) = (self.swaps[0].dest, self.swaps[0].src);
        self.send.clear();
        self.pack_reverse(store, 0, reverse_fields);
        let split = self.send.len();
        // no ghost of swap 0 returned anything yet this colour
        self.returned[0].clear();
        self.pack_forward(store, 0, fields, lower, Travel::Fresh);
        let at = self.traffic.round(self.t.as_ref(), &self.send, split, (src, dest), Some((dest, src)), &mut self.recv);
        self.unpack_reverse(store, 0, reverse_fields, 0..at);
        self.unpack_forward(store, 0, fields, at..self.recv.len(), Travel::Fresh);
    }

    /// Appends swap `n`'s reverse message to `send`: one bit per ghost of the swap, set
    /// for the ghosts written, then their records.
    fn pack_reverse(&mut self, store: &Particles, n: usize, fields: Fields) {
        let s = &self.swaps[n];
        self.slots.clear();
        self.slots.extend((0..s.recv_count as u32).filter(|&k| self.written[s.recv_start + k as usize]));
        self.idx.clear();
        self.idx.extend(self.slots.iter().map(|&k| s.recv_start as u32 + k));
        lead_with_mask(&mut self.send, s.recv_count, &self.slots);
        store.pack_fields(&self.idx, fields, None, &mut self.send);
    }

    /// Reads swap `n`'s reverse message, `recv[at]`, into the owners (or the ghosts of
    /// earlier swaps) its ghosts were sent from, and marks them; keeps its mask in
    /// `returned`.
    fn unpack_reverse(&mut self, store: &mut Particles, n: usize, fields: Fields, at: std::ops::Range<usize>) {
        let s = &self.swaps[n];
        let msg = &self.recv[at];
        let records = masked_slots(msg, s.send.len(), &mut self.slots);
        self.returned[n].clear();
        self.returned[n].extend_from_slice(&msg[..msg.len() - records.len()]);
        self.idx.clear();
        self.idx.extend(self.slots.iter().map(|&k| s.send[k as usize]));
        store.unpack_fields(self.idx.iter().map(|&i| i as usize), fields, records);
        for &i in &self.idx {
            let i = i as usize;
            self.written[i] |= i >= store.nlocal;
            if let Some(f) = self.fresh.get_mut(i) {
                *f = true;
            }
        }
    }

    /// Copies `fields` from owners to their ghosts through the swaps from swap `first` on:
    /// every swap, or (not `lower`) the `upper` ones only (to the ghosts a sweep colour
    /// reads). With [`Travel::Fresh`] only the particles marked in `fresh` travel through
    /// `upper` swaps, and the ghosts reached are marked in turn (they travel on in later
    /// swaps), except to the ghosts that returned their values through the same swap in
    /// [`Comm::reverse`]. A dimension's two swaps travel in one round when both do.
    fn forward_rounds(&mut self, store: &mut Particles, fields: Fields, lower: bool, first: usize, travel: Travel) {
        let me = self.t.rank();
        let mut n = first;
        while n < self.swaps.len() {
            let s = &self.swaps[n];
            if !(lower || s.upper) {
                n += 1;
                continue;
            }
            if s.dest == me && s.src == me {
                // every ghost copied (unchanged values are the same bits), the marks passed on
                if travel == Travel::Fresh {
                    for (k, &i) in s.send.iter().enumerate() {
                        self.fresh[s.recv_start + k] = self.fresh[i as usize];
                    }
                }
                store.copy_to_ghosts(&s.send, s.recv_start, fields, (s.dim, s.shift));
                n += 1;
                continue;
            }
            let swaps = self.together(n, lower);
            self.send.clear();
            let mut split = 0;
            for m in swaps.clone() {
                self.pack_forward(store, m, fields, lower, travel);
                split = if m == n { self.send.len() } else { split };
            }
            let second = (swaps.len() == 2).then(|| self.route(n + 1));
            let at = self.traffic.round(self.t.as_ref(), &self.send, split, self.route(n), second, &mut self.recv);
            for (m, part) in swaps.clone().zip([0..at, at..self.recv.len()]) {
                self.unpack_forward(store, m, fields, part, travel);
            }
            n = swaps.end;
        }
    }

    /// Appends swap `n`'s forward message to `send`. [`Travel::Every`]: the records of
    /// every particle the swap sends. [`Travel::Fresh`]: one bit per particle the swap
    /// sends, set for those that travel ([`Comm::forward_rounds`]), then their records.
    fn pack_forward(&mut self, store: &Particles, n: usize, fields: Fields, lower: bool, travel: Travel) {
        let s = &self.swaps[n];
        if travel == Travel::Every {
            store.pack_fields(&s.send, fields, Some((s.dim, s.shift)), &mut self.send);
            return;
        }
        let (fresh, returned, below) = (&self.fresh, &self.returned[n], &self.lower);
        // the mask of [`lead_with_mask`] a word (64 slots) at a time, with the particles
        // that travel
        self.idx.clear();
        for (w, slots) in s.send.chunks(64).enumerate() {
            let back = returned.get(w).map_or(0, |x| x.to_bits());
            let mut bits = 0u64;
            for (b, &i) in slots.iter().enumerate() {
                let travels = !s.upper || (fresh[i as usize] && back >> b & 1 == 0) || (lower && below[i as usize]);
                if travels {
                    bits |= 1 << b;
                    self.idx.push(i);
                }
            }
            self.send.push(f64::from_bits(bits));
        }
        store.pack_fields(&self.idx, fields, Some((s.dim, s.shift)), &mut self.send);
    }

    /// Reads swap `n`'s forward message, `recv[at]`, into its ghosts ([`Travel::Fresh`]:
    /// those that travelled, which are marked).
    fn unpack_forward(&mut self, store: &mut Particles, n: usize, fields: Fields, at: std::ops::Range<usize>, travel: Travel) {
        let s = &self.swaps[n];
        if travel == Travel::Every {
            store.unpack_fields(s.recv_start..s.recv_start + s.recv_count, fields, &self.recv[at]);
            return;
        }
        let records = masked_slots(&self.recv[at], s.recv_count, &mut self.slots);
        let ghosts = self.slots.iter().map(|&k| s.recv_start + k as usize);
        store.unpack_fields(ghosts.clone(), fields, records);
        for g in ghosts {
            self.fresh[g] = true;
        }
    }
}

/// Appends to message `buf` one bit per record slot 0..n, set for the slots `travel`
/// (ascending) whose records follow.
fn lead_with_mask(buf: &mut Vec<f64>, n: usize, travel: &[u32]) {
    let start = buf.len();
    buf.resize(start + n.div_ceil(64), 0.0);
    for &k in travel {
        let w = &mut buf[start + k as usize / 64];
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

/// The owned particles' order: by cell (z, then y, then x), then by tag, packed into one
/// integer so that the sort compares plain numbers (each coordinate biased into 21 bits:
/// cell indices lie well within +-2^20).
#[inline]
fn order_key(c: [i32; 3], tag: u64) -> u128 {
    const BIAS: i64 = 1 << 20;
    let bits = |x: i32| {
        debug_assert!((-BIAS..BIAS).contains(&(x as i64)), "cell index {x} beyond the order key");
        (x as i64 + BIAS) as u128
    };
    (((bits(c[2]) << 42) | (bits(c[1]) << 21) | bits(c[0])) << 64) | tag as u128
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

    /// The packed order key sorts as the tuple (z, y, x, tag) it stands for.
    #[test]
    fn order_key_sorts_as_cell_then_tag() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let mut items: Vec<([i32; 3], u64)> = (0..5000)
            .map(|_| {
                let c = [0, 1, 2].map(|_| [-3, -1, 0, 1, 2, 5, 1000, (1 << 20) - 1, -(1 << 20)][(next() % 9) as usize]);
                (c, [0, 1, 7, u64::MAX, next()][(next() % 5) as usize])
            })
            .collect();
        items.sort_unstable_by_key(|&(c, tag)| order_key(c, tag));
        assert!(items.windows(2).all(|w| (w[0].0[2], w[0].0[1], w[0].0[0], w[0].1) <= (w[1].0[2], w[1].0[1], w[1].0[0], w[1].1)));
    }
}
