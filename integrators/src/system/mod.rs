//! The simulated system: box, particles, communication and the lists built on them.

use crate::passes::barostat::state::NphState;
use crate::error::StepError;
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use gendpde_engine::cells::CellBins;
use gendpde_engine::{build_lists, dot, sub, CellGrid, Comm, Domain, ListRequest, NeighborList, Particles, SweepPairs, Vec3};

/// State that the step mutates.
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
    /// The neighbour pairs closer than the density cutoff at the last density pass, in
    /// list order: the pairs the force and work passes visit (the others, in the skin,
    /// contribute exact zeros). Emptied by a list build.
    pub active: Vec<[u32; 2]>,
    /// w'(r_ij)/([w] r_ij) of each pair of `active`, from the last density pass.
    pub pair_geometry: Vec<f64>,
    /// F_ij of each pair of `active` (f_ij = F_ij r_ij), from the last force pass.
    pub pair_force: Vec<f64>,
    /// Per-particle sums of the pair passes, or multi/lucy's table values (scratch).
    pub pair_sums: Vec<f64>,
    /// zeta_i = dn_i/dn^b_i of the owned particles at the last density pass (corrected
    /// particle volume only; empty otherwise).
    pub zeta: Vec<f64>,
    /// Friction force and random impulse of the owned particles (`fix vv/euler`, scratch
    /// within one step).
    pub friction: Vec<Vec3>,
    pub noise: Vec<Vec3>,
    /// Velocities of all particles for the work passes (scratch).
    pub velocity: Vec<Vec3>,
    /// 1/m of all particles for the sweep (scratch).
    pub inv_mass: Vec<f64>,
    pub step: u64,
    /// The first and last step of the current run (LAMMPS's beginstep, endstep), over
    /// which the thermostat pair styles ramp their temperature.
    pub run: [u64; 2],
    /// What `reset_timestep` moved the step by, summed (wrapping): the counter-based noise
    /// is keyed by [`System::noise_step`], which a reset leaves running on, so no stretch of
    /// noise repeats (kept in restart files).
    pub noise_shift: u64,
    pub time: f64,
    /// Step of the last list build.
    pub last_build: u64,
    /// Number of list builds so far.
    pub builds: u64,
    /// Pair updates split into half steps so far (theta -> 0 guard of the sweep).
    pub substeps: u64,
    /// Pair updates left out because no split could keep theta positive (`reject yes`).
    pub rejected: u64,
    /// Energy each `fix heat/reservoir` (by fix ID) has put into the particles since the
    /// fix was defined (all ranks, the same on each).
    pub reservoir_heat: Vec<(String, f64)>,
    /// The state of the `fix nph` barostat, if one is defined (kept across runs and in
    /// restart files, as LAMMPS keeps it in the fix).
    pub barostat: Option<NphState>,
    /// The particles, cells and build positions were read from a restart: the next
    /// build keeps them as stored, so the lists come out as when it was written.
    pub restored: bool,
    /// Cell counts of the grid the restored cells belong to.
    pub restored_grid: Option<[usize; 3]>,
    /// Smallest cell side the grid must have beyond the styles' own reach (outputs that
    /// search pairs farther out, e.g. `compute rdf ... cutoff`).
    pub min_cell: f64,
    /// Whether the force passes of the coming step must sum the per-particle pair
    /// energies and virials (a step after which nothing is written skips them, as
    /// LAMMPS's eflag/vflag; the run sets it before each step).
    pub tally: bool,
    /// Whether the stored per-particle energies and virials belong to the current state
    /// (false after a step that skipped them).
    pub tallied: bool,
    /// The number of a signal this rank received (set by the program's handler; 0: none).
    pub interrupt: Arc<AtomicUsize>,
    /// The largest `interrupt` of all ranks at the last `settle` (0: none): the ranks
    /// agree on it, so they stop at the same step.
    pub interrupted: Cell<usize>,
}

impl System {
    /// The step the noise of step `step` is keyed by: the step count as if no
    /// `reset_timestep` had moved the clock.
    /// `inv_mass` set to 1/m of every particle (owned and ghost), for a sweep.
    pub fn take_inverse_masses(&mut self) {
        self.inv_mass.clear();
        self.inv_mass.extend(self.store.mass.iter().map(|m| 1.0 / m));
    }

