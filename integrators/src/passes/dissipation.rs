//! What the Shardlow sweep and the heat reservoir apply: the pair friction, noise and
//! heat flow of `fix shardlow` or `fix vv/euler`, and a `fix heat/reservoir` bath.

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
    /// The fix ID: the key of the reservoir's energy tally ([`crate::FixState::reservoir_tally`]).
    pub id: String,
    /// Group bit mask of the particles it couples (all bits: group all).
    pub mask: u32,
    pub temperature: f64,
    pub kappa: f64,
    pub heat: HeatModel,
    pub seed: u64,
}
