#!/usr/bin/env python3
"""Hydrodynamics and equilibrium of thermal SDPD (pair sdpd/generic, Serrano-Espanol
Sec VII) against its inputs. The fluid is eos/vdw/reduced 1.0 at n~ = 1 and T~ = 1.5
(mass 1, C_V = 3/2), Lucy kernel of support h in mean particle spacings (h/lambda,
lambda = n^-1/3 = 1), eta = zeta = kappa = 1.

**Hydrodynamics** (`--parts hydro`). A fluid start: N particles at random positions,
relaxed for --eq steps with the noise on (kB, default 0.01: the per-particle fluctuations
k_B/C_V = 1/150 of particles of 100 molecules), then waves of wave number k = 2 pi/L,
each along its own axis so that linear hydrodynamics keeps them apart (the two velocity
waves in one run, the temperature wave in runs of its own with a larger amplitude --dT):

- temperature theta += dT sin(k x): its x-mode relaxes as A e^(-D_T k^2 t) plus a damped
  sound mode; the entropy mode gives D_T = kappa/(n c_p), A = dT c_v/c_p;
- transverse v_x += a sin(k z): decays as e^(-eta k^2 t/rho);
- longitudinal v_y += a sin(k y): a damped oscillation e^(-G t) cos(w t + phi),
  sqrt(w^2 + G^2) = c_s k with c_s^2 = dP/drho at fixed entropy of the EOS.

Each seed runs twice, with +amplitude and -amplitude and the same noise (Philox keyed by
seed, step, tag): half the difference of the two mode series removes the thermal
background to linear order; the spread over seeds gives the errors. SPH smooths every
gradient of a Fourier mode by the kernel's transform W^(k) = int W(r) e^(ik.r) d^3r (by
parts, int grad W sin(k x) = -k int W cos(k x)), so the continuum SPH equations give
rate_shear = nu k^2 W^2, w0 = c_s k W^, rate_heat = D_T k^2 W^2; both the bare and the
smoothed targets are reported.

**Heat-mode sign** (`--parts heat`): the temperature wave alone, deterministic (kB 0),
from the sc lattice and from the relaxed random start, at k h = 1.26 (box 12^3) and
0.63 (box 24 x 8 x 8), +/- runs as above: the entropy mode's theta amplitude against
c_v/c_p dT and its rate against D_T k^2.

**Equilibrium** (`--parts equilibrium`): N0 = 10 molecules per particle (C_V = 15,
kB = 1), 12^3 particles from the lattice: T_kin against <theta>, the per-particle
theta distribution against eq 111 (Gamma, shape C_V/k_B, mean T: var T^2 k_B/C_V,
skewness 2 (k_B/C_V)^1/2) and the velocity components against Maxwell (variance
k_B T/M, excess kurtosis 0).

`--volume normalized` repeats the hydrodynamics with the remnant-free force of eqs 97-99
(entry "hydro_normalized"), `--eq-dt` the equilibrium at a smaller time step over the same
times (entry "equilibrium_dt<dt>"). Runs are cached in $VALIDATION_WORK/sdpd_hydro/*/row.json.

    python3 scripts/validation/sdpd_hydro.py [--parts hydro heat equilibrium] [--seeds 4] [--plot]

Writes docs/validation/results.json entry "sdpd_hydro" and docs/validation/sdpd_hydro.png.
"""
import argparse
import math
import subprocess
import time
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


def lucy_transform(h, k):
    """W^(k) = 4 pi int W(r) r^2 sin(kr)/(kr) dr of the normalised Lucy kernel of support h."""
    r = np.linspace(0.0, h, 4001)
    q = r / h
    w = (1 + 3 * q) * (1 - q) ** 3 / (16 * math.pi / 105 * h ** 3)
    f = 4 * math.pi * w * r * r * np.sinc(k * r / math.pi)
    return float(np.sum((f[1:] + f[:-1]) / 2) * (r[1] - r[0]))