    pub fn noise_step(&self, step: u64) -> u64 {
        step.wrapping_add(self.noise_shift)
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
            pair_force: Vec::new(),
            pair_geometry: Vec::new(),
            active: Vec::new(),
            pair_sums: Vec::new(),
            zeta: Vec::new(),
            friction: Vec::new(),
            noise: Vec::new(),
            velocity: Vec::new(),
            inv_mass: Vec::new(),
            step: 0,
            run: [0, 0],
            noise_shift: 0,
            time: 0.0,
            last_build: 0,
            builds: 0,
            substeps: 0,
            rejected: 0,
            reservoir_heat: Vec::new(),
            barostat: None,
            restored: false,
            restored_grid: None,
            min_cell: 0.0,
            interrupt: Arc::default(),
            interrupted: Cell::new(0),
            tally: true,
            tallied: true,
        }
    }

    /// The energy tally of reservoir `id` (created at 0).
    pub fn reservoir_tally(&mut self, id: &str) -> &mut f64 {
        let k = match self.reservoir_heat.iter().position(|(name, _)| name == id) {
            Some(k) => k,
            None => {
                self.reservoir_heat.push((id.to_string(), 0.0));
                self.reservoir_heat.len() - 1
            }
        };
        &mut self.reservoir_heat[k].1
    }

    /// Lays the cell grid for interactions up to `cut` (cutoff plus skin) or `min_cell`,
    /// whichever is larger, with no more cells than needed ([`CellGrid::at_most`]);
    /// every rank must own at least k cells (the grid's reach, cells of side >= cut / k)
    /// along each dimension, so that its sub-domain is at least `cut` long.
    pub fn lay_grid(&mut self, cut: f64) -> Result<(), String> {
        let cut = cut.max(self.min_cell);
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
        if self.restored && self.restored_grid != Some(grid.count) {
            log::warn!(
                "the cell grid {:?} differs from the restart's {:?} (other cutoffs or skin): lists are rebuilt \
                 and the continuation is not bit-identical",
                grid.count,
                self.restored_grid
            );
            self.restored = false;
        }
        self.grid = Some(grid);
        Ok(())
    }

    /// The owned particle of lowest tag whose value in `values` is not finite and
    /// positive, as the error `what(value)` of this rank.
    pub fn check_positive(&self, values: &[f64], what: impl Fn(f64) -> String) -> Result<(), StepError> {
        let s = &self.store;
        let bad = (0..s.nlocal).filter(|&i| !(values[i] > 0.0 && values[i].is_finite())).min_by_key(|&i| s.tag[i]);
        bad.map_or(Ok(()), |i| Err(StepError::state(s, i, self.step, &what(values[i]))))
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
        let mut agreed = [outcome.as_ref().err().map_or(f64::NEG_INFINITY, key), self.interrupt.load(Ordering::Relaxed) as f64, value];
        self.comm.max_each(&mut agreed);
        if agreed[0] == f64::NEG_INFINITY {
            self.interrupted.set(agreed[1] as usize);
            return Ok(agreed[2]);
        }
        Err(StepError::agree(self.comm.transport(), outcome.err().filter(|e| key(e) == agreed[0])))
    }

    /// Migrates particles, rebuilds ghosts and bins, and the lists of the given radii;
    /// `at_step` is the step whose positions the lists are built from.
    pub fn rebuild(&mut self, density_radius: Option<f64>, sweep_radius: Option<f64>, at_step: u64) {
        let grid = self.grid.as_ref().expect("grid laid before rebuild");
        let restored = std::mem::take(&mut self.restored);
        self.comm.exchange(&mut self.store, &self.domain, grid, restored);
        let (lo, hi) = self.comm.owned_cells(grid);
        self.bins.build(&self.store.cell, &self.store.octant, &self.store.tag, grid, lo, hi);
        let req = ListRequest { nlist: density_radius.map(|r| (&mut self.nlist, r)), sweep: sweep_radius.map(|r| (&mut self.sweep, r)) };
        build_lists(&self.store, &self.bins, lo, hi, req);
        if density_radius.is_some() {
            self.active.clear();
            self.pair_geometry.clear();
            self.pair_force.clear();
        }
        if !restored {
            self.last_build = at_step;
            let s = &mut self.store;
            s.r_build[..s.nlocal].copy_from_slice(&s.r[..s.nlocal]);
        }
        self.builds += 1;
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
    step: u64,
    time: f64,
    last_build: u64,
    tallied: bool,
    /// The box and the barostat (which `fix nph` changes every step).
    domain: Option<Domain>,
    barostat: Option<NphState>,
}

impl System {
    /// Saves the owned particles and the clock into `snap` (reusing its memory).
    pub fn save(&self, snap: &mut Snapshot) {
        snap.store.copy_owned_from(&self.store);
        (snap.step, snap.time, snap.last_build, snap.tallied) = (self.step, self.time, self.last_build, self.tallied);
        snap.domain = Some(self.domain.clone());
        snap.barostat.clone_from(&self.barostat);
    }

    /// Puts back the owned particles and the clock of `snap`; ghosts and lists are
    /// dropped (the next setup rebuilds them from the saved cells).
    pub fn restore(&mut self, snap: &Snapshot) {
        self.store.copy_owned_from(&snap.store);
        (self.step, self.time, self.last_build, self.tallied) = (snap.step, snap.time, snap.last_build, snap.tallied);
        if let Some(d) = &snap.domain {
            self.domain = d.clone();
        }
        self.barostat.clone_from(&snap.barostat);
        self.restored = true;
        self.restored_grid = self.grid.as_ref().map(|g| g.count);
    }
}
