#!/usr/bin/env bash
# Runs the gendpde test suite: unit, integration, release-profile physics tests and the
# MPI tests (mpirun --oversubscribe on 1-8 ranks), then the Python package's tests
# (python/tests) against the release binary. Installs OpenMPI and clang (for the MPI
# bindings) on a fresh Debian machine when missing; idempotent.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source scripts/deps.sh
install_build_deps
# Statistical physics tests need optimised code: the whole suite runs in release.
cargo test --release --workspace --features mpi "$@"
# The Python package (python/) on the binary cargo test built.
python3 -m pip install -q ./python 2>/dev/null || python3 -m pip install -q --break-system-packages ./python
target="${CARGO_TARGET_DIR:-target}"
[[ "$target" = /* ]] || target="$PWD/$target"
GENDPDE="$target/release/gendpde" python3 -m pytest -q python/tests
