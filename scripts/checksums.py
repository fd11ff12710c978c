#!/usr/bin/env python3
"""Checksums of short runs of every input script, to prove that a change leaves every
trajectory bit-identical.

The scenes are every example (examples/*/in.*), every script in scripts/lammps/
(scripts/lammps/in.*) and every LAMMPS example in scripts/lammps/examples/ (*/*/in.*),
plus a few variants that switch a style with `-var` (VARIANTS). Each scene runs on each
rank count of --ranks in its own folder, target/checksums/<scene>/<ranks>/, from a staged
copy of its script (and of the files it reads) edited to be short and fully observable:

* every `run N` becomes `run min(N, cap)` (cap: CAPS, default DEFAULT_CAP; a variable
  argument is resolved from the script's `variable NAME index VALUE` lines and the
  scene's -var overrides), each run preceded by `thermo K` (K = max(1, steps // 20)) and
  `thermo_modify format float %.17g` (every float column at full precision);
* at the end, `write_dump all custom FINAL.dump id type mass x y z ix iy iz vx vy vz px
  py pz fx fy fz u theta` and the per-particle fields the scene's styles allocate
  (uCond, n, rho, drho, edpd_temp/cv/flux, vol: `extras`), written by write_dump's default
  float format, the shortest text that reads back to the same double; rows sorted by ID.

A run gives one line `scene ranks sha256(thermo) sha256(final dump) steps`: the thermo
hash covers the header and the numeric rows of every run's table, words joined by single
spaces (never the wall-clock columns CPU, T/CPU, S/CPU, nor the Loop time, Performance,
memory or timing lines); steps is the sum of the `Loop time ... for N steps` counts. A run
that stops gives `scene ranks refused sha256(error) sha256(thermo so far) steps : ERROR
line` (some scenes refuse 3 ranks by design: pair voronoi/fv runs on one rank, a small
box does not split into 3); the refusal is compared like any other line.

    python3 scripts/checksums.py --write scripts/checksums/reference.txt --gendpde PATH
    python3 scripts/checksums.py --check scripts/checksums/reference.txt --gendpde target/release/gendpde
    python3 scripts/checksums.py --check scripts/checksums/reference.txt --only heat,lammps/dpd

--check prints every line that differs from FILE, and every line of FILE for the chosen
scenes and rank counts that the run did not give, and exits 1 if there is any (a scene
FILE does not know is printed as `not in FILE` without failing). Without --write/--check
the lines are only printed. 1 rank runs the binary directly, more ranks under `mpirun
--oversubscribe -np N` (with OMPI_ALLOW_RUN_AS_ROOT and a session directory per launch
set by the script); the binary must be built with MPI, which the script checks from the
`on N procs` of the Loop time line.
Standard library only.
"""
import argparse
import gzip
import hashlib
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WORK = ROOT / "target" / "checksums"
DEFAULT_GENDPDE = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release" / "gendpde"

