#!/usr/bin/env python3
"""Generates the LAMMPS data files used by the parity inputs in this directory.

Standard library only, fixed seeds: running it again rewrites byte-identical files.

    python3 scripts/lammps/make_data.py [OUTDIR]     (default: the directory of this script)

Files (all single atom type, periodic orthogonal boxes starting at 0):
  data.dpde-small   atom_style dpd,  lj,    N = 2197, L = 9.0137 (rho = 3),    theta = 1, v ~ N(0, 1)
  data.dpde-3000    atom_style dpd,  lj,    N = 3000, L = 10     (rho = 3),    theta = 1, v ~ N(0, 1)
  data.mdpd-small   atom_style mdpd, lj,    N = 2197, L = 7.1534 (rho = 6),               v ~ N(0, 1)
  data.mdpd-liquid  atom_style mdpd, lj,    N = 2197, L = 7.1337 (rho = 6.05),            v ~ N(0, 1)
  data.dpde         atom_style dpd,  metal, N = 1000, L = 60 A,               theta = 300 K,
                    v ~ N(0, kT/m) for m = 100 g/mol at 300 K (the mass comes from `mass 1 100.0`)

  data.edpd-small   atom_style edpd, lj,    N = 2048, L = 8      (rho = 4), 2 types (alternating),
                    T ~ U(0.7, 1.3), cv ~ U(5, 15), uniform random positions, v ~ N(0, 1)

Atoms lines: edpd `id type edpd_temp edpd_cv x y z`; dpd  `id type dpdTheta x y z`;  mdpd `id type rho x y z` (rho is recomputed by
pair mdpd/rhosum before the first force, the column is written as 0).
Positions: data.dpde-3000 is uniform random in the box (soft potential: overlaps are harmless,
the statistical scene equilibrates first); the three 13^3 files are simple-cubic lattices with
every site moved by uniform(-0.25, 0.25) lattice spacings (a smaller initial force spike, so the
deterministic runs start from a liquid-like state); data.dpde is a 10x10x10 simple-cubic
lattice with spacing 6 A jittered by +-1 A (the metal scene uses a cutoff of 10 A). The centre-of-mass velocity is removed.
"""
import math
import os
import random
import sys

# metal units: kB in eV/K, mvv2e converts (g/mol)(A/ps)^2 to eV (LAMMPS force.cpp/update.cpp values)
BOLTZ_METAL = 8.617343e-5
MVV2E_METAL = 1.0364269e-4


def gaussian_velocities(rng, n, std):
    v = [[rng.gauss(0.0, std) for _ in range(3)] for _ in range(n)]
    for k in range(3):
        mean = sum(vi[k] for vi in v) / n
        for vi in v:
            vi[k] -= mean
    return v


def write(path, title, style, length, pos, vel, col3, fmt, ntypes=1):
    """Particle i (from 1) gets type 1 + (i - 1) % ntypes; `col3` is the third column of
    the Atoms lines (dpdTheta, rho), None for atom_style atomic."""
    n = len(pos)
    lines = [f"LAMMPS data file: {title} (scripts/lammps/make_data.py)", "",
             f"{n} atoms", f"{ntypes} atom types", ""]
    for ax in "xyz":
        lines.append(f"0.0 {length!r} {ax}lo {ax}hi")
    lines += ["", f"Atoms # {style}", ""]
    for i, (x, y, z) in enumerate(pos, start=1):
        extra = "" if col3 is None else f" {col3}"
        lines.append(f"{i} {1 + (i - 1) % ntypes}{extra} {x:{fmt}} {y:{fmt}} {z:{fmt}}")
    lines += ["", "Velocities", ""]
    for i, (a, b, c) in enumerate(vel, start=1):
        lines.append(f"{i} {a:{fmt}} {b:{fmt}} {c:{fmt}}")
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")


def uniform_positions(rng, n, length):
    return [[rng.random() * length for _ in range(3)] for _ in range(n)]


