#!/usr/bin/env python3
"""The LTh argon model (Colella et al., argon paper): Tables 5, 6, 7, 8 and 9, Figs 1-5.

    python3 scripts/validation/lth_argon.py [--n 16] [--scan-n 15] [--full-n 30] [--equil-t 30]
        [--prod-t 10] [--jobs 2] [--only NAME,...]

Runs examples/lth-argon for
- the three liquid cutoffs of Tables 1-4 (Table 5),
- the tuned liquid run of Table 7 (pi00* = 0.1239, R* = 2.1564),
- the supercritical state of Table 9,
- the scans of Fig 4 (tuned liquid: T* +-10 %, c* +-1 % and +-10 %) and Fig 5
  (supercritical: c* +-5 % and +-10 %),
then g(r) from the production snapshots (Figs 1-3), the macroscopic state of eqs 78,
85-91, 99 from the simulated g(r) (Table 6) and from the self-consistent HNC (Table 8)
with `gendpde lth-macro`, and the figure docs/validation/lth_argon.png.

The paper: N = 27000, 1000 t* of velocity rescaling, 2000 t* of NVE (Table 3: up to
6e6 steps). Here: N = n^3 with --n (default 16, the scans --scan-n 15), --equil-t time
units coupled to a heat reservoir at T with timestep 2 dt (the simple cubic start takes
some 20 t* to become the liquid: <n_i> climbs from 0.98 and overshoots), then --prod-t of
NVE at the paper's dt. Each run's numbers are cached in its work directory
(row.json): a rerun only redoes what is missing.
"""
import argparse
import math
import subprocess
from concurrent.futures import ThreadPoolExecutor

import common

LIQUID = {"CV": 12.51, "alpha": 29.345, "kt": 1.0112, "pi00": 0.11606, "theta0": 0.011054, "T": 0.011054}
SUPER = {"CV": 8.56, "alpha": 9.78, "kt": 1.09, "pi00": 0.5211, "theta0": 0.0828, "T": 0.0828,
         "R": 2.1564, "fcut": 1.33, "gamma": 1.05, "kappa": 0.034, "dt": 0.001}
# Tables 2-4: R*, f_cut, gamma*, kappa*, dt*
CUTOFFS = [(1.3365, 1.41, 23.42, 0.0079, 0.0005), (1.6839, 1.35, 7.37, 0.0025, 0.001),
           (2.1564, 1.33, 2.14, 0.00072, 0.001)]
# Table 5 (simulation) and Table 6 (EOS from the simulated g), Table 7, Table 8 (HNC g)
PAPER_T5 = {1.3365: (0.0112, 1.007, 0.121, -0.62), 1.6839: (0.0112, 1.003, 0.116, -0.62),
            2.1564: (0.0111, 1.001, 0.119, -0.63)}
PAPER_T6 = {1.3365: (0.990, 0.137, -0.61), 1.6839: (0.993, 0.126, -0.61), 2.1564: (0.995, 0.123, -0.62)}
PAPER_T7 = (0.0111, 1.000, 0.127, -0.63)
PAPER_T8 = {1.3365: (1.034, 0.169, -0.70), 1.6839: (1.019, 0.148, -0.67), 2.1564: (1.010, 0.136, -0.65)}


def liquid(R, fcut, gamma, kappa, dt, **extra):
    v = dict(LIQUID, R=R, fcut=fcut, gamma=gamma, kappa=kappa, dt=dt)
    v.update(extra)
    return v


def runs(args):
    """(name, group, variables, N cells per side) of every run."""
    out = []
    for R, fcut, gamma, kappa, dt in CUTOFFS:
        out.append((f"liquid_R{R}", "table5", liquid(R, fcut, gamma, kappa, dt), args.n))
    if args.full_n:
        out.append((f"liquid_R{CUTOFFS[2][0]}_N{args.full_n ** 3}", "table5", liquid(*CUTOFFS[2]), args.full_n))
    tuned = liquid(*CUTOFFS[2], pi00=0.1239)
    out.append(("tuned", "table7", tuned, args.n))
    out.append(("supercritical", "table9", dict(SUPER), args.n))
    for f in (0.9, 1.1):
        out.append((f"fig4_T{f}", "fig4", dict(tuned, T=tuned["T"] * f), args.scan_n))
    for f in (0.9, 0.99, 1.01, 1.1):
        out.append((f"fig4_c{f}", "fig4", dict(tuned, c=f), args.scan_n))
    for f in (0.9, 0.95, 1.05, 1.1):
        out.append((f"fig5_c{f}", "fig5", dict(SUPER, c=f), args.scan_n))
    return out


