//! gendpde: Generalised energy-conserving Dissipative Particle Dynamics driven by
//! LAMMPS-style input scripts. The binary is a thin CLI over [`Interpreter`].
//!
//! Layers, each importing only those before it: `base` (shared types) <- `styles` (pair,
//! fix and compute styles) <- `model` (what a script defined) <- `output` (screen, log,
//! thermo, dumps, restart files) <- `commands` (the interpreter) <- the CLI (main.rs).

mod base;
mod commands;
pub mod lth_macro;
mod model;
mod output;
pub mod styles;

pub use base::script::{AppError, Mode};
pub use base::signals;
pub use commands::Interpreter;
pub use output::console::Output;
pub use output::thermo::Observables;
