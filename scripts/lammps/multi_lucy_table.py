#!/usr/bin/env python3
"""Writes `table.multibody`, OUR SUBSTITUTE for the pressure-density table of LAMMPS's
example dpd-react/multi-lucy (LAMMPS's own file is missing from every copy we can reach:
an absent Git LFS blob upstream). It is not LAMMPS's file and not the RDX model's table.

Format: LAMMPS's pair multi/lucy table section (pair_multi_lucy.cpp read_table):

    KEYWORD
    N n R rho_lo rho_hi

    i rho e(rho) f(rho)

The model is a quadratic free energy per particle about the density rho* of the
example's initial hcp lattice,

    e(rho) = e* + f* (rho - rho*) + b/2 (rho - rho*)^2,   f(rho) = de/drho,

so that the force (f(rho_i) + f(rho_j))/2 (1 + 3r/rc)(1 - r/rc)^3 of pair multi/lucy is
minus the gradient of the energy sum_i e(rho_i) pi rc^4/84 (energy conserving). e* and f*
are chosen so that step 0 of the example reproduces the reference log's PotEng
(-22.12267153 eV) and Press (1214.85216295 bar): rho* = 3.966693e-3 A^-3 (the density
of every site of the example's lattice, rc = 16 A) and 94540.73 bar (the virial pressure
of that lattice with f = 1) were measured with the reference LAMMPS running the example
for 0 steps on the trial table e = rho, f = 1; b = 115 puts step 18 near the reference
log (this table: Temp 294.34, Press 1281.0, PotEng -19.199; log: 294.26, 1271.5,
-19.154).
"""
import argparse
import math
import random

RC = 16.0
PE0, P0 = -22.12267153, 1214.85216295  # reference log, step 0
NATOMS, VOLUME, T0 = 4000, 807346.78400379, 300.0
KB_METAL, NKTV2P_METAL = 8.617343e-5, 1.6021765e6


def model(rho_star, virial_per_f):
    """(e*, f*) from the step-0 targets."""
    scale = math.pi * RC**4 / 84.0
    e_star = PE0 / (NATOMS * scale)
    p_kin = NATOMS * KB_METAL * T0 / VOLUME * NKTV2P_METAL
    f_star = (P0 - p_kin) / virial_per_f
    return e_star, f_star


def write(path, n, rho_hi, rho_star, e_star, f_star, b):
    with open(path, "w") as out:
        out.write("# table.multibody: gendpde's SUBSTITUTE for the missing LAMMPS file (see\n")
        out.write("# scripts/lammps/multi_lucy_table.py); quadratic free energy about rho* =\n")
        out.write(f"# {rho_star:.6e}: e* = {e_star:.6e}, f* = {f_star:.6e}, b = {b:.6e}\n\n")
        out.write(f"KEYWORD\nN {n} R 0.0 {rho_hi}\n\n")
        for i in range(n):
            rho = rho_hi * i / (n - 1)
            d = rho - rho_star
            out.write(f"{i + 1} {rho:.10e} {e_star + f_star * d + 0.5 * b * d * d:.10e} {f_star + b * d:.10e}\n")


def parity_files(outdir):
    """The inputs of tests/it/styles/multi_lucy.rs (in.multi-lucy-parity): data.multi-lucy (atom_style
    dpd, metal, N = 1000 on a 10^3 lattice of spacing 6 A with every site moved by
    uniform(-1.5, 1.5) A, types 1 and 2 alternating, v ~ N(0, kT/m) for m = 100 g/mol at
    300 K) and multi-lucy.table with three sections of e(rho) and f = de/drho: ML_RSQ
    (N 400 RSQ 0 0.02, used as given by `linear 400`), ML_R (N 300 R 0 0.02, splined) and
    ML_FP (N 250 R 0.0005 0.025 with FP end slopes)."""
    rng = random.Random(20261202)
    n_side, a = 10, 6.0
    sd = math.sqrt(KB_METAL * 300.0 / 100.0 * 9648.53)
    lines = []
    for k in range(n_side ** 3):
        ix, iy, iz = k // 100, (k // 10) % 10, k % 10
        x = [(c + 0.5) * a + rng.uniform(-1.5, 1.5) for c in (ix, iy, iz)]
        lines.append((k + 1, 1 + k % 2, x, [rng.gauss(0.0, sd) for _ in range(3)]))
    with open(f"{outdir}/data.multi-lucy", "w") as out:
        out.write("LAMMPS data file: pair multi/lucy parity, metal, N=1000, L=60 A (scripts/lammps/multi_lucy_table.py --parity)\n\n")
        out.write("1000 atoms\n2 atom types\n\n0.0 60.0 xlo xhi\n0.0 60.0 ylo yhi\n0.0 60.0 zlo zhi\n\nAtoms # dpd\n\n")
        for i, t, x, _ in lines:
            out.write(f"{i} {t} 300.0 {x[0]:.8f} {x[1]:.8f} {x[2]:.8f}\n")
        out.write("\nVelocities\n\n")
        for i, _, _, v in lines:
            out.write(f"{i} {v[0]:.8f} {v[1]:.8f} {v[2]:.8f}\n")
    sections = [
        ("ML_RSQ", 400, "RSQ", 0.0, 0.02, "", lambda r: (1e-3 * (r - 0.005) ** 2 * 1e4 - 2e-6, 20.0 * (r - 0.005))),
        ("ML_R", 300, "R", 0.0, 0.02, "", lambda r: (0.3 * r ** 3 - 0.01 * r, 0.9 * r ** 2 - 0.01)),
        ("ML_FP", 250, "R", 0.0005, 0.025, " FP 0.002 0.0", lambda r: (1e-4 * math.exp(-r / 0.005), -0.02 * math.exp(-r / 0.005))),
    ]
    with open(f"{outdir}/multi-lucy.table", "w") as out:
        out.write("# pair multi/lucy sections for tests/it/styles/multi_lucy.rs (scripts/lammps/multi_lucy_table.py --parity)\n")
        for key, n, spacing, lo, hi, fp, ef in sections:
            out.write(f"\n{key}\nN {n} {spacing} {lo} {hi}{fp}\n\n")
            for i in range(n):
                if spacing == "R":
                    rho = lo + (hi - lo) * i / (n - 1)
                else:
                    rho = math.sqrt(lo * lo + (hi * hi - lo * lo) * i / (n - 1))
                e, f = ef(rho)
                out.write(f"{i + 1} {rho:.12e} {e:.12e} {f:.12e}\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="table.multibody")
    ap.add_argument("--n", type=int, default=500, help="points of the file (N)")
    ap.add_argument("--rho-hi", type=float, default=0.02, help="largest density of the table (A^-3)")
    ap.add_argument("--rho-star", type=float, default=3.966693e-3, help="density of the lattice (A^-3)")
    ap.add_argument("--virial-per-f", type=float, default=94540.73, help="virial pressure (bar) of the lattice with f = 1")
    ap.add_argument("--b", type=float, default=115.0, help="curvature d^2e/drho^2")
    ap.add_argument("--parity", metavar="DIR", help="write the parity test's data.multi-lucy and multi-lucy.table into DIR instead")
    args = ap.parse_args()
    if args.parity:
        parity_files(args.parity)
        return
    e_star, f_star = model(args.rho_star, args.virial_per_f)
    write(args.out, args.n, args.rho_hi, args.rho_star, e_star, f_star, args.b)

if __name__ == "__main__":
    main()
