//! The dynamics of each pair-style family, each a [`crate::Physics`]: GenDPDE
//! ([`gendpde`]), LAMMPS's pairwise DPD styles ([`classic`]), eDPD ([`edpd`]), SDPD
//! ([`sdpd`]) and Voronoi fluid particles ([`voronoi`]).

pub mod classic;
pub mod edpd;
pub mod gendpde;
pub mod sdpd;
pub mod voronoi;
