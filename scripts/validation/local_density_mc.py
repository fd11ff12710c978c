#!/usr/bin/env python3
"""Eq 92 of the 2019 paper: the local-density distribution of the vdW GenDPDE fluid at
T = 1.5, rho = 0.5 (Fig 1, bottom right) from a Metropolis Monte Carlo of the
configurational integral, against the GenDPDE runs of distributions.py.

    python3 scripts/validation/local_density_mc.py [--n 15] [--sweeps 400] [--equil 100]
    python3 scripts/validation/local_density_mc.py --rc 3 --n 11 --sweeps 100   # pressure only

Integrating eq 88 over u and momenta leaves the positions with the weight
exp(-sum_i [Y(n_i)/(k_B T) + ln psi(n_i)]) (eq 92), Y = V for the EOS family of eqs 43-46.
For the vdW excess EOS (C_V = 60, a = 2.4682, b = 1.4142, self term excluded, quadratic
weight, rc = 4) the exponent per particle is f(n) = [u(T, n) - C_V T]/T + C_V ln T - s(T, n),
which this script tabulates through `gendpde eos` so that the engine's cap of n below 1/b
is included. Single-particle moves in an sc-started box of n^3 sites at rho = 0.5; the step
is raised towards 40 % acceptance during equilibration, and since the soft weight accepts
even moves across the whole box three times in four, it ends larger than the box (random
re-insertion; the proposal stays symmetric). All n_i are recomputed every sweep (no drift
of the incremental updates). With the n distribution, eq 90 becomes a mixture:
u + a n ~ Gamma(C_V, T) for each particle's n, so P(u) = <Gamma pdf(u + a n)>_n.

The virial pressure of the sampled weight (issue 19, item 4): with F(n) = k_B T f(n) the
configurational free energy per particle (V + k_B T ln psi for the linear family), the pair
force is -(F'(n_i) + F'(n_j)) w'(r) e_ij (eq 50 with pi/n^2 = F'), and
P = rho k_B T + <sum_{i<j} r_ij . f_ij>/(3V), recorded every sweep. With --rc other than 4
the script records the pressure only (the GenDPDE comparison runs are at rc = 4).
"""
import argparse
import time

import numpy as np
from scipy import stats

import common

T, RHO, CV, A, B, RC = 1.5, 0.5, 60.0, 2.4682, 1.4142, 4.0
EOS = f"vdw {CV} {A} {B} excess"


def exponent_table(grid):
    """f(n) of eq 92 per particle on `grid`, from the engine's EOS at theta = T."""
    f = []
    for x in grid:
        e = common.eos(EOS, T, x)
        f.append((e["u"] - CV * T) / T + CV * np.log(T) - e["s"])
    return np.array(f)


def weight_derivative(r):
    """d/dr of `weight`."""
    return -2.0 * np.clip(1.0 - r / RC, 0.0, None) / RC * 15.0 / (2.0 * np.pi * RC ** 3)


def virial(pos, n, box, dfdn):
    """sum_{i<j} r_ij . f_ij for the weight exp(-sum f(n_i)) (f in units of k_B T)."""
    total = 0.0
    dfn = dfdn(n)
    for i, x in enumerate(pos):
        r = distances(pos, x, box)
        r[i] = 2.0 * RC
        total += -((dfn[i] + dfn) * weight_derivative(r) * r).sum()
    return 0.5 * T * total


def weight(r):
    """Quadratic weight (1 - r/rc)^2 normalised to unit integral, zero beyond rc."""
    w = np.clip(1.0 - r / RC, 0.0, None) ** 2
    return w * 15.0 / (2.0 * np.pi * RC ** 3)


def distances(pos, x, box):
    d = pos - x
    d -= box * np.round(d / box)
    return np.sqrt((d * d).sum(axis=1))


def densities(pos, box):
    n = np.empty(len(pos))
    for i, x in enumerate(pos):
        w = weight(distances(pos, x, box))
        w[i] = 0.0
        n[i] = w.sum()
    return n