START = {
    "lattice": "lattice sc 1.0\nregion box block 0 {nx} 0 {ny} 0 {nz}\ncreate_box 1 box\ncreate_atoms 1 box\n",
    "random": "region box block 0 {nx} 0 {ny} 0 {nz}\ncreate_box 1 box\ncreate_atoms 1 random {count} {seed} NULL\n",
}

SCRIPT = """units lj
atom_style gendpde
{start}mass 1 1.0
set group all theta {T}
pair_style sdpd/generic {h} {seed} kB {kB} volume {volume}
pair_coeff * * {eta} {zeta} {kappa}
fix eos all eos/vdw/reduced 1.0
fix int all nve/sdpd
timestep {dt}
neighbor 0.3 bin
neigh_modify every 1 delay 0 check yes
thermo 100
run {eq}
variable kx equal 2*PI/lx
variable ky equal 2*PI/ly
variable kz equal 2*PI/lz
variable tw atom {T}+{dT}*sin(v_kx*x)
variable vxw atom vx+{av}*sin(v_kz*z)
variable vyw atom vy+{av}*sin(v_ky*y)
set group all theta v_tw vx v_vxw vy v_vyw
dump d all custom {every} wave.dump id x y z vx vy theta n
run {steps}
"""


def frames(path):
    """[array of rows (id x y z vx vy theta n)] of a text dump, in dump order."""
    lines = Path(path).read_text().splitlines()
    out, i = [], 0
    while i < len(lines):
        count = int(lines[i + 3])
        out.append(np.loadtxt(lines[i + 9:i + 9 + count]))
        i += 9 + count
    return out


def mode(values, coord, k):
    """Amplitude of the field's sin(k coord) mode from per-particle `values`, the mean
    taken out first: sum_i f_i sin(k x_i) samples n(x) f(x), so without it a density
    mode adds f_mean dn/n (the particle-weighted projection of a uniform field is not 0)."""
    return float(2 * np.mean((values - values.mean()) * np.sin(k * coord)))


def run(case, sign, args):
    """Mode series of one run: {t, theta_x, n_x, vx_z, vy_y}."""
    nx, ny, nz = case["dims"]
    tag = f"{case['start']}_{nx}x{ny}x{nz}_h{case['h']}_kB{case['kB']}_s{case['seed']}{case.get('label', '')}_{'p' if sign > 0 else 'm'}"
    wd = common.workdir("sdpd_hydro", tag)
    wd.mkdir(parents=True, exist_ok=True)

    def compute():
        start = START[case["start"]].format(nx=nx, ny=ny, nz=nz, count=nx * ny * nz, seed=case["seed"])
        script = SCRIPT.format(start=start, T=args.T, h=case["h"], seed=case["seed"], kB=case["kB"], eta=args.eta,
                               zeta=args.zeta, kappa=args.kappa, dt=args.dt, eq=case["eq"], dT=sign * case["dT"], volume=args.volume,
                               av=sign * case["av"], every=case["every"], steps=case["steps"])
        (wd / "in.wave").write_text(script)
        t0 = time.time()
        subprocess.run([common.GENDPDE, "run", "in.wave", "-log", "none"], cwd=wd, check=True, capture_output=True)
        wall = time.time() - t0
        ks = [2 * math.pi / d for d in (nx, ny, nz)]
        rows = {"t": [], "theta_x": [], "n_x": [], "vx_z": [], "vy_y": []}
        for j, f in enumerate(frames(wd / "wave.dump")):
            x, y, z, vx, vy, theta, n = (f[:, c] for c in range(1, 8))
            rows["t"].append(j * case["every"] * args.dt)
            rows["theta_x"].append(mode(theta, x, ks[0]))
            rows["n_x"].append(mode(n, x, ks[0]))
            rows["vx_z"].append(mode(vx, z, ks[2]))
            rows["vy_y"].append(mode(vy, y, ks[1]))
        (wd / "wave.dump").unlink()
        rows["wall_s"] = wall
        return rows
    return common.cached(wd, compute)


