//! Input-script handling for gendpde: a LAMMPS-style script reader with
//! variable substitution, the variable store, an equal-style expression
//! evaluator and C-printf-compatible number formatting.

pub mod expr;
pub mod format;
pub mod script;
pub mod variables;

pub use expr::evaluate;
pub use format::{format_g, format_printf};
pub use script::{Command, Location, ScriptError, ScriptReader};
pub use variables::Variables;
