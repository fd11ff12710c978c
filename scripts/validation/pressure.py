#!/usr/bin/env python3
"""Figs 4 and 5 of the 2019 paper: the virial pressure of the LJ GenDPDE fluid against the
Kolafa-Nezbeda EOS pressure over isotherms, and its dependence on the density cutoff rc.

    python3 scripts/validation/pressure.py [--states 1.5:0.2,0.5,0.8 ...] [--rc 3,4,5,6,7] [--rc-steps 7:1500]
        [--eos "lj 60.0 TABLE"] [--equil 500] [--steps 3000] [--n N] [--gamma 0.45]
        [--check-n 30] [--check-equil 500] [--check-steps 3000] [--check-discard 0.5]
    python3 scripts/validation/pressure.py --plot   # only the figure, from results.json

Each state runs examples/lj-fluid (NVE GenDPDE, C_V = 60, kappa = 1, dt = 0.01) in the
smallest sc box that holds the cell grid (or n^3 particles with --n); the EOS pressure is
evaluated at the measured <T_int> (the NVE run settles near, not at, the initial T).

The friction is gamma = 0.45 rather than the paper's 4.5. The configurational statics are
the same at both (the check run below agrees to 0.05 %; gamma only reshapes the theta
distribution slightly, theta_shape.py), and with 4.5 the local-density field, which carries
the pressure, decorrelates ten times more slowly (particles diffuse across rc in ~100 time
units; from a lattice, <n_i> overshoots and settles over ~20). One run at the paper's
gamma = 4.5 and N = --check-n^3 checks that the statics agree, averaged over the part of
its production past the overshoot.

The LJ EOS runs through a table by default (docs/commands/fix_eos.md: errors below 1e-6 in
u and theta, 5e-5 in pi/n^2 on this grid); --eos "lj 60.0" uses the analytic model, about
5x slower. Each run's row is cached in its work directory (row.json).
"""
import argparse

import common

DEFAULT_STATES = "1:0.7,0.8 1.5:0.2,0.3,0.4,0.5,0.6,0.7,0.8 3:0.2,0.3,0.4,0.5,0.6,0.7,0.8"


def run_dir(T, rho, rc, args):
    n = args.n or common.lattice_cells(rho, rc)
    return n, common.workdir("pressure", f"T{T}_rho{rho}_rc{rc}_n{n}_g{args.gamma}_e{args.equil}_s{args.steps}")


def measure(T, rho, rc, args):
    n, wd = run_dir(T, rho, rc, args)
    return common.cached(wd, lambda: simulate(wd, T, rho, rc, n, args))


def simulate(wd, T, rho, rc, n, args):
    v = {"n": n, "rho": rho, "T": T, "rc": rc, "gamma": args.gamma, "eos": args.eos, "equil": args.equil,
         "steps": args.steps, "every": 10}
    blocks, wall = common.run("lj-fluid", v, wd)
    row = analyse(blocks[-1], T, rho, rc, n, args)
    row["wall_s"] = round(wall, 1)
    print(row, flush=True)
    return row


def analyse(prod, T, rho, rc, n, args):
    """Means and block errors over the production run, less its first `args.discard` part."""
    first = int(len(prod["Step"]) * args.discard)
    mean = {c: common.mean_sem(prod[c][first:]) for c in ("Press", "Temp", "Tint", "Nmean")}
    (p, p_err), (tk, tk_err), (ti, ti_err), (nm, nm_err) = mean.values()
    p_eos = common.eos("lj 60.0", ti, rho)["pressure"]
    return {"T": T, "rho": rho, "rc": rc, "N": n ** 3, "P_virial": p, "P_err": p_err, "P_eos": p_eos,
            "rel_dev": (p - p_eos) / abs(p_eos), "T_kin": tk, "T_kin_err": tk_err, "T_int": ti, "T_int_err": ti_err,
            "n_mean": nm, "n_mean_err": nm_err, "gamma": args.gamma, "equil": args.equil, "steps": args.steps,
            "discard": args.discard}


