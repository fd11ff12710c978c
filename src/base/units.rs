//! `units lj` and `units metal`, with LAMMPS's constants.
//!
//! Internally masses are kept in energy * time^2 / length^2 (m * mvv2e), so that
//! momenta p = m v give K = p^2 / 2m in energy units and dp/dt = f directly: every
//! formula of the dynamics is free of conversion factors in every unit system.

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Units {
    pub name: &'static str,
    /// Boltzmann's constant (energy / temperature).
    pub kb: f64,
    /// mass * velocity^2 to energy.
    pub mvv2e: f64,
    pub default_dt: f64,
    pub default_skin: f64,
    /// Whether thermo normalises extensive quantities by N by default.
    pub default_norm: bool,
}

impl Units {
    /// Reduced Lennard-Jones units: k_B = 1.
    pub const LJ: Self = Self { name: "lj", kb: 1.0, mvv2e: 1.0, default_dt: 0.005, default_skin: 0.3, default_norm: true };
    /// g/mol, Angstrom, ps, eV, K (LAMMPS's update.cpp and force.cpp values).
    pub const METAL: Self =
        Self { name: "metal", kb: 8.617343e-5, mvv2e: 1.0364269e-4, default_dt: 0.001, default_skin: 2.0, default_norm: false };

    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "lj" => Some(Self::LJ),
            "metal" => Some(Self::METAL),
            _ => None,
        }
    }
}