def simulate(name, group, v, n, args):
    wd = common.workdir("lth_argon", f"{name}_n{n}")
    return common.cached(wd, lambda: simulate_in(wd, name, group, v, n, args))


def simulate_in(wd, name, group, v, n, args):
    dt = v["dt"]
    dteq = 2 * dt
    prod_steps = round(args.prod_t / dt)
    variables = dict(v, n=n, dteq=dteq, equil=round(args.equil_t / dteq), steps=prod_steps,
                     every=max(1, prod_steps // 200), dumpevery=max(1, prod_steps // args.frames),
                     bath=v["CV"] * v["T"] ** 2)
    blocks, wall = common.run("lth-argon", variables, wd)
    prod = blocks[-1]
    half = len(prod["Step"]) // 5  # the first fifth of the production run is discarded
    row = {"name": name, "group": group, "N": n ** 3, "vars": v, "equil_t": args.equil_t, "prod_t": args.prod_t,
           "steps": prod_steps, "wall_s": round(wall, 1)}
    for key, col in [("T_kin", "Temp"), ("T_int", "Tint"), ("n", "Nmean"), ("P", "Press"), ("U", "TotEng")]:
        m, e = common.mean_sem(prod[col][half:])
        row[key], row[key + "_err"] = m, e
    row["max_edrift"] = max(abs(x - prod["Edrift"][0]) for x in prod["Edrift"])
    print(name, {k: row[k] for k in ("T_kin", "n", "P", "U", "wall_s")}, flush=True)
    return row


def rdf(path, rmax, bins=400):
    """g(r) on (0, rmax] from the h5md snapshots (all frames after the first fifth)."""
    import numpy as np
    from scipy.spatial import cKDTree
    with common.gendpde.read_h5md(path) as f:
        x = f.array("position")
        box = f[0].box
    edges = np.linspace(0.0, rmax, bins + 1)
    hist = np.zeros(bins)
    frames = x[len(x) // 5:]
    for pos in frames:
        tree = cKDTree(np.mod(pos, box), boxsize=box)
        d = tree.sparse_distance_matrix(tree, rmax, output_type="ndarray")["v"]
        hist += np.histogram(d[d > 0], edges)[0]
    n = x.shape[1]
    c = n / np.prod(box)
    shell = 4.0 / 3.0 * np.pi * (edges[1:] ** 3 - edges[:-1] ** 3)
    g = hist / (len(frames) * n * c * shell)
    return {"r": list(0.5 * (edges[1:] + edges[:-1])), "g": list(g)}


def lth_macro(v, c, temperature, source):
    """`gendpde lth-macro` with the model of `v` at density c and `temperature`."""
    cmd = [common.GENDPDE, "lth-macro", str(v["CV"]), str(v["alpha"]), str(v["kt"]), str(v["pi00"]),
           str(v["theta0"]), "1.0", "--rc", str(v["R"]), "--fcut", str(v["fcut"]), "--density", str(c),
           "--temperature", str(temperature)] + source
    out = subprocess.run(cmd, capture_output=True, text=True, check=True)
    return {k: float(x) for k, x in (line.split() for line in out.stdout.splitlines())}


def with_macro(row):
    """Adds g(r) to 2 R_cut (the triplet term of eq 91 convolves over it), the macroscopic
    state from it at the run's kinetic temperature (Table 6), and that of the HNC at the
    nominal one (Table 8)."""
    v = row["vars"]
    wd = common.workdir("lth_argon", f"{row['name']}_n{round(row['N'] ** (1 / 3))}")
    row["gr"] = rdf(wd / "lth.h5", 2 * v["R"])
    path = wd / "gr.txt"
    path.write_text("".join(f"{r:.6f} {g:.8f}\n" for r, g in zip(row["gr"]["r"], row["gr"]["g"])))
    row["from_g"] = lth_macro(v, v.get("c", 1.0), row["T_kin"], ["--gr", str(path)])
    row["hnc"] = lth_macro(v, v.get("c", 1.0), v["T"], ["--hnc"])
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=16)
    ap.add_argument("--scan-n", type=int, default=15)
    ap.add_argument("--full-n", type=int, default=0, help="also R* = 2.1564 with N = full_n^3 (the paper: 30)")
    ap.add_argument("--equil-t", type=float, default=30.0)
    ap.add_argument("--prod-t", type=float, default=10.0)
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default="", help="comma-separated run names: run (and cache) only these, no report")
    args = ap.parse_args()
    todo = [r for r in runs(args) if not args.only or r[0] in args.only.split(",")]
    with ThreadPoolExecutor(args.jobs) as pool:
        rows = list(pool.map(lambda r: simulate(*r, args), todo))
    if args.only:
        return
    rows = [with_macro(r) if r["group"] in ("table5", "table7") else r for r in rows]
    refs = {state: reference(state) for state in ("liquid", "supercritical")}
    for r in rows:
        v = r["vars"]
        p0, t0, alpha, kt = refs["liquid" if v["theta0"] < 0.05 else "supercritical"]
        r["reference_P"] = p0 + (alpha * (r["T_kin"] - t0) + math.log(v.get("c", 1.0))) / kt
    figure(rows)
    for r in rows:
        r.pop("gr", None)
    common.save("lth_argon", {"runs": rows, "paper": {"table5": PAPER_T5, "table6": PAPER_T6, "table7": PAPER_T7,
                                                      "table8": PAPER_T8}})


