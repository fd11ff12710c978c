#!/usr/bin/env python3
"""LAMMPS's DPD-BASIC example in.dpd (scripts/lammps/in.dpd-basic, verbatim) in gendpde and
in the reference LAMMPS over several seeds: the mean temp and press of steps 1000-5000 of
each run, then the mean over seeds with its standard error (seed-to-seed spread / sqrt(n))
and the difference of the two codes in combined standard errors.

    python3 scripts/lammps/in_dpd_seeds.py [NSEEDS] [GENDPDE] [LMP]

Standard library only. Each run has its own seeds: the four seeds of the script are
replaced by fixed functions of the seed index (so the script text is otherwise unchanged)."""
import math, os, re, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
nseeds = int(sys.argv[1]) if len(sys.argv) > 1 else 8
gendpde = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")), "release", "gendpde")
lmp = sys.argv[3] if len(sys.argv) > 3 else "/work/shared/lammps/lmp"
script = open(os.path.join(HERE, "in.dpd-basic")).read()


def seeded(k):
    s = script
    for old in ["12456", "13245", "3854262", "68768932"]:
        s = s.replace(old, str(int(old) + 7919 * (k + 1)))
    return s


def averages(out):
    rows = []
    for line in out.splitlines():
        w = line.split()
        if len(w) == 4 and re.fullmatch(r"\d+", w[0]) and 1000 <= int(w[0]) <= 5000:
            rows.append([float(x) for x in w[2:]])
    assert len(rows) == 41, f"expected 41 thermo rows, got {len(rows)}:\n{out[-2000:]}"
    return [sum(r[c] for r in rows) / len(rows) for c in range(2)]


def run(cmd, k):
    with tempfile.TemporaryDirectory() as d:
        open(os.path.join(d, "in.dpd"), "w").write(seeded(k))
        out = subprocess.run(cmd + ["-in", "in.dpd", "-log", "none"], cwd=d, capture_output=True, text=True)
        assert out.returncode == 0, out.stderr[-2000:] + out.stdout[-2000:]
        return averages(out.stdout)


def mean_se(xs):
    m = sum(xs) / len(xs)
    return m, math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1) / len(xs))


res = {"gendpde": [run([gendpde], k) for k in range(nseeds)], "LAMMPS": [run([lmp], k) for k in range(nseeds)]}
print(f"in.dpd (LAMMPS examples/PACKAGES/dpd-basic/dpd), {nseeds} seeds, steps 1000-5000:")
for c, name in enumerate(["temp", "press"]):
    (mg, sg), (ml, sl) = mean_se([r[c] for r in res["gendpde"]]), mean_se([r[c] for r in res["LAMMPS"]])
    z = (mg - ml) / math.hypot(sg, sl)
    print(f"  {name:5s}  gendpde {mg:.4f} +- {sg:.4f}   LAMMPS {ml:.4f} +- {sl:.4f}   difference {z:+.2f} combined SE")
