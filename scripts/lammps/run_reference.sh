#!/usr/bin/env bash
# Runs one of the parity inputs with the reference LAMMPS (22 Jul 2025, installed on demand by
# /work/shared/lammps/setup.sh) in a work directory, leaving log.lammps, screen.txt and the dumps
# there.
#   scripts/lammps/run_reference.sh INPUT [WORKDIR] [-var NAME VALUE ...]
# INPUT is a path or a name in this directory (in.dpde-deterministic or dpde-deterministic).
# WORKDIR defaults to target/lammps/<name>; the input and every data.* file of this directory are
# copied into it first, so relative read_data / write_dump paths work. Extra arguments go to lmp.
#   LAMMPS_SETUP  setup script (default /work/shared/lammps/setup.sh)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
setup="${LAMMPS_SETUP:-/work/shared/lammps/setup.sh}"

if [ $# -lt 1 ]; then
  sed -n '2,9p' "$0" >&2
  exit 2
fi
input="$1"; shift
if [ ! -f "$input" ]; then
  if [ -f "$here/$input" ]; then input="$here/$input"
  elif [ -f "$here/in.$input" ]; then input="$here/in.$input"
  else echo "run_reference.sh: no input $input" >&2; exit 2; fi
fi
name="$(basename "$input")"; name="${name#in.}"
workdir="$root/target/lammps/$name"
if [ $# -ge 1 ] && [ "$1" != "-var" ]; then workdir="$1"; shift; fi

lmp="$("$setup" | tail -n 1)"
[ -x "$lmp" ] || { echo "run_reference.sh: LAMMPS setup did not give an executable ($lmp)" >&2; exit 1; }

mkdir -p "$workdir"
cp "$input" "$workdir/"
cp "$here"/data.* "$workdir/" 2>/dev/null || true
cd "$workdir"
start=$(date +%s.%N)
"$lmp" -in "$(basename "$input")" -log log.lammps -screen screen.txt "$@"
end=$(date +%s.%N)
awk -v s="$start" -v e="$end" -v n="$name" -v w="$workdir" 'BEGIN { printf "run_reference.sh: %s done in %.1f s; output in %s\n", n, e - s, w }'
