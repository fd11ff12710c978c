#!/usr/bin/env python3
"""Side-by-side benchmark of gendpde and the reference LAMMPS (issue: performance).

Runs every case for both codes in one invocation, alternating gendpde / LAMMPS (and the
1- and 2-rank runs of an MPI scene with each other), REPS times, and reads atom-steps/s from the `Loop time of T on P procs for S steps with N
atoms` line of the timed run (the last `run` of the script; a short untimed warm-up run
precedes it). Writes the table (median, min-max, ratio) between the bench markers of
docs/PERFORMANCE.md and prints it.

    scripts/bench/run.sh            # everything (about 16 minutes on 2 cores)
    scripts/bench/run.sh classic    # only cases whose name contains "classic"

The 1- and 2-rank runs of an MPI scene alternate with two ceilings of the machine: the
scene's 1-rank run twice at once (the same work on both cores, no messages: the slower
copy's rate over the run alone) and an ideal bulk-synchronous kernel of the scene's pace
(sync_kernel.c: gendpde's rounds, bytes and reductions per step, arithmetic only, no
extra work on more ranks).

Environment: GENDPDE (binary), SYNC_KERNEL (the kernel, built by run.sh), LMP (reference
LAMMPS launcher), REPS (default 3).
"""
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))  # the gendpde package
import gendpde  # noqa: E402
BENCH = ROOT / "scripts" / "bench"
GENDPDE = os.environ.get("GENDPDE", str(ROOT / "target" / "release" / "gendpde"))
SYNC_KERNEL = os.environ.get("SYNC_KERNEL", str(Path(GENDPDE).with_name("sync_kernel")))
LMP = os.environ.get("LMP", "/work/shared/lammps/lmp")
REPS = int(os.environ.get("REPS", "3"))
CACHE = ROOT / "docs" / "bench.json"

VDW = "vdw 60.0 2.4682 1.4142 excess"
CLASSIC_RC1 = {"rho": 3.0, "rc": 1.0, "skin": 0.3, "n": 20, "steps": 300}
CLASSIC_RC4 = {"rho": 0.5, "rc": 4.0, "skin": 0.4, "n": 30, "steps": 30}


def case(name, script, gvars, lvars=None, ranks=1, lammps=True, group=None, kind="gendpde", kernel=None):
    """`group`: cases that alternate run by run (default: the case alone). `kind`:
    "gendpde", "pair" (its 1-rank run twice at once, the slower copy's rate) or "kernel"
    (sync_kernel with the arguments `kernel`: WORK ROUNDS BYTES COLLS STEPS; steps/s)."""
    return {"name": name, "script": script, "gvars": gvars, "lvars": lvars if lvars is not None else gvars,
            "ranks": ranks, "lammps": lammps, "group": group or name, "kind": kind, "kernel": kernel}


def cases():
    out = [
        case("classic DPDE + shardlow, rho 3, rc 1, N 8000", "in.dpde", CLASSIC_RC1),
        case("classic DPDE + shardlow, rho 0.5, rc 4, N 27000", "in.dpde", CLASSIC_RC4),
        case("GenDPDE vdW, rho 0.5, rc 4, N 27000 (LAMMPS: DPDE)", "in.gendpde",
             {"eos": VDW, "n": 30, "steps": 40, "warm": 10}, CLASSIC_RC4),
        case("GenDPDE LJ, rho 0.5, rc 4, N 27000 (LAMMPS: DPDE)", "in.gendpde",
             {"eos": "lj 60.0", "n": 30, "steps": 5, "warm": 2}, CLASSIC_RC4),
        case("GenDPDE LJ tabulated, rho 0.5, rc 4, N 27000 (LAMMPS: DPDE)", "in.gendpde",
             {"eos": "lj 60.0 table 0.3 8.0 121 0.0 1.2 129", "n": 30, "steps": 10, "warm": 2}, CLASSIC_RC4),
    ]
    # O(N): classic DPDE at rho 3, rc 1 from 10^3 to 2.5 10^5 particles
    for n, steps in [(10, 2000), (22, 200), (32, 60), (47, 20), (63, 8)]:
        out.append(case(f"N scaling classic rho 3, N {n ** 3}", "in.dpde", {**CLASSIC_RC1, "n": n, "steps": steps}))
    # parallel efficiency: the 1- and 2-rank runs of a scene, the pair of 1-rank runs and
    # the 1- and 2-rank runs of the ideal kernel alternate. The kernel's pace: about the
    # scene's one-rank step on this machine (8e6 and 75e6 multiply-adds: 12 and 115 ms),
    # the rounds, bytes and reductions per step of the scene's 2-rank run ("Comm messages
    # per step", comm_counts.sh).
    for scene, script, gvars, kernel in [
            ("classic rho 3, N 27000", "in.dpde", {**CLASSIC_RC1, "n": 30, "steps": 300},
             (8_000_000, 11, 675_000, 1, 300)),
            ("GenDPDE vdW N 27000", "in.gendpde", {"eos": VDW, "n": 30, "steps": 100},
             (75_000_000, 15, 2_256_000, 3, 100))]:
        for ranks in (1, 2):
            out.append(case(f"MPI {scene}, {ranks} rank(s)", script, gvars, ranks=ranks, lammps=False, group=scene))
        out.append(case(f"MPI {scene}: two 1-rank runs at once, the slower", script, gvars, lammps=False, group=scene,
                        kind="pair"))
        for ranks in (1, 2):
            out.append(case(f"MPI {scene}: ideal kernel (steps/s), {ranks} rank(s)", script, gvars, ranks=ranks,
                            lammps=False, group=scene, kind="kernel", kernel=kernel))
    return out