def jittered_lattice(rng, cells, length, jitter=0.25):
    """cells^3 sites of a simple-cubic lattice, each moved by uniform(-jitter, jitter) * spacing."""
    a = length / cells
    pos = []
    for ix in range(cells):
        for iy in range(cells):
            for iz in range(cells):
                pos.append([((c + 0.5) + rng.uniform(-jitter, jitter)) * a for c in (ix, iy, iz)])
    return pos


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    os.makedirs(out, exist_ok=True)

    # a. deterministic DPDE (lj): 13^3 = 2197 particles on a jittered lattice, rho = 3
    rng = random.Random(20250722)
    n, length = 13 ** 3, 13 / 3.0 ** (1 / 3)
    write(os.path.join(out, "data.dpde-small"), "DPDE lj rho=3 N=2197 theta=1", "dpd", length,
          jittered_lattice(rng, 13, length), gaussian_velocities(rng, n, 1.0), "1.0", ".10f")

    # c. DPDE statistical scene (lj): 3000 particles, L = 10, rho = 3
    rng = random.Random(3000)
    n, length = 3000, 10.0
    write(os.path.join(out, "data.dpde-3000"), "DPDE lj rho=3 N=3000 theta=1", "dpd", length,
          uniform_positions(rng, n, length), gaussian_velocities(rng, n, 1.0), "1.0", ".6f")

    # b. deterministic MDPD (lj): 13^3 = 2197 particles on a jittered lattice, rho = 6
    rng = random.Random(6006)
    n, length = 13 ** 3, 13 / 6.0 ** (1 / 3)
    write(os.path.join(out, "data.mdpd-small"), "MDPD lj rho=6 N=2197", "mdpd", length,
          jittered_lattice(rng, 13, length), gaussian_velocities(rng, n, 1.0), "0.0", ".10f")

    # d. MDPD liquid (lj): 13^3 = 2197 particles on a jittered lattice, rho = 6.05
    rng = random.Random(6050)
    n, length = 13 ** 3, 13 / 6.05 ** (1 / 3)
    write(os.path.join(out, "data.mdpd-liquid"), "MDPD liquid lj rho=6.05 N=2197", "mdpd", length,
          jittered_lattice(rng, 13, length), gaussian_velocities(rng, n, 1.0), "0.0", ".6f")

    # e. DPDE metal example: 1000 atoms in a 60 A cube, theta = 300 K, m = 100 g/mol
    rng = random.Random(245455)
    length, a = 60.0, 6.0
    pos = []
    for ix in range(10):
        for iy in range(10):
            for iz in range(10):
                pos.append([(c + 0.5) * a + rng.uniform(-1.0, 1.0) for c in (ix, iy, iz)])
    std = math.sqrt(BOLTZ_METAL * 300.0 / (100.0 * MVV2E_METAL))  # A/ps
    write(os.path.join(out, "data.dpde"), "DPDE metal N=1000 L=60 A theta=300 K", "dpd", length,
          pos, gaussian_velocities(rng, len(pos), std), "300.0", ".8f")

    # f. eDPD parity scene (lj): 2048 particles of two types, per-particle T and cv
    rng = random.Random(2014)
    n, length = 2048, 8.0
    pos = uniform_positions(rng, n, length)
    vel = gaussian_velocities(rng, n, 1.0)
    lines = ["LAMMPS data file: eDPD lj rho=4 N=2048 two types (scripts/lammps/make_data.py)", "",
             f"{n} atoms", "2 atom types", ""]
    for ax in "xyz":
        lines.append(f"0.0 {length!r} {ax}lo {ax}hi")
    lines += ["", "Masses", "", "1 1.0", "2 1.0", "", "Atoms # edpd", ""]
    for i, (x, y, z) in enumerate(pos, start=1):
        t, cv = rng.uniform(0.7, 1.3), rng.uniform(5.0, 15.0)
        lines.append(f"{i} {1 + i % 2} {t:.10f} {cv:.10f} {x:.10f} {y:.10f} {z:.10f}")
    lines += ["", "Velocities", ""]
    for i, (a, b, c) in enumerate(vel, start=1):
        lines.append(f"{i} {a:.10f} {b:.10f} {c:.10f}")
    with open(os.path.join(out, "data.edpd-small"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    # g. two-type mixtures on small boxes (per-pair coefficients): 9^3 = 729 particles in a
    # 6.0 cube (2 cells of cutoff + skin per dimension), and 2197 MDPD particles at rho = 6
    rng = random.Random(1212)
    write(os.path.join(out, "data.mix-dpd"), "two-type DPD mixture lj N=729 L=6", "atomic", 6.0,
          jittered_lattice(rng, 9, 6.0), gaussian_velocities(rng, 729, 1.0), None, ".10f", 2)
    rng = random.Random(1213)
    length = 13 / 6.0 ** (1 / 3)
    write(os.path.join(out, "data.mix-mdpd"), "two-type MDPD mixture lj N=2197", "mdpd", length,
          jittered_lattice(rng, 13, length), gaussian_velocities(rng, 13 ** 3, 1.0), "0.0", ".10f", 2)


if __name__ == "__main__":
    main()