def relaxed_factors(case, args):
    """`discrete_factors` on the relaxed start of `case` (the state the waves are added to)."""
    nx = case["dims"][0]
    wd = common.workdir("sdpd_hydro", f"relaxed_{nx}_h{case['h']}_kB{case['kB']}_s{case['seed']}{case.get('label', '')}")
    wd.mkdir(parents=True, exist_ok=True)

    def compute():
        start = START[case["start"]].format(nx=nx, ny=nx, nz=nx, count=nx ** 3, seed=case["seed"])
        script = SCRIPT.format(start=start, T=args.T, h=case["h"], seed=case["seed"], kB=case["kB"], eta=args.eta,
                               zeta=args.zeta, kappa=args.kappa, dt=args.dt, eq=case["eq"], dT=0, av=0, every=1, steps=0,
                               volume=args.volume)
        (wd / "in.relax").write_text(script.split("variable kx")[0] + "write_dump all custom relaxed.dump id x y z\n")
        subprocess.run([common.GENDPDE, "run", "in.relax", "-log", "none"], cwd=wd, check=True, capture_output=True)
        pos = np.loadtxt(wd / "relaxed.dump", skiprows=9)[:, 1:4]
        return discrete_factors(pos, float(nx), case["h"], args)
    return common.cached(wd, compute)


def antithetic(case, args):
    """Half the difference of the +/- runs' mode series (the response to the waves)."""
    p, m = run(case, 1, args), run(case, -1, args)
    return {key: np.array(p["t"]) if key == "t" else (np.array(p[key]) - np.array(m[key])) / 2
            for key in ("t", "theta_x", "n_x", "vx_z", "vy_y")}, p["wall_s"] + m["wall_s"]


def fit_shear(t, a, k):
    keep = a > 0.15 * a[0]
    from scipy.optimize import curve_fit
    p, _ = curve_fit(lambda t_, a0, r: a0 * np.exp(-r * t_), t[keep], a[keep], p0=[a[0], k * k])
    return float(p[1])


def fit_sound(t, a, k, c0):
    from scipy.optimize import curve_fit
    p, _ = curve_fit(lambda t_, a0, g, w, ph: a0 * np.exp(-g * t_) * np.cos(w * t_ + ph), t, a,
                     p0=[a[0], k * k, c0 * k, 0.0], maxfev=20000)
    g, w = float(p[1]), abs(float(p[2]))
    return math.sqrt(w * w + g * g) / k, g


def fit_heat(t, a, k, c0, d0):
    """Entropy-mode rate and amplitude of theta's mode: A e^(-r t) + B e^(-G t) cos(w t + phi)."""
    from scipy.optimize import curve_fit
    p, _ = curve_fit(lambda t_, a0, r, b0, g, w, ph: a0 * np.exp(-r * t_) + b0 * np.exp(-g * t_) * np.cos(w * t_ + ph),
                     t, a, p0=[a[0] / 3, d0 * k * k, a[0] * 2 / 3, k * k, c0 * k, 0.0], maxfev=40000)
    return float(p[1]), float(p[0])


def lucy(h):
    """W(r) and W'(r) of the normalised Lucy kernel of support h (the pair style's default)."""
    norm = 16 * math.pi / 105 * h ** 3

    def w(r):
        q = r / h
        return np.where(q < 1, (1 + 3 * q) * (1 - q) ** 3 / norm, 0.0)

    def dw(r):
        q = r / h
        return np.where(q < 1, -12 * q * (1 - q) ** 2 / h / norm, 0.0)
    return w, dw


