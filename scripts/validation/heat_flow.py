#!/usr/bin/env python3
"""Heat conduction of the 2021 PRE (validation scene V4, examples/heat-gradient).

Fixed particles on a simple cubic lattice (rho = 1), u = C_V theta (C_V = 100), pair heat
flow with kappa_ij = kappa (1 - r/rc)^2, rc = 2.2, between a hot and a cold reservoir slab
(fix heat/reservoir on groups). J = (E_hot - E_cold)/2 per time per 2 cross-sections from
the reservoirs' tallies (thermo f_hot, f_cold); the theta profile along x (folded onto the
distance from the hot slab) from the H5MD dump; lambda = -J / slope of a linear fit over
the layers at least rc inside a conduction zone. Error: jackknife over 10 time blocks.
Predictions: the exact lattice sum (rho/2) sum_R kappa (1 - R/rc)^2 R_x^2 and the continuum
2 pi rho^2 kappa rc^5 / 315 (2021 eq 67; eq 66 with the 1/315 restored divides by T^2).
Writes docs/validation/heat_flow.json and docs/validation/heat_flow.png (`--plot`: only the
figure, from heat_flow.json).
"""
import argparse
import json
import math

import numpy as np

import common

L, W, NY, RC = 12, 3, 10, 2.2
BLOCKS = 10


def lattice_sum(rc):
    n = int(rc) + 1
    r = np.arange(-n, n + 1)
    x, y, z = np.meshgrid(r, r, r, indexing="ij")
    d = np.sqrt(x**2 + y**2 + z**2)
    w = np.where((d < rc) & (d > 0), (1 - d / rc) ** 2, 0.0)
    return 0.5 * float(np.sum(w * x**2))


def run(heat, t, dt_rel, seed, equil, steps, every, dt):
    wd = common.workdir("heat_flow", f"{heat}-T{t}")
    wd.mkdir(parents=True, exist_ok=True)
    script = wd / "in.wrapper"
    script.write_text(f"include {common.ROOT / 'examples' / 'heat-gradient' / 'in.heat-gradient'}\n"
                      f"reset_timestep 0\ndump traj all h5md {every} traj.h5 x theta\nthermo {steps // BLOCKS}\nrun {steps}\n")
    (wd / "traj.h5").unlink(missing_ok=True)
    v = {"heat": heat, "T": t, "dT": dt_rel, "seed": seed, "steps": equil, "dt": dt}
    try:
        r = common.gendpde.run(script, v, cwd=wd, binary=common.GENDPDE)
    except common.gendpde.GendpdeError as e:
        raise SystemExit(e.stdout[-2000:] + e.stderr[-2000:])
    prod, wall = r.logs[-1], r.wall_s
    x = common.h5md_frames(wd / "traj.h5", "position")[0, :, 0]
    theta = common.h5md_frames(wd / "traj.h5", "temperature")[1:]  # frames after the start
    lx = 2 * (L + W)
    c = 0.5 * (W - 1)
    dd = (x - c) % lx
    layer = np.rint(np.minimum(dd, lx - dd)).astype(int)
    layers = lx // 2 + 1
    fit = [d for d in range(layers) if d - 0.5 * W >= RC - 1e-9 and 0.5 * W + L - d >= RC - 1e-9]
    e = np.array(prod["f_hot"]) - np.array(prod["f_cold"])
    flux = 0.5 * np.diff(e) / (steps / BLOCKS * dt) / (2 * NY * NY)
    frames = np.array_split(np.arange(theta.shape[0]), BLOCKS)
    prof = np.array([[theta[f][:, layer == d].mean() for d in range(layers)] for f in frames])
    grad = np.array([np.polyfit(fit, p[fit], 1)[0] for p in prof])
    lam = -flux.sum() / grad.sum()
    jack = np.array([-(flux.sum() - flux[b]) / (grad.sum() - grad[b]) for b in range(BLOCKS)])
    err = math.sqrt((BLOCKS - 1) / BLOCKS * np.sum((jack - jack.mean()) ** 2))
    t_mid = float(prof.mean(axis=0)[fit].mean())
    return {"heat": heat, "T": t, "dT": dt_rel, "lambda": [float(lam), err], "T_fit": t_mid,
            "profile": prof.mean(axis=0).tolist(), "fit_layers": fit, "steps": steps, "equil": equil,
            "dt": dt, "N": int(x.size), "wall": wall}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--equil", type=int, default=4000)
    ap.add_argument("--steps", type=int, default=10000)
    ap.add_argument("--dt", type=float, default=2.0)
    ap.add_argument("--plot", action="store_true", help="only redraw the figure from heat_flow.json")
    args = ap.parse_args()
    if args.plot:
        return plot(json.loads((common.OUT / "heat_flow.json").read_text()))
    lat, cont = lattice_sum(RC), 2 * math.pi * RC**5 / 315
    runs = []
    for heat, t, dt_rel, seed in [("fourier", 1.0, 0.5, 2021), ("fourier", 2.0, 0.5, 77), ("original", 1.0, 0.1, 2021), ("original", 2.0, 0.1, 77)]:
        r = run(heat, t, dt_rel, seed, args.equil, args.steps, 50, args.dt)
        scale = 1.0 if heat == "fourier" else 1.0 / r["T_fit"] ** 2
        r["predicted_lattice"], r["predicted_continuum"] = lat * scale, cont * scale
        print(f"{heat} T = {t}: lambda = {r['lambda'][0]:.4f} +- {r['lambda'][1]:.4f}, lattice {r['predicted_lattice']:.4f}, "
              f"continuum {r['predicted_continuum']:.4f}, {r['wall']:.0f} s")
        runs.append(r)
    data = {"rc": RC, "rho": 1.0, "kappa": 1.0, "cv": 100.0, "L": L, "w": W, "ny": NY, "runs": runs}
    (common.OUT / "heat_flow.json").write_text(json.dumps(data, indent=1) + "\n")
    plot(data)


def plot(data):
    """The theta profiles of heat_flow.json."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = data["runs"]
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for r in runs:
        p = np.array(r["profile"])
        ax.plot(np.arange(p.size), (p / r["T"] - 1) / r["dT"], "o-", ms=3, label=f"{r['heat']}, T = {r['T']:g}, dT = {r['dT']:g}")
    fit = runs[0]["fit_layers"]
    ax.axvspan(fit[0], fit[-1], color="0.9", label="fitted layers")
    ax.set_xlabel("distance from the hot slab centre [σ, reduced units; layers 1 σ apart]")
    ax.set_ylabel(r"($\langle\theta\rangle$/T - 1) / dT [dimensionless]")
    ax.set_title("heat-gradient: theta profiles (reservoirs at T(1 +- dT))")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(common.OUT / "heat_flow.png", dpi=120)


if __name__ == "__main__":
    main()