def reference(state):
    """P0*, T0*, alpha and kappa_T of the macroscopic reference state (eqs 101-117; kappa_T*
    = 1 by the choice of units): P = P0 + (alpha (T - T0) + ln c)/kappa_T is the
    macroscopic LTh law around it, first order in the deviations (the NIST proxy)."""
    out = subprocess.run([common.GENDPDE, "lth-params", "--state", state], capture_output=True, text=True, check=True)
    p = {k: float(x) for k, x in (line.split() for line in out.stdout.splitlines())}
    return p["P0"], p["T0"], p["alpha_macro"], p["kappa_t_macro"] if "kappa_t_macro" in p else 1.0


def figure(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, ax = plt.subplots(2, 2, figsize=(11, 8.5))
    by = {r["name"]: r for r in rows}
    a = ax[0][0]
    for r in rows:
        if r["group"] in ("table5", "table7"):
            a.plot(r["gr"]["r"], r["gr"]["g"], label=f"{r['name']} (N = {r['N']})")
    a.axhline(1.0, color="grey", lw=0.5)
    a.set_xlabel("r*")
    a.set_ylabel("g(r)")
    a.set_title("Figs 1-2: g(r), the three cutoffs and the tuned run")
    a.legend(fontsize=7)
    b = ax[0][1]
    names = [r["name"] for r in rows if r["group"] == "table5"] + (["tuned"] if "tuned" in by else [])
    xs = np.arange(len(names))
    b.errorbar(xs - 0.1, [by[k]["P"] for k in names], [by[k]["P_err"] for k in names], fmt="o", label="gendpde virial")
    b.plot(xs + 0.1, [by[k]["from_g"]["pressure"] for k in names], "s", mfc="none", label="eqs 85-91 from own g (Table 6)")
    b.plot(xs + 0.2, [by[k]["hnc"]["pressure"] for k in names], "^", mfc="none", label="HNC (Table 8)")
    paper = [PAPER_T5[by[k]["vars"]["R"]][2] if k.startswith("liquid") else PAPER_T7[2] for k in names]
    b.plot(xs, paper, "k_", ms=20, label="paper (Tables 5, 7)")
    b.set_xticks(xs, [k.replace("liquid_", "") for k in names])
    b.set_ylabel("P*")
    b.set_title("Tables 5-8: pressure")
    b.legend(fontsize=7)
    for axis, group, state in [(ax[1][0], "fig4", "liquid"), (ax[1][1], "fig5", "supercritical")]:
        base = by.get("tuned" if state == "liquid" else "supercritical")
        pts = [r for r in rows if r["group"] == group and "_c" in r["name"]] + ([base] if base else [])
        if not pts:
            continue
        p0, t0, _, kt = reference(state)
        c = np.array(sorted(r["vars"].get("c", 1.0) for r in pts))
        axis.errorbar([r["vars"].get("c", 1.0) for r in pts], [r["P"] for r in pts], [r["P_err"] for r in pts],
                      fmt="o", label="gendpde")
        axis.plot(c, p0 + np.log(c) / kt, "--", label="macroscopic LTh law, first order")
        axis.set_xlabel("c*")
        axis.set_ylabel("P*")
        axis.set_title(f"Fig {4 if state == 'liquid' else 5}: {state}, density scan")
        axis.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(common.figure_path("lth_argon"), dpi=80)


if __name__ == "__main__":
    main()
