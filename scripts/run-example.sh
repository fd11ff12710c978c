#!/usr/bin/env bash
# Builds gendpde (with MPI) and runs the default example, a small van der Waals scene
# (examples/vdw-equilibrium: N = 3375, 500 steps, about half a minute).
# Extra arguments go to gendpde, e.g.  scripts/run-example.sh -var steps 2000
# NP=2 scripts/run-example.sh runs it on 2 MPI ranks.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source scripts/deps.sh
install_build_deps
cargo build --release --quiet --features mpi
target="${CARGO_TARGET_DIR:-target}"
[[ "$target" = /* ]] || target="$PWD/$target"
cd examples/vdw-equilibrium
if [ "${NP:-1}" -gt 1 ]; then
  # idle ranks yield the core (more ranks than cores: docs/PERFORMANCE.md)
  exec mpirun --oversubscribe --mca mpi_yield_when_idle 1 -np "$NP" "$target/release/gendpde" run in.vdw-equilibrium "$@"
fi
exec "$target/release/gendpde" run in.vdw-equilibrium "$@"
