//! gendpde: Generalised energy-conserving Dissipative Particle Dynamics driven by
//! LAMMPS-style input scripts. The binary is a thin CLI over [`Interpreter`].

mod args;
mod ave_time;
pub mod commands;
mod computes;
mod data;
mod dump;
mod gather;
mod groups;
mod h5md_out;
mod restart;
pub mod lattice;
pub mod lth_macro;
mod memory;
pub mod output;
pub mod run;
pub mod sim;
pub mod styles;
pub mod thermo;
pub mod units;
mod pairwise;
mod rdf;
mod velocity;

pub use commands::{AppError, Interpreter, Mode};
pub use output::Output;
pub use thermo::Observables;
