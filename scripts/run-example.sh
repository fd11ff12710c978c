#!/usr/bin/env bash
# Builds gendpde and runs the default example, a small van der Waals scene
# (examples/vdw-equilibrium: N = 3375, 500 steps, about half a minute).
# Extra arguments go to gendpde, e.g.  scripts/run-example.sh -var steps 2000
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
if ! command -v cargo >/dev/null; then
  echo "cargo is missing: install the Rust toolchain (https://rustup.rs)" >&2
  exit 1
fi
cargo build --release --quiet
cd examples/vdw-equilibrium
exec ../../target/release/gendpde run in.vdw-equilibrium "$@"
