//! The simulated system: box, particles, communication and the lists built on them.

use gendpde_engine::cells::CellBins;
use gendpde_engine::{dot, sub, CellGrid, Comm, Domain, GridError, NeighborList, Particles, SweepPairs, Vec3};

/// State that the step mutates.
pub struct System {
    pub domain: Domain,
    pub store: Particles,
    pub comm: Box<dyn Comm>,
    pub grid: Option<CellGrid>,
    pub bins: CellBins,
    /// Full neighbour lists for the density and force passes.
    pub nlist: NeighborList,
    /// Coloured pair lists for the Shardlow sweep.
    pub sweep: SweepPairs,
    /// F_ij of each neighbour-list entry (f_ij = F_ij r_ij), from the last force pass.
    pub pair_force: Vec<f64>,
    /// This rank's sum over pairs i<j of r_ij . f^C_ij (eq 52), from the last force pass.
    pub virial: f64,
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
    pub fn new(domain: Domain, comm: Box<dyn Comm>) -> Self {
        Self {
            domain,
            store: Particles::default(),
            comm,
            grid: None,
            bins: CellBins::default(),
            nlist: NeighborList::default(),
            sweep: SweepPairs::default(),
            pair_force: Vec::new(),
            virial: 0.0,
            step: 0,
            time: 0.0,
            last_build: 0,
            builds: 0,
            r_at_build: Vec::new(),
        }
    }

    /// Lays the cell grid for interactions up to `cut` (cutoff plus skin).
    pub fn lay_grid(&mut self, cut: f64) -> Result<(), GridError> {
        self.grid = Some(CellGrid::new(&self.domain, cut)?);
        Ok(())
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
