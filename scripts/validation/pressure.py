#!/usr/bin/env python3
"""Figs 4 and 5 of the 2019 paper: the virial pressure of the LJ GenDPDE fluid against the
Kolafa-Nezbeda EOS pressure over isotherms, and its dependence on the density cutoff rc.

    python3 scripts/validation/pressure.py [--states 1.5:0.2,0.5,0.8 ...] [--rc 3,4,5]
        [--eos "lj 60.0 TABLE"] [--equil 500] [--steps 1000] [--n N]

Each state runs examples/lj-fluid (NVE GenDPDE, C_V = 60, gamma = 4.5, kappa = 1, dt =
0.01) in the smallest sc box that holds the cell grid (or n^3 particles with --n); the
EOS pressure is evaluated at the measured <T_int> (the NVE run settles near, not at, the
initial T). The LJ EOS runs through a table by default (docs/commands/fix_eos.md: errors
below 1e-6 in u and theta, 5e-5 in pi/n^2 on this grid); --eos "lj 60.0" uses the analytic
model, about 5x slower.
"""
import argparse

import common

DEFAULT_STATES = "1:0.7,0.8 1.5:0.2,0.3,0.4,0.5,0.6,0.7,0.8 3:0.2,0.3,0.4,0.5,0.6,0.7,0.8"


def measure(T, rho, rc, args):
    n = args.n or common.lattice_cells(rho, rc)
    wd = common.workdir("pressure", f"T{T}_rho{rho}_rc{rc}_n{n}")
    v = {"n": n, "rho": rho, "T": T, "rc": rc, "eos": args.eos, "equil": args.equil, "steps": args.steps, "every": 10}
    blocks, wall = common.run("lj-fluid", v, wd)
    prod = blocks[-1]
    p, p_err = common.mean_sem(prod["Press"])
    tk, _ = common.mean_sem(prod["Temp"])
    ti, _ = common.mean_sem(prod["Tint"])
    p_eos = common.eos("lj 60.0", ti, rho)["pressure"]
    row = {"T": T, "rho": rho, "rc": rc, "N": n ** 3, "P_virial": p, "P_err": p_err, "P_eos": p_eos,
           "rel_dev": (p - p_eos) / abs(p_eos), "T_kin": tk, "T_int": ti, "steps": args.steps, "wall_s": round(wall, 1)}
    print(row, flush=True)
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--states", default=DEFAULT_STATES, help="T:rho,rho,... groups (Fig 4)")
    ap.add_argument("--rc", default="3,4,5", help="density cutoffs of Fig 5")
    ap.add_argument("--rc-states", default="1.5:0.5,0.8", help="states of the rc scan")
    ap.add_argument("--eos", default=f"lj 60.0 {common.LJ_TABLE}")
    ap.add_argument("--equil", type=int, default=500)
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--n", type=int, default=0, help="lattice cells per side (0: smallest box)")
    args = ap.parse_args()

    def parse(groups):
        return [(float(t), float(r)) for g in groups.split() for t, rs in [g.split(":")] for r in rs.split(",")]

    iso = [measure(T, rho, 4.0, args) for T, rho in parse(args.states)]
    done = {(r["T"], r["rho"], r["rc"]): r for r in iso}
    cut = [done.get((T, rho, float(rc))) or measure(T, rho, float(rc), args)
           for T, rho in parse(args.rc_states) for rc in args.rc.split(",")]

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.5))
    for T, mark in [(1.0, "o"), (1.5, "s"), (3.0, "^")]:
        rows = [r for r in iso if r["T"] == T]
        if not rows:
            continue
        g = np.linspace(0.15, 0.85, 60)
        line = a.plot(g, [common.eos("lj 60.0", T, x)["pressure"] for x in g], "-", label=f"KN EOS, T = {T:g}")
        a.errorbar([r["rho"] for r in rows], [r["P_virial"] for r in rows], [r["P_err"] for r in rows],
                   fmt=mark, color=line[0].get_color(), mfc="none", label=f"gendpde, T = {T:g}")
    a.set_xlabel(r"$\rho$")
    a.set_ylabel("P")
    a.set_title("Fig 4: virial vs EOS pressure (rc = 4)")
    a.legend(fontsize=8)
    for T, rho in parse(args.rc_states):
        rows = [r for r in cut if r["T"] == T and r["rho"] == rho]
        line = b.errorbar([r["rc"] for r in rows], [r["P_virial"] for r in rows], [r["P_err"] for r in rows],
                          fmt="o-", label=f"T = {T:g}, rho = {rho:g}")
        b.axhline(np.mean([r["P_eos"] for r in rows]), color=line[0].get_color(), ls="--")
    b.set_xlabel("rc")
    b.set_ylabel("P")
    b.set_title("Fig 5: cutoff dependence (dashed: EOS)")
    b.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(common.figure_path("pressure"), dpi=80)
    common.save("pressure", {"isotherms": iso, "cutoff": cut, "eos": args.eos})


if __name__ == "__main__":
    main()
