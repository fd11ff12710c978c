#!/usr/bin/env python3
"""The speed-accuracy table: for a vdW and an LJ GenDPDE scene (rho = 0.5, T = 1.5,
N = 14^3, rc = 4, C_V = 60, gamma = 4.5, kappa = 1), the relative energy drift rate and
the errors of <P> and <T_int> against a small-dt reference, beside atom-steps/s, over the
time step and over the options that trade one for the other; and for LAMMPS's classic
DPDE (pair dpd/fdt/energy, rho = 3, N = 14^3, a0 25, sigma 3, kappa 1, C_V 10) the
Shardlow scheme against velocity Verlet (fix dpd/energy) over dt. Writes the table
between the accuracy markers of docs/PERFORMANCE.md (a run of some scenes replaces their
rows only) and the plot docs/speed-accuracy.png.

    scripts/bench/accuracy.sh            # everything (about 40 minutes on one core)
    python3 scripts/bench/accuracy.py vdw  # only the vdW rows
    python3 scripts/bench/accuracy.py dpde  # only the classic DPDE rows (a few minutes)
    python3 scripts/bench/accuracy.py --plot  # only the figure, from the table in PERFORMANCE.md

Every run equilibrates 300 steps at dt = 0.01 from the same lattice and seed, then runs
`TIME` (default 10) time units with thermo every 0.05; errors are differences of time
averages, with the standard error of the reference's mean (10 blocks) as the noise floor.
Environment: GENDPDE, TIME.
"""
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))  # the gendpde package
import gendpde  # noqa: E402
GENDPDE = os.environ.get("GENDPDE", str(ROOT / "target" / "release" / "gendpde"))
TIME = float(os.environ.get("TIME", "10"))
TABLE = "table 0.3 8.0 121 0.0 1.2 129"
MODELS = {"vdw": "vdw 60.0 2.4682 1.4142 excess", "lj": "lj 60.0", "dpde": None}
BEGIN, END = "<!-- accuracy:begin -->", "<!-- accuracy:end -->"
FIGURE = ROOT / "docs" / "speed-accuracy.png"

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
"""

# both scenes: 300 steps at dt 0.01 from the lattice, then the measured run
RUNS = """timestep 0.01
thermo 100
run 300
reset_timestep 0
timestep {dt}
thermo {every}
run {steps}
"""
TEMPLATE += RUNS

# classic DPDE (LAMMPS's pairwise style); <T_int> is compute dpd's harmonic-mean theta
DPDE_TEMPLATE = """units lj
atom_style dpd
comm_modify vel yes
lattice sc 3.0
region box block 0 14 0 14 0 14
create_box 1 box
create_atoms 1 box
mass 1 1.0
velocity all create 1.0 87287 dist gaussian
set group all dpd/theta 1.0
pair_style dpd/fdt/energy 1.0 87287
pair_coeff 1 1 25.0 3.0 1.0 1.0
{integrate}
fix cv all eos/cv 10.0
neighbor 0.3 bin
neigh_modify every 1 delay 0 check yes
compute dpdU all dpd
variable etot equal pe+ke+c_dpdU[1]+c_dpdU[2]
thermo_style custom step time temp press v_etot c_dpdU[4]
thermo_modify norm no format float %.15g
"""
# the thermo columns of the energy and of <T_int>
DPDE_TEMPLATE += RUNS
COLUMNS = {"vdw": ("TotEng", "Tint"), "lj": ("TotEng", "Tint"), "dpde": ("v_etot", "c_dpdU[4]")}

INTEGRATORS = {
    "eSSA": "fix rev all nve/gendpde\nfix ssa all shardlow heat original",
    "eSSA, isentropic step": "fix rev all nve/gendpde work isentropic\nfix ssa all shardlow heat original",
    "VV + Euler": "fix vv all vv/euler heat original",
    "Shardlow": "fix ssa all shardlow\nfix nve all nve",
    "VV": "fix energy all dpd/energy\nfix nve all nve",
}


def options(model):
    """(label, settings) rows: the dt scan with the defaults, then one option at a time
    (classic DPDE: the dt scans of the Shardlow and the velocity-Verlet scheme)."""
    if model == "dpde":
        base = {"model": model, "integrate": "Shardlow"}
        rows = [(f"dt {dt:g}" if dt == 0.0025 else f"Shardlow dt {dt:g}", {**base, "dt": dt}) for dt in (0.0025, 0.005, 0.01, 0.02, 0.04)]
        return rows + [(f"VV dt {dt:g}", {**base, "integrate": "VV", "dt": dt}) for dt in (0.0025, 0.005, 0.01, 0.02)]
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
    steps = int(round(TIME / opt["dt"]))
    every = max(1, int(round(0.05 / opt["dt"])))
    if opt["model"] == "dpde":
        text = DPDE_TEMPLATE.format(integrate=INTEGRATORS[opt["integrate"]], dt=opt["dt"], every=every, steps=steps)
    else:
        eos = MODELS[opt["model"]] + (f" {TABLE}" if opt["table"] else "")
        text = TEMPLATE.format(rc=opt["rc"], weight=opt["weight"], eos=eos, integrate=INTEGRATORS[opt["integrate"]],
                               skin=opt["skin"], dt=opt["dt"], every=every, steps=steps)
    with tempfile.TemporaryDirectory() as d:
        Path(d, "in.acc").write_text(text)
        try:
            r = gendpde.run(Path(d, "in.acc"), log=None, cwd=d, binary=GENDPDE)
        except gendpde.GendpdeError as e:
            return None, e.stdout[-300:] + e.stderr[-300:]
    log = r.logs[-1]
    energy, tint_column = COLUMNS[opt["model"]]
    t, e = log["Time"].to_numpy(), log[energy].to_numpy()
    drift = np.polyfit(t, (e - e[0]) / abs(e[0]), 1)[0]
    blocks = np.array_split(np.arange(len(log)), 10)
    sem = lambda x: float(np.std([x[b].mean() for b in blocks], ddof=1) / np.sqrt(10))
    p, tint = log["Press"].to_numpy(), log[tint_column].to_numpy()
    return {"drift": float(drift), "P": float(p.mean()), "P_sem": sem(p), "Tint": float(tint.mean()),
            "Tint_sem": sem(tint), "rate": log.attrs["atom_steps_per_s"], "wall": r.wall_s}, None


def table_rows(text):
    """(rows, noise) of the accuracy table in `text`: rows are dicts with model, label,
    drift, dP and dT (%), rate; noise maps a model to its (P, T_int) noise floor (%)."""
    rows, noise = [], {}
    for line in text.split(BEGIN, 1)[1].split(END, 1)[0].splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 6 or cells[0] not in MODELS:
            continue
        model, label, drift, dp, dt_, rate = cells
        if label.startswith("noise floor"):
            noise[model] = (float(dp), float(dt_))
        elif rate:
            rows.append({"model": model, "label": label, "drift": float(drift), "dP": float(dp), "dT": float(dt_),
                         "rate": float(rate)})
    return rows, noise


def pareto(points):
    """The points no other point beats in both speed (higher) and error (lower), by speed."""
    front = [p for p in points if not any(q[0] >= p[0] and q[1] <= p[1] and q != p for q in points)]
    return sorted(front)


def figure(rows, noise, path):
    """Error against speed, one panel per error, one colour per setting, one marker per scene."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    labels = list(dict.fromkeys(r["label"] for r in rows))
    colours = {l: (plt.cm.tab20 if k < 20 else plt.cm.tab20b)(k % 20) for k, l in enumerate(labels)}
    floors = {"vdw": ":", "lj": "-.", "dpde": (0, (1, 4))}
    marks = {"vdw": ("o", "vdW (filled)"), "lj": ("s", "LJ (open)"), "dpde": ("^", "classic DPDE (filled)")}
    panels = [("drift", "|relative energy drift rate| [1/τ, reduced units]", "log", None, "energy conservation"),
              ("dP", "|<P> error| [%]", "symlog", 0, "pressure, against the dt 0.0025 reference"),
              ("dT", "|<T_int> error| [%]", "symlog", 1, "internal temperature, against dt 0.0025")]
    fig, axes = plt.subplots(1, 3, figsize=(18, 6.4))
    for ax, (key, ylabel, scale, floor, title) in zip(axes, panels):
        for model, (mark, _) in marks.items():
            # the reference is the zero of the errors: shown on the drift panel only
            mine = [r for r in rows if r["model"] == model and (key == "drift" or r["label"] != "dt 0.0025")]
            pts = [(r["rate"], abs(r[key])) for r in mine]
            for r in mine:
                c = colours[r["label"]]
                ax.plot(r["rate"], abs(r[key]), mark, ms=8, color=c, mfc="none" if model == "lj" else c, mew=1.6)
            if not pts:
                continue
            front = pareto(pts)
            ax.plot(*zip(*front), {"vdw": "-", "lj": "--"}.get(model, ":"), color="0.4", lw=1, zorder=0)
            if floor is not None and model in noise:
                ax.axhline(noise[model][floor], color="0.4", ls=floors[model], lw=1)
        ax.set_xscale("log")
        ax.set_xticks([2e4, 5e4, 1e5, 2e5, 5e5, 1e6, 2e6], ["20k", "50k", "100k", "200k", "500k", "1M", "2M"])
        ax.set_xticks([], minor=True)
        ax.set_title(title, fontsize=10)
        if scale == "symlog":
            ax.set_yscale("symlog", linthresh=0.01 if key == "dT" else 0.1)
            ax.set_ylim(0, 2 * max(abs(r[key]) for r in rows))
        else:
            ax.set_yscale("log")
        ax.set_xlabel("speed [atom-steps/s, one core]")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3, which="both" if scale == "log" else "major")
    settings = [Line2D([], [], ls="", marker="o", ms=8, color=colours[l], label=l) for l in labels]
    scenes = [Line2D([], [], ls="", marker=m, ms=8, color="k", mfc="none" if model == "lj" else "k", label=name)
              for model, (m, name) in marks.items()]
    lines = [Line2D([], [], color="0.4", ls="-", label="Pareto front, vdW"),
             Line2D([], [], color="0.4", ls="--", label="Pareto front, LJ"),
             Line2D([], [], color="0.4", ls=":", lw=1, label="Pareto front, classic DPDE"),
             Line2D([], [], color="0.4", ls=":", label="noise floor (reference SEM), vdW"),
             Line2D([], [], color="0.4", ls="-.", label="noise floor, LJ"),
             Line2D([], [], color="0.4", ls=floors["dpde"], label="noise floor, classic DPDE")]
    fig.legend(handles=settings + scenes + lines, loc="center right", fontsize=7, title="setting (colour), scene (marker)",
               title_fontsize=8)
    fig.suptitle("speed against accuracy, N = 2744; GenDPDE defaults: dt 0.01, rc 4, quadratic weight, skin 0.4, eSSA; "
                 "classic DPDE: rho 3, rc 1")
    fig.tight_layout(rect=(0, 0, 0.84, 1))
    fig.savefig(path, dpi=90)