DEFAULT_CAP = 200
# Steps per run of the costly scenes (each `run` of the script is cut to this many steps;
# the others: DEFAULT_CAP), chosen so that the whole matrix (1 and 3 ranks) takes about
# 6 minutes on 2 busy cores while every scene runs at least 40 steps per run (or its
# script's own shorter count) and, where particles move and the script checks its
# neighbour list (`check yes`), rebuilds it at least once (the counts: "Neighbor list
# builds" in target/checksums/<scene>/<ranks>/stdout.txt).
CAPS = {
    "examples/vapour-liquid": 40,  # 29233 particles, rc 4
    "examples/distributions": 80,  # two runs each (equilibration and production)
    "examples/flash-heating": 80,
    "examples/isothermal": 80,
    "examples/lj-fluid": 80,
    "examples/lth-argon": 80,  # 27000 particles
    "examples/vdw-equilibrium": 120,
    "lammps/edpd": 40,  # 16000 particles, rc 1.58, two runs each
    "lammps/edpd-region": 40,
    "lammps-examples/dpd-meso/edpd": 40,
    "lammps-examples/dpd-meso/edpd-region": 40,
    "lammps-examples/dpd-meso/mdpd": 120,  # 14333 particles
    "lammps-examples/dpd-react/dpd-vv": 100,  # 10125 particles, lists rebuilt every step
    "lammps-examples/dpd-react/dpde-vv": 100,
    "lammps-examples/dpd-react/dpdh-shardlow": 100,
    "lammps-examples/dpd-react/multi-lucy": 120,
    "lammps/table-water": 120,
}
# -var overrides of a scene (sizes of scripts whose default system is too large for a
# check of a few minutes; the names are the scripts' own variables).
VARS = {}
# Variants: scene name -> (base scene, -var pairs): the same script with a -var that switches
# a style or a model (another code path), run like the scripts themselves.
VARIANTS = {
    "examples/isothermal,motion=vv": ("examples/isothermal", [("motion", "vv")]),  # fix vv/euler
    "examples/lj-fluid,eos=table": ("examples/lj-fluid", [("eos", "lj 60.0 table 0.3 8.0 121 0.0 1.2 129")]),
    "examples/distributions,noise=harmonic,heat=fourier,reject=yes": (
        "examples/distributions", [("noise", "harmonic 1.5"), ("heat", "fourier"), ("reject", "yes")]),
    "examples/heat-only,heat=original": ("examples/heat-only", [("heat", "original")]),
    "examples/voronoi-vdw,diss=dpd": ("examples/voronoi-vdw", [("diss", "dpd")]),
    # the example stops at step 121 of its 200 (a cell state goes non-finite; reference
    # binary of this commit): its line is that refusal; 100 steps give a final state
    "examples/voronoi-coexistence,steps=100": ("examples/voronoi-coexistence", [("steps", "100")]),
    "lammps/edpd-forces,case=poly": ("lammps/edpd-forces", [("case", "poly")]),
    "lammps/multi-lucy-parity,tstyle=lookup": ("lammps/multi-lucy-parity", [("tstyle", "lookup")]),
    "lammps/nph,baro=aniso,temp=low": ("lammps/nph", [("baro", "aniso 20.0 20.0 2.0"), ("modify", "fix_modify 2 temp lowtemp")]),
    "lammps/table-lj,tstyle=lookup": ("lammps/table-lj", [("tstyle", "lookup")]),
    "lammps/table-lj,tstyle=spline": ("lammps/table-lj", [("tstyle", "spline")]),
}
# Scenes that read a file another scene writes: scene -> (script of the producer, relative
# to the repository). The producer runs first in the same folder (its runs capped at 0
# steps); its output is not hashed, but its failure is the scene's.
PRODUCERS = {"lammps/mix-dpd-data": "scripts/lammps/in.mix-dpd"}

BASE_FIELDS = "id type mass x y z ix iy iz vx vy vz px py pz fx fy fz u theta"
WALL_CLOCK_COLUMNS = {"CPU", "T/CPU", "S/CPU"}
LOOP = re.compile(r"Loop time of\s+\S+\s+on\s+(\d+)\s+procs?\s+for\s+(\d+)\s+steps")
HEADER = re.compile(r"[A-Za-z_][^\s:'\"]*(\s+[A-Za-z_][^\s:'\"]*)*")


def scenes():
    """{name: (script, -var pairs, steps per run)} of every scene, in run order (a variant
    after its base scene, with its cap)."""
    found = {}
    for script in sorted((ROOT / "examples").glob("*/in.*")):
        found[f"examples/{script.name[3:]}"] = script
    for script in sorted((ROOT / "scripts" / "lammps").glob("in.*")):
        found[f"lammps/{script.name[3:]}"] = script
    for script in sorted((ROOT / "scripts" / "lammps" / "examples").glob("*/*/in.*")):
        found[f"lammps-examples/{script.parent.parent.name}/{script.name[3:]}"] = script
    out = {}
    for name, script in found.items():
        out[name] = (script, list(VARS.get(name, [])), CAPS.get(name, DEFAULT_CAP))
        for variant, (base, pairs) in VARIANTS.items():
            if base == name:
                out[variant] = (script, out[name][1] + list(pairs), CAPS.get(variant, out[name][2]))
    return out


