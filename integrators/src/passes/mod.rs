//! The building blocks the models share: the many-body density and force passes, the
//! Shardlow sweep and its pair update, heat-flow and noise laws, the isentropic hold,
//! velocity-Verlet kicks and drifts, per-type EOS lists, tabulated pair forces and the
//! `fix nph` barostat.

pub mod barostat;
pub mod dissipation;
pub mod heat;
pub mod isentropic;
pub mod many_body;
pub mod noise;
pub mod pair_tables;
pub mod pair_update;
pub mod scratch;
pub mod species;
pub mod sweep;
pub mod verlet;