def analytic_table(grid):
    """f(n) = V/T + ln psi = -a n/T - ln(1 - b n), the vdW excess EOS below its cap
    (n < 0.95/b = 0.672): no `gendpde eos` calls (1201 of them take minutes on a busy
    machine); the run checks that no n_i reaches the cap."""
    return -A * grid / T - np.log(np.clip(1.0 - B * grid, 1e-12, None))


def monte_carlo(cells, sweeps, equil, seed, analytic=False):
    rng = np.random.default_rng(seed)
    box = cells / RHO ** (1 / 3)
    g = (np.arange(cells) + 0.5) * box / cells
    pos = np.array(np.meshgrid(g, g, g, indexing="ij")).reshape(3, -1).T.copy()
    grid = np.linspace(0.0, 1.2, 1201)
    table = analytic_table(grid) if analytic else exponent_table(grid)
    f = lambda n: np.interp(n, grid, table)  # noqa: E731
    slope = np.gradient(table, grid)
    dfdn = lambda n: np.interp(n, grid, slope)  # noqa: E731
    N = len(pos)
    step, accepted, tried = 1.0, 0, 0
    hist_edges = np.linspace(0.0, 1.0, 201)
    hist = np.zeros(len(hist_edges) - 1)
    means, variances, samples, pressures = [], [], [], []
    for sweep in range(equil + sweeps):
        n = densities(pos, box)
        if analytic and n.max() >= 0.95 / B:
            raise SystemExit(f"n_i = {n.max():.4f} reached the vdW cap: run without --analytic")
        if sweep >= equil:
            hist += np.histogram(n, hist_edges)[0]
            means.append(n.mean())
            variances.append(n.var())
            samples.append(n[rng.integers(0, N, 64)])
            pressures.append(RHO * T + virial(pos, n, box, dfdn) / (3.0 * box ** 3))
        for k in rng.integers(0, N, N):
            new = (pos[k] + step * rng.uniform(-1.0, 1.0, 3)) % box
            w_old = weight(distances(pos, pos[k], box))
            w_old[k] = 0.0
            w_new = weight(distances(pos, new, box))
            w_new[k] = 0.0
            touched = (w_old > 0.0) | (w_new > 0.0)
            n_j = n[touched]
            n_j_new = n_j - w_old[touched] + w_new[touched]
            n_k_new = w_new.sum()
            df = f(n_j_new).sum() - f(n_j).sum() + f(n_k_new) - f(n[k])
            tried += 1
            if df <= 0.0 or rng.random() < np.exp(-df):
                accepted += 1
                n[touched] = n_j_new
                n[k] = n_k_new
                pos[k] = new
        if sweep < equil and sweep % 5 == 4:
            step *= np.exp(accepted / tried - 0.4)
            accepted = tried = 0
    return {"N": N, "box": box, "step": step, "acceptance": accepted / max(tried, 1), "edges": hist_edges,
            "hist": hist, "means": np.array(means), "vars": np.array(variances),
            "samples": np.concatenate(samples), "pressures": np.array(pressures)}


def block_sem(x, blocks=10):
    b = np.array([c.mean() for c in np.array_split(np.asarray(x), blocks)])
    return float(x.mean()), float(b.std(ddof=1) / np.sqrt(blocks))


def md_frames(tag):
    """Local densities of the GenDPDE run of distributions.py (frames after the first)."""
    n = common.h5md_frames(common.workdir("distributions", tag) / "dist.h5", "density")
    return n[1:]


