//! What every model's step reads: the time step, the neighbour skin and LAMMPS's list
//! rebuild rule.

/// LAMMPS `neigh_modify every N delay M check yes|no`.
#[derive(Clone, Debug, PartialEq)]
pub struct RebuildPolicy {
    pub every: u64,
    pub delay: u64,
    pub check: bool,
}

impl Default for RebuildPolicy {
    fn default() -> Self {
        Self { every: 1, delay: 0, check: true }
    }
}

/// The run settings every model takes (its own parameters are its own fields).
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    pub dt: f64,
    pub skin: f64,
    pub rebuild: RebuildPolicy,
}