def discrete_factors(pos, box, h, args):
    """The linearised irreversible operators of integrators/src/models/sdpd/generic.rs on one configuration
    (kB 0): the initial decay rates of v_x = sin(k z) and of theta = T + e sin(k x) at fixed
    positions, over their continuum values eta k^2/rho and kappa k^2/(n c_v)."""
    from scipy.spatial import cKDTree
    w, dw = lucy(h)
    pos = np.mod(pos, box)
    i, j = cKDTree(pos, boxsize=box).query_pairs(h, output_type="ndarray").T
    r_ij = pos[i] - pos[j]
    r_ij -= box * np.round(r_ij / box)
    r = np.linalg.norm(r_ij, axis=1)
    om = (dw(r) / r)[:, None] * r_ij
    count = len(pos)
    d = float(w(0.0)) + np.bincount(i, w(r), count) + np.bincount(j, w(r), count)
    k = 2 * math.pi / box

    def pair_sum(terms):
        """sum over nu of a pair term that is the same for both partners."""
        out = np.zeros((count,) + terms.shape[1:])
        np.add.at(out, i, terms)
        np.add.at(out, j, terms)
        return out

    def divergence(flux):
        """-sum_nu omega_{mu nu} . (flux_mu/d_mu^2 + flux_nu/d_nu^2), pairwise antisymmetric."""
        f = flux / (d * d).reshape((-1,) + (1,) * (flux.ndim - 1))
        t = -np.einsum("pa,pa...->p...", om, f[i] + f[j])
        out = np.zeros((count,) + t.shape[1:])
        np.add.at(out, i, t)
        np.add.at(out, j, -t)
        return out
    v = np.zeros((count, 3))
    v[:, 0] = np.sin(k * pos[:, 2])
    grad = pair_sum(np.einsum("pa,pb->pab", om, v[j] - v[i])) / (d * d)[:, None, None]
    sym = (grad + grad.transpose(0, 2, 1)) / 2
    tr = np.trace(grad, axis1=1, axis2=2)
    eye = np.eye(3)[None]
    sigma = -(2 * args.eta * d[:, None, None] * (sym - tr[:, None, None] * eye / 3) + args.zeta * d[:, None, None] * tr[:, None, None] * eye)
    shear = -2 * np.mean(divergence(sigma)[:, 0] * np.sin(k * pos[:, 2])) / (args.eta * k * k)
    eps = 1e-4
    theta = args.T + eps * np.sin(k * pos[:, 0])
    a = pair_sum(om * (1 / theta[j] - 1 / theta[i])[:, None])
    du = divergence(args.kappa * (theta * theta / d)[:, None] * a)
    heat = -2 * np.mean(du * np.sin(k * pos[:, 0])) / (CV * eps) / (args.kappa * k * k / CV)
    return {"shear": float(shear), "heat": float(heat), "d_mean": float(d.mean())}


def mean_err(values):
    v = np.asarray(values, float)
    return float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v))) if len(v) > 1 else float("nan")


