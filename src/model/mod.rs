//! The model: everything a script defined (box, particles, styles, run settings).

pub mod group_functions;
pub mod per_atom;
pub mod sim;
