//! The model a script builds: box, particles, styles and run settings.

use crate::lattice::{Block, Lattice};
use crate::styles::{Fix, PairGendpde};
use crate::thermo::ThermoConfig;
use gendpde_integrators::{RebuildPolicy, System};
use gendpde_io::AtomStyle;
use std::collections::HashMap;

/// Everything the commands of a script have defined so far.
pub struct Sim {
    pub lattice: Option<Lattice>,
    pub regions: HashMap<String, Block>,
    pub ntypes: usize,
    /// Mass of each type (index type - 1).
    pub masses: Vec<Option<f64>>,
    pub system: Option<System>,
    pub pair: Option<PairGendpde>,
    pub fixes: Vec<Fix>,
    pub dt: f64,
    pub skin: f64,
    pub rebuild: RebuildPolicy,
    pub thermo: ThermoConfig,
    /// Total energy at the first setup, for `edrift`.
    pub energy0: Option<f64>,
    /// Largest tag handed out.
    pub max_tag: u64,
    /// Ranks per dimension fixed by `processors` (None: chosen to minimise surface).
    pub procs: [Option<usize>; 3],
    /// Column layout of data files (`atom_style dpd` or `gendpde`: with dpdTheta).
    pub atom_style: AtomStyle,
}

impl Default for Sim {
    /// LAMMPS's lj-unit defaults: timestep 0.005, skin 0.3.
    fn default() -> Self {
        Self {
            lattice: None,
            regions: HashMap::new(),
            ntypes: 0,
            masses: Vec::new(),
            system: None,
            pair: None,
            fixes: Vec::new(),
            dt: 0.005,
            skin: 0.3,
            rebuild: RebuildPolicy::default(),
            thermo: ThermoConfig::default(),
            energy0: None,
            max_tag: 0,
            procs: [None; 3],
            atom_style: AtomStyle::Atomic,
        }
    }
}
