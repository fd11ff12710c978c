#!/usr/bin/env python3
"""Fig 7 of the 2019 paper: flash heating of a box-centred slab holding half of the
particles to T = 5 after equilibration at T = 1.5 (LJ GenDPDE, rho = 0.5).

    python3 scripts/validation/flash.py [--n 30] [--steps 5000] [--eos "lj 60.0"]
    python3 scripts/validation/flash.py --plot     # only the figure, from results.json

Reports the steady-state <T_kin> and <T_int> (second half of the run) and their relative
difference (paper: below 0.01 %), and the relative energy drift over the run (paper: 1e-7).
"""
import argparse

import common

# The LJ grid of the other scenes (theta 0.3-8, common.LJ_TABLE) with the same spacing up
# to theta = 16: at N = 27000 single particles of the heated fluid reach theta = 8.
FLASH_TABLE = "table 0.3 16.0 241 0.0 1.2 129"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=30)
    ap.add_argument("--equil", type=int, default=1000)
    ap.add_argument("--steps", type=int, default=5000)
    ap.add_argument("--eos", default=f"lj 60.0 {FLASH_TABLE}")
    ap.add_argument("--plot", action="store_true", help="only redraw the figure from results.json")
    args = ap.parse_args()
    if args.plot:
        return plot(common.saved("flash"))
    wd = common.workdir("flash", f"n{args.n}")
    v = {"n": args.n, "equil": args.equil, "steps": args.steps, "eos": args.eos, "every": 10}
    blocks, wall = common.run("flash-heating", v, wd)
    run = blocks[-1]
    half = len(run["Step"]) // 2
    tk, tk_err = common.mean_sem(run["Temp"][half:])
    ti, ti_err = common.mean_sem(run["Tint"][half:])
    drift = max(abs(e) for e in common.relative(run["TotEng"]))
    entry = {"N": args.n ** 3, "steps": args.steps, "eos": args.eos, "T_kin": tk, "T_kin_err": tk_err, "T_int": ti,
             "T_int_err": ti_err, "rel_diff": (tk - ti) / ti, "max_rel_energy_drift": drift,
             "drift_rate": common.drift_rate(run["Time"], common.relative(run["TotEng"])), "wall_s": round(wall, 1)}
    entry["series"] = common.series(run, t="Time", T_kin="Temp", T_int="Tint", P="Press")
    print({k: v for k, v in entry.items() if k != "series"})
    plot(entry)
    common.save("flash", entry)


def plot(entry):
    """Fig 7 from the results entry: temperatures and pressure against time, one panel each."""
    import sys
    if "series" not in entry:
        sys.exit("results.json holds no flash time series (written from this version on): rerun the scene")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    s = entry["series"]
    fig, (a, b) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    a.plot(s["t"], s["T_kin"], "k", lw=0.8, label=r"$T_{kin}$")
    a.plot(s["t"], s["T_int"], "r", lw=0.8, label=r"$T_{int}$")
    a.set_ylabel("temperature [ε/k_B, reduced units]")
    a.legend()
    b.plot(s["t"], s["P"], "b", lw=0.8)
    b.set_ylabel("pressure P [ε/σ³, reduced units]")
    b.set_xlabel("time t [τ, reduced units]")
    tk, ti = entry["T_kin"], entry["T_int"]
    a.set_title(f"Fig 7: flash heating, N = {entry['N']}; steady state "
                f"T_kin/T_int - 1 = {100 * (tk / ti - 1):.3f} %, |dE/E| <= {entry['max_rel_energy_drift']:.1e}", fontsize=9)
    fig.tight_layout()
    fig.savefig(common.figure_path("flash"), dpi=80)


if __name__ == "__main__":
    main()