def hydro(args, out):
    c0 = adiabatic_sound_speed(1.0, args.T)
    cv, cp = heat_capacities(1.0, args.T)
    d0 = args.kappa / cp
    n = args.n
    k = 2 * math.pi / n
    rows = []
    volume_label = "" if args.volume == "plain" else f"_{args.volume}"
    for h in args.h:
        wk = lucy_transform(h, k)
        per = {"shear": [], "c_s": [], "D_T": [], "A_entropy": [], "wall_s": 0.0}
        series = {}
        for s in range(args.seeds):
            case = {"start": "random", "dims": (n, n, n), "h": h, "kB": args.kB, "seed": 4928 + 17 * s, "eq": args.eq,
                    "dT": 0.1, "av": 0.1, "every": 5, "steps": args.steps, "label": volume_label}
            m, wall = antithetic(case, args)
            per["wall_s"] += wall
            per["shear"].append(fit_shear(m["t"], m["vx_z"], k) / (k * k))
            per["c_s"].append(fit_sound(m["t"], m["vy_y"], k, c0 * wk)[0])
            if s < args.heat_seeds:
                # the entropy mode is weaker (c_v/c_p of dT) and slower: its own runs, larger dT
                hot = dict(case, dT=args.dT, av=0.0, label=f"_dT{args.dT}{volume_label}")
                mh, wall = antithetic(hot, args)
                per["wall_s"] += wall
                r, a0 = fit_heat(mh["t"], mh["theta_x"], k, c0 * wk, d0 * wk * wk)
                per["D_T"].append(r / (k * k))
                per["A_entropy"].append(a0 / args.dT)
                if s == 0:
                    series["theta_x_dT"] = [float(f"{v:.5g}") for v in mh["theta_x"]]
            f = relaxed_factors(case, args)
            for key in ("shear", "heat", "d_mean"):
                per.setdefault("op_" + key, []).append(f[key])
            if s == 0:
                series.update({key: [float(f"{v:.5g}") for v in m[key]] for key in m})
        row = {"h": h, "kh": h * k, "W_k": wk, "wall_s": per["wall_s"], "series_seed0": series}
        for key in ("shear", "c_s", "D_T", "A_entropy", "op_shear", "op_heat", "op_d_mean"):
            if not per.get(key):
                continue
            row[key] = mean_err(per[key])
            row[key + "_seeds"] = per[key]
        row["targets"] = {"nu": args.eta, "nu_sph": args.eta * wk * wk, "c_s": c0, "c_s_sph": c0 * wk,
                          "D_T": d0, "D_T_sph": d0 * wk * wk, "A_entropy": cv / cp}
        # uniform compression scales d with n: c^2 = (d/n) dP/dd|_s at the fluid's mean d
        dm = row["op_d_mean"][0]
        row["targets"]["c_s_d"] = math.sqrt(dm) * adiabatic_sound_speed(dm, args.T)
        print(f"h {h}: {({q: row.get(q) for q in ('kh', 'W_k', 'shear', 'c_s', 'D_T', 'A_entropy', 'op_shear', 'op_heat', 'op_d_mean', 'wall_s')})}", flush=True)
        rows.append(row)
    for i, row in enumerate(rows):  # the figure draws the plain runs' middle row, every 2nd frame
        keep = i == len(rows) // 2 and not volume_label
        row["series_seed0"] = {q: v[::2] for q, v in row["series_seed0"].items()} if keep else {}
    out["hydro" + volume_label] = {"inputs": {"eta": args.eta, "zeta": args.zeta, "kappa": args.kappa, "T": args.T, "kB": args.kB,
                               "N": n ** 3, "dt": args.dt, "eq_steps": args.eq, "steps": args.steps, "seeds": args.seeds,
                               "heat_seeds": args.heat_seeds, "dT": args.dT, "volume": args.volume,
                               "c_s": c0, "c_v": cv, "c_p": cp}, "rows": rows}


def heat(args, out):
    """The entropy mode's sign: lattice and random starts, kB 0, two k h."""
    cv, cp = heat_capacities(1.0, args.T)
    c0 = adiabatic_sound_speed(1.0, args.T)
    rows = []
    for dims, steps in (((12, 12, 12), 1600), ((24, 8, 8), 3200)):
        k = 2 * math.pi / dims[0]
        wk = lucy_transform(2.4, k)
        for start in ("lattice", "random"):
            case = {"start": start, "dims": dims, "h": 2.4, "kB": 0.0, "seed": 4928, "eq": 0 if start == "lattice" else args.eq,
                    "dT": 0.1, "av": 0.0, "every": 10, "steps": steps}
            m, wall = antithetic(case, args)
            t, a, d = (m[q] for q in ("t", "theta_x", "n_x"))
            r, a0 = fit_heat(t, a, k, c0 * wk, args.kappa / cp * wk * wk)
            late = t >= t[-1] - 5
            row = {"start": start, "dims": dims, "kh": 2.4 * k, "A_entropy": a0 / 0.1, "D_T": r / (k * k),
                   "D_T_sph": args.kappa / cp * wk * wk, "theta_late": float(a[late].mean()), "n_late": float(d[late].mean()),
                   "t_end": float(t[-1]), "wall_s": wall, "series": {q: [float(f"{v:.4g}") for v in m[q][::2]] for q in ("t", "theta_x")}}
            print({q: row[q] for q in row if q != "series"}, flush=True)
            rows.append(row)
    out["heat"] = {"A_entropy_target": cv / cp, "rows": rows}


