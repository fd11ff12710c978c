#!/usr/bin/env python3
"""The speed-accuracy table: for a vdW and an LJ GenDPDE scene (rho = 0.5, T = 1.5,
N = 14^3, rc = 4, C_V = 60, gamma = 4.5, kappa = 1), the relative energy drift rate and
the errors of <P> and <T_int> against a small-dt reference, beside atom-steps/s, over the
time step and over the options that trade one for the other. Writes the table between
the accuracy markers of docs/PERFORMANCE.md and the plot docs/speed-accuracy.png.

    scripts/bench/accuracy.sh            # everything (about 40 minutes on one core)
    python3 scripts/bench/accuracy.py vdw  # only the vdW rows

Every run equilibrates 300 steps at dt = 0.01 from the same lattice and seed, then runs
`TIME` (default 10) time units with thermo every 0.05; errors are differences of time
averages, with the standard error of the reference's mean (10 blocks) as the noise floor.
Environment: GENDPDE, TIME.
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
GENDPDE = os.environ.get("GENDPDE", str(ROOT / "target" / "release" / "gendpde"))
TIME = float(os.environ.get("TIME", "10"))
TABLE = "table 0.3 8.0 121 0.0 1.2 129"
MODELS = {"vdw": "vdw 60.0 2.4682 1.4142 excess", "lj": "lj 60.0"}

TEMPLATE = """units lj
atom_style gendpde
lattice sc 0.5
region box block 0 14 0 14 0 14
create_box 1 box
create_atoms 1 box
mass 1 1.0
velocity all create 1.5 87287 dist gaussian
set group all theta 1.5
pair_style gendpde {rc} 87287 weight {weight}
pair_coeff * * 4.5 1.0 {rc} {rc}
fix eos all eos/{eos}
{integrate}
neighbor {skin} bin
neigh_modify every 1 delay 0 check yes
thermo_style custom step time temp tint press etotal
thermo_modify format float %.15g
timestep 0.01
thermo 100
run 300
reset_timestep 0
timestep {dt}
thermo {every}
run {steps}
"""

INTEGRATORS = {
    "eSSA": "fix rev all nve/gendpde\nfix ssa all shardlow heat original",
    "eSSA, isentropic step": "fix rev all nve/gendpde work isentropic\nfix ssa all shardlow heat original",
    "VV + Euler": "fix vv all vv/euler heat original",
}


def options(model):
    """(label, settings) rows: the dt scan with the defaults, then one option at a time."""
    # the LJ rows run through the table (the analytic model costs 5x per step): its own
    # row measures the table against the analytic model
    base = {"model": model, "dt": 0.01, "rc": 4.0, "weight": "quadratic", "skin": 0.4, "integrate": "eSSA", "table": model == "lj"}
    rows = [(f"dt {dt:g}", {**base, "dt": dt}) for dt in (0.0025, 0.005, 0.01, 0.02, 0.05, 0.1)]
    rows += [
        ("isentropic reversible step", {**base, "integrate": "eSSA, isentropic step"}),
        ("VV + Euler (dt 0.01)", {**base, "integrate": "VV + Euler"}),
        ("VV + Euler (dt 0.005)", {**base, "integrate": "VV + Euler", "dt": 0.005}),
        ("analytic EOS" if base["table"] else "tabulated EOS", {**base, "table": not base["table"]}),
        ("rc 3", {**base, "rc": 3.0}),
        ("Lucy weight", {**base, "weight": "lucy"}),
        ("skin 0.2", {**base, "skin": 0.2}),
        ("skin 0.3", {**base, "skin": 0.3}),
    ]
    return rows


def run(opt):
    eos = MODELS[opt["model"]] + (f" {TABLE}" if opt["table"] else "")
    steps = int(round(TIME / opt["dt"]))
    text = TEMPLATE.format(rc=opt["rc"], weight=opt["weight"], eos=eos, integrate=INTEGRATORS[opt["integrate"]],
                           skin=opt["skin"], dt=opt["dt"], every=max(1, int(round(0.05 / opt["dt"]))), steps=steps)
    with tempfile.TemporaryDirectory() as d:
        Path(d, "in.acc").write_text(text)
        start = time.time()
        out = subprocess.run([GENDPDE, "run", "in.acc", "-log", "none"], cwd=d, capture_output=True, text=True)
        wall = time.time() - start
    if out.returncode != 0:
        return None, out.stdout[-300:] + out.stderr[-300:]
    lines = out.stdout.splitlines()
    loop = [l for l in lines if l.startswith("Loop time")][-1].split()
    rate = int(loop[-2]) * int(loop[8]) / float(loop[3])
    head = [k for k, l in enumerate(lines) if l.split()[:1] == ["Step"]][-1]
    rows = []
    for l in lines[head + 1:]:
        w = l.split()
        if len(w) != 6:
            break
        rows.append([float(x) for x in w])
    a = np.array(rows)
    t, e = a[:, 1], a[:, 5]
    drift = np.polyfit(t, (e - e[0]) / abs(e[0]), 1)[0]
    blocks = np.array_split(np.arange(len(a)), 10)
    sem = lambda x: float(np.std([x[b].mean() for b in blocks], ddof=1) / np.sqrt(10))
    return {"drift": float(drift), "P": float(a[:, 4].mean()), "P_sem": sem(a[:, 4]), "Tint": float(a[:, 3].mean()),
            "Tint_sem": sem(a[:, 3]), "rate": rate, "wall": wall}, None


def main():
    wanted = sys.argv[1:] or list(MODELS)
    table, plot = [], {}
    for model in wanted:
        results = []
        for label, opt in options(model):
            r, err = run(opt)
            print(model, label, r or err, flush=True)
            results.append((label, r, err))
        ref = next(r for l, r, _ in results if l == "dt 0.0025")
        for label, r, err in results:
            if r is None:
                table.append(f"| {model} | {label} | not available: {err.strip().splitlines()[-1] if err.strip() else 'failed'} | | | |")
                continue
            dp = (r["P"] - ref["P"]) / abs(ref["P"])
            dt_ = (r["Tint"] - ref["Tint"]) / ref["Tint"]
            table.append(f"| {model} | {label} | {r['drift']:.2e} | {100 * dp:+.3f} | {100 * dt_:+.3f} | {r['rate']:.3g} |")
            plot.setdefault(model, []).append((label, r["rate"], abs(r["drift"]), abs(dp)))
        noise = f"| {model} | noise floor (reference SEM) | | {100 * ref['P_sem'] / abs(ref['P']):.3f} | {100 * ref['Tint_sem'] / ref['Tint']:.3f} | |"
        table.append(noise)

    head = ["scene", "setting (others: dt 0.01, rc 4, quadratic, skin 0.4, eSSA; vdW analytic, LJ tabulated)",
            "energy drift rate (1/time)", "<P> error %", "<T_int> error %", "atom-steps/s"]
    text = "\n".join([f"Generated by `scripts/bench/accuracy.sh` (N = 2744, {TIME:g} time units per run, one core; "
                      "reference: dt = 0.0025).", "", "| " + " | ".join(head) + " |", "|" + "---|" * len(head), *table])
    print(text)
    doc = ROOT / "docs" / "PERFORMANCE.md"
    s = doc.read_text()
    b, e = "<!-- accuracy:begin -->", "<!-- accuracy:end -->"
    if b in s and set(wanted) == set(MODELS):
        s = s.split(b)[0] + b + "\n" + text + "\n" + e + s.split(e, 1)[1]
        doc.write_text(s)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for (model, pts), mark in zip(plot.items(), "os"):
        for label, rate, drift, dp in pts:
            axes[0].loglog(rate, max(drift, 1e-12), mark, mfc="none" if model == "lj" else None)
            axes[0].annotate(f"{model}: {label}", (rate, max(drift, 1e-12)), fontsize=6)
            axes[1].semilogx(rate, 100 * dp, mark, mfc="none" if model == "lj" else None)
            axes[1].annotate(f"{model}: {label}", (rate, 100 * dp), fontsize=6)
    axes[0].set_xlabel("atom-steps/s")
    axes[0].set_ylabel("|energy drift rate|")
    axes[1].set_xlabel("atom-steps/s")
    axes[1].set_ylabel("|<P> error| %")
    fig.suptitle("speed against accuracy (open: LJ, filled: vdW)")
    fig.tight_layout()
    fig.savefig(ROOT / "docs" / "speed-accuracy.png", dpi=80)


if __name__ == "__main__":
    main()
