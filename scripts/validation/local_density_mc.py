#!/usr/bin/env python3
"""Eq 92 of the 2019 paper: the local-density distribution of the vdW GenDPDE fluid at
T = 1.5, rho = 0.5 (Fig 1, bottom right) from a Metropolis Monte Carlo of the
configurational integral, against the GenDPDE runs of distributions.py.

    python3 scripts/validation/local_density_mc.py [--n 15] [--sweeps 400] [--equil 100]
    python3 scripts/validation/local_density_mc.py --rc 3 --n 11 --sweeps 500 [--model lj] [--T 1.507]   # pressure only

Integrating eq 88 over u and momenta leaves the positions with the weight
exp(-sum_i [Y(n_i)/(k_B T) + ln psi(n_i)]) (eq 92), Y = V for the EOS family of eqs 43-46.
For the vdW excess EOS (C_V = 60, a = 2.4682, b = 1.4142, self term excluded, quadratic
weight, rc = 4) the exponent per particle is f(n) = [u(T, n) - C_V T]/T + C_V ln T - s(T, n),
which this script tabulates through `gendpde eos` so that the engine's cap of n below 1/b
is included. For the LJ (Kolafa-Nezbeda) EOS, whose excess free energy depends on theta,
integrating u out gives F_eff(n) = -k_B T ln int dtheta (C_V/theta) exp(s - u/(k_B T))
instead (issue 19; it reduces to the above for the linear family). The sampling runs in
the compiled kernel local_density_mc.c (built with gcc on first use). Single-particle moves in an sc-started box of n^3 sites at rho = 0.5; the step
is raised towards 40 % acceptance during equilibration, and since the soft weight accepts
even moves across the whole box three times in four, it ends larger than the box (random
re-insertion; the proposal stays symmetric). All n_i are recomputed every sweep (no drift
of the incremental updates). With the n distribution, eq 90 becomes a mixture:
u + a n ~ Gamma(C_V, T) for each particle's n, so P(u) = <Gamma pdf(u + a n)>_n.

The virial pressure of the sampled weight (issue 19, item 4): with F(n) = k_B T f(n) the
configurational free energy per particle (V + k_B T ln psi for the linear family), the pair
force is -(F'(n_i) + F'(n_j)) w'(r) e_ij (eq 50 with pi/n^2 = F'), and
P = rho k_B T + <sum_{i<j} r_ij . f_ij>/(3V), recorded every sweep. With --rc other than 4,
--model lj or --T other than 1.5 the script records the pressure only (results entry
local_density_mc_pressure); pressure_mc.py runs it against the engine.
"""
import argparse
import time
from pathlib import Path

import numpy as np
from scipy import stats

import common

T, RHO, CV, A, B, RC = 1.5, 0.5, 60.0, 2.4682, 1.4142, 4.0
EOS = f"vdw {CV} {A} {B} excess"
LJ_EOS = f"lj {CV}"


def exponent_table(grid):
    """f(n) of eq 92 per particle on `grid`, from the engine's EOS at theta = T."""
    f = []
    for x in grid:
        e = common.eos(EOS, T, x)
        f.append((e["u"] - CV * T) / T + CV * np.log(T) - e["s"])
    return np.array(f)


def lj_exponent_table(grid, nodes=16):
    """F_eff(n)/(k_B T) of the LJ (Kolafa-Nezbeda) particle EOS on `grid`: integrating u
    out of eq 88 leaves -ln int dtheta (C_V/theta) exp(s - u/T) (issue 19; for the linear
    family V/T + ln psi + const), here by Gauss-Hermite in x = ln(theta/T), where the
    integrand is nearly Gaussian with width 1/sqrt(C_V). Constant terms dropped."""
    x, w = np.polynomial.hermite.hermgauss(nodes)
    width = np.sqrt(2.0 / CV)
    f = []
    for n in grid:
        h = []
        for xk in x:
            e = common.eos(LJ_EOS, T * np.exp(width * xk), n)
            h.append(e["s"] - e["u"] / T + np.log(e["cv"]))
        h = np.array(h) + x * x
        top = h.max()
        f.append(-(top + np.log((w * np.exp(h - top)).sum())))
    return np.array(f)


def analytic_table(grid):
    """f(n) = V/T + ln psi = -a n/T - ln(1 - b n), the vdW excess EOS below its cap
    (n < 0.95/b = 0.672): no `gendpde eos` calls (1201 of them take minutes on a busy
    machine); the run checks that no n_i reaches the cap."""
    return -A * grid / T - np.log(np.clip(1.0 - B * grid, 1e-12, None))


def table(model, analytic):
    """(fine grid, f, df/dn): the engine's EOS on a coarse grid (`gendpde eos` calls are
    slow), interpolated by a cubic spline (LJ, smooth) or linearly (vdW, whose cap below
    1/b is a kink)."""
    from scipy.interpolate import CubicSpline
    fine = np.linspace(0.0, 1.2, 1201)
    cache = common.workdir("local_density_mc", "tables") / f"{model}_T{T!r}{'_analytic' if analytic else ''}.npy"
    if cache.exists():
        f = np.load(cache)
        return fine, f, np.gradient(f, fine)
    if model == "lj":
        coarse = np.linspace(0.0, 1.2, 49)
        f = CubicSpline(coarse, lj_exponent_table(coarse))(fine)
    elif analytic:
        f = analytic_table(fine)
    else:
        coarse = np.linspace(0.0, 1.2, 241)
        f = np.interp(fine, coarse, exponent_table(coarse))
    cache.parent.mkdir(parents=True, exist_ok=True)
    np.save(cache, f)
    return fine, f, np.gradient(f, fine)


