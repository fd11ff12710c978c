#!/usr/bin/env python3
"""Issue 19, item 4: the engine's virial pressure against a Monte Carlo of the model's
configurational weight, vdW (excess) and LJ (Kolafa-Nezbeda) particle EOS at T = 1.5,
rho = 0.5, C_V = 60, rc = 3, 4, 5, and where the engine's small excess over the MC comes
from (time step, momentum-noise form).

    python3 scripts/validation/pressure_mc.py [--runs vdw:3,vdw:4,lj:3:dt0.005,lj:3:harmonic ...]
        [--n 11] [--equil 500] [--steps 6000] [--gamma 0.45] [--sweeps 500] [--mc-equil 200]
    python3 scripts/validation/pressure_mc.py --collect   # results.json from the cached rows

A run is MODEL:RC[:VARIANT...] with VARIANT dt<value>, harmonic (`noise harmonic 1.5`) or
s<steps> (production steps at dt = 0.01, instead of --steps) or m<sweeps> (MC sweeps,
instead of --sweeps);
each runs examples/lj-fluid (NVE GenDPDE, gamma = 0.45 as in pressure.py, kappa = 1,
dt = 0.01, eq 76 noise) on an sc lattice of n^3 particles, then local_density_mc.py's
Monte Carlo of eq 92 with the same N and box at the run's <T_int> (the NVE run's
temperature is its own: the MC samples exp(-sum_i F_eff(n_i)/T) at that T, with
F_eff = V + T ln psi for vdW and -T ln int dtheta (C_V/theta) exp(s - u/T) for LJ).
The engine's pressure carries rho T_kin, the MC's rho T; the configurational part
P - rho T_kin is compared as well. Errors: engine, from the integrated autocorrelation time
of the thermo series (every 10 steps after `equil`; 10-block errors of 16000-step runs
scattered by a factor 2 around it); MC, 10 block averages of the per-sweep values (sweeps
of re-insertion moves at 92 % acceptance are nearly independent). Rows are cached per work
directory.
"""
import argparse

import common
import local_density_mc as mc

RHO = 0.5
# the runs of docs/VALIDATION.md: the cutoff scan, and at rc = 3 the long runs of the dt and
# noise-form checks
RUNS = "vdw:3:s3000:m300,vdw:4:s2000:m300,vdw:5:s1000:m300,lj:3:s16000:m2000,lj:4:s2000:m300,lj:5:s1000:m300,lj:3:s16000:harmonic,lj:3:s10000:dt0.005"
MODELS = {"vdw": mc.EOS, "lj": f"{mc.LJ_EOS} {common.LJ_TABLE}"}


def parse(run):
    model, rc, *variant = run.split(":")
    spec = {"model": model, "rc": float(rc), "dt": 0.01, "noise": "arithmetic", "steps": None, "sweeps": None}
    for v in variant:
        if v.startswith("dt"):
            spec["dt"] = float(v[2:])
        elif v.startswith("s"):
            spec["steps"] = int(v[1:])
        elif v.startswith("m"):
            spec["sweeps"] = int(v[1:])
        elif v == "harmonic":
            spec["noise"] = "harmonic 1.5"
        else:
            raise SystemExit(f"unknown variant {v!r} in {run!r}")
    return spec


def run_dir(spec, args):
    """(work directory, production steps, equilibration steps) of the engine run of `spec`."""
    steps = round((spec["steps"] or args.steps) * 0.01 / spec["dt"])
    equil = round(args.equil * 0.01 / spec["dt"])
    tag = f"{spec['model']}_rc{spec['rc']:g}_dt{spec['dt']:g}_{spec['noise'].split()[0]}_n{args.n}_g{args.gamma}_e{equil}_s{steps}"
    return common.workdir("pressure_mc", tag), steps, equil


def engine(spec, args):
    wd, steps, equil = run_dir(spec, args)
    wd.mkdir(parents=True, exist_ok=True)
    v = {"n": args.n, "rho": RHO, "T": 1.5, "rc": spec["rc"], "dt": spec["dt"], "gamma": args.gamma,
         "eos": MODELS[spec["model"]], "equil": equil, "steps": steps, "every": 10, "noise": spec["noise"]}

    def simulate():
        blocks, wall = common.run_once("lj-fluid", v, wd)
        prod = blocks[-1]
        row = {c: common.mean_sem_tau(prod[c]) for c in ("Press", "Temp", "Tint", "Nmean")}
        conf = [p - RHO * t for p, t in zip(prod["Press"], prod["Temp"])]
        row["Pconf"] = common.mean_sem_tau(conf)
        row["dT"] = common.mean_sem_tau([a - b for a, b in zip(prod["Temp"], prod["Tint"])])
        row.update(spec, N=args.n ** 3, steps=steps, equil=equil, gamma=args.gamma, wall_s=round(wall, 1))
        print(row, flush=True)
        return row
    return wd, common.cached(wd, simulate)


def monte_carlo(spec, T, args):
    import time
    sweeps = spec["sweeps"] or args.sweeps
    wd = common.workdir("pressure_mc", f"mc_{spec['model']}_rc{spec['rc']:g}_T{T:.5f}_n{args.n}_s{sweeps}_e{args.mc_equil}")
    wd.mkdir(parents=True, exist_ok=True)

    def sample():
        mc.RC, mc.T = spec["rc"], T
        start = time.time()
        r = mc.monte_carlo(args.n, sweeps, args.mc_equil, args.seed, spec["model"])
        p, m = mc.block_sem(r["pressures"]), mc.block_sem(r["means"])
        row = {"T": T, "P": p, "Nmean": m, "std_n": float(r["vars"].mean() ** 0.5), "sweeps": sweeps,
               "equil": args.mc_equil, "acceptance": float(r["acceptance"]), "wall_s": round(time.time() - start, 1),
               "P_eos": common.eos(MODELS[spec["model"]].split(" table")[0], T, RHO)["pressure"]}
        print(row, flush=True)
        return row
    return common.cached(wd, sample)


def compare(spec, args):
    _, e = engine(spec, args)
    m = monte_carlo(spec, round(e["Tint"][0], 5), args)
    return {"engine": e, "mc": m}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", default=RUNS)
    ap.add_argument("--n", type=int, default=11, help="lattice cells per side (11: N = 1331, box 13.9)")
    ap.add_argument("--equil", type=int, default=500, help="equilibration steps at dt = 0.01 (scaled with dt)")
    ap.add_argument("--steps", type=int, default=6000, help="production steps at dt = 0.01 (scaled with dt)")
    ap.add_argument("--gamma", type=float, default=0.45)
    ap.add_argument("--sweeps", type=int, default=500)
    ap.add_argument("--mc-equil", type=int, default=200)
    ap.add_argument("--seed", type=int, default=92)
    ap.add_argument("--collect", action="store_true", help="only gather the cached rows into results.json")
    args = ap.parse_args()
    rows = []
    for run in args.runs.split(","):
        spec = parse(run)
        if args.collect and not (run_dir(spec, args)[0] / "run.json").exists():
            continue
        rows.append({"run": run, **compare(spec, args)})
    common.save("pressure_mc", {"n": args.n, "gamma": args.gamma, "rows": rows})


if __name__ == "__main__":
    main()
