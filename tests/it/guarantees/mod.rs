//! What users pick gendpde for: bit-identical runs on any rank count, restarts that
//! continue bit for bit, clean stops on signals, designed behaviour at the edges.

mod edges;
#[allow(clippy::module_inception)]
mod guarantees;
mod mpi;
mod restart_roundtrip;
mod signals;