def relaxation(T, rho, rc, args, points=60):
    """(time, P, <n_i>) from the lattice start, block means of the whole run's thermo."""
    import numpy as np
    _, wd = run_dir(T, rho, rc, args)
    blocks = common.gendpde.read_log(wd / "log.gendpde")
    t = np.concatenate([np.array(b["Step"]) + (0 if i == 0 else args.equil) for i, b in enumerate(blocks)]) * 0.01
    cols = [t] + [np.concatenate([b[c] for b in blocks]) for c in ("Press", "Nmean")]
    k = max(1, len(t) // points)
    return [[float(x[i:i + k].mean()) for i in range(0, len(x) - k + 1, k)] for x in cols]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--states", default=DEFAULT_STATES, help="T:rho,rho,... groups (Fig 4)")
    ap.add_argument("--rc", default="3,4,5,6,7", help="density cutoffs of Fig 5")
    ap.add_argument("--rc-states", default="1.5:0.5", help="states of the rc scan")
    ap.add_argument("--rc-steps", default="7:1500", help="rc:steps overrides of --steps (the costly cutoffs)")
    ap.add_argument("--eos", default=f"lj 60.0 {common.LJ_TABLE}")
    ap.add_argument("--equil", type=int, default=500)
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--n", type=int, default=0, help="lattice cells per side (0: smallest box)")
    ap.add_argument("--gamma", type=float, default=0.45, help="friction (the pressure is the same at 4.5)")
    ap.add_argument("--check-n", type=int, default=30, help="cells per side of the gamma = 4.5 run (0: none)")
    ap.add_argument("--check-equil", type=int, default=500)
    ap.add_argument("--check-steps", type=int, default=3000)
    ap.add_argument("--check-discard", type=float, default=0.5, help="part of its production past the overshoot")
    ap.add_argument("--plot", action="store_true", help="only redraw the figure from results.json")
    args = ap.parse_args()
    if args.plot:
        return plot(common.saved("pressure"))
    args.discard = 0.0

    def parse(groups):
        return [(float(t), float(r)) for g in groups.split() for t, rs in [g.split(":")] for r in rs.split(",")]

    iso = [measure(T, rho, 4.0, args) for T, rho in parse(args.states)]
    done = {(r["T"], r["rho"], r["rc"]): r for r in iso}
    rc_steps = {float(k): int(v) for k, v in (x.split(":") for x in args.rc_steps.split())}

    def cutoff_run(T, rho, rc):
        if rc in rc_steps:
            return measure(T, rho, rc, argparse.Namespace(**dict(vars(args), steps=rc_steps[rc])))
        return done.get((T, rho, rc)) or measure(T, rho, rc, args)
    cut = [cutoff_run(T, rho, float(rc)) for T, rho in parse(args.rc_states) for rc in args.rc.split(",")]
    paper = argparse.Namespace(**dict(vars(args), n=args.check_n, gamma=4.5, equil=args.check_equil,
                                      steps=args.check_steps, discard=args.check_discard))
    check = [dict(measure(1.5, 0.5, 4.0, paper), relaxation=relaxation(1.5, 0.5, 4.0, paper))] if args.check_n else []
    if check and (1.5, 0.5, 4.0) in done:
        done[(1.5, 0.5, 4.0)]["relaxation"] = relaxation(1.5, 0.5, 4.0, args)

    fits = {f"{T:g}:{rho:g}": cutoff_fit([r for r in cut if r["T"] == T and r["rho"] == rho])
            for T, rho in parse(args.rc_states)}
    entry = {"isotherms": iso, "cutoff": cut, "cutoff_fit": fits, "paper_gamma": check, "eos": args.eos}
    plot(entry)
    common.save("pressure", entry)


def deviations(rows):
    """1/rc^3, the relative deviations of the virial pressure from the EOS (%) and their errors."""
    import numpy as np
    return (np.array([r["rc"] ** -3.0 for r in rows]), np.array([100 * r["rel_dev"] for r in rows]),
            np.array([100 * r["P_err"] / r["P_eos"] for r in rows]))


def cutoff_fit(rows):
    """Weighted fit of y = slope / rc^3 to the relative deviations (%) of one state."""
    x, y, e = deviations(rows)
    slope = float((x * y / e ** 2).sum() / (x * x / e ** 2).sum())
    return {"slope": slope, "rc_2pct": (slope / 2.0) ** (1 / 3), "chi2": float((((y - slope * x) / e) ** 2).sum()),
            "points": len(rows)}


def plot(entry):
    """Figs 4, 5 and the relaxation panel from the results entry (the EOS curves from
    `gendpde eos`)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    iso, cut, check = entry["isotherms"], entry["cutoff"], entry["paper_gamma"]
    p_unit = "[ε/σ³, reduced units]"
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(16, 4.5))
    for T, mark in [(1.0, "o"), (1.5, "s"), (3.0, "^")]:
        rows = [r for r in iso if r["T"] == T]
        if not rows:
            continue
        g = np.linspace(0.15, 0.85, 60)
        line = a.plot(g, [common.eos("lj 60.0", T, x)["pressure"] for x in g], "-", label=f"KN EOS, T = {T:g}")
        a.errorbar([r["rho"] for r in rows], [r["P_virial"] for r in rows], [r["P_err"] for r in rows],
                   fmt=mark, color=line[0].get_color(), mfc="none", label=f"gendpde, T = {T:g}")
    for r in check:
        a.errorbar(r["rho"], r["P_virial"], r["P_err"], fmt="k*", label=f"gamma = 4.5, N = {r['N']}")
    a.set_xlabel(r"density $\rho$ [σ$^{-3}$, reduced units]")
    a.set_ylabel(f"pressure P {p_unit}")
    a.set_title("Fig 4: virial vs EOS pressure (rc = 4; T in ε/k_B)")
    a.legend(fontsize=8)
    for state, fit in entry["cutoff_fit"].items():
        T, rho = (float(v) for v in state.split(":"))
        rows = [r for r in cut if r["T"] == T and r["rho"] == rho]
        x, y, e = deviations(rows)
        line = b.errorbar(x, y, e, fmt="o", label=f"T = {T:g}, rho = {rho:g}")
        g = np.linspace(0.0, x.max() * 1.05, 50)
        b.plot(g, fit["slope"] * g, "--", color=line[0].get_color(), label=f"{fit['slope']:.0f} % / rc$^3$")
        for r, xi, yi in zip(rows, x, y):
            b.annotate(f"rc {r['rc']:g}", (xi, yi), textcoords="offset points", xytext=(4, -10), fontsize=7)
    b.axhspan(-2, 2, color="0.9", label="2 %")
    b.set_xlabel(r"$1/r_c^3$ [σ$^{-3}$, reduced units]")
    b.set_ylabel("(P virial - P EOS) / P EOS [%]")
    b.set_title("Fig 5: cutoff dependence")
    b.legend(fontsize=8)
    relaxed = check + [r for r in iso if "relaxation" in r]
    for r in relaxed:
        t, pv, _ = r["relaxation"]
        c.plot(t, pv, label=f"gamma = {r['gamma']:g}, N = {r['N']}")
        c.axvline(r["equil"] * 0.01, color=c.lines[-1].get_color(), ls=":")
    if check:
        c.axhline(check[0]["P_eos"], color="k", ls="--", label="KN EOS")
    if relaxed:
        c.set_xlabel("time from the lattice [τ, reduced units] (dotted: end of equilibration)")
        c.set_ylabel(f"pressure P, block means {p_unit}")
        c.set_title("T = 1.5, rho = 0.5, rc = 4: relaxation")
        c.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(common.figure_path("pressure"), dpi=80)


if __name__ == "__main__":
    main()
