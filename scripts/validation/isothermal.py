#!/usr/bin/env python3
"""The isothermal-equivalence check at the end of sec 5.1 of the 2019 paper: the vdW
GenDPDE fluid (T = 1.5, rho = 0.5) with theta held at T (C_V = 1e8) integrated by eSSA
and by velocity Verlet with all pair forces (standard isothermal DPD) gives the same
<T_kin> and virial pressure (paper: within 0.1 %).

    python3 scripts/validation/isothermal.py [--n 15] [--steps 5000] [--dt 0.01]
"""
import argparse

import common

EXAMPLE = common.ROOT / "examples" / "isothermal"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=15)
    ap.add_argument("--steps", type=int, default=5000)
    ap.add_argument("--dt", type=float, default=0.01)
    args = ap.parse_args()
    out = {}
    for motion in ["essa", "vv"]:
        wd = common.workdir("isothermal", f"{motion}_n{args.n}_dt{args.dt}")
        v = {"n": args.n, "steps": args.steps, "dt": args.dt, "motion": str(EXAMPLE / motion)}
        blocks, wall = common.run("isothermal", v, wd)
        run = blocks[-1]
        out[motion] = {"T_kin": common.mean_sem(run["Temp"]), "P": common.mean_sem(run["Press"]),
                       "T_int": common.mean_sem(run["Tint"]), "wall_s": round(wall, 1)}
        print(motion, out[motion], flush=True)
    e, v = out["essa"], out["vv"]
    out["rel_diff"] = {"T_kin": e["T_kin"][0] / v["T_kin"][0] - 1, "P": e["P"][0] / v["P"][0] - 1}
    out.update({"N": args.n ** 3, "steps": args.steps, "dt": args.dt})
    print(out["rel_diff"])
    common.save(f"isothermal_dt{args.dt:g}", out)


if __name__ == "__main__":
    main()
