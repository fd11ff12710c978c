//! What a scene switches on: the fixes and their parameters, as the step reads them.

use crate::heat::HeatModel;

/// `fix shardlow`: friction, momentum noise and pair heat flow (eqs 65-81).
#[derive(Clone, Debug, PartialEq)]
pub struct Dissipation {
    /// Friction amplitude gamma (eq 66) and its cutoff R^D_cut.
    pub gamma: f64,
    pub rc_friction: f64,
    /// Heat-conduction amplitude kappa (eq 71) and its cutoff.
    pub kappa: f64,
    pub rc_heat: f64,
    pub heat: HeatModel,
    pub seed: u64,
    /// Levels of halving a pair update may use when a temperature would turn
    /// non-positive (0: stop at once; 4: down to dt/16).
    pub substeps: u32,
    /// Leave a pair that fails at the last level unchanged for the step instead of
    /// stopping the run.
    pub reject: bool,
}

impl Dissipation {
    /// Largest cutoff of the sweep.
    pub fn cutoff(&self) -> f64 {
        let f = if self.gamma > 0.0 { self.rc_friction } else { 0.0 };
        let h = if self.kappa > 0.0 { self.rc_heat } else { 0.0 };
        f.max(h)
    }
}

/// `fix heat/reservoir`: every particle exchanges heat with a bath at T (eq 72).
#[derive(Clone, Debug, PartialEq)]
pub struct Reservoir {
    pub temperature: f64,
    pub kappa: f64,
    pub heat: HeatModel,
    pub seed: u64,
}

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

/// Everything the integrator needs besides the EOS and the weight.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    pub dt: f64,
    pub skin: f64,
    pub rebuild: RebuildPolicy,
    /// `fix nve/gendpde`: the reversible step moves the particles; without it they stay fixed.
    pub verlet: bool,
    pub dissipation: Option<Dissipation>,
    pub reservoir: Option<Reservoir>,
}
