#!/usr/bin/env python3
"""Figs 8 and 9 of the 2019 paper: spontaneous vapour-liquid separation of the LJ GenDPDE
fluid at T = 1, rho = 0.2 in the 68.4 x 38.5 x 51.3 box, from a simple cubic lattice.

    python3 scripts/validation/vapour_liquid.py [--ly 38.5 --lz 51.3] [--steps 20000] [--gamma 0.45]
    python3 scripts/validation/vapour_liquid.py --plot   # only the figure, from results.json

The friction is gamma = 0.45 rather than the paper's 4.5 unless --gamma says otherwise: the
pressure of the homogeneous fluid is the same at both (pressure.py), and the separation, limited by the
particles' diffusion (D ~ T / (gamma n [w]) with [w] = 2 pi rc^3 / 15: 0.04 in the vapour
and 0.01 in the liquid at gamma = 4.5), runs about ten times faster.

Outputs: density profiles along x at several times (from the H5MD dump), the coexistence
densities (means of the densest and the most dilute quarter of the final profile bins,
with the profile centred on its centre of mass), the pressure, Pxx, Pyy, Pzz over the
last half, and the surface tension sigma = (Lx/k) <Pxx - (Pyy + Pzz)/2> over the k interfaces
of the last profile (k = 2 for one slab spanning y and z, normal x). Reference lines: the coexistence of the Kolafa-Nezbeda EOS
itself at T = 1 (Maxwell's equal-area construction on its isotherm, `gendpde eos`), and
the paper's saturation pressure 0.029(22) and surface tension 0.18.
"""
import argparse

import numpy as np

import common

LX = 68.4


