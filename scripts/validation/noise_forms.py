#!/usr/bin/env python3
"""The momentum friction/noise law of fix shardlow against eq 91 (issue 19): the papers'
eq 76 (`noise arithmetic`, constant gamma, sigma^2 = k_B (theta_i + theta_j) gamma) and the
classic DPDE form (`noise harmonic T0`, constant sigma, gamma_ij = sigma^2/(2 k_B Theta_ij),
1/Theta_ij = (1/tau_i + 1/tau_j)/2).

    python3 scripts/validation/noise_forms.py momentum [--n 10] [--time 100]
    python3 scripts/validation/noise_forms.py vdw [--n 10] [--rc 2.5] [--steps 3000]
    python3 scripts/validation/noise_forms.py flash [--n 14] [--steps 3000] [--law harmonic]
    python3 scripts/validation/noise_forms.py table    # markdown rows from results.json

momentum: examples/momentum-noise (u = C_V theta, no conservative force, kappa = 0, so the
heat model does not enter), C_V in {5, 10, 20, 60} with each law; at C_V = 10 also
dt = 0.005 and 0.02 and a mixture with masses 1 and 3. vdw: examples/distributions (vdW
excess, T = 1.5, rho = 0.5) with both heat models (kappa 1 original, 1/T^2 fourier).
For each run: T_kin - <theta>, <theta>, var(theta)/<theta>^2 and the skewness of theta
against eq 91 (Gamma of shape C_V/k_B: 1/C_V and 2/sqrt(C_V)), with standard errors from 5
blocks of consecutive frames. flash: examples/flash-heating (Fig 7) with each law,
T_kin/T_int - 1 over the second half with its block error.
"""
import argparse

import numpy as np
from scipy import stats

import common

T = 1.5
LAWS = {"arithmetic": "arithmetic", "harmonic": f"harmonic {T}"}
# theta of one particle decorrelates in about 7 time units at C_V = 10 (longer at larger
# C_V), so blocks of 20 time units and more (5 per run)
BLOCKS = 5


def moments(theta, tkin_minus_tint):
    """Block means and errors of <theta>, var/mean^2 and skewness (theta: [frames, N])."""
    def stat(f):
        values = np.array([f(b.ravel()) for b in np.array_split(theta, BLOCKS)])
        return float(f(theta.ravel())), float(values.std(ddof=1) / np.sqrt(BLOCKS))
    row = {}
    for name, f in [("theta", np.mean), ("var_ratio", lambda x: x.var() / x.mean() ** 2), ("skew", stats.skew)]:
        row[name], row[name + "_err"] = stat(f)
    row["dT"], row["dT_err"] = common.mean_sem(tkin_minus_tint, BLOCKS)
    return row


def measure(scene, example, tag, variables, cv):
    wd = common.workdir("noise_forms", f"{scene}_{tag}")

    def simulate():
        try:
            blocks, wall = common.run_once(example, variables, wd)
        except SystemExit as e:  # a particle temperature turned non-positive: record it
            stop = [line for line in str(e).splitlines() if "ERROR" in line]
            return {"tag": tag, "cv": cv, "failed": stop[0] if stop else str(e)[-300:]}
        name = "theta.h5" if example == "momentum-noise" else "dist.h5"
        theta = common.h5md_frames(wd / name, "temperature")[1:]
        run = blocks[-1]
        row = moments(theta, np.asarray(run["Temp"][1:]) - np.asarray(run["Tint"][1:]))
        row.update({"tag": tag, "cv": cv, "N": int(theta.shape[1]), "frames": int(theta.shape[0]),
                    "T_kin": float(np.mean(run["Temp"][1:])), "wall_s": round(wall, 1),
                    "gamma_var": 1 / cv, "gamma_skew": 2 / np.sqrt(cv)})
        row.update({k: v for k, v in variables.items() if k in ("noise", "dt", "heat", "m2", "steps", "n", "rc", "reject")})
        log = (wd / "log.gendpde").read_text()
        row["splits_left_out"] = [line.split("=", 1)[1].strip() for line in log.splitlines() if "split into half steps" in line]
        return row
    row = common.cached(wd, simulate)
    print(fmt(row), flush=True)
    return row


def fmt(r):
    if "failed" in r:
        return f"{r['tag']:32s} FAILED: {r['failed']}"
    return (f"{r['tag']:32s} T_kin {r['T_kin']:.4f}  T_kin-<theta> {r['dT']:+.4f} +- {r['dT_err']:.4f}  "
            f"<theta> {r['theta']:.4f} +- {r['theta_err']:.4f}  var/m^2 {r['var_ratio']:.4f} +- {r['var_ratio_err']:.4f} "
            f"(Gamma {r['gamma_var']:.4f})  skew {r['skew']:.3f} +- {r['skew_err']:.3f} (Gamma {r['gamma_skew']:.3f})  "
            f"{r['wall_s']} s")


