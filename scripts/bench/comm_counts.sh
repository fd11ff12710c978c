#!/usr/bin/env bash
# Point-to-point messages, bytes and exchange rounds per step of rank 0 (the run
# summary's "Comm messages per step" line) for the classic rho 3, rc 1 scene (in.dpde,
# N 27000) and the GenDPDE vdW scene (in.gendpde, N 27000) on RANKS ranks (default "2 4 8"; one rank sends nothing:
# every exchange is a copy). Counts do not depend on the machine's load, so this runs
# oversubscribed (OpenMPI yields when idle). Prints the table of docs/PERFORMANCE.md
# ("Communication and a scaling model").
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
GENDPDE="${GENDPDE:-${CARGO_TARGET_DIR:-$PWD/target}/release/gendpde}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
cd scripts/bench
echo "| scene | ranks | messages per step | kB per step | rounds per step |"
echo "|---|---|---|---|---|"
for scene in "classic DPDE rho 3, rc 1, skin 0.3 (in.dpde, n 30)|in.dpde|-var rho 3.0 -var rc 1.0 -var skin 0.3 -var n 30 -var warm 2 -var steps 20" \
             "GenDPDE vdW rho 0.5, rc 4, skin 0.4 (in.gendpde)|in.gendpde|-var n 30 -var warm 1 -var steps 4"; do
  IFS='|' read -r name script vars <<<"$scene"
  for np in ${RANKS:-2 4 8}; do
    # shellcheck disable=SC2086
    line=$(mpirun --oversubscribe --mca mpi_yield_when_idle 1 -np "$np" "$GENDPDE" run "$script" -log none $vars \
           | grep 'Comm messages per step' | tail -1)
    msgs=$(echo "$line" | sed -n 's/.*= \([0-9.]*\), .*/\1/p')
    kb=$(echo "$line" | sed -n 's/.*, \([0-9.]*\) kB per step.*/\1/p')
    rounds=$(echo "$line" | sed -n 's/.*in \([0-9.]*\) rounds.*/\1/p')
    echo "| $name | $np | $msgs | $kb | $rounds |"
    name=""
  done
done