def main():
    global RC
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=15, help="lattice cells per side (15: the Fig 6 runs' box)")
    ap.add_argument("--sweeps", type=int, default=400)
    ap.add_argument("--equil", type=int, default=100)
    ap.add_argument("--seed", type=int, default=92)
    ap.add_argument("--analytic", action="store_true", help="f(n) in closed form (valid below the cap) instead of `gendpde eos`")
    ap.add_argument("--rc", type=float, default=RC, help="density cutoff (4: the paper's, with the GenDPDE comparison)")
    args = ap.parse_args()
    RC = args.rc

    start = time.time()
    mc = monte_carlo(args.n, args.sweeps, args.equil, args.seed, args.analytic)
    wall = time.time() - start
    m, m_err = block_sem(mc["means"])
    v, v_err = block_sem(mc["vars"])
    p, p_err = block_sem(mc["pressures"])
    pressure = {"rc": RC, "N": mc["N"], "sweeps": args.sweeps, "P": p, "P_err": p_err, "mean_n": m, "mean_n_err": m_err,
                "std_n": v ** 0.5, "wall_s": round(wall, 1)}
    print(pressure)
    if RC != 4.0:
        common.save(f"local_density_mc_pressure_rc{RC:g}", pressure)
        return
    entry = {"pressure": pressure, "N": mc["N"], "sweeps": args.sweeps, "equil": args.equil, "acceptance": mc["acceptance"],
             "step": mc["step"], "wall_s": round(wall, 1), "mc": {"mean": m, "mean_err": m_err, "std": v ** 0.5,
                                                                  "var": v, "var_err": v_err}}
    md = {}
    for tag, label in [("cv60", "N = 3375"), ("n30", "N = 27000")]:
        try:
            frames = md_frames(tag)
        except OSError:
            continue
        fm, fm_err = block_sem(frames.mean(axis=1), blocks=min(5, len(frames)))
        fv, fv_err = block_sem(frames.var(axis=1), blocks=min(5, len(frames)))
        md[tag] = {"label": label, "N": frames.shape[1], "frames": len(frames), "mean": fm, "mean_err": fm_err,
                   "std": fv ** 0.5, "var": fv, "var_err": fv_err, "values": frames.ravel()}
    # eq 90 with the MC's n: u + a n ~ Gamma(C_V, T) particle by particle
    u_dist = stats.gamma(CV, scale=T)
    n_s = mc["samples"]
    entry["u_mixture_mean"] = float(CV * T - A * n_s.mean())
    entry["u_mixture_var"] = float(CV * T * T + A * A * n_s.var())
    entry["md"] = {k: {kk: vv for kk, vv in d.items() if kk != "values"} for k, d in md.items()}
    if "n30" in md:
        u = common.h5md_frames(common.workdir("distributions", "n30") / "dist.h5", "internal_energy")[-1]
        # Pearson chi^2 on 30 bins equiprobable under the mixture (quantiles of a large sample)
        rng = np.random.default_rng(1)
        draw = u_dist.rvs(size=400000, random_state=rng) - A * rng.choice(n_s, 400000)
        chi2, pval = common.pearson(u, lambda q: np.quantile(draw, q))
        entry["u_chi2_mixture"] = {"chi2": chi2, "p_value": pval, "N": len(u)}

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.5))
    centres = 0.5 * (mc["edges"][1:] + mc["edges"][:-1])
    width = mc["edges"][1] - mc["edges"][0]
    ax.plot(centres, mc["hist"] / mc["hist"].sum() / width, "r--", label=f"eq 92 (MC, N = {mc['N']})")
    for d in md.values():
        ax.hist(d["values"], bins=mc["edges"], density=True, histtype="step", label=f"gendpde, {d['label']}")
    ax.axvline(RHO, color="gray", ls=":", label=r"$\rho$")
    ax.set_xlim(0.2, 0.8)
    ax.set_xlabel("local density n [σ⁻³, reduced units]")
    ax.set_ylabel("probability density P(n) [σ³]")
    ax.set_title("Fig 1 (bottom right): vdW, T = 1.5, rho = 0.5")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(common.figure_path("local_density"), dpi=80)
    common.save("local_density", entry)
    print(entry)


if __name__ == "__main__":
    main()