def kernel():
    """The compiled Monte Carlo kernel (local_density_mc.c), built once per source version."""
    import hashlib
    import subprocess
    src = Path(__file__).with_suffix(".c")
    exe = common.workdir("local_density_mc", "bin") / f"mc_{hashlib.sha1(src.read_bytes()).hexdigest()[:10]}"
    if not exe.exists():
        exe.parent.mkdir(parents=True, exist_ok=True)
        subprocess.run(["gcc", "-O3", "-o", str(exe), str(src), "-lm"], check=True)
    return exe


def monte_carlo(cells, sweeps, equil, seed, model="vdw", analytic=False):
    import subprocess
    grid, f, slope = table(model, analytic)
    wd = common.workdir("local_density_mc", f"{model}_rc{RC:g}_T{T:g}_n{cells}_s{sweeps}_e{equil}_seed{seed}")
    wd.mkdir(parents=True, exist_ok=True)
    np.concatenate([[grid[0], grid[1] - grid[0], len(grid)], f, slope]).astype("<f8").tofile(wd / "table.bin")
    subprocess.run([str(kernel()), str(cells), str(RHO), str(RC), repr(T), str(sweeps), str(equil), str(seed),
                    str(wd / "table.bin"), str(wd / "out.bin")], check=True)
    out = np.fromfile(wd / "out.bin", dtype="<f8")
    rec = out[:3 * sweeps].reshape(sweeps, 3)
    hist = out[3 * sweeps:3 * sweeps + 200]
    samples = out[3 * sweeps + 200:-2]
    if model == "vdw" and analytic and samples.max() >= 0.95 / B:
        raise SystemExit(f"n_i = {samples.max():.4f} reached the vdW cap: run without --analytic")
    return {"N": cells ** 3, "box": cells / RHO ** (1 / 3), "step": out[-2], "acceptance": out[-1],
            "edges": np.linspace(0.0, 1.0, 201), "hist": hist, "means": rec[:, 1], "vars": rec[:, 2], "samples": samples,
            "pressures": rec[:, 0], "table": (grid, f, slope)}


def block_sem(x, blocks=10):
    b = np.array([c.mean() for c in np.array_split(np.asarray(x), blocks)])
    return float(x.mean()), float(b.std(ddof=1) / np.sqrt(blocks))


def md_frames(tag):
    """Local densities of the GenDPDE run of distributions.py (frames after the first)."""
    n = common.h5md_frames(common.workdir("distributions", tag) / "dist.h5", "density")
    return n[1:]


def main():
    global RC, T
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=15, help="lattice cells per side (15: the Fig 6 runs' box)")
    ap.add_argument("--sweeps", type=int, default=400)
    ap.add_argument("--equil", type=int, default=100)
    ap.add_argument("--seed", type=int, default=92)
    ap.add_argument("--analytic", action="store_true", help="f(n) in closed form (valid below the cap) instead of `gendpde eos`")
    ap.add_argument("--rc", type=float, default=RC, help="density cutoff (4: the paper's, with the GenDPDE comparison)")
    ap.add_argument("--model", choices=["vdw", "lj"], default="vdw", help="particle EOS: vdW excess or LJ (Kolafa-Nezbeda)")
    ap.add_argument("--T", type=float, default=T, help="temperature (a run's <T_int> for the engine comparison)")
    args = ap.parse_args()
    RC, T = args.rc, args.T

    start = time.time()
    mc = monte_carlo(args.n, args.sweeps, args.equil, args.seed, args.model, args.analytic)
    wall = time.time() - start
    m, m_err = block_sem(mc["means"])
    v, v_err = block_sem(mc["vars"])
    p, p_err = block_sem(mc["pressures"])
    grid, f, slope = mc["table"]
    rho_t = np.interp(RHO, grid, slope)
    eos = common.eos(LJ_EOS if args.model == "lj" else EOS, T, RHO)["pressure"]
    pressure = {"model": args.model, "rc": RC, "T": T, "N": mc["N"], "sweeps": args.sweeps, "equil": args.equil,
                "P": p, "P_err": p_err, "mean_n": m, "mean_n_err": m_err, "std_n": v ** 0.5, "P_eos": eos,
                "P_mean_field": RHO * T + RHO * RHO * T * rho_t, "acceptance": mc["acceptance"], "wall_s": round(wall, 1)}
    print(pressure, flush=True)
    if RC != 4.0 or args.model != "vdw" or args.T != 1.5:
        try:
            rows = common.saved("local_density_mc_pressure")
        except (OSError, KeyError):
            rows = {}
        rows[f"{args.model}_rc{RC:g}_N{mc['N']}_T{T:.4f}"] = pressure
        common.save("local_density_mc_pressure", rows)
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