def maxwell(T=1.0):
    """(rho_vapour, rho_liquid, P_sat) of the KN EOS by equal areas in the P-v plane."""
    rho = np.linspace(0.004, 0.9, 450)
    p = np.array([common.eos("lj 60.0", T, r)["pressure"] for r in rho])
    v = 1.0 / rho

    def roots(ps):
        s = np.sign(p - ps)
        k = np.nonzero(s[:-1] != s[1:])[0]
        return [(rho[i] + (ps - p[i]) * (rho[i + 1] - rho[i]) / (p[i + 1] - p[i])) for i in k]

    def area(ps):
        r = roots(ps)
        lo, hi = r[0], r[-1]  # vapour and liquid densities
        g = np.linspace(1 / hi, 1 / lo, 4000)
        pg = np.interp(1 / g, rho, p)
        return np.trapezoid(pg - ps, g), lo, hi

    a, b = max(p.min(), 1e-6), p[(rho > 0.05) & (rho < 0.3)].max()  # within the loop
    for _ in range(60):
        mid = 0.5 * (a + b)
        s, _, _ = area(mid)
        a, b = (mid, b) if s > 0 else (a, mid)
    _, lo, hi = area(0.5 * (a + b))
    return lo, hi, 0.5 * (a + b)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ly", type=float, default=38.5)
    ap.add_argument("--lz", type=float, default=51.3)
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--dump", type=int, default=1000)
    ap.add_argument("--gamma", type=float, default=0.45)
    ap.add_argument("--eos", default=f"lj 60.0 {common.LJ_TABLE}")
    ap.add_argument("--start", choices=["lattice", "slab"], default="lattice",
                    help="the paper's quench from the lattice, or a liquid slab in vapour (results: vapour_liquid_slab)")
    ap.add_argument("--slab", default="25.35,43.05,0.66,0.04", help="slab start: xlo,xhi,rho_liquid,rho_vapour")
    ap.add_argument("--plot", action="store_true", help="only redraw the figure from results.json")
    args = ap.parse_args()
    scene = "vapour_liquid" if args.start == "lattice" else "vapour_liquid_slab"
    if args.plot:
        return plot(common.saved(scene), scene)
    tag = f"{args.ly}x{args.lz}_g{args.gamma}" + ("" if args.start == "lattice" else f"_slab{args.slab}_s{args.steps}")
    wd = common.workdir("vapour_liquid", tag)
    wd.mkdir(parents=True, exist_ok=True)
    v = {"ly": args.ly, "lz": args.lz, "steps": args.steps, "dump": args.dump, "eos": args.eos, "every": 100,
         "gamma": args.gamma, "start": args.start, "ckpt": args.dump}
    if args.start == "slab":
        v.update(zip(("xlo", "xhi", "rhol", "rhov"), args.slab.split(",")))
    blocks, wall = common.run_once("vapour-liquid", v, wd)
    run = blocks[-1]
    x = common.h5md_frames(wd / "traj.h5", "position")[..., 0] % LX
    frames = x.shape[0]
    nbins = 40
    area = args.ly * args.lz
    width = LX / nbins

    def profile(xs):
        # centre the slab: shift by the circular mean of x
        ang = 2 * np.pi * xs / LX
        c = np.arctan2(np.sin(ang).mean(), np.cos(ang).mean()) * LX / (2 * np.pi)
        h, _ = np.histogram((xs - c + LX / 2) % LX, bins=nbins, range=(0, LX))
        return h / (area * width)

    final = np.mean([profile(x[k]) for k in range(frames // 2, frames)], axis=0)
    srt = np.sort(final)
    q = nbins // 4
    rho_v, rho_l = float(srt[:q].mean()), float(srt[-q:].mean())
    # errors: the same quarters frame by frame over the second half, block averages
    per_frame = np.sort([profile(x[k]) for k in range(frames // 2, frames)], axis=1)
    rho_v_err = common.mean_sem(per_frame[:, :q].mean(axis=1), blocks=5)[1]
    rho_l_err = common.mean_sem(per_frame[:, -q:].mean(axis=1), blocks=5)[1]
    half = len(run["Step"]) // 2
    stats = {k: common.mean_sem(run[k][half:]) for k in ["Press", "Pxx", "Pyy", "Pzz", "Temp", "Tint"]}
    pn = np.asarray(run["Pxx"][half:]) - 0.5 * (np.asarray(run["Pyy"][half:]) + np.asarray(run["Pzz"][half:]))
    # interfaces: crossings of the mid density in the last frame's profile (periodic); the
    # pressure-tensor integral over x counts each one, so sigma = Lx <Pxx - Pt> / interfaces
    last = profile(x[-1])
    above = last > 0.5 * (rho_v + rho_l)
    interfaces = int(np.count_nonzero(above != np.roll(above, 1)))
    sigma = common.mean_sem(LX / max(interfaces, 2) * pn)
    slab_peak = float(np.convolve(last, np.ones(3) / 3, mode="valid").max())
    try:  # the EOS's own coexistence, as the quench run stored it (450 `gendpde eos` calls)
        c = common.saved("vapour_liquid")["eos_coexistence"]
        mv, ml, ps = c["rho_vapour"], c["rho_liquid"], c["P_sat"]
    except (OSError, KeyError):
        mv, ml, ps = maxwell()
    entry = {"box": [LX, args.ly, args.lz], "N": int(x.shape[1]), "steps": args.steps, "gamma": args.gamma, "wall_s": round(wall, 1),
             "rho_vapour": rho_v, "rho_liquid": rho_l, "rho_vapour_err": rho_v_err, "rho_liquid_err": rho_l_err,
             "progress": progress([profile(x[k]) for k in range(frames)], args.dump * 0.01, rho_v, rho_l),
             "start": args.start, "P": stats["Press"], "T_kin": stats["Temp"], "T_int": stats["Tint"],
             "surface_tension": sigma, "interfaces": interfaces, "slab_peak": slab_peak, "last_profile": [float(r) for r in last],
             "eos_coexistence": {"rho_vapour": mv, "rho_liquid": ml, "P_sat": ps},
             "paper": {"P_sat_reference": 0.029, "surface_tension": 0.18}, "eos": args.eos}
    centres = (np.arange(nbins) + 0.5) * width
    entry["profiles"] = {"x": [float(c) for c in centres],
                         **{f"{k * args.dump * 0.01:g}": [float(r) for r in profile(x[k])]
                            for k in sorted({0, frames // 4, frames // 2, frames - 1})}}
    entry["series"] = common.series(run, t="Time", T_kin="Temp", T_int="Tint", P="Press")
    print({k: v for k, v in entry.items() if k not in ("series", "profiles", "last_profile")})
    plot(entry, scene)
    common.save(scene, entry)


def progress(profiles, dt, rho_v, rho_l):
    """The separation's progress frame by frame: time, the number of interfaces (crossings
    of the mid density) and the amplitudes |rho_m| / (rho_l - rho_v) of the profile's first
    four Fourier modes along x (one sharp slab filling a fraction f of the box: mode 1 at
    2 sin(pi f)/pi, 0.47 at f = 1/4; shorter wavelengths dominate while several domains
    remain)."""
    rows = []
    for k, p in enumerate(profiles):
        above = p > 0.5 * (rho_v + rho_l)
        modes = np.abs(np.fft.rfft(p - p.mean()))[1:5] * 2 / len(p) / (rho_l - rho_v)
        rows.append([round(k * dt, 3), int(np.count_nonzero(above != np.roll(above, 1)))] + [round(float(a), 4) for a in modes])
    return rows


def plot(entry, scene="vapour_liquid"):
    """Figs 8 and 9 from the results entry: density profiles, temperatures, pressure."""
    import sys
    if "series" not in entry:
        sys.exit("results.json holds no vapour_liquid series (written from this version on): rerun the scene")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    coex, s = entry["eos_coexistence"], entry["series"]
    fig, (a, b, c) = plt.subplots(1, 3, figsize=(16, 4.5))
    profiles = dict(entry["profiles"])
    centres = profiles.pop("x")
    for t, prof in profiles.items():
        a.plot(centres, prof, label=f"t = {t} τ")
    a.axhline(coex["rho_vapour"], color="k", ls=":", label="KN EOS coexistence")
    a.axhline(coex["rho_liquid"], color="k", ls=":")
    a.set_xlabel("x, slab centred [σ, reduced units]")
    a.set_ylabel("number density [σ⁻³, reduced units]")
    a.set_title("Fig 8: density profiles")
    a.legend(fontsize=8)
    b.plot(s["t"], s["T_kin"], "k", lw=0.7, label=r"$T_{kin}$")
    b.plot(s["t"], s["T_int"], "r", lw=0.7, label=r"$T_{int}$")
    b.set_xlabel("time t [τ, reduced units]")
    b.set_ylabel("temperature [ε/k_B, reduced units]")
    b.set_title("Fig 9: temperatures")
    b.legend(fontsize=8)
    c.plot(s["t"], s["P"], "b", lw=0.7, label="P")
    c.axhline(entry["paper"]["P_sat_reference"], color="orange", label="P_sat (paper's reference)")
    c.axhline(coex["P_sat"], color="orange", ls=":", label="P_sat (KN EOS)")
    c.set_xlabel("time t [τ, reduced units]")
    c.set_ylabel("pressure P [ε/σ³, reduced units]")
    c.set_title("Fig 9: pressure")
    c.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(common.figure_path(scene), dpi=80)


if __name__ == "__main__":
    main()
