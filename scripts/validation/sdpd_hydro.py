#!/usr/bin/env python3
"""Hydrodynamics of thermal SDPD (pair sdpd/generic, Serrano-Espanol Sec VII) against
its inputs, deterministic (kB 0) so that one run per point suffices:

- shear: v_x = A sin(k z) decays as exp(-eta k^2 t / rho)          -> eta
  (fitted over t < --fit: started from a lattice, the sheared lattice's elasticity takes
  over later); compared with eta/rho and with the linearised discrete equations on the
  lattice (kernel smoothing W(k)^2, exact for small amplitudes)
- heat:  theta = T + dT sin(k x) relaxes as A e^(-D_T k^2 t) + B e^(-G t) cos(c k t + phi):
  the entropy mode gives D_T = kappa/(n c_p), the sound mode c_s^2 = dP/drho|_s

each as a function of the kernel support h (in lattice spacings, h/lambda). The
fluid is eos/vdw/reduced 1.0 at n~ = 1 and T~ (default 1.5), lattice sc 1, mass 1.
Deterministic (kB 0) and from a lattice: a skeleton for the fluid-state, noisy runs.

    python3 scripts/validation/sdpd_hydro.py [--n 12] [--h 2.0 2.4 3.0] [--tests shear heat]

Writes docs/validation/results.json entry "sdpd_hydro".
"""
import argparse
import math
import subprocess
from pathlib import Path

import numpy as np

import common

# eos/vdw/reduced 1.0: C_V = 3/2, P = n T/(1 - n/3) - (9/8) n^2 (k_B = 1, mass 1)
CV = 1.5


def pressure(n, t):
    return n * t / (1 - n / 3) - 9 / 8 * n * n


def adiabatic_sound_speed(n, t, h=1e-6):
    """c^2 = dP/dn at fixed entropy: along T(n) with dT/dn|_s = T (dP/dT)_n/(n^2 C_V)."""
    dpdn_t = (pressure(n + h, t) - pressure(n - h, t)) / (2 * h)
    dpdt_n = (pressure(n, t + h) - pressure(n, t - h)) / (2 * h)
    dtdn_s = t * dpdt_n / (n * n * CV)
    return math.sqrt(dpdn_t + dpdt_n * dtdn_s)


def heat_capacities(n, t, h=1e-6):
    """(c_v, c_p) per particle."""
    dpdn_t = (pressure(n + h, t) - pressure(n - h, t)) / (2 * h)
    dpdt_n = (pressure(n, t + h) - pressure(n, t - h)) / (2 * h)
    return CV, CV + t * dpdt_n ** 2 / (n * n * dpdn_t)


def data_file(path, n, t, test, amp):
    """An sc lattice of n^3 particles with the initial wave of `test`."""
    box = float(n)
    k = 2 * math.pi / box
    lines = ["sdpd validation\n", f"{n ** 3} atoms", "1 atom types",
             f"0 {box} xlo xhi", f"0 {box} ylo yhi", f"0 {box} zlo zhi", "", "Masses", "", "1 1.0", "", "Atoms # dpd", ""]
    vel = ["", "Velocities", ""]
    i = 0
    for a in range(n):
        for b in range(n):
            for c in range(n):
                i += 1
                x, y, z = a + 0.5, b + 0.5, c + 0.5
                theta, vx = t, 0.0
                if test == "shear":
                    vx = amp * math.sin(k * z)
                else:
                    theta = t + amp * math.sin(k * x)
                lines.append(f"{i} 1 {theta!r} {x!r} {y!r} {z!r}")
                vel.append(f"{i} {vx!r} 0 0")
    Path(path).write_text("\n".join(lines + vel) + "\n")


SCRIPT = """units lj
atom_style gendpde
read_data data.wave
pair_style sdpd/generic {h} 4928 kB 0
pair_coeff * * {eta} {zeta} {kappa}
fix eos all eos/vdw/reduced 1.0
fix int all nve/sdpd
timestep {dt}
neighbor 0.3 bin
neigh_modify every 1 delay 0 check yes
thermo {every}
dump d all custom {every} wave.dump id x y z vx theta
run {steps}
"""


def frames(path):
    """[(step, array of rows id x y z vx theta)] from a text dump."""
    out, lines = [], Path(path).read_text().splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            count = int(lines[i + 3])
            rows = np.array([[float(v) for v in lines[i + 9 + j].split()] for j in range(count)])
            out.append((step, rows[np.argsort(rows[:, 0])]))
            i += 9 + count
        else:
            i += 1
    return out


def mode(values, coord, k):
    """Amplitude of sin(k coord) and cos(k coord) in `values`."""
    return 2 * np.mean(values * np.sin(k * coord)), 2 * np.mean(values * np.cos(k * coord))


def lucy(h):
    """W(r) and W'(r) of the normalised Lucy kernel of support h (the pair style's default)."""
    norm = 16 * math.pi / 105 * h ** 3

    def w(r):
        q = r / h
        return np.where(q < 1, (1 + 3 * q) * (1 - q) ** 3 / norm, 0.0)

    def dw(r):
        q = r / h
        return np.where(q < 1, (3 * (1 - q) ** 3 - 3 * (1 + 3 * q) * (1 - q) ** 2) / h / norm, 0.0)
    return w, dw


