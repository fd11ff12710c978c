//! gendpde's integration tests, one binary (`it`) organised by area: every former
//! `tests/NAME.rs` is the module `AREA::NAME` (same test names). One binary links the
//! library and HDF5 once instead of once per file.
//!
//! Run all: `cargo test --release --test it`; one area or file: `cargo test --release --test
//! it styles::` or `... --test it guarantees::signals::`. The MPI tests need `--features mpi`.
//!
//! - `common`: the shared helpers (LAMMPS runs and parsing, mpirun, statistics) and the
//!   checks of the statistics helpers (`common::statistics_helpers`);
//! - `commands`: computes, variables, groups, `velocity` and `set` of the input language;
//! - `guarantees`: rank independence, restarts, signals, edges (issue 16);
//! - `io`: the command line, restarts and H5MD files, dumps and their readers;
//! - `lammps`: LAMMPS scripts run unchanged, parity with the reference LAMMPS;
//! - `properties`: the property tests (proptest; regressions in
//!   tests/proptest-regressions/properties.txt);
//! - `styles`: pair styles, fixes and models as physics (eDPD, SDPD, tables, heat flow, ...).

mod commands;
mod common;
mod guarantees;
mod io;
mod lammps;
mod properties;
mod styles;
