#!/usr/bin/env python3
"""A latency-bandwidth model of gendpde's strong and weak scaling, from measured counts.

Inputs measured on this machine (docs/PERFORMANCE.md, "Communication and a scaling model"):
the single-core speed of each scene, and per rank and step on a 3D decomposition the
exchange rounds (one or two point-to-point messages travelling at once: one latency each)
and the bytes per ghost particle (the run summary's "Comm messages per step" line at 8
ranks, the bytes divided by the ghost count of the cell geometry). Assumed: an
interconnect of latency ALPHA and bandwidth BETA, COLLECTIVES allreduce-like operations per
step costing log2(P) latencies each, and the pair passes evaluating pairs with a ghost on
both ranks (a fraction PASS_SHARE of the step's work done again for half the ghosts).

    python3 scripts/bench/scaling_model.py      # prints the markdown tables
"""
import math

ALPHA = 1.5e-6       # s per message (InfiniBand HDR, MPI latency)
BETA = 12.5e9        # bytes/s per link (100 Gb/s)
COLLECTIVES = 3      # per step (neighbour-list check, thermo sums, signal/blow-up check)

# scene: density, cutoff + skin, single-core atom-steps/s (quiet machine), exchange rounds
# per step per rank on a 3D grid, bytes per ghost per step, share of the step in pair passes
SCENES = {
    "GenDPDE vdW (rho 0.5, rc 4, skin 0.4)": dict(rho=0.5, cut=4.4, rate=2.1e5, rounds=58.2, per_ghost=307.3, pass_share=0.3),
    "classic DPDE (rho 3, rc 1, skin 0.3)": dict(rho=3.0, cut=1.3, rate=1.9e6, rounds=45.8, per_ghost=160.4, pass_share=0.3),
}


def cells_per_dim(n, rho, cut):
    """Cells per dimension of a cubic box of n particles: the even count of side >= cut."""
    length = (n / rho) ** (1 / 3)
    return (int(length / cut) // 2) * 2, length


def step_time(scene, n, p):
    """(seconds per step, communication share, ghosts per rank) of n particles on p ranks
    (p a cube, the box split evenly in 3D); None if a rank would own less than one cell."""
    s = SCENES[scene]
    k = round(p ** (1 / 3))
    count, length = cells_per_dim(n, s["rho"], s["cut"])
    if k ** 3 != p or count < k:
        return None
    own = count / k                       # cells per rank per dimension (mean)
    side = length / count
    local = n / p
    ghosts = ((own + 2) ** 3 - own ** 3) * side ** 3 * s["rho"] if p > 1 else 0.0
    compute = (local + s["pass_share"] * 0.5 * ghosts) / s["rate"]
    if p == 1:
        return compute, 0.0, 0.0
    comm = s["rounds"] * ALPHA + s["per_ghost"] * ghosts / BETA + COLLECTIVES * math.log2(p) * ALPHA
    return compute + comm, comm / (compute + comm), ghosts


def table(title, rows):
    print(f"\n{title}\n")
    print("| scene | N | ranks | N per rank | ghosts per rank | step (ms) | comm share | efficiency |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(r)


def main():
    ranks = [8, 64, 216, 512, 1000]
    for scene in SCENES:
        rows = []
        for n in [27000, 10**6, 10**7]:
            t1 = step_time(scene, n, 1)[0]
            for p in ranks:
                m = step_time(scene, n, p)
                if m is None:
                    rows.append(f"| {scene} | {n:.0e} | {p} | {n / p:.0f} | - | - | - | below one cell per rank |")
                    continue
                t, share, ghosts = m
                rows.append(f"| {scene} | {n:.0e} | {p} | {n / p:.0f} | {ghosts:.0f} | {1e3 * t:.3g} | {100 * share:.0f} % | {t1 / (p * t):.2f} |")
        table(f"Strong scaling, {scene}", rows)
        rows = []
        for per in [27000, 10**5]:
            t1 = step_time(scene, per * 8, 8)[0]
            for p in ranks:
                m = step_time(scene, per * p, p)
                t, share, ghosts = m
                rows.append(f"| {scene} | {per * p:.0e} | {p} | {per} | {ghosts:.0f} | {1e3 * t:.3g} | {100 * share:.0f} % | {t1 / t:.2f} |")
        table(f"Weak scaling (efficiency against 8 ranks), {scene}", rows)


if __name__ == "__main__":
    main()
