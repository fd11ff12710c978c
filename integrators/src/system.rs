//! The simulated system: box, particles, communication and the lists built on them.

use crate::error::StepError;
use gendpde_engine::cells::CellBins;
use gendpde_engine::{dot, sub, CellGrid, Comm, Domain, NeighborList, Particles, SweepPairs, Vec3};

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
    /// F_ij of each neighbour-list entry (f_ij = F_ij r_ij).
    pub pair_force: Vec<f64>,
    /// w'(r_ij)/([w] r_ij) of each neighbour-list entry, from the last force pass.
    pub pair_geometry: Vec<f64>,
    pub step: u64,
    pub time: f64,
    /// Step of the last list build.
    pub last_build: u64,
    /// Number of list builds so far.
    pub builds: u64,
    /// Owned positions at the last list build.
    r_at_build: Vec<Vec3>,
}

impl System {
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
            step: 0,
            time: 0.0,
            last_build: 0,
            builds: 0,
            r_at_build: Vec::new(),
        }
    }

    /// Lays the cell grid for interactions up to `cut` (cutoff plus skin); every rank
    /// must own at least one cell along each dimension.
    pub fn lay_grid(&mut self, cut: f64) -> Result<(), String> {
        let grid = CellGrid::new(&self.domain, cut).map_err(|e| e.to_string())?;
        let procs = self.comm.grid.dims;
        for d in 0..3 {
            if grid.count[d] < procs[d] {
                let axis = ["x", "y", "z"][d];
                return Err(format!(
                    "{} ranks along {axis} need at least {} cells of side cutoff + skin = {cut:.6}, the box holds {}: \
                     use at most {} ranks along {axis} (processors command) or a box of length >= {:.6}",
                    procs[d],
                    procs[d],
                    grid.count[d],
                    grid.count[d],
                    (procs[d].div_ceil(2) * 2).max(4) as f64 * cut
                ));
            }
        }
        self.grid = Some(grid);
        Ok(())
    }

    /// Agrees over all ranks whether the step failed: Err on every rank if any failed.
    pub fn settle(&self, outcome: Result<(), StepError>) -> Result<(), StepError> {
        if self.comm.any(outcome.is_err()) {
            Err(outcome.err().unwrap_or_else(|| StepError::elsewhere(self.step)))
        } else {
            Ok(())
        }
    }

    /// Migrates particles, rebuilds ghosts and bins, and the lists of the given radii;
    /// `at_step` is the step whose positions the lists are built from.
    pub fn rebuild(&mut self, density_radius: Option<f64>, sweep_radius: Option<f64>, at_step: u64) {
        let grid = self.grid.as_ref().expect("grid laid before rebuild");
        self.comm.exchange(&mut self.store, &self.domain, grid);
        let (lo, hi) = self.comm.owned_cells(grid);
        self.bins.build(&self.store.cell, lo, hi);
        if let Some(radius) = density_radius {
            self.nlist.build(&self.store, &self.bins, radius);
            self.pair_force.resize(self.nlist.neighbors.len(), 0.0);
            self.pair_geometry.resize(self.nlist.neighbors.len(), 0.0);
        }
        if let Some(radius) = sweep_radius {
            self.sweep.build(&self.store, &self.bins, lo, hi, radius);
        }
        self.last_build = at_step;
        self.builds += 1;
        self.r_at_build.clear();
        self.r_at_build.extend_from_slice(&self.store.r[..self.store.nlocal]);
    }
}

impl System {
    /// Largest displacement of an owned particle since the last list build (this rank).
    pub fn displacement_since_build(&self) -> f64 {
        if self.r_at_build.len() != self.store.nlocal {
            return f64::INFINITY;
        }
        let mut m: f64 = 0.0;
        for (r, r0) in self.store.r[..self.store.nlocal].iter().zip(&self.r_at_build) {
            let d = sub(*r, *r0);
            m = m.max(dot(d, d));
        }
        m.sqrt()
    }
}