EQ_SCRIPT = """units lj
atom_style gendpde
lattice sc 0.1
region box block 0 12 0 12 0 12
create_box 1 box
create_atoms 1 box
mass 1 10.0
velocity all create 1.5 {seed} dist gaussian
set group all theta 1.5
pair_style sdpd/generic {h} {seed} kB 1.0
pair_coeff * * 1.0 1.0 1.0
fix eos all eos/vdw/reduced 10.0
fix int all nve/sdpd
timestep {dt}
neighbor 0.6 bin
neigh_modify every 1 delay 0 check yes
thermo 100
run {eq}
dump d all custom {every} eq.dump id x y z vx vy theta n
run {steps}
"""


def equilibrium(args, out):
    """T_kin, theta and velocity distributions at N0 = 10, kB = 1 (eq 111 and Maxwell)."""
    from scipy import stats
    per = []
    dt, scale = args.eq_dt, round(0.05 / args.eq_dt)
    for s in range(args.seeds):
        seed = 4928 + 17 * s
        wd = common.workdir("sdpd_hydro", f"equilibrium_s{seed}" + ("" if scale == 1 else f"_dt{dt}"))
        wd.mkdir(parents=True, exist_ok=True)

        def compute():
            (wd / "in.eq").write_text(EQ_SCRIPT.format(seed=seed, h=2.4 * 10 ** (1 / 3), dt=dt, eq=1000 * scale, every=50 * scale, steps=2000 * scale))
            t0 = time.time()
            subprocess.run([common.GENDPDE, "run", "in.eq", "-log", "none"], cwd=wd, check=True, capture_output=True)
            wall = time.time() - t0
            fs = frames(wd / "eq.dump")
            theta = np.concatenate([f[:, 6] for f in fs])
            v = np.concatenate([f[:, 4:6].ravel() for f in fs])
            tkin = [10.0 * float(np.mean(f[:, 4:6] ** 2)) for f in fs]
            (wd / "eq.dump").unlink()
            return {"theta_mean": float(theta.mean()), "theta_var": float(theta.var()), "theta_skew": float(stats.skew(theta)),
                    "tkin": float(np.mean(tkin)), "v_var": float(v.var()), "v_kurt": float(stats.kurtosis(v)), "wall_s": wall}
        per.append(common.cached(wd, compute))
    cv = 15.0
    row = {q: mean_err([p[q] for p in per]) for q in per[0] if q != "wall_s"}
    row["tkin_over_theta"] = mean_err([p["tkin"] / p["theta_mean"] for p in per])
    row["var_over_theta2"] = mean_err([p["theta_var"] / p["theta_mean"] ** 2 for p in per])
    row["targets"] = {"var_over_theta2": 1 / cv, "theta_skew": 2 / math.sqrt(cv), "v_kurt": 0.0, "tkin_over_theta": 1.0}
    row["wall_s"] = sum(p["wall_s"] for p in per)
    row["seeds"] = args.seeds
    row["dt"] = dt
    print(row, flush=True)
    out["equilibrium" if scale == 1 else f"equilibrium_dt{dt}"] = row


