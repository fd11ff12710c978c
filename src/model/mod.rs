//! The model: everything a script defined (box, particles, styles, run settings).

pub mod sim;
pub mod per_atom;