def number(word):
    try:
        float(word)
        return True
    except ValueError:
        return False


def index_values(text, overrides):
    """The first value of every `variable NAME index VALUE ...` line (overridden by the
    scene's -var pairs), for resolving `run ${NAME}`."""
    values = {}
    for line in text.splitlines():
        words = line.split("#")[0].split()
        if len(words) >= 4 and words[0] == "variable" and words[2] in ("index", "equal") and words[1] not in values:
            values[words[1]] = words[3]
    values.update(dict(overrides))
    return values


def resolve(word, values):
    m = re.fullmatch(r"\$\{(\w+)\}|\$(\w)", word)
    if m:
        word = values.get(m.group(1) or m.group(2), "")
    try:
        return int(float(word))
    except ValueError:
        return None


def extras(text):
    """The per-particle fields beyond BASE_FIELDS that the scene's styles allocate
    (write_dump refuses a keyword the scene lacks): uCond (dpd/fdt/energy), n (the local
    density of pair gendpde and sdpd/generic, unless the EOS is eos/cv, which reads none),
    rho (mdpd and sph atoms, multi/lucy), drho (sph), eDPD's T, C_V and heat flux, and the
    Voronoi cell volume."""
    lines = [l.split("#")[0].split() for l in text.splitlines()]
    atom_style = next((l[1] for l in lines if l[:1] == ["atom_style"] and len(l) > 1), "atomic")
    pair = " ".join(" ".join(l[1:]) for l in lines if l[:1] == ["pair_style"])
    fixes = " ".join(" ".join(l[3:4]) for l in lines if l[:1] == ["fix"])
    out = []
    if "dpd/fdt/energy" in pair:
        out.append("uCond")
    if re.search(r"(^|\s)(gendpde|sdpd/generic)\b", pair) and "eos/cv" not in fixes.split():
        out.append("n")
    if atom_style in ("mdpd", "sph") or "multi/lucy" in pair:
        out.append("rho")
    if atom_style == "sph":
        out.append("drho")
    if atom_style == "edpd":
        out += ["edpd_temp", "edpd_cv", "edpd_flux"]
    if "voronoi/fv" in pair:
        out.append("vol")
    return out


def stage(name, script, dest):
    """Copies the scene's folder (scripts/lammps/: the files the script names) into
    `dest` (*.gz unpacked) and writes the edited script; returns its file name."""
    if dest.exists():
        shutil.rmtree(dest)
    dest.mkdir(parents=True)
    text = script.read_text()
    shared = script.parent == ROOT / "scripts" / "lammps"
    tokens = set(re.findall(r"[\w.+-]+", text))
    for f in sorted(script.parent.iterdir()):
        if not f.is_file() or (f.name.startswith("in.") and f != script):
            continue
        if shared and f.name not in tokens:
            continue
        if f.suffix == ".gz":
            with gzip.open(f, "rb") as src, open(dest / f.stem, "wb") as out:
                shutil.copyfileobj(src, out)
        elif f != script:
            shutil.copy(f, dest / f.name)
    return script.name, text


def edit(text, cap, overrides, final=True):
    """The script shortened and made observable (see the module documentation)."""
    values = index_values(text, overrides)
    out = []
    for line in text.splitlines():
        words = line.split("#")[0].split()
        if words[:1] == ["run"] and len(words) >= 2:
            n = resolve(words[1], values)
            steps = cap if n is None else min(n, cap)
            out.append(f"thermo {max(1, steps // 20)}")
            out.append("thermo_modify format float %.17g")
            out.append(" ".join(["run", str(steps)] + words[2:]))
            continue
        out.append(line)
    if final:
        out.append(f"write_dump all custom FINAL.dump {BASE_FIELDS} {' '.join(extras(text))}".rstrip() + " modify sort id")
    return "\n".join(out) + "\n"


