#!/usr/bin/env bash
# Runs the gendpde test suite: unit, integration, release-profile physics tests and the
# MPI tests (mpirun --oversubscribe on 1-8 ranks). Installs OpenMPI and clang (for the
# MPI bindings) on a fresh Debian machine when missing; idempotent.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source scripts/deps.sh
install_build_deps
# Statistical physics tests need optimised code: the whole suite runs in release.
cargo test --release --workspace --features mpi "$@"
