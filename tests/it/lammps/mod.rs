//! LAMMPS compatibility: scripts run unchanged, LAMMPS's examples, pair coefficients, and
//! parity with the reference LAMMPS (22 Jul 2025).

mod computes_parity;
mod language;
mod lammps_change_box;
mod lammps_examples;
mod lammps_parity;
mod lammps_vv;
mod pair_coeffs;
mod script_compat;
mod setup_compat;
