//! The passes' scratch: per-pair values kept from one pass of a step for the next, and
//! per-particle work vectors reused across steps (no allocation in the loops).

use gendpde_engine::Vec3;

/// Scratch vectors of the passes, owned by [`crate::System`] so their memory is reused.
#[derive(Clone, Debug, Default)]
pub struct Scratch {
    /// The neighbour pairs closer than the density cutoff at the last density pass, in
    /// list order: the pairs the force and work passes visit (the others, in the skin,
    /// contribute exact zeros). Emptied by a list build.
    pub active: Vec<[u32; 2]>,
    /// w'(r_ij)/([w] r_ij) of each pair of `active`, from the last density pass.
    pub pair_geometry: Vec<f64>,
    /// F_ij of each pair of `active` (f_ij = F_ij r_ij), from the last force pass.
    pub pair_force: Vec<f64>,
    /// Per-particle sums of the pair passes, or multi/lucy's table values.
    pub pair_sums: Vec<f64>,
    /// zeta_i = dn_i/dn^b_i of the owned particles at the last density pass (corrected
    /// particle volume only; empty otherwise).
    pub zeta: Vec<f64>,
    /// Friction force and random impulse of the owned particles (`fix vv/euler`, within
    /// one step).
    pub friction: Vec<Vec3>,
    pub noise: Vec<Vec3>,
    /// Velocities of all particles for the work passes.
    pub velocity: Vec<Vec3>,
    /// 1/m of all particles for the sweep.
    pub inv_mass: Vec<f64>,
}
