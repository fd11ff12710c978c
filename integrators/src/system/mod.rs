//! The simulated system: box, particles, communication, the lists built on them, the
//! clock, and the bookkeeping of a run (its own types in this folder).

mod clock;
mod control;
mod fix_state;

pub use self::clock::Clock;
pub use self::control::RunControl;
pub use self::fix_state::{FixRecord, FixState};
use crate::error::StepError;
use crate::passes::scratch::Scratch;
use std::sync::atomic::Ordering;
use gendpde_engine::cells::CellBins;
use gendpde_engine::{build_lists, dot, sub, CellGrid, Comm, Domain, ListRequest, NeighborList, Particles, SweepPairs};

/// State that the step mutates: the box, the particles, the communication, the spatial
/// structures built on them, the clock, and the run's bookkeeping.
pub struct System {
    pub domain: Domain,
    pub store: Particles,
    pub comm: Comm,
    pub grid: Option<CellGrid>,
    pub bins: CellBins,
    /// Full neighbour lists for the density and force passes.
    pub nlist: NeighborList,
    /// Coloured pair lists for the Shardlow sweep.
    pub sweep: SweepPairs,
    pub clock: Clock,
    /// When and how often the lists were built, and the reach they need.
    pub lists: ListLog,
    /// The passes' per-pair and per-particle scratch.
    pub scratch: Scratch,
    /// What the run loop and the restore tell the step, and what the step reports back.
    pub control: RunControl,
    /// The accumulated state of fixes (reservoir tallies, barostats), by fix ID.
    pub fixes: FixState,
}

/// The list builds of a run and the reach the lists and cells need.
#[derive(Clone, Debug, Default)]
pub struct ListLog {
    /// Step of the last list build.
    pub last: u64,
    /// Number of list builds so far.
    pub count: u64,
    /// Builds the displacement check asked for at the first step it could (LAMMPS's
    /// dangerous builds: a particle may have moved too far before).
    pub dangerous: u64,
    /// Smallest cell side the grid must have beyond the styles' own reach (outputs that
    /// search pairs farther out, e.g. `compute rdf ... cutoff`).
    pub min_cell: f64,
    /// The interaction cutoff of the run's model ([`crate::Physics::cutoff`]).
    pub cutoff: f64,
}

impl System {
    /// `inv_mass` set to 1/m of every particle (owned and ghost), for a sweep.
    pub fn take_inverse_masses(&mut self) {
        self.scratch.inv_mass.clear();
        self.scratch.inv_mass.extend(self.store.mass.iter().map(|m| 1.0 / m));
    }

    /// The step the noise of step `step` is keyed by ([`Clock::noise_step`]).
    pub fn noise_step(&self, step: u64) -> u64 {
        self.clock.noise_step(step)
    }

    pub fn new(domain: Domain, comm: Comm) -> Self {
        Self {
            domain,
            store: Particles::default(),
            comm,
            grid: None,
            bins: CellBins::default(),
            nlist: NeighborList::default(),
            sweep: SweepPairs::default(),
            clock: Clock::default(),
            lists: ListLog::default(),
            scratch: Scratch::default(),
            control: RunControl::default(),
            fixes: FixState::default(),
        }
    }

    /// Lays the cell grid for interactions up to `cut` (cutoff plus skin) or `min_cell`,
    /// whichever is larger, with no more cells than needed ([`CellGrid::at_most`]);
    /// every rank must own at least k cells (the grid's reach, cells of side >= cut / k)
    /// along each dimension, so that its sub-domain is at least `cut` long.
    pub fn lay_grid(&mut self, cut: f64) -> Result<(), String> {
        let cut = cut.max(self.lists.min_cell);
        let particles = self.comm.count(self.store.nlocal) as usize;
        let grid = CellGrid::new(&self.domain, cut).map_err(|e| e.to_string())?.at_most(particles);
        let procs = self.comm.grid.dims;
        let k = grid.reach;
        for d in 0..3 {
            if grid.count[d] / procs[d] < k {
                let axis = ["x", "y", "z"][d];
                return Err(format!(
                    "{} ranks along {axis} need at least {} cells of side cutoff + skin = {cut:.6}{}, the box holds {}: \
                     use at most {} ranks along {axis} (processors command) or a box of length >= {:.6}",
                    procs[d],
                    procs[d] * k,
                    if k > 1 { format!(" / {k}") } else { String::new() },
                    grid.count[d],
                    grid.count[d] / k,
                    (procs[d].div_ceil(2) * 2) as f64 * cut
                ));
            }
        }
        if self.control.restored && self.control.restored_grid != Some(grid.count) {
            log::warn!(
                "the cell grid {:?} differs from the restart's {:?} (other cutoffs or skin): lists are rebuilt \
                 and the continuation is not bit-identical",
                grid.count,
                self.control.restored_grid
            );
            self.control.restored = false;
        }
        self.grid = Some(grid);
        Ok(())
    }

