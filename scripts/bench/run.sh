#!/usr/bin/env bash
# Side-by-side benchmark of gendpde and the reference LAMMPS; writes the table into
# docs/PERFORMANCE.md. Usage: scripts/bench/run.sh [case-name-filter]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
source scripts/deps.sh
install_build_deps
bash "${LAMMPS_SETUP:-/work/shared/lammps/setup.sh}" >/dev/null
cargo build --release --quiet --features mpi
# the binary just built (cargo honours CARGO_TARGET_DIR)
export GENDPDE="${GENDPDE:-${CARGO_TARGET_DIR:-$PWD/target}/release/gendpde}"
# the MPI rows' ideal bulk-synchronous kernel (the machine's ceiling), next to the binary
export SYNC_KERNEL="${SYNC_KERNEL:-${CARGO_TARGET_DIR:-$PWD/target}/release/sync_kernel}"
mpicc -O2 -o "$SYNC_KERNEL" scripts/bench/sync_kernel.c
exec python3 scripts/bench/bench.py "$@"
