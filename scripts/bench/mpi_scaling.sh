#!/usr/bin/env bash
# Parallel efficiency of the MPI decomposition: the vdW scene at the 2019 paper's scale
# (N = 27000, rho = 0.5, rc = 4, skin 0.4, dt = 0.01) on 1 and 2 ranks (more with
# RANKS="1 2 4"), STEPS steps each (default 50). Prints atom-steps/s, the parallel
# efficiency and rank 0's time in communication.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
source scripts/deps.sh
install_build_deps
cargo build --release --quiet --features mpi
GENDPDE="${GENDPDE:-${CARGO_TARGET_DIR:-$PWD/target}/release/gendpde}"
steps="${STEPS:-50}"
cd examples/vdw-equilibrium
printf "%6s %14s %12s %12s\n" ranks atom-steps/s efficiency comm-%
base=""
for np in ${RANKS:-1 2}; do
  out=$(mpirun --oversubscribe -np "$np" "$GENDPDE" run in.vdw-equilibrium \
        -var n 30 -var steps "$steps" -log none)
  rate=$(echo "$out" | awk '/^Performance/ {print $(NF-1)}')     # katom-step/s
  comm=$(echo "$out" | sed -n 's/.*(\([0-9.]*\) % of the loop).*/\1/p')
  [ -n "$base" ] || base="$rate"
  eff=$(awk -v r="$rate" -v b="$base" -v p="$np" 'BEGIN {printf "%.2f", r / (b * p)}')
  printf "%6s %14.0f %12s %12s\n" "$np" "$(awk -v r="$rate" 'BEGIN {print r * 1000}')" "$eff" "$comm"
done