def thermo(stdout):
    """(canonical text of every thermo table: headers and numeric rows, wall-clock
    columns left out; steps run; rank counts of the Loop time lines)."""
    lines, steps, procs = [], 0, set()
    header, keep = None, None
    for line in stdout.splitlines():
        words = line.split()
        if not words:
            continue
        if "Step" in words and not any(number(w) for w in words) and HEADER.fullmatch(line.strip()):
            header = words
            keep = [k for k, w in enumerate(words) if w not in WALL_CLOCK_COLUMNS]
            lines.append(" ".join(words[k] for k in keep))
            continue
        m = LOOP.match(line.strip())
        if m:
            procs.add(int(m.group(1)))
            steps += int(m.group(2))
            header = None
            continue
        if header is not None and len(words) == len(header) and all(number(w) for w in words):
            lines.append(" ".join(words[k] for k in keep))
    return "\n".join(lines) + "\n", steps, procs


def sha(data):
    return hashlib.sha256(data if isinstance(data, bytes) else data.encode()).hexdigest()


def launch(gendpde, ranks, script, args, cwd, timeout):
    """Runs `gendpde run SCRIPT ARGS -log none` in `cwd` on `ranks` ranks: (exit code or
    None on timeout, stdout, stderr, wall seconds)."""
    env = dict(os.environ)
    run = ["run", script] + args + ["-log", "none"]
    if ranks == 1:
        command = [gendpde] + run
    else:
        # a session directory of its own per launch (OpenMPI 4.1 fails a launch whose shared
        # one another launch creates at the same moment), at a plain path: OpenMPI reads a
        # comma in it as a list separator (and cleans up the wrong directories)
        session = Path(tempfile.mkdtemp(prefix="gendpde-checksums-ompi-"))
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_mpi_yield_when_idle="1",
                   OMPI_MCA_orte_tmpdir_base=str(session))
        command = ["mpirun", "--oversubscribe", "-np", str(ranks), gendpde] + run
    start = time.monotonic()
    try:
        p = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
        code, out, err = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        code, out, err = None, e.stdout or "", (e.stderr or "") + f"\nERROR: timed out after {timeout} s"
        out = out.decode() if isinstance(out, bytes) else out
        err = err.decode() if isinstance(err, bytes) else err
    wall = time.monotonic() - start
    if ranks != 1:
        shutil.rmtree(session, ignore_errors=True)
    return code, out, err, wall


def error_text(stdout, stderr):
    """The ERROR lines of a failed run (stderr first), in order, duplicates (one per rank)
    dropped."""
    seen, lines = set(), []
    for line in (stderr + "\n" + stdout).splitlines():
        line = line.strip()
        if "ERROR" in line and line not in seen:
            seen.add(line)
            lines.append(line)
    return "\n".join(lines) if lines else "no ERROR line (exit without message)"


def run_scene(name, script, overrides, cap, ranks, gendpde, timeout):
    """The checksum line of the scene on `ranks` ranks, and its wall time."""
    dest = WORK / re.sub(r"[^\w./-]", "_", name) / str(ranks)
    script_name, text = stage(name, script, dest)
    (dest / script_name).write_text(edit(text, cap, overrides))
    args = [a for k, v in overrides for a in ("-var", k, v)]
    wall = 0.0
    if name in PRODUCERS:
        producer = ROOT / PRODUCERS[name]
        pname, ptext = stage(name, producer, dest / "producer")
        for f in (dest / "producer").iterdir():
            shutil.move(str(f), dest / f.name)
        (dest / "producer").rmdir()
        (dest / pname).write_text(edit(ptext, 0, [], final=False))
        code, out, err, w = launch(gendpde, ranks, pname, [], dest, timeout)
        wall += w
        if code != 0:
            return f"{name} {ranks} refused {sha(error_text(out, err))} {sha('')} 0 : producer {pname}: {error_text(out, err).splitlines()[0]}", wall
    code, out, err, w = launch(gendpde, ranks, script_name, args, dest, timeout)
    wall += w
    (dest / "stdout.txt").write_text(out)
    (dest / "stderr.txt").write_text(err)
    rows, steps, procs = thermo(out)
    if code == 0 and procs and procs != {ranks}:
        msg = f"ERROR: asked for {ranks} ranks, the run says {sorted(procs)} procs (a binary without MPI?)"
        return f"{name} {ranks} refused {sha(msg)} {sha(rows)} {steps} : {msg}", wall
    final = dest / "FINAL.dump"
    if code != 0 or not final.exists():
        text = error_text(out, err)
        return f"{name} {ranks} refused {sha(text)} {sha(rows)} {steps} : {text.splitlines()[0]}", wall
    return f"{name} {ranks} {sha(rows)} {sha(final.read_bytes())} {steps}", wall


