#!/usr/bin/env python3
"""Generates the LAMMPS data files used by the parity inputs in this directory.

Standard library only, fixed seeds: running it again rewrites byte-identical files.

    python3 scripts/lammps/make_data.py [OUTDIR]     (default: the directory of this script)

Files (periodic orthogonal boxes starting at 0, one atom type unless stated):
  data.dpde-small   atom_style dpd,  lj,    N = 2197, L = 9.0137 (rho = 3),    theta = 1, v ~ N(0, 1)
  data.dpde-3000    atom_style dpd,  lj,    N = 3000, L = 10     (rho = 3),    theta = 1, v ~ N(0, 1)
  data.mdpd-small   atom_style mdpd, lj,    N = 2197, L = 7.1534 (rho = 6),               v ~ N(0, 1)
  data.mdpd-liquid  atom_style mdpd, lj,    N = 2197, L = 7.1337 (rho = 6.05),            v ~ N(0, 1)
  data.dpde         atom_style dpd,  metal, N = 1000, L = 60 A,               theta = 300 K,
                    v ~ N(0, kT/m) for m = 100 g/mol at 300 K (the mass comes from `mass 1 100.0`)
  data.table-lj     atom_style atomic, lj, 2 types, N = 1000, L = 11.5, v ~ N(0, 1)
  data.cg-water     atom_style atomic, real, N = 2197, L = 40.31 A (the density of LAMMPS's
                    cg_spce.data), v ~ N(0, kT/m) for m = 18.0154 g/mol at 300 K
  table-lj.pot      pair_style table sections: LJ_RSQ (N 400 RSQ 0.8 2.5), LJ_R (N 300 R 0.8
                    2.5) of LJ 12-6 (epsilon = sigma = 1), SOFT (N 200, r from the file,
                    unevenly spaced, FPRIME) of E = 2 exp(-r^2) - 0.5 exp(-(r - 1.5)^2 / 0.1)

  data.edpd-small   atom_style edpd, lj,    N = 2048, L = 8      (rho = 4), 2 types (alternating),
                    T ~ U(0.7, 1.3), cv ~ U(5, 15), uniform random positions, v ~ N(0, 1)

  data.sdpd-taitwater  atom_style sph, micro, N = 512, L = 0.8 um (8^3 jittered lattice, +-0.2
                    spacings), 2 types (alternating, masses 1e-3 and 1.2e-3 pg), rho ~ U(0.98, 1.02)
                    rho0 of the type (rho0 = 1.0, 1.2), v ~ N(0, 0.05 um/us)

Atoms lines: sph `id type rho esph cv x y z`; edpd `id type edpd_temp edpd_cv x y z`; dpd  `id type dpdTheta x y z`;  mdpd `id type rho x y z`;  atomic `id type x y z` (rho is recomputed by
pair mdpd/rhosum before the first force, the column is written as 0).
Positions: data.dpde-3000 is uniform random in the box (soft potential: overlaps are harmless,
the statistical scene equilibrates first); the three 13^3 files are simple-cubic lattices with
every site moved by uniform(-0.25, 0.25) lattice spacings (data.table-lj and data.cg-water:
uniform(-0.12, 0.12) and (-0.15, 0.15), so no pair is closer than the inner distance of the
tables, 0.8 and 2 A) (a smaller initial force spike, so the
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


def alternating(n):
    """Types 1, 2, 1, 2 ... of n particles."""
    return [1 + i % 2 for i in range(n)]


def write(path, title, style, length, pos, vel, col3, fmt, types=None):
    """A data file; `col3` is the column after the type (dpdTheta, rho; None: atom_style
    atomic), `types` the type of each atom (default all 1)."""
    n = len(pos)
    types = types or [1] * n
    lines = [f"LAMMPS data file: {title} (scripts/lammps/make_data.py)", "",
             f"{n} atoms", f"{max(types)} atom types", ""]
    for ax in "xyz":
        lines.append(f"0.0 {length!r} {ax}lo {ax}hi")
    lines += ["", f"Atoms # {style}", ""]
    for i, (t, (x, y, z)) in enumerate(zip(types, pos), start=1):
        extra = "" if col3 is None else f"{col3} "
        lines.append(f"{i} {t} {extra}{x:{fmt}} {y:{fmt}} {z:{fmt}}")
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


# real units: kB in kcal/mol/K, mvv2e converts (g/mol)(A/fs)^2 to kcal/mol
BOLTZ_REAL = 0.0019872067
MVV2E_REAL = 48.88821291 * 48.88821291


def lj(r):
    return 4.0 * (r ** -12 - r ** -6), 4.0 * (12.0 * r ** -13 - 6.0 * r ** -7)


def soft(r):
    e = 2.0 * math.exp(-r * r) - 0.5 * math.exp(-(r - 1.5) ** 2 / 0.1)
    f = 4.0 * r * math.exp(-r * r) - 0.5 * 2.0 * (r - 1.5) / 0.1 * math.exp(-(r - 1.5) ** 2 / 0.1)
    return e, f


def table_sections():
    """table-lj.pot: three sections, with comments and blank lines between them."""
    out = ["# pair_style table test potentials (scripts/lammps/make_data.py)", "# E in energy, F = -dE/dr", ""]
    lo, hi = 0.8, 2.5
    out += ["LJ_RSQ   # r^2 evenly spaced", "N 400 RSQ 0.8 2.5", ""]
    for i in range(400):
        r = math.sqrt(lo * lo + (hi * hi - lo * lo) * i / 399)
        e, f = lj(r)
        out.append(f"{i + 1} {r:.15e} {e:.15e} {f:.15e}")
    out += ["", "LJ_R", "N 300 R 0.8 2.5", ""]
    for i in range(300):
        r = lo + (hi - lo) * i / 299
        e, f = lj(r)
        out.append(f"{i + 1} {r:.15e} {e:.15e} {f:.15e}")
    # r from the file, denser at short range: r = 0.5 + 2 x^1.5
    xs = [0.5 + 2.0 * (i / 199) ** 1.5 for i in range(200)]
    fp = lambda r: (soft(r + 1e-6)[1] - soft(r - 1e-6)[1]) / 2e-6
    out += ["", "# an uneven grid with its end slopes", "SOFT", f"N 200 FPRIME {fp(xs[0]):.15e} {fp(xs[-1]):.15e}", ""]
    for i, r in enumerate(xs):
        e, f = soft(r)
        out.append(f"{i + 1} {r:.15e} {e:.15e} {f:.15e}")
    return "\n".join(out) + "\n"


def write_typed(path, title, style, length, masses, atoms, vel):
    """A data file with a Masses section (one mass string per type) and ready Atoms lines."""
    lines = [f"LAMMPS data file: {title} (scripts/lammps/make_data.py)", "",
             f"{len(atoms)} atoms", f"{len(masses)} atom types", ""]
    for ax in "xyz":
        lines.append(f"0.0 {length!r} {ax}lo {ax}hi")
    lines += ["", "Masses", ""] + [f"{t} {m}" for t, m in enumerate(masses, start=1)]
    lines += ["", f"Atoms # {style}", ""] + atoms + ["", "Velocities", ""]
    for i, (a, b, c) in enumerate(vel, start=1):
        lines.append(f"{i} {a:.10f} {b:.10f} {c:.10f}")
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")


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
    atoms = []
    for i, (x, y, z) in enumerate(pos, start=1):
        t, cv = rng.uniform(0.7, 1.3), rng.uniform(5.0, 15.0)
        atoms.append(f"{i} {1 + i % 2} {t:.10f} {cv:.10f} {x:.10f} {y:.10f} {z:.10f}")
    write_typed(os.path.join(out, "data.edpd-small"), "eDPD lj rho=4 N=2048 two types", "edpd", length,
                ["1.0", "1.0"], atoms, vel)
    # g. two-type mixtures on small boxes (per-pair coefficients): 9^3 = 729 particles in a
    # 6.0 cube (2 cells of cutoff + skin per dimension), and 2197 MDPD particles at rho = 6
    rng = random.Random(1212)
    write(os.path.join(out, "data.mix-dpd"), "two-type DPD mixture lj N=729 L=6", "atomic", 6.0,
          jittered_lattice(rng, 9, 6.0), gaussian_velocities(rng, 729, 1.0), None, ".10f", alternating(729))
    rng = random.Random(1213)
    length = 13 / 6.0 ** (1 / 3)
    write(os.path.join(out, "data.mix-mdpd"), "two-type MDPD mixture lj N=2197", "mdpd", length,
          jittered_lattice(rng, 13, length), gaussian_velocities(rng, 13 ** 3, 1.0), "0.0", ".10f", alternating(13 ** 3))
    # h. pair_style table (lj): 10^3 particles of two types on a jittered lattice
    rng = random.Random(4004)
    length = 11.5
    pos = jittered_lattice(rng, 10, length, 0.12)
    types = [rng.choice((1, 2)) for _ in pos]
    write(os.path.join(out, "data.table-lj"), "table lj N=1000 two types", "atomic", length, pos,
          gaussian_velocities(rng, len(pos), 1.0), None, ".10f", types)
    with open(os.path.join(out, "table-lj.pot"), "w") as fh:
        fh.write(table_sections())

    # j. isothermal Tait-water SDPD (micro): 8^3 = 512 particles of two types
    rng = random.Random(2003)
    n, length = 8 ** 3, 0.8
    pos = jittered_lattice(rng, 8, length, 0.2)
    vel = gaussian_velocities(rng, n, 0.05)
    atoms = []
    for i, (x, y, z) in enumerate(pos, start=1):
        t = 1 + i % 2
        rho = (1.0 if t == 1 else 1.2) * rng.uniform(0.98, 1.02)
        atoms.append(f"{i} {t} {rho:.10f} 0.0 1.0 {x:.10f} {y:.10f} {z:.10f}")
    write_typed(os.path.join(out, "data.sdpd-taitwater"), "SDPD Tait water micro N=512 two types", "sph", length,
                ["0.001", "0.0012"], atoms, vel)

    # i. coarse-grained water (real): 13^3 = 2197 particles, L = 40.31 A, 300 K
    rng = random.Random(2180)
    length = 40.31
    pos = jittered_lattice(rng, 13, length, 0.15)
    std = math.sqrt(BOLTZ_REAL * 300.0 / (18.0154 * MVV2E_REAL))  # A/fs
    write(os.path.join(out, "data.cg-water"), "CG water real N=2197 L=40.31 A", "atomic", length, pos,
          gaussian_velocities(rng, len(pos), std), None, ".10f")


if __name__ == "__main__":
    main()
