#!/usr/bin/env bash
# Cost per cell-step of the Voronoi fluid models (pair voronoi/fv, finite-volume and
# Voronoi DPD dissipation) against N, with the tessellation's share; prints the markdown
# table of docs/PERFORMANCE.md "Voronoi fluid particles: cost per cell-step (issue 23)".
# Usage: scripts/bench/voronoi_cost.sh [N ...]   (default 1000 3375 8000 27000 64000 97336)
# Times are thread CPU times (integrators/examples/voronoi_cost.rs), one thread.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(1000 3375 8000 27000 64000 97336)
cargo build --release --quiet -p gendpde-integrators --example voronoi_cost
bin="${CARGO_TARGET_DIR:-$PWD/target}/release/examples/voronoi_cost"
load_before=$(cut -d' ' -f1 /proc/loadavg)
out=$("$bin" "${sizes[@]}")
load_after=$(cut -d' ' -f1 /proc/loadavg)
echo "$(nproc) cores, load average $load_before before and $load_after after; $(date -u +%Y-%m-%d)"
echo
echo "| N | model | steps | CPU us per cell-step | tessellation share | tessellation cells/s |"
echo "|---|---|---|---|---|---|"
echo "$out" | awk '{ name = ($2 == "fv") ? "finite volume" : "Voronoi DPD";
  printf "| %d | %s | %d | %.1f | %.0f %% | %.0f |\n", $1, name, $3, 1e6 * $4 / $1, 100 * 2 * $5 / $4, $1 / $5 }'
