#!/usr/bin/env python3
"""Figs 2 and 3 of the 2019 paper: the relative energy drift rate of the LJ GenDPDE fluid
(slope of a linear fit of (E(t) - E(0))/E(0) against t) against the time step at
rho = 0.5, T = 1.5 and 3, and against the density at dt = 0.01.

    python3 scripts/validation/drift.py [--dts 0.005,0.01,0.02,0.05,0.1] [--time 20]
        [--rhos 0.2,0.4,0.6,0.8] [--eos "lj 60.0 TABLE"] [--n N]
    python3 scripts/validation/drift.py --plot      # only the figure, from results.json

Each run equilibrates 200 steps at its own dt, then runs `time` time units.
"""
import argparse

import common


def measure(T, rho, dt, args):
    n = args.n or common.lattice_cells(rho, 4.0)
    steps = int(round(args.time / dt))
    wd = common.workdir("drift", f"T{T}_rho{rho}_dt{dt}_n{n}")
    v = {"n": n, "rho": rho, "T": T, "dt": dt, "eos": args.eos, "equil": 200, "steps": steps, "every": max(1, steps // 200)}
    blocks, wall = common.run("lj-fluid", v, wd)
    run = blocks[-1]
    row = {"T": T, "rho": rho, "dt": dt, "N": n ** 3, "steps": steps, "drift_rate": common.drift_rate(run["Time"], common.relative(run["TotEng"])),
           "max_rel_drift": max(abs(e) for e in common.relative(run["TotEng"])), "wall_s": round(wall, 1),
           "atom_steps_per_s": n ** 3 * (steps + 200) / wall}
    print(row, flush=True)
    return row


def plot(entry):
    """Figs 2 and 3 from the results entry."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    by_dt, by_rho = entry["by_dt"], entry["by_rho"]
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.5))
    for T, mark in zip(sorted({r["T"] for r in by_dt + by_rho}), "os^"):
        rows = [r for r in by_dt if r["T"] == T]
        a.semilogy([r["dt"] for r in rows], [abs(r["drift_rate"]) for r in rows], mark + "-", label=f"T = {T:g}")
        rows = [r for r in by_rho if r["T"] == T]
        b.semilogy([r["rho"] for r in rows], [abs(r["drift_rate"]) for r in rows], mark + "-", label=f"T = {T:g}")
    a.set_xlabel(r"time step $\delta t$ [τ, reduced units]")
    b.set_xlabel(r"density $\rho$ [σ$^{-3}$, reduced units]")
    for ax in (a, b):
        ax.set_ylabel("|relative energy drift rate| [1/τ, reduced units]")
        ax.legend()
    a.set_title(r"Fig 2: $\rho$ = 0.5")
    b.set_title(r"Fig 3: $\delta t$ = 0.01")
    fig.tight_layout()
    fig.savefig(common.figure_path("drift"), dpi=80)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dts", default="0.005,0.01,0.02,0.05,0.1")
    ap.add_argument("--temps", default="1.5,3")
    ap.add_argument("--rhos", default="0.2,0.4,0.6,0.8")
    ap.add_argument("--time", type=float, default=20.0)
    ap.add_argument("--eos", default=f"lj 60.0 {common.LJ_TABLE}")
    ap.add_argument("--n", type=int, default=0)
    ap.add_argument("--plot", action="store_true", help="only redraw the figure from results.json")
    args = ap.parse_args()
    if args.plot:
        return plot(common.saved("drift"))
    temps = [float(t) for t in args.temps.split(",")]
    by_dt = [measure(T, 0.5, float(dt), args) for T in temps for dt in args.dts.split(",")]
    by_rho = [measure(T, float(r), 0.01, args) for T in temps for r in args.rhos.split(",")]
    entry = {"by_dt": by_dt, "by_rho": by_rho, "eos": args.eos, "time": args.time}
    plot(entry)
    common.save("drift", entry)


if __name__ == "__main__":
    main()
