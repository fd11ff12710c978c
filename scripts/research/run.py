#!/usr/bin/env python3
"""Run real LAMMPS DPD input scripts from public research repositories in the
reference LAMMPS and in gendpde, side by side, and print a markdown table.

    python3 scripts/research/run.py [--gendpde BIN] [--lammps BIN] [--only NAME,...]
                                    [--timeout S] [--json OUT]

Each scene is a folder of scripts/research/ (input unchanged, its include files,
SOURCE.md). Scenes that run too long are run from a shortened copy beside the
original (IN.short, the change in SOURCE.md); -var values are passed only where
the script reads them from the command line. Every program runs in its own
scratch copy of the folder, so nothing is written into the repository.

Recorded per scene: does LAMMPS run it (exit 0 and a completed run), does
`gendpde check` pass, does `gendpde run` run it, gendpde's first error line, and
where both ran, the thermo columns both print compared row by row at the same
step: the largest relative difference |a-b|/max(|a|,|b|,1e-300) over the first
row (the initial state, which is deterministic: same lattice, same velocity
seed; except the virial columns, Press and its components, which already hold the
DPD random force, reported apart) and over all rows. Values are compared as each program prints them (no
thermo_modify format is added), so ~1e-6 is the floor of agreement.

"agrees": deterministic scenes (no random force: T = 0 or sigma = 0) need every
shared row within 1e-5; stochastic scenes (each program draws its own random
numbers, trajectories diverge after step 0) need the first row within 1e-5 and
every later row within 10 % (a sanity bound, not a statistical test; see
scripts/lammps/examples.py for averaged comparisons).
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# name, folder, input file run, -var pairs, deterministic, short note
SCENES = [
    ("poiseuille-reverse-3d", "poiseuille-reverse", "in.dpd.short", [], False,
     "reverse Poiseuille, addforce v_fy, ave/chunk, stress/atom, 4608 atoms, SI units"),
    ("poiseuille-reverse-2d", "poiseuille-reverse", "in.dpd.short", [("ndim", "2")], False,
     "same in 2D (-var ndim 2, as the script's header says), enforce2d"),
    ("dpd2d-ave-spatial-3d", "dpd2d-ave-spatial", "in.dpd.short", [], False,
     "reverse Poiseuille, fix ave/spatial, `communicate`"),
    ("dpd2d-ave-spatial-2d", "dpd2d-ave-spatial", "in.dpd.short", [("ndim", "2")], False,
     "same in 2D (-var ndim 2)"),
    ("dpd3d-ave-spatial", "dpd3d-ave-spatial", "in.dpd.3d.short", [], False,
     "3D reverse Poiseuille, ave/spatial, thermo round(0.1*ntime)"),
    ("fedosov-poiseuille", "fedosov-poiseuille", "in.fedosov.short", [], False,
     "Fedosov 2010 parameters, pair_style dpd ... vfd yes vfc no vfr no (patched LAMMPS), 5-arg pair_coeff"),
    ("fedosov-solvent-2d", "fedosov-solvent-2d", "in.solvent", [], False,
     "2D equilibrium solvent, temp/profile, stress/atom virial, ave/spatial"),
    ("fedosov-couette-2d", "fedosov-couette-2d", "in.couette.short", [], False,
     "2D Couette between particle walls: prism box, boundary p f p, wall/reflect, aveforce, image dump"),
    ("dpd-solvent-trap-3d", "dpd-solvent-trap", "in.dpd.short", [], False,
     "solvent + one heavy particle in a harmonic trap (addforce on a group)"),
    ("dpd-solvent-trap-2d", "dpd-solvent-trap", "in.dpd.short", [("ndim", "2")], False,
     "same in 2D (-var ndim 2)"),
    ("dpd2d-wall", "dpd2d-wall", "in.dpd",
     [("fwallx", "1e-3"), ("id", "t"), ("ntime", "200"), ("savetime", "100000")], False,
     "2D channel between frozen walls: boundary p f p, wall/reflect, aveforce, setforce, nve on a group"),
    ("two-atoms", "two-atoms", "in.twoatoms", [], True,
     "two atoms, T = 0 (no random force), 10000 steps"),
    ("two-atoms-setforce", "two-atoms-setforce", "in.two-one-fix", [], True,
     "two atoms, one held by setforce, gamma = 0, 5-arg pair_coeff (patched LAMMPS)"),
    ("two-atoms-msd", "two-atoms-msd", "in.msd", [], True,
     "two atoms, compute msd, fix print to a file"),
    ("shardlow-dpdext-fdt", "shardlow-dpdext-fdt", "in.water.txt.short", [], False,
     "pair_style dpdext/fdt (the authors' LAMMPS extension) + fix shardlow, create_atoms random"),
    ("mdpd-droplet", "mdpd-droplet", "in.mdpd.short", [], False,
     "mDPD droplet: atom_style mdpd, hybrid/overlay mdpd/rhosum mdpd, fix mvv/dpd, CRLF line ends"),
    ("edpd-heat", "edpd-heat", "in.edpd.short", [], False,
     "eDPD heat conduction: edpd/source cuboid, chunk/atom + ave/chunk of edpd/temp/atom, CRLF line ends"),
    ("bilayer-pressure", "bilayer-pressure", "pressure.lmps", [], False,
     "lipid bilayer: package gpu, atom_style full, kspace, dpd/coul/slater/long/gpu, nph aniso"),
    ("nips-membrane", "nips-membrane", "in.dpd", [], False,
     "membrane formation: atom_style bond, read_data (file not published), 3.3 M atoms"),
]

# Not a research script: a small lj DPD fluid written for this harness, to check that the
# comparison path works (both programs run it). Run with --selftest; never counted.
SELFTEST = [
    ("selftest", "selftest", "in.selftest", [], False,
     "harness self-test: 4x4x4 fcc DPD fluid, 50 steps, then 20 steps with T = 0 and gamma = 0"),
]

# Columns holding the virial: with the DPD random force already in the step-0 forces, they
# differ between the programs from the first row on (each draws its own random numbers).
VIRIAL = re.compile(r"^(Press|P[xyz][xyz]|c_\w*press\w*(\[\S*\])?|v_p\w*)$", re.I)

NUM = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^[-+]?(nan|inf)$", re.I)


def thermo_blocks(text):
    """Thermo tables in LAMMPS's layout: a header line starting with `Step`,
    numeric rows, ended by `Loop time` or any non-numeric line."""
    blocks, cur, header = [], None, None
    for line in text.splitlines():
        words = line.split()
        if words and words[0] == "Step" and len(words) > 1 and not NUM.match(words[1]):
            header, cur = words, []
            blocks.append((header, cur))
            continue
        if cur is not None:
            if len(words) == len(header) and all(NUM.match(w) for w in words):
                cur.append([float(w) for w in words])
            else:
                cur = None
    return [(h, r) for h, r in blocks if r]


def run(cmd, cwd, timeout):
    t0 = time.time()
    try:
        p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout)
        return p.returncode, p.stdout, p.stderr, time.time() - t0
    except subprocess.TimeoutExpired as e:
        out = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
        err = e.stderr.decode() if isinstance(e.stderr, bytes) else (e.stderr or "")
        return "timeout", out, err, time.time() - t0


def first_error(out, err):
    for text in (err, out):
        for line in text.splitlines():
            s = line.strip()
            if not s or s.startswith("WARNING") or s.startswith("warning"):
                continue
            if re.search(r"error|unsupported|unknown|not supported|expected|panick", s, re.I):
                return s
    for line in err.splitlines():
        if line.strip():
            return line.strip()
    return ""


def lammps_error(out):
    for line in out.splitlines():
        if line.startswith("ERROR"):
            return line.strip()
    return ""


ERR_AT = re.compile(r"ERROR: ([^:\s]+):(\d+): (.*)")


def probe(gendpde, inp, gv, cdir, timeout, limit=12):
    """What stands behind the first failure: comment out the line `gendpde check`
    names (with its & continuation lines) and check again, up to `limit` times.
    Indicative only: a removed line can make later lines fail (undefined
    variables, groups) or pass for the wrong reason."""
    found = []
    for _ in range(limit):
        rc, out, err, _ = run([gendpde, "check", inp] + gv, cdir, timeout)
        if rc == 0:
            found.append(("", "", "check passes"))
            break
        msg = first_error(out, err)
        m = ERR_AT.search(msg)
        if not m:
            found.append(("", "", msg))
            break
        fname, lineno, what = m.group(1), int(m.group(2)), m.group(3)
        path = os.path.join(cdir, fname)
        if not os.path.exists(path):
            found.append((fname, lineno, what))
            break
        lines = open(path, newline="").read().split("\n")
        i = lineno - 1
        if i >= len(lines) or lines[i].lstrip().startswith("#"):
            found.append((fname, lineno, what))
            break
        found.append((fname, lineno, what))
        while True:
            cont = lines[i].rstrip("\r").rstrip().endswith("&")
            lines[i] = "#" + lines[i]
            i += 1
            if not cont or i >= len(lines):
                break
        open(path, "w", newline="").write("\n".join(lines))
    return found


def rel(a, b):
    if math.isnan(a) or math.isnan(b):
        return 0.0 if (math.isnan(a) and math.isnan(b)) else math.inf
    d = abs(a - b)
    return 0.0 if d == 0 else d / max(abs(a), abs(b), 1e-300)


def compare(lb, gb):
    """Row-by-row comparison of the thermo tables, run by run, at equal steps."""
    res = {"runs": min(len(lb), len(gb)), "runs_lammps": len(lb), "runs_gendpde": len(gb),
           "columns": [], "rows": 0, "first": 0.0, "first_virial": 0.0, "max": 0.0, "worst": ""}
    cols = None
    for (lh, lr), (gh, gr) in zip(lb, gb):
        shared = [c for c in lh if c in gh and c != "Step"]
        cols = shared if cols is None else [c for c in cols if c in shared]
        gsteps = {row[gh.index("Step")]: row for row in gr}
        first = True
        for row in lr:
            step = row[lh.index("Step")]
            if step not in gsteps:
                continue
            grow = gsteps[step]
            res["rows"] += 1
            for c in shared:
                r = rel(row[lh.index(c)], grow[gh.index(c)])
                if first and res["rows"] == 1:
                    k = "first_virial" if VIRIAL.match(c) else "first"
                    res[k] = max(res[k], r)
                if r > res["max"]:
                    res["max"] = r
                    res["worst"] = f"{c} at step {int(step)}: {row[lh.index(c)]:.6g} vs {grow[gh.index(c)]:.6g}"
            first = False
    res["columns"] = cols or []
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--gendpde", default=os.path.join(ROOT, "target/release/gendpde"))
    ap.add_argument("--lammps", default="/work/shared/lammps/lmp")
    ap.add_argument("--only", default="", help="comma-separated scene names")
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--json", default="", help="also write the results as JSON")
    ap.add_argument("--keep", action="store_true", help="keep the scratch folders")
    ap.add_argument("--selftest", action="store_true", help="run only the harness self-test scene")
    a = ap.parse_args()
    gendpde = os.path.abspath(a.gendpde)
    only = set(s for s in a.only.split(",") if s)
    results = []
    for name, folder, inp, vars_, det, note in (SELFTEST if a.selftest else SCENES):
        if only and name not in only:
            continue
        src = os.path.join(HERE, folder)
        r = {"name": name, "folder": folder, "input": inp, "vars": vars_, "deterministic": det, "note": note}
        scratch = tempfile.mkdtemp(prefix=f"research-{name}-")
        ldir, gdir, cdir = (os.path.join(scratch, k) for k in ("lammps", "gendpde", "check"))
        for d in (ldir, gdir, cdir):
            shutil.copytree(src, d)
        lv = sum((["-var", k, v] for k, v in vars_), [])
        gv = sum((["--var", k, v] for k, v in vars_), [])
        # the screen (stdout) carries everything, also after a script's own `log` command
        rc, out, err, dt = run([a.lammps, "-in", inp, "-log", "none"] + lv, ldir, a.timeout)
        log = out
        lb = thermo_blocks(log)
        r["lammps_rc"], r["lammps_s"] = rc, round(dt, 1)
        r["lammps_runs"] = rc == 0 and "Total wall time" in (log + out)
        r["lammps_error"] = lammps_error(log + "\n" + out + "\n" + err) if not r["lammps_runs"] else ""
        rc, out, err, _ = run([gendpde, "check", inp] + gv, cdir, a.timeout)
        r["check_passes"] = rc == 0
        r["check_error"] = "" if rc == 0 else first_error(out, err)
        if rc == "timeout":
            r["check_error"] = "timeout"
        r["blockers"] = probe(gendpde, inp, gv, cdir, a.timeout) if rc not in (0, "timeout") else []
        rc, out, err, dt = run([gendpde, "run", inp, "--log", "none"] + gv, gdir, a.timeout)
        gb = thermo_blocks(out)
        r["gendpde_rc"], r["gendpde_s"] = rc, round(dt, 1)
        r["gendpde_runs"] = rc == 0
        r["gendpde_error"] = "" if rc == 0 else ("timeout" if rc == "timeout" else first_error(out, err))
        r["agrees"] = False
        if r["lammps_runs"] and r["gendpde_runs"]:
            c = compare(lb, gb)
            r["compare"] = c
            if c["rows"] and c["runs_lammps"] == c["runs_gendpde"]:
                if det:
                    r["agrees"] = c["max"] <= 1e-5
                else:
                    r["agrees"] = c["first"] <= 1e-5 and c["max"] <= 0.10
        results.append(r)
        if not a.keep:
            shutil.rmtree(scratch, ignore_errors=True)
        print(f"{name}: lammps {'runs' if r['lammps_runs'] else 'fails'} ({r['lammps_s']} s), "
              f"check {'passes' if r['check_passes'] else 'fails'}, "
              f"gendpde {'runs' if r['gendpde_runs'] else 'fails'} ({r['gendpde_s']} s)"
              + (f", agrees {r['agrees']}" if "compare" in r else ""), file=sys.stderr)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=1)
    print(table(results))


def cell(s):
    return s.replace("|", "\\|")


def table(results):
    lines = ["| scene | deterministic | LAMMPS runs | gendpde check | gendpde runs | first gendpde error | shared columns | rows | rel diff first row (virial) / max | agrees |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        c = r.get("compare")
        err = r["gendpde_error"] or r["check_error"]
        lines.append("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |".format(
            r["name"], "yes" if r["deterministic"] else "no",
            "yes" if r["lammps_runs"] else "no: " + cell(r["lammps_error"][:90]),
            "passes" if r["check_passes"] else "fails",
            "yes" if r["gendpde_runs"] else "no",
            "`" + cell(err[:140]) + "`" if err else "",
            " ".join(c["columns"]) if c else "", c["rows"] if c else "",
            f"{c['first']:.1e} ({c['first_virial']:.1e}) / {c['max']:.1e}" if c and c["rows"] else "",
            "yes" if r["agrees"] else ("no" if c else "")))
    n = len(results)
    lines.append("")
    lines.append("scenes {}: LAMMPS runs {}, gendpde check passes {}, gendpde runs {}, both run {}, agree {}".format(
        n, sum(r["lammps_runs"] for r in results), sum(r["check_passes"] for r in results),
        sum(r["gendpde_runs"] for r in results),
        sum(r["lammps_runs"] and r["gendpde_runs"] for r in results), sum(r["agrees"] for r in results)))
    lines.append("")
    lines.append("Probe (`gendpde check` again after commenting out each failing line; indicative):")
    lines.append("")
    for r in results:
        if r.get("blockers"):
            lines.append("- {}: ".format(r["name"]) + "; ".join(
                (f"{f}:{n}: " if f else "") + cell(w[:110]) for f, n, w in r["blockers"]))
    return "\n".join(lines)


if __name__ == "__main__":
    main()
