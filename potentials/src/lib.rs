//! Particle equations of state (EOS) and weight functions of GenDPDE.
//!
//! Equation numbers refer to Bonet Avalos et al., PCCP 21, 24891 (2019) unless a
//! docstring names another paper. This crate depends on nothing project-internal.

pub mod cell_energy;
pub mod eos;
pub mod hnc;
pub mod lth_params;
pub mod pair_table;
pub mod volume;
pub mod weight;

pub use eos::{
    AffineAt, AtDensity, AtN, Before, Eos, EosError, EosState, FixedDensity, ErrorAt, LennardJones, LinearTheta, TableError, TableErrors, TableGrid,
    Tabulated, Tait, ISOLATED_DENSITY,
};
pub use cell_energy::{CellEnergy, CellState, CellStateError, IdealCell, VdwCell};
pub use weight::{CubicSpline, Linear, Lucy, Quadratic, Weight, WeightKind};