def lattice_shear_rate(h, n, eta):
    """Decay rate of v_x = sin(k z) under the linearised viscous step on the sc lattice:
    L^zx = d^-2 sum W' e_z (v_nu - v_mu), sigma^zx = -eta d L^zx, F^x = -sum W' e_z
    (sigma_nu + sigma_mu)/d^2 (mass 1, eq 82 with the SPH Omega)."""
    w, dw = lucy(h)
    m = int(math.ceil(h))
    pts = np.array([(a, b, c) for a in range(-m, m + 1) for b in range(-m, m + 1) for c in range(-m, m + 1) if (a, b, c) != (0, 0, 0)], float)
    r = np.linalg.norm(pts, axis=1)
    d = float(w(0.0) + w(r).sum())
    k = 2 * math.pi / n
    ez = -pts[:, 2] / r

    def lzx(z0):
        return float((dw(r) * ez * (np.sin(k * (z0 + pts[:, 2])) - np.sin(k * z0))).sum()) / d ** 2

    def sig(z0):
        return -eta * d * lzx(z0)
    z0 = n / 4
    force = -float((dw(r) * ez * (np.array([sig(z0 + dz) for dz in pts[:, 2]]) + sig(z0))).sum()) / d ** 2
    return -force


def run_case(test, n, h, t, args):
    wd = common.workdir("sdpd_hydro", f"{test}_n{n}_h{h}")
    wd.mkdir(parents=True, exist_ok=True)
    data_file(Path(wd) / "data.wave", n, t, test, 0.1)
    steps = args.steps if test == "shear" else args.heat_steps
    script = SCRIPT.format(h=h, eta=args.eta, zeta=args.zeta, kappa=args.kappa, dt=args.dt, every=10, steps=steps)
    (Path(wd) / "in.wave").write_text(script)
    subprocess.run([common.GENDPDE, "run", "in.wave", "-log", "none"], cwd=wd, check=True, capture_output=True)
    k = 2 * math.pi / n
    series = []
    for step, rows in frames(Path(wd) / "wave.dump"):
        x, z, vx, theta = rows[:, 1], rows[:, 3], rows[:, 4], rows[:, 5]
        if test == "shear":
            series.append((step * args.dt, mode(vx, z, k)[0]))
        else:
            series.append((step * args.dt, mode(theta, x, k)[0]))
    tt, a = np.array(series).T
    if test == "shear":
        keep = tt <= args.fit
        rate = -np.polyfit(tt[keep], np.log(a[keep]), 1)[0]
        return {"rate": float(rate), "eta_measured": float(rate / k ** 2), "rate_lattice": lattice_shear_rate(h, n, args.eta),
                "rate_continuum": args.eta * k * k}
    from scipy.optimize import curve_fit

    def model(t_, a0, ra, b0, rb, om, ph):
        return a0 * np.exp(-ra * t_) + b0 * np.exp(-rb * t_) * np.cos(om * t_ + ph)
    c0 = adiabatic_sound_speed(1.0, t)
    p0 = [0.03, 0.05, 0.07, 0.05, c0 * k, 0.0]
    try:
        p, cov = curve_fit(model, tt, a, p0=p0, maxfev=20000)
    except RuntimeError as e:
        return {"fit": str(e)}
    err = np.sqrt(np.diag(cov))
    return {"D_T": float(p[1] / k ** 2), "D_T_err": float(err[1] / k ** 2), "c_s": float(abs(p[4]) / k),
            "c_s_err": float(err[4] / k), "entropy_fraction": float(p[0] / 0.1)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=12)
    ap.add_argument("--h", type=float, nargs="+", default=[2.0, 2.4, 3.0])
    ap.add_argument("--T", type=float, default=1.5)
    ap.add_argument("--eta", type=float, default=1.0)
    ap.add_argument("--zeta", type=float, default=1.0)
    ap.add_argument("--kappa", type=float, default=1.0)
    ap.add_argument("--dt", type=float, default=0.01)
    ap.add_argument("--steps", type=int, default=300, help="steps of the shear runs")
    ap.add_argument("--heat-steps", type=int, default=4000)
    ap.add_argument("--fit", type=float, default=1.0, help="shear fit window (time)")
    ap.add_argument("--tests", nargs="+", default=["shear", "heat"])
    args = ap.parse_args()
    n_mol = 1.0
    c_s = adiabatic_sound_speed(n_mol, args.T)
    cv, cp = heat_capacities(n_mol, args.T)
    out = {"inputs": {"eta": args.eta, "kappa": args.kappa, "c_s": c_s, "D_T_cp": args.kappa / cp, "D_T_cv": args.kappa / cv,
                      "nu": args.eta, "T": args.T, "N": args.n ** 3, "dt": args.dt}}
    for h in args.h:
        row = {}
        for test in args.tests:
            row[test] = run_case(test, args.n, h, args.T, args)
            print(f"h {h} {test}: {row[test]}", flush=True)
        out[f"h{h}"] = row
    common.save("sdpd_hydro", out)


if __name__ == "__main__":
    main()
