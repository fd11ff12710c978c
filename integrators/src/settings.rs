//! What a scene switches on: the fixes and their parameters, as the step reads them.

use crate::passes::heat::HeatModel;
use crate::passes::noise::NoiseForm;

/// Friction, momentum noise and pair heat flow (eqs 65-81), applied by `fix shardlow`'s
/// sweep or by `fix vv/euler`'s pair forces.
#[derive(Clone, Debug, PartialEq)]
pub struct Dissipation {
    /// Friction amplitude gamma (eq 66) and its cutoff R^D_cut.
    pub gamma: f64,
    pub rc_friction: f64,
    /// Heat-conduction amplitude kappa (eq 71) and its cutoff.
    pub kappa: f64,
    pub rc_heat: f64,
    pub heat: HeatModel,
    /// Momentum friction and noise law of the sweep (`fix shardlow ... noise`).
    pub noise: NoiseForm,
    pub seed: u64,
    /// Levels of halving a sweep pair update may use when a temperature would turn
    /// non-positive (0: stop at once; 4: down to dt/16).
    pub substeps: u32,
    /// Leave a sweep pair that fails at the last level unchanged for the step instead of
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

/// `fix heat/reservoir`: every particle of a group exchanges heat with a bath at T
/// (2019 eq 72; 2021 text after eq 62).
#[derive(Clone, Debug, PartialEq)]
pub struct Reservoir {
    /// The fix ID: the key of the reservoir's energy tally ([`crate::System::reservoir_heat`]).
    pub id: String,
    /// Group bit mask of the particles it couples (all bits: group all).
    pub mask: u32,
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

/// How the particles move.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// No integrator fix: particles stay fixed (heat-only scenes), lists never rebuild.
    Fixed,
    /// `fix nve/gendpde`: the reversible velocity-Verlet part of the eSSA (eq 84); the
    /// dissipation, if any, is `fix shardlow`'s sweep.
    Verlet(Work),
    /// `fix vv/euler`: velocity Verlet for r and p with all pair forces, forward Euler for
    /// u (argon paper eqs 19-21); the dissipation acts through the pair forces.
    VvEuler,
}

/// How the reversible velocity-Verlet step changes the internal energies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Work {
    /// Each pair's work split equally between u_i and u_j (eq 84).
    Split,
    /// u_i = u(s_i, n_i) at the entropy s_i of the start of the step (SPEC section 6).
    Isentropic,
}

/// Everything the integrator needs besides the EOS and the weight.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    pub dt: f64,
    pub skin: f64,
    pub rebuild: RebuildPolicy,
    pub motion: Motion,
    pub dissipation: Option<Dissipation>,
    /// Heat baths, each on its own group (applied in this order after the sweep).
    pub reservoirs: Vec<Reservoir>,
}
