#!/usr/bin/env bash
# The speed-accuracy table and plot of docs/PERFORMANCE.md (about 40 minutes on one core).
# Usage: scripts/bench/accuracy.sh [vdw|lj]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
source scripts/deps.sh
install_build_deps
cargo build --release --quiet --features mpi
export GENDPDE="${GENDPDE:-${CARGO_TARGET_DIR:-$PWD/target}/release/gendpde}"
exec python3 scripts/bench/accuracy.py "$@"
