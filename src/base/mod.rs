//! Shared types with no upward imports: argument reading, script errors and modes,
//! units, memory checks, collectives over the particles, lattices, regions and group masks.

pub mod args;
pub mod gather;
pub mod groups;
pub mod lattice;
pub mod memory;
pub mod region;
pub mod script;
pub mod units;
