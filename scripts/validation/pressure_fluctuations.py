#!/usr/bin/env python3
"""Why the LJ virial pressure exceeds the EOS pressure at T = 1.5, rho = 0.5, rc = 4
(Fig 4 scene): the local density fluctuates, and pi(n)/n^2 is curved.

    python3 scripts/validation/pressure_fluctuations.py [--n 14] [--steps 3000] [--gamma 0.45]

Runs examples/lj-fluid with an H5MD dump of the local densities n_i and compares
- the virial pressure of the run,
- the EOS pressure P(T, rho) = rho T + pi(T, rho),
- the mean field at the mean local density, rho T + rho^2 [pi/n^2](<n_i>),
- the mean field averaged over the distribution of n_i, rho T + rho^2 <[pi/n^2](n_i)>.
For a homogeneous fluid the virial of the many-body force is
sum_i (pi_i/n_i^2) m_i / V with m_i = -sum_j r_ij w'(r_ij)/3, and <m_i> = rho for g = 1;
the last estimate keeps the spread of n_i and drops the correlation of m_i with n_i.
For an uncorrelated fluid the spread is the counting noise of the weight,
var(n_i) = rho * integral of w^2 = rho * 225 / (105 pi rc^3) for the quadratic weight.
The friction is 0.45 (the pressure is the same as at 4.5; see pressure.py).
"""
import argparse

import numpy as np

import common


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=14)
    ap.add_argument("--equil", type=int, default=400)
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--gamma", type=float, default=0.45)
    args = ap.parse_args()
    T, rho = 1.5, 0.5
    wd = common.workdir("pressure_fluctuations", f"n{args.n}")
    wd.mkdir(parents=True, exist_ok=True)
    script = (common.ROOT / "examples" / "lj-fluid" / "in.lj-fluid").read_text()
    head, tail = script.rsplit("run          ${steps}", 1)
    (wd / "in.script").write_text(head + "dump         d all h5md 50 lj.h5 n\nrun          ${steps}" + tail)
    variables = {"n": args.n, "T": T, "rho": rho, "gamma": args.gamma, "eos": f"lj 60.0 {common.LJ_TABLE}", "equil": args.equil,
                 "steps": args.steps, "every": 10}
    prod = common.gendpde.run(wd / "in.script", variables, log=None, cwd=wd, binary=common.GENDPDE).logs[-1]
    p, p_err = common.mean_sem(prod["Press"])
    ti, _ = common.mean_sem(prod["Tint"])
    n = common.h5md_frames(wd / "lj.h5", "density")[2:].ravel()
    grid = np.linspace(0.02, 1.2, 119)
    pn2 = np.array([common.eos("lj 60.0", ti, x)["pi"] / x ** 2 for x in grid])
    p_eos = common.eos("lj 60.0", ti, rho)["pressure"]
    rc = 4.0
    entry = {"T": T, "rho": rho, "rc": rc, "N": args.n ** 3, "steps": args.steps, "gamma": args.gamma, "T_int": ti,
             "n_rel_std_counting": float(np.sqrt(rho * 225 / (105 * np.pi * rc ** 3)) / rho),
             "P_virial": p, "P_err": p_err, "P_eos": p_eos, "n_mean": float(n.mean()), "n_rel_std": float(n.std() / n.mean()),
             "P_mean_field": rho * ti + rho ** 2 * float(np.interp(n.mean(), grid, pn2)),
             "P_fluctuating": rho * ti + rho ** 2 * float(np.interp(n, grid, pn2).mean())}
    print(entry)
    common.save("pressure_fluctuations", entry)


if __name__ == "__main__":
    main()
