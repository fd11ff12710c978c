#!/usr/bin/env python3
"""eDPD temperature profile between a heat source and a sink: LAMMPS's example
examples/PACKAGES/dpd-meso/edpd/in.edpd (copied unchanged to scripts/lammps/in.edpd), run
unchanged by the reference LAMMPS and by gendpde over several seeds.

The example: 16000 eDPD particles in 20 x 20 x 10 (periodic), T = 1, C_V = 1e5;
fix edpd/source heats y in [0, 10] and cools y in [-10, 0] at dT/dt = +-0.01; 500 steps,
then fix ave/chunk averages c_temp (compute edpd/temp/atom) over 1 bins of y, every step of
the next 500 (t = 5.01 .. 10). Seeds: the example's three (create_atoms, pair_style,
velocity) plus k for run k = 0, 1, ...

Per bin: mean and standard error over the seeds, for each code, and the difference in units
of the combined standard error. Analytic: the heat equation dT/dt = D T'' + s(y) with the
square-wave source s, from T = 1 at t = 0, is T - 1 = sum_{n odd} 4 s0 / (n pi)
sin(k_n y) (1 - exp(-D k_n^2 t)) / (D k_n^2), k_n = n pi / 10 (the steady state, the
periodic parabola, is 8.5 time units of the slowest mode away at t = 10); averaged over each
bin and over the sampled steps. D is fitted (least squares over the bins) for each code and
compared with the conduction part predicted from pair edpd at T = 1 for an ideal-gas
structure, D_c = C_V kappa rho (1/6) int (1 - r/r_cT)^p_T r^2 d^3r (the particles' own
diffusion adds to it).

    python3 scripts/validation/edpd_profile.py [--seeds 3] [--narrow] [--jobs 2] [--script in.edpd-region]
        [--out docs/validation/edpd_profile.json]

--narrow shrinks the box across the gradient (x and z to 8, 5120 particles) for a cheaper
run with the same profile.

Environment: GENDPDE (default target/release/gendpde), LMP (default
/work/shared/lammps/lmp). Writes the JSON with both profiles, the fit and the comparison.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
GENDPDE = os.environ.get("GENDPDE", str(ROOT / "target" / "release" / "gendpde"))
LMP = os.environ.get("LMP", "/work/shared/lammps/lmp")
SEEDS = ("276438", "9872598", "432982")
NARROW_N = 5120  # --narrow: x and z of 8 instead of 20 and 10, the same density 4
S0, HALF, CV, KAPPA, RHO, RCT, PT = 0.01, 10.0, 1.0e5, 1.41e-5, 4.0, 1.58, 2.0


def run(code, k, script, narrow):
    text = (ROOT / "scripts" / "lammps" / script).read_text()
    if narrow:
        text = text.replace("block -10 10 -10 10 -5 5 units box", "block -4 4 -10 10 -4 4 units box").replace("random 16000", f"random {NARROW_N}")
    for s in SEEDS:
        text = text.replace(s, str(int(s) + k))
    d = Path(tempfile.mkdtemp(prefix=f"edpd-{code}-{k}-"))
    (d / script).write_text(text)
    exe = [LMP, "-in", script, "-log", "none"] if code == "lammps" else [GENDPDE, "-in", script, "-log", "none"]
    r = subprocess.run(exe, cwd=d, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{code} seed {k}: {r.stdout[-2000:]}{r.stderr[-2000:]}")
    rows = [line.split() for line in (d / "temp.profile").read_text().splitlines() if line.strip() and not line.startswith("#")]
    prof = [(float(w[1]), float(w[3])) for w in rows if len(w) == 5]
    shutil.rmtree(d)
    return [y for y, _ in prof], [t for _, t in prof]


def stats(runs):
    n = len(runs)
    mean = [sum(r[b] for r in runs) / n for b in range(len(runs[0]))]
    se = [math.sqrt(sum((r[b] - mean[b]) ** 2 for r in runs) / (n - 1) / n) for b in range(len(mean))]
    return mean, se


def analytic(ys, d, times):
    """Bin- and time-averaged T - 1 at the bin centres ys for diffusivity d."""
    modes = []
    for n in range(1, 200, 2):
        k = n * math.pi / HALF
        growth = sum(1 - math.exp(-d * k * k * t) for t in times) / len(times)
        modes.append((k, 4 * S0 / (n * math.pi) * math.sin(k / 2) / (k / 2) * growth / (d * k * k)))
    return [sum(a * math.sin(k * y) for k, a in modes) for y in ys]


def fit_d(ys, mean, times):
    """Least-squares D by golden-section search on the sum of squared residuals."""
    cost = lambda d: sum((a - (m - 1.0)) ** 2 for a, m in zip(analytic(ys, d, times), mean))
    lo, hi = 0.05, 20.0
    g = (math.sqrt(5) - 1) / 2
    for _ in range(60):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if cost(a) < cost(b):
            hi = b
        else:
            lo = a
    d = 0.5 * (lo + hi)
    return d, math.sqrt(cost(d) / len(ys))


def conduction_d():
    """D_c = C_V kappa rho (1/6) int w_rT^2 r^2 d^3r, w_rT^2 = (1 - r/r_cT)^p_T (T = 1)."""
    m = 20000
    h = RCT / m
    integral = sum(4 * math.pi * ((i + 0.5) * h) ** 4 * (1 - (i + 0.5) * h / RCT) ** PT for i in range(m)) * h
    return CV * KAPPA * RHO * integral / 6


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--script", default="in.edpd")
    ap.add_argument("--narrow", action="store_true", help="a box 8 x 20 x 8 (5120 particles) instead of 20 x 20 x 10")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--first", type=int, default=0, help="the first seed offset k")
    ap.add_argument("--combine", nargs="+", help="no runs: combine the runs kept in these JSON files")
    ap.add_argument("--out", default=str(ROOT / "docs" / "validation" / "edpd_profile.json"))
    args = ap.parse_args()
    if args.combine:
        loaded = [json.loads(Path(f).read_text()) for f in args.combine]
        ys, narrow, script = loaded[0]["y"], loaded[0]["narrow"], loaded[0]["script"]
        runs = {code: [r for j in loaded for r in j["runs"][code]] for code in ("lammps", "gendpde")}
    else:
        jobs = [(code, k) for k in range(args.first, args.first + args.seeds) for code in ("lammps", "gendpde")]
        with ThreadPoolExecutor(args.jobs) as pool:
            results = list(pool.map(lambda job: (job, run(job[0], job[1], args.script, args.narrow)), jobs))
        ys, narrow, script = results[0][1][0], args.narrow, args.script
        runs = {code: [prof for (c, _), (_, prof) in results if c == code] for code in ("lammps", "gendpde")}
    times = [0.01 * (500 + s) for s in range(1, 501)]
    nseeds = len(runs["lammps"])
    out = {"script": script, "narrow": narrow, "seeds": nseeds, "y": ys, "D_conduction_predicted": conduction_d(), "runs": runs}
    for code in ("lammps", "gendpde"):
        mean, se = stats(runs[code])
        d, rms = fit_d(ys, mean, times)
        # the seed noise is alike in every bin: its variance pooled over the bins
        pooled = math.sqrt(sum(x * x for x in se) / len(se))
        out[code] = {"mean": mean, "se": se, "se_pooled": pooled, "D_fit": d, "fit_rms": rms}
    diff = [a - b for a, b in zip(out["lammps"]["mean"], out["gendpde"]["mean"])]
    z = [x / math.hypot(s, t) for x, s, t in zip(diff, out["lammps"]["se"], out["gendpde"]["se"])]
    zp = [x / math.hypot(out["lammps"]["se_pooled"], out["gendpde"]["se_pooled"]) for x in diff]
    out.update(z=z, max_abs_z=max(map(abs, z)), chi2_per_bin=sum(v * v for v in z) / len(z))
    out.update(z_pooled=zp, max_abs_z_pooled=max(map(abs, zp)), chi2_per_bin_pooled=sum(v * v for v in zp) / len(zp))
    out["max_abs_diff"] = max(map(abs, diff))
    Path(args.out).write_text(json.dumps(out, indent=1) + "\n")
    print(f"{script}{' (narrow)' if narrow else ''}, {nseeds} seeds: max |diff| = {out['max_abs_diff']:.2e}; per-bin SE: max |z| = {out['max_abs_z']:.2f}, "
          f"chi2/bin = {out['chi2_per_bin']:.2f}; pooled SE: max |z| = {out['max_abs_z_pooled']:.2f}, chi2/bin = {out['chi2_per_bin_pooled']:.2f}")
    for code in ("lammps", "gendpde"):
        print(f"  {code}: D_fit = {out[code]['D_fit']:.3f} (rms {out[code]['fit_rms']:.2e}); D_c predicted {out['D_conduction_predicted']:.3f}")
    for y, a, s, b, t in zip(ys, out["lammps"]["mean"], out["lammps"]["se"], out["gendpde"]["mean"], out["gendpde"]["se"]):
        print(f"  y {y:6.2f}  LAMMPS {a:.5f} +- {s:.5f}  gendpde {b:.5f} +- {t:.5f}")


if __name__ == "__main__":
    main()