def momentum(args):
    rows = []
    cases = [(5.0, 0.01, 1.0), (10.0, 0.01, 1.0), (10.0, 0.02, 1.0), (10.0, 0.01, 3.0), (20.0, 0.01, 1.0), (60.0, 0.01, 1.0),
             (10.0, 0.005, 1.0)][:None if args.fine_dt else -1]
    for cv, dt, m2 in cases:
        for law, noise in LAWS.items():
            steps = round(args.time / dt)
            every = max(1, round(0.5 / dt))  # frames 0.5 time units apart
            # eq 76 drives single particles to theta <= 0 (at C_V = 10 within 1300 steps: their
            # momentum noise follows the partner's theta): its failing pair updates are left
            # out (counted in the row); the harmonic form runs without
            v = {"n": args.n, "cv": cv, "dt": dt, "m2": m2, "noise": noise, "equil": round(10 / dt), "steps": steps,
                 "dump": every, "reject": "yes" if law == "arithmetic" else "no"}
            rows.append(measure("momentum", "momentum-noise", f"{law}_cv{cv:g}_dt{dt:g}_m{m2:g}_n{args.n}_t{args.time:g}", v, cv))
    common.save("noise_forms_momentum", {"T": T, "time": args.time, "runs": rows})


def vdw(args):
    rows = []
    for cv in (5.0, 10.0, 20.0, 60.0):
        for heat, kappa in (("original", 1.0), ("fourier", 1.0 / T ** 2)):
            for law, noise in LAWS.items():
                v = {"n": args.n, "rc": args.rc, "cv": cv, "heat": heat, "kappa": kappa, "noise": noise,
                     "equil": args.steps // 4, "steps": args.steps, "dump": max(1, args.steps // 100),
                     "reject": "yes" if law == "arithmetic" else "no"}
                rows.append(measure("vdw", "distributions", f"{law}_{heat}_cv{cv:g}_n{args.n}_rc{args.rc:g}_s{args.steps}", v, cv))
    common.save("noise_forms_vdw", {"T": T, "runs": rows})


def flash(args):
    from flash import FLASH_TABLE
    rows = []
    for law, noise in LAWS.items():
        if args.law and law != args.law:
            continue
        wd = common.workdir("noise_forms", f"flash_{law}_n{args.n}_s{args.steps}")

        def simulate():
            v = {"n": args.n, "equil": args.equil, "steps": args.steps, "eos": f"lj 60.0 {FLASH_TABLE}", "every": 10,
                 "noise": noise}
            blocks, wall = common.run("flash-heating", v, wd)
            run = blocks[-1]
            half = len(run["Step"]) // 2
            tk, ti = np.asarray(run["Temp"][half:]), np.asarray(run["Tint"][half:])
            rel, rel_err = common.mean_sem(tk / ti - 1, BLOCKS)
            return {"law": law, "N": args.n ** 3, "steps": args.steps, "T_kin": float(tk.mean()), "T_int": float(ti.mean()),
                    "rel_diff": rel, "rel_diff_err": rel_err,
                    "max_rel_energy_drift": max(abs(e) for e in common.relative(run["TotEng"])), "wall_s": round(wall, 1)}
        row = common.cached(wd, simulate)
        print(row, flush=True)
        rows.append(row)
    common.save(f"noise_forms_flash_{args.law or 'all'}", {"runs": rows})


def table(args):
    """Markdown rows of the saved runs (for docs/VALIDATION.md)."""
    import json
    data = json.loads((common.OUT / "results.json").read_text())
    for scene in ("noise_forms_momentum", "noise_forms_vdw"):
        if scene not in data:
            continue
        print(f"\n{scene}\n")
        print("| run | T_kin - <theta> | <theta> | var/<theta>^2 (eq 91) | skewness (eq 91) |")
        print("|---|---|---|---|---|")
        for r in data[scene]["runs"]:
            if "failed" in r:
                print(f"| {r['tag']} | stopped: {r['failed'].split('run stopped: ')[-1][:60]} | | | |")
                continue
            print(f"| {r['tag']} | {r['dT']:+.4f} +- {r['dT_err']:.4f} | {r['theta']:.4f} +- {r['theta_err']:.4f} | "
                  f"{r['var_ratio']:.4f} +- {r['var_ratio_err']:.4f} ({r['gamma_var']:.4f}) | "
                  f"{r['skew']:.3f} +- {r['skew_err']:.3f} ({r['gamma_skew']:.3f}) |")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("part", choices=["momentum", "vdw", "flash", "table"])
    ap.add_argument("--n", type=int, default=None, help="lattice cells per side (momentum, vdw 10; flash 14)")
    ap.add_argument("--rc", type=float, default=2.5, help="vdw: density, friction and heat cutoff")
    ap.add_argument("--time", type=float, default=100.0, help="momentum: sampled time units per run")
    ap.add_argument("--steps", type=int, default=None, help="vdw and flash: sampled steps (3000)")
    ap.add_argument("--equil", type=int, default=500, help="flash: steps at T = 1.5 before the heating")
    ap.add_argument("--no-fine-dt", dest="fine_dt", action="store_false", help="momentum: leave out dt = 0.005")
    ap.add_argument("--law", choices=list(LAWS), help="flash: only this law (to run the two side by side)")
    args = ap.parse_args()
    args.n = args.n or (14 if args.part == "flash" else 10)
    args.steps = args.steps or 3000
    {"momentum": momentum, "vdw": vdw, "flash": flash, "table": table}[args.part](args)


if __name__ == "__main__":
    main()