def read_lines(path):
    lines = {}
    for line in Path(path).read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            words = line.split()
            lines[(words[0], words[1])] = line.rstrip()
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--gendpde", default=str(DEFAULT_GENDPDE), help="the binary to run (default target/release/gendpde)")
    ap.add_argument("--ranks", default="1,3", help="comma-separated rank counts (default 1,3)")
    ap.add_argument("--only", help="comma-separated substrings: only the scenes whose name holds one")
    ap.add_argument("--write", metavar="FILE", help="write the checksum lines to FILE")
    ap.add_argument("--check", metavar="FILE", help="compare with the lines of FILE; exit 1 if any differs")
    ap.add_argument("--timeout", type=float, default=900, help="seconds per run (default 900)")
    ap.add_argument("--list", action="store_true", help="print the scenes and exit")
    args = ap.parse_args()
    gendpde = str(Path(args.gendpde).resolve())
    ranks = [int(r) for r in args.ranks.split(",")]
    wanted = args.only.split(",") if args.only else None
    chosen = {n: s for n, s in scenes().items() if not wanted or any(w in n for w in wanted)}
    if args.list:
        for n, (script, overrides, cap) in chosen.items():
            print(n, script.relative_to(ROOT), f"cap {cap}", " ".join(f"-var {k} '{v}'" for k, v in overrides))
        return 0
    if not Path(gendpde).exists():
        sys.exit(f"no binary at {gendpde} (build it, or pass --gendpde PATH)")
    reference = read_lines(args.check) if args.check else None
    lines, differ, start = [], 0, time.monotonic()
    for name, (script, overrides, cap) in chosen.items():
        for r in ranks:
            line, wall = run_scene(name, script, overrides, cap, r, gendpde, args.timeout)
            lines.append(line)
            key = (name, str(r))
            status = ""
            if reference is not None and key not in reference:
                status = f"not in {args.check}"
            elif reference is not None and reference[key] != line:
                differ += 1
                status = "DIFFERS"
            print(f"{line}  [{wall:.1f} s]" + (f"  {status}" if status else ""), flush=True)
            if status == "DIFFERS":
                print(f"  reference: {reference[key]}", flush=True)
    if reference is not None:
        ran = {(l.split()[0], l.split()[1]) for l in lines}
        for key, line in reference.items():
            in_selection = (not wanted or any(w in key[0] for w in wanted)) and int(key[1]) in ranks
            if in_selection and key not in ran:
                differ += 1
                print(f"missing from this run: {line}")
    if args.write:
        out = Path(args.write)
        if wanted and out.exists():  # --only: replace the lines of the chosen scenes, keep the others
            new = {(l.split()[0], l.split()[1]): l for l in lines}
            old = read_lines(out)
            keys = list(old) + [k for k in new if k not in old]
            lines = [new.get(k, old.get(k)) for k in keys]
        version = subprocess.run([gendpde, "--version"], capture_output=True, text=True).stdout.strip()
        head = ["# scene ranks sha256(thermo rows) sha256(final dump) steps",
                "# or: scene ranks refused sha256(error) sha256(thermo so far) steps : first ERROR line",
                f"# written by scripts/checksums.py --ranks {args.ranks} with {version}"]
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text("\n".join(head + lines) + "\n")
        print(f"wrote {out}")
    print(f"{len(lines)} lines in {time.monotonic() - start:.0f} s" + (f", {differ} differ" if reference is not None else ""))
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