    /// The owned particle of lowest tag whose value in `values` is not finite and
    /// positive, as the error `what(value)` of this rank.
    pub fn check_positive(&self, values: &[f64], what: impl Fn(f64) -> String) -> Result<(), StepError> {
        let s = &self.store;
        let bad = (0..s.nlocal).filter(|&i| !(values[i] > 0.0 && values[i].is_finite())).min_by_key(|&i| s.tag[i]);
        bad.map_or(Ok(()), |i| Err(StepError::state(s, i, self.clock.step, &what(values[i]))))
    }

    /// Agrees over all ranks whether the step failed: if any did, every rank returns the
    /// same error, that of the failing particle of lowest tag. The same reduction agrees
    /// on `interrupted` (the largest signal number any rank received).
    pub fn settle(&self, outcome: Result<(), StepError>) -> Result<(), StepError> {
        self.settle_with(outcome, 0.0).map(|_| ())
    }

    /// [`System::settle`] that also returns the largest `value` over all ranks, found in
    /// the same reduction.
    pub fn settle_with(&self, outcome: Result<(), StepError>, value: f64) -> Result<f64, StepError> {
        // tags are exact in f64 below 2^53
        let key = |e: &StepError| -(e.tag as f64);
        let mut agreed = [outcome.as_ref().err().map_or(f64::NEG_INFINITY, key), self.control.interrupt.load(Ordering::Relaxed) as f64, value];
        self.comm.max_each(&mut agreed);
        if agreed[0] == f64::NEG_INFINITY {
            self.control.interrupted.set(agreed[1] as usize);
            return Ok(agreed[2]);
        }
        Err(StepError::agree(self.comm.transport(), outcome.err().filter(|e| key(e) == agreed[0])))
    }

    /// Migrates particles, rebuilds ghosts and bins, and the lists of the given radii;
    /// `at_step` is the step whose positions the lists are built from.
    pub fn rebuild(&mut self, density_radius: Option<f64>, sweep_radius: Option<f64>, at_step: u64) {
        let grid = self.grid.as_ref().expect("grid laid before rebuild");
        let restored = std::mem::take(&mut self.control.restored);
        self.comm.exchange(&mut self.store, &self.domain, grid, restored);
        let (lo, hi) = self.comm.owned_cells(grid);
        self.bins.build(&self.store.cell, &self.store.octant, &self.store.tag, grid, lo, hi);
        let req = ListRequest { nlist: density_radius.map(|r| (&mut self.nlist, r)), sweep: sweep_radius.map(|r| (&mut self.sweep, r)) };
        build_lists(&self.store, &self.bins, lo, hi, req);
        if density_radius.is_some() {
            self.scratch.active.clear();
            self.scratch.pair_geometry.clear();
            self.scratch.pair_force.clear();
        }
        if !restored {
            self.lists.last = at_step;
            let s = &mut self.store;
            s.r_build[..s.nlocal].copy_from_slice(&s.r[..s.nlocal]);
        }
        self.lists.count += 1;
    }
}

impl System {
    /// Largest displacement of an owned particle since the last list build (this rank).
    pub fn displacement_since_build(&self) -> f64 {
        let s = &self.store;
        let mut m: f64 = 0.0;
        for (r, r0) in s.r[..s.nlocal].iter().zip(&s.r_build[..s.nlocal]) {
            let d = sub(*r, *r0);
            m = m.max(dot(d, d));
        }
        m.sqrt()
    }
}

/// The owned particles of one step, kept so a failed step can be undone and written out.
#[derive(Clone, Debug, Default)]
pub struct Snapshot {
    store: Particles,
    clock: Clock,
    last_build: u64,
    tallied: bool,
    /// The box and the fixes' states (`fix nph` changes both every step).
    domain: Option<Domain>,
    fixes: FixState,
}

impl System {
    /// Saves the owned particles, the clock and the fixes' states into `snap` (reusing
    /// its memory).
    pub fn save(&self, snap: &mut Snapshot) {
        snap.store.copy_owned_from(&self.store);
        snap.clock.clone_from(&self.clock);
        (snap.last_build, snap.tallied) = (self.lists.last, self.control.tallied);
        snap.domain = Some(self.domain.clone());
        snap.fixes.clone_from(&self.fixes);
    }

    /// Puts back the owned particles, the clock and the fixes' states of `snap`; ghosts
    /// and lists are dropped (the next setup rebuilds them from the saved cells).
    pub fn restore(&mut self, snap: &Snapshot) {
        self.store.copy_owned_from(&snap.store);
        self.clock.clone_from(&snap.clock);
        (self.lists.last, self.control.tallied) = (snap.last_build, snap.tallied);
        if let Some(d) = &snap.domain {
            self.domain = d.clone();
        }
        self.fixes.clone_from(&snap.fixes);
        self.control.restored = true;
        self.control.restored_grid = self.grid.as_ref().map(|g| g.count);
    }
}