def plot(out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    hyd = out.get("hydro")
    if hyd:
        rows = hyd["rows"]
        kh = [r["kh"] for r in rows]
        for key, tkey, label, mk in (("shear", "nu", "nu (shear wave)", "o"), ("c_s", "c_s", "c_s (sound)", "s"),
                                     ("D_T", "D_T", "D_T (heat)", "^")):
            y = [r[key][0] / r["targets"][tkey] for r in rows]
            e = [r[key][1] / r["targets"][tkey] for r in rows]
            ax[0].errorbar(kh, y, e, fmt=mk, capsize=3, label=label)
        ax[0].plot(kh, [r["W_k"] ** 2 for r in rows], "k--", lw=1, label="W^2 (nu, D_T)")
        ax[0].plot(kh, [r["W_k"] for r in rows], "k:", lw=1, label="W^ (c_s)")
        ax[0].plot(kh, [r["op_shear"][0] for r in rows], "kx", label="operator on the fluid (nu, D_T)")
        ax[0].axhline(1, color="k", lw=0.5)
        ax[0].set_xlabel("k h (dimensionless)")
        ax[0].set_ylabel("measured / input (dimensionless)")
        ax[0].legend(fontsize=8)
        ax[0].set_title(f"fluid start, kB {hyd['inputs']['kB']}, {hyd['inputs']['seeds']} seeds, N {hyd['inputs']['N']}")
        s = rows[len(rows) // 2]["series_seed0"]
        for key, scale, label in (("vx_z", 0.1, "v_x(z): shear"), ("vy_y", 0.1, "v_y(y): sound"),
                                  ("theta_x_dT", hyd["inputs"]["dT"], "theta(x): heat")):
            ax[1].plot(s["t"], np.array(s[key]) / scale, label=label, lw=1)
        ax[1].axhline(0, color="k", lw=0.5)
        ax[1].set_xlabel("time t (reduced units)")
        ax[1].set_ylabel("mode / initial amplitude (dimensionless)")
        ax[1].set_title(f"h = {rows[len(rows) // 2]['h']}, one seed")
        ax[1].legend(fontsize=8)
    heat_out = out.get("heat")
    if heat_out:
        for r in heat_out["rows"]:
            s = r["series"]
            ax[2].plot(s["t"], s["theta_x"], lw=1, label=f"{r['start']} {'x'.join(map(str, r['dims']))} (kh {r['kh']:.2f})")
        ax[2].axhline(0.1 * heat_out["A_entropy_target"], color="k", ls="--", lw=0.7, label="c_v/c_p dT (uniform P)")
        ax[2].axhline(0, color="k", lw=0.5)
        ax[2].set_xlabel("time t (reduced units)")
        ax[2].set_ylabel("theta mode amplitude (reduced units)")
        ax[2].set_title("heat wave, kB 0: lattice vs fluid start")
        ax[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(common.figure_path("sdpd_hydro"), dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--parts", nargs="+", default=["hydro", "heat", "equilibrium"])
    ap.add_argument("--n", type=int, default=12, help="box side (particles per side at n = 1)")
    ap.add_argument("--h", type=float, nargs="+", default=[2.0, 2.4, 3.0])
    ap.add_argument("--T", type=float, default=1.5)
    ap.add_argument("--eta", type=float, default=1.0)
    ap.add_argument("--zeta", type=float, default=1.0)
    ap.add_argument("--kappa", type=float, default=1.0)
    ap.add_argument("--kB", type=float, default=0.01)
    ap.add_argument("--dt", type=float, default=0.05)
    ap.add_argument("--eq", type=int, default=300, help="relaxation steps of the random start")
    ap.add_argument("--steps", type=int, default=800, help="steps after the waves are added")
    ap.add_argument("--seeds", type=int, default=4)
    ap.add_argument("--heat-seeds", type=int, default=3, help="seeds of the temperature-wave runs")
    ap.add_argument("--dT", type=float, default=0.25, help="temperature-wave amplitude of those runs")
    ap.add_argument("--volume", default="plain", help="particle volume of the hydrodynamics runs (plain: eq 96, normalized: eq 99)")
    ap.add_argument("--eq-dt", type=float, default=0.05, help="time step of the equilibrium runs (same times)")
    ap.add_argument("--plot", action="store_true", help="redraw the figure from results.json")
    args = ap.parse_args()
    if args.plot:
        plot(common.saved("sdpd_hydro"))
        return
    try:
        out = common.saved("sdpd_hydro")
    except (KeyError, FileNotFoundError):
        out = {}
    out = {q: out[q] for q in out if q.split("_")[0] in ("hydro", "heat", "equilibrium")}
    for part in args.parts:
        {"hydro": hydro, "heat": heat, "equilibrium": equilibrium}[part](args, out)
    common.save("sdpd_hydro", out)
    plot(out)


if __name__ == "__main__":
    main()
