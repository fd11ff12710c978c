//! LAMMPS's unit styles (`units lj`, `real`, `metal`, `si`, `cgs`, `electron`, `micro`,
//! `nano`), with the constants of its update.cpp (checked against the reference LAMMPS's
//! force->boltz, mvv2e, nktv2p, mv2d and femtosecond).
//!
//! Internally masses are kept in energy * time^2 / length^2 (m * mvv2e), so that
//! momenta p = m v give K = p^2 / 2m in energy units and dp/dt = f directly: every
//! formula of the dynamics is free of conversion factors in every unit system. Output
//! converts as LAMMPS does: pressure by nktv2p, density by mv2d.

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Units {
    pub name: &'static str,
    /// Boltzmann's constant (energy / temperature).
    pub kb: f64,
    /// mass * velocity^2 to energy.
    pub mvv2e: f64,
    /// energy / volume to pressure (LAMMPS's nktv2p: bar in metal, atm in real).
    pub nktv2p: f64,
    /// mass / volume to density (g/cm^3 in metal and real).
    pub mv2d: f64,
    /// One femtosecond in time units (the Performance line's ns/day).
    pub femtosecond: f64,
    pub default_dt: f64,
    pub default_skin: f64,
    /// Whether thermo normalises extensive quantities by N by default.
    pub default_norm: bool,
}

impl Units {
    /// Reduced Lennard-Jones units: k_B = 1.
    pub const LJ: Self = Self {
        name: "lj",
        kb: 1.0,
        mvv2e: 1.0,
        nktv2p: 1.0,
        mv2d: 1.0,
        femtosecond: 1.0,
        default_dt: 0.005,
        default_skin: 0.3,
        default_norm: true,
    };
    /// g/mol, Angstrom, fs, kcal/mol, K, atm (LAMMPS's update.cpp and force.cpp values).
    pub const REAL: Self = Self {
        name: "real",
        kb: 0.0019872067,
        mvv2e: 48.88821291 * 48.88821291,
        nktv2p: 68568.415,
        mv2d: 1.0 / 0.602214129,
        femtosecond: 1.0,
        default_dt: 1.0,
        default_skin: 2.0,
        default_norm: false,
    };
    /// g/mol, Angstrom, ps, eV, K, bar (LAMMPS's update.cpp and force.cpp values).
    pub const METAL: Self = Self {
        name: "metal",
        kb: 8.617343e-5,
        mvv2e: 1.0364269e-4,
        nktv2p: 1.6021765e6,
        mv2d: 1.0 / 0.602214129,
        femtosecond: 0.001,
        default_dt: 0.001,
        default_skin: 2.0,
        default_norm: false,
    };

    /// picogram, micrometer, microsecond, picogram-micrometer^2/microsecond^2, K,
    /// picogram/(micrometer-microsecond^2) (LAMMPS's update.cpp and force.cpp values).
    pub const MICRO: Self = Self {
        name: "micro",
        kb: 1.3806504e-8,
        mvv2e: 1.0,
        nktv2p: 1.0,
        mv2d: 1.0,
        femtosecond: 1.0e-9,
        default_dt: 2.0,
        default_skin: 0.1,
        default_norm: false,
    };

    /// kilograms, meters, seconds, Joules, Kelvin, Pascals.
    pub const SI: Self = Self {
        name: "si",
        kb: 1.3806504e-23,
        mvv2e: 1.0,
        nktv2p: 1.0,
        mv2d: 1.0,
        femtosecond: 1.0e-15,
        default_dt: 1.0e-8,
        default_skin: 0.001,
        default_norm: false,
    };

    /// grams, centimeters, seconds, ergs, Kelvin, dyne/cm^2.
    pub const CGS: Self = Self {
        name: "cgs",
        kb: 1.3806504e-16,
        mvv2e: 1.0,
        nktv2p: 1.0,
        mv2d: 1.0,
        femtosecond: 1.0e-15,
        default_dt: 1.0e-8,
        default_skin: 0.1,
        default_norm: false,
    };

    /// amu, Bohr, femtoseconds, Hartrees, Kelvin, Pascals.
    pub const ELECTRON: Self = Self {
        name: "electron",
        kb: 3.16681534e-6,
        mvv2e: 1.06657236,
        nktv2p: 2.94210108e13,
        mv2d: 1.0,
        femtosecond: 1.0,
        default_dt: 0.001,
        default_skin: 2.0,
        default_norm: false,
    };

    /// attograms, nanometers, nanoseconds, attogram-nanometer^2/nanosecond^2, Kelvin,
    /// attogram/(nanometer-nanosecond^2).
    pub const NANO: Self = Self {
        name: "nano",
        kb: 0.013806504,
        mvv2e: 1.0,
        nktv2p: 1.0,
        mv2d: 1.0,
        femtosecond: 1.0e-6,
        default_dt: 0.00045,
        default_skin: 0.1,
        default_norm: false,
    };

    /// Every style, in LAMMPS's order.
    pub const ALL: [Self; 8] = [Self::LJ, Self::REAL, Self::METAL, Self::SI, Self::CGS, Self::ELECTRON, Self::MICRO, Self::NANO];

    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|u| u.name == name)
    }
}
