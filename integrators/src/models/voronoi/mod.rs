//! Voronoi fluid particles (Serrano & Español, "Thermodynamically consistent mesoscopic
//! fluid particle models for a van der Waals fluid"): the periodic tessellation and the
//! Lagrangian finite-volume model with dynamic mass and entropy.

pub mod dpd;
pub mod finite_volume;
pub mod run;
pub mod tessellation;

pub use finite_volume::{Cells, CellDissipation, FiniteVolume, CellFrame, ModelError, Rates, CellTransport};
pub use run::VoronoiFv;
pub use tessellation::{Face, Tessellation, TessellationError};

#[cfg(test)]
mod tests;
#[cfg(test)]
mod finite_volume_tests;
