//! Shared types with no upward imports: argument reading, script errors and modes,
//! units, memory checks, collectives over the particles, lattices, regions, group masks
//! and the signals that stop a run.

pub mod args;
pub mod gather;
pub mod groups;
pub mod lattice;
pub mod memory;
pub mod park;
pub mod particle_keywords;
pub mod region;
pub mod script;
pub mod signals;
pub mod units;
