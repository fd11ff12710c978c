//! The styles a script names, by family (LAMMPS's pair, fix and compute styles): each
//! family parses its commands into its own types. A pair style is one unit ([`pair`]):
//! it also builds the dynamics of a run from itself and the fixes it works with.

pub mod compute;
pub mod fix;
pub mod pair;