def groups(selected):
    """The cases that alternate run by run: the MPI rows of a scene together (so that a
    drift of the machine's speed falls on both rank counts and on the ceilings alike)."""
    out = {}
    for c in selected:
        out.setdefault(c["group"], []).append(c)
    return list(out.values())


def var_args(flag, values):
    args = []
    for k, v in values.items():
        args += [flag, k, str(v)]
    return args


def mpi(ranks, cmd):
    return ["mpirun", "--oversubscribe", "-np", str(ranks)] + cmd if ranks > 1 else cmd


def run(code, c):
    """atom-steps/s of the timed run of case `c` by `code` (the kernel: steps/s)."""
    # OpenMPI refuses root without these (containers, CI)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if c["kind"] == "kernel":
        cmd = mpi(c["ranks"], [SYNC_KERNEL] + [str(a) for a in c["kernel"]])
        out = subprocess.run(cmd, capture_output=True, text=True, env=env)
        words = out.stdout.split()
        if out.returncode != 0 or len(words) < 2 or words[0] != "steps/s":
            sys.exit(f"sync_kernel failed on '{c['name']}':\n{' '.join(cmd)}\n{out.stdout[-2000:]}\n{out.stderr[-2000:]}")
        return float(words[1])
    if code == "gendpde":
        cmd = mpi(c["ranks"], [GENDPDE, "run", str(BENCH / c["script"]), "-log", "none"] + var_args("-var", c["gvars"]))
    else:
        cmd = [LMP, "-in", str(BENCH / "in.dpde"), "-log", "none"] + var_args("-var", c["lvars"])
    copies = 2 if c["kind"] == "pair" else 1
    procs = [subprocess.Popen(cmd, cwd=BENCH, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
             for _ in range(copies)]
    rates = []
    for proc in procs:
        stdout, stderr = proc.communicate()
        runs = [r for r in gendpde.parse_log(stdout) if "atom_steps_per_s" in r.attrs]
        if proc.returncode != 0 or not runs:
            sys.exit(f"{code} failed on '{c['name']}':\n{' '.join(cmd)}\n{stdout[-2000:]}\n{stderr[-2000:]}")
        rates.append(runs[-1].attrs["atom_steps_per_s"])
    return min(rates)


def fmt(x):
    return f"{x:.3g}"


def main():
    wanted = sys.argv[1] if len(sys.argv) > 1 else ""
    # rows of earlier runs, so that a filtered run updates its cases and keeps the others
    cache = json.loads(CACHE.read_text()) if CACHE.exists() else {}
    for group in groups([c for c in cases() if wanted in c["name"]]):
        rates = [{"gendpde": [], "lammps": []} for _ in group]
        for _ in range(REPS):
            for c, r in zip(group, rates):
                r["gendpde"].append(run("gendpde", c))
                if c["lammps"]:
                    r["lammps"].append(run("lammps", c))
        medians = {(c["kind"], c["ranks"]): statistics.median(r["gendpde"]) for c, r in zip(group, rates)}
        for c, r in zip(group, rates):
            g = statistics.median(r["gendpde"])
            cells = [c["name"], fmt(g), f"{fmt(min(r['gendpde']))}-{fmt(max(r['gendpde']))}"]
            if r["lammps"]:
                lmp = statistics.median(r["lammps"])
                cells += [fmt(lmp), f"{fmt(min(r['lammps']))}-{fmt(max(r['lammps']))}", f"{g / lmp:.2f}"]
            elif c["kind"] == "pair" and ("gendpde", 1) in medians:
                cells += ["", "", f"over alone {g / medians[('gendpde', 1)]:.2f}"]
            elif c["ranks"] > 1 and (c["kind"], 1) in medians:
                # parallel efficiency: the P-rank median over P times the 1-rank median
                cells += ["", "", f"efficiency {g / (c['ranks'] * medians[(c['kind'], 1)]):.2f}"]
            else:
                cells += ["", "", ""]
            cache[c["name"]] = cells
            CACHE.write_text(json.dumps(cache, indent=1) + "\n")
            print(" | ".join(cells), flush=True)
    rows = [cache[c["name"]] for c in cases() if c["name"] in cache]
    header = ["case", "gendpde atom-steps/s (median)", "min-max", "LAMMPS atom-steps/s (median)", "min-max",
              "ratio"]
    table = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    table += ["| " + " | ".join(r) + " |" for r in rows]
    note = (f"Generated by `scripts/bench/run.sh` ({REPS} alternating repetitions per case, the 1- and 2-rank "
            "runs of an MPI scene and of its two ceilings alternating too; one core per rank; rows kept in "
            "docs/bench.json, a filtered run updates its own).")
    block = "\n".join([note, "", *table])
    doc = ROOT / "docs" / "PERFORMANCE.md"
    text = doc.read_text()
    begin, end = "<!-- bench:begin -->", "<!-- bench:end -->"
    if begin in text:
        head, rest = text.split(begin, 1)
        text = head + begin + "\n" + block + "\n" + end + rest.split(end, 1)[1]
        doc.write_text(text)
    print("\n" + block)


if __name__ == "__main__":
    main()