def main():
    if sys.argv[1:] == ["--plot"]:
        figure(*table_rows((ROOT / "docs" / "PERFORMANCE.md").read_text()), FIGURE)
        return
    wanted = sys.argv[1:] or list(MODELS)
    table = []
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
        noise = f"| {model} | noise floor (reference SEM) | | {100 * ref['P_sem'] / abs(ref['P']):.3f} | {100 * ref['Tint_sem'] / ref['Tint']:.3f} | |"
        table.append(noise)

    head = ["scene", "setting (others: dt 0.01, rc 4, quadratic, skin 0.4, eSSA; vdW analytic, LJ tabulated; dpde: classic DPDE, rho 3, rc 1)",
            "energy drift rate (1/time)", "<P> error %", "<T_int> error %", "atom-steps/s"]
    text = "\n".join([f"Generated by `scripts/bench/accuracy.sh` (N = 2744, {TIME:g} time units per run, one core; "
                      "reference: dt = 0.0025).", "", "| " + " | ".join(head) + " |", "|" + "---|" * len(head), *table])
    print(text)
    doc = ROOT / "docs" / "PERFORMANCE.md"
    s = doc.read_text()
    if BEGIN in s:
        # the rows of the scenes not run now stay as they are
        kept = [l for l in s.split(BEGIN, 1)[1].split(END, 1)[0].splitlines()
                if l.startswith("| ") and l.split("|")[1].strip() in MODELS and l.split("|")[1].strip() not in wanted]
        rows = sorted(kept + table, key=lambda l: list(MODELS).index(l.split("|")[1].strip()))
        text = "\n".join(text.splitlines()[:4] + rows)
        s = s.split(BEGIN)[0] + BEGIN + "\n" + text + "\n" + END + s.split(END, 1)[1]
        doc.write_text(s)
    figure(*table_rows(BEGIN + "\n" + text + "\n" + END), FIGURE)


if __name__ == "__main__":
    main()
