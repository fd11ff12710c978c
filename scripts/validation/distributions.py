#!/usr/bin/env python3
"""Figs 1 and 6 of the 2019 paper: equilibrium distributions of u, theta, p and n for the
vdW GenDPDE fluid at T = 1.5, rho = 0.5 against eqs 89-91, and the theta distribution for
several C_V.

    python3 scripts/validation/distributions.py [--n 30] [--steps 2000] [--cvs 10,30,60,120]

Theory (k_B = 1, vdW excess EOS u = C_V theta - a n, mean field n = rho = 0.5):
p_a ~ N(0, m T) (eq 89); u + a rho ~ Gamma(shape C_V, scale T) (eq 90); theta ~ Gamma(shape
C_V, scale T / C_V) (eq 91, constant C_V). The local density has no closed form: its
histogram is shown with its mean beside rho here, and against eq 92 by a Monte Carlo of the
configurational integral in local_density_mc.py (which reads this script's runs).
"""
import argparse

import numpy as np
from scipy import stats

import common

T, RHO, A = 1.5, 0.5, 2.4682


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=30, help="lattice cells per side (N = n^3; paper 30)")
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--equil", type=int, default=1000)
    ap.add_argument("--cvs", default="10,30,60,120", help="C_V values of Fig 6")
    ap.add_argument("--cv-n", type=int, default=15, help="lattice cells per side of the Fig 6 runs")
    args = ap.parse_args()

    wd = common.workdir("distributions", f"n{args.n}")
    _, wall = common.run("distributions", {"n": args.n, "steps": args.steps, "equil": args.equil}, wd)
    u = common.h5md_frames(wd / "dist.h5", "internal_energy").ravel()
    theta = common.h5md_frames(wd / "dist.h5", "temperature").ravel()
    p = common.h5md_frames(wd / "dist.h5", "momentum").reshape(-1)
    n = common.h5md_frames(wd / "dist.h5", "density").ravel()
    frames = common.h5md_frames(wd / "dist.h5", "temperature").shape[0]
    cv = 60.0
    theory = {
        "u": stats.gamma(cv, loc=-A * RHO, scale=T),
        "theta": stats.gamma(cv, scale=T / cv),
        "p": stats.norm(0.0, np.sqrt(T)),
    }
    entry = {"N": args.n ** 3, "frames": int(frames), "steps": args.steps, "wall_s": round(wall, 1)}
    for name, x in [("u", u), ("theta", theta), ("p", p)]:
        d = theory[name]
        # one frame of independent particles for the test, all frames for the moments
        one = x[: x.size // frames]
        chi2, pval = common.pearson(one, d.ppf)
        entry[name] = {"mean": float(x.mean()), "theory_mean": float(d.mean()), "var": float(x.var()),
                       "theory_var": float(d.var()), "chi2_last_frame": chi2, "p_value": pval}
    entry["n"] = {"mean": float(n.mean()), "rho": RHO, "std": float(n.std())}

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cvs = [float(c) for c in args.cvs.split(",")]
    fig, ax = plt.subplots(2, 3, figsize=(13, 7))
    quantities = [("u", u, "internal energy u", "ε", "1/ε"), ("theta", theta, r"particle temperature $\theta$", "ε/k_B", "k_B/ε"),
                  ("p", p, r"momentum component $p_\alpha$", "(mε)$^{1/2}$", "(mε)$^{-1/2}$")]
    for a, (name, x, label, unit, inverse) in zip(ax.flat, quantities):
        a.hist(x, bins=80, density=True, histtype="step", color="k", label="gendpde")
        g = np.linspace(*np.percentile(x, [0.01, 99.99]), 300)
        a.plot(g, theory[name].pdf(g), "r--", label="eq %s" % {"u": 90, "theta": 91, "p": 89}[name])
        a.set_xlabel(f"{label} [{unit}, reduced units]")
        a.set_ylabel(f"probability density [{inverse}]")
        a.legend()
    ax[1, 0].hist(n, bins=80, density=True, histtype="step", color="k")
    ax[1, 0].axvline(RHO, color="r", ls="--", label=r"$\rho$")
    ax[1, 0].set_xlabel("local density n [σ⁻³, reduced units]")
    ax[1, 0].set_ylabel("probability density [σ³]")
    ax[1, 0].legend()

    fig6 = {}
    for c in cvs:
        wd6 = common.workdir("distributions", f"cv{c:g}")
        _, wall6 = common.run("distributions", {"n": args.cv_n, "cv": c, "steps": args.steps // 2, "equil": args.equil}, wd6)
        th = common.h5md_frames(wd6 / "dist.h5", "temperature")
        d = stats.gamma(c, scale=T / c)
        chi2, pval = common.pearson(th[-1], d.ppf)
        fig6[f"{c:g}"] = {"mean": float(th.mean()), "var": float(th.var()), "theory_var": float(d.var()),
                          "p_value": pval, "N": args.cv_n ** 3, "wall_s": round(wall6, 1)}
        line = ax[1, 1].hist(th.ravel(), bins=80, density=True, histtype="step", label=f"$C_V$ = {c:g}")
        g = np.linspace(0.2 * T, 2.2 * T, 300)
        ax[1, 1].plot(g, d.pdf(g), "--", color=line[2][0].get_edgecolor())
    ax[1, 1].set_xlabel(r"particle temperature $\theta$ [ε/k_B, reduced units] (Fig 6; dashed: eq 91)")
    ax[1, 1].set_ylabel("probability density [k_B/ε]")
    ax[1, 1].set_xlim(0.2 * T, 2.2 * T)
    ax[1, 1].legend(fontsize=8)
    ax[1, 2].axis("off")
    entry["fig6"] = fig6
    fig.suptitle(f"vdW GenDPDE, T = {T}, rho = {RHO}, N = {args.n ** 3} (Fig 1) and C_V scan (Fig 6)")
    fig.tight_layout()
    fig.savefig(common.figure_path("distributions"), dpi=80)
    common.save("distributions", entry)
    print(entry)


if __name__ == "__main__":
    main()
