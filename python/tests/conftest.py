"""Shared gendpde runs of reduced size (a few seconds each, once per session)."""
import os
from pathlib import Path

import pytest

import gendpde

DATA = Path(__file__).parent / "data"
ROOT = Path(__file__).resolve().parents[2]

# vdW GenDPDE fluid (the smallest box of rc = 4), two runs of 100 steps with different
# thermo keywords, H5MD every 50 steps, a text dump at the end
FLUID = """variable n     index 15
variable steps index 100
units        lj
atom_style   gendpde
lattice      sc 0.5
region       box block 0 ${n} 0 ${n} 0 ${n}
create_box   1 box
create_atoms 1 box
mass         1 1.0
velocity     all create 1.5 4928459 dist gaussian
set          group all theta 1.5
pair_style   gendpde 4.0 4928459 weight quadratic
pair_coeff   * * 4.5 1.0 4.0 4.0
fix          eos all eos/vdw 60.0 2.4682 1.4142 excess
fix          rev all nve/gendpde
fix          ssa all shardlow heat original
timestep     0.01
thermo       20
thermo_style custom step time temp tint press pe ke etotal edrift
dump         traj all h5md 50 traj.h5 x v p u theta n id type mass image
run          ${steps}
thermo_style custom step temp press
run          ${steps}
write_dump   all custom final.dump id type mass x y z xu yu zu ix iy iz vx vy vz px py pz u theta n
"""

# fixed particles on an sc lattice exchanging heat only (examples/heat-only, N = 1000)
LATTICE = """units        lj
atom_style   gendpde
lattice      sc 0.5
region       box block 0 10 0 10 0 10
create_box   1 box
create_atoms 1 box
mass         1 1.0
set          group all theta 1.5
pair_style   gendpde 3.0 2021
pair_coeff   * * 0.0 1.0 3.0 3.0
fix          eos all eos/cv 5.0
fix          ssa all shardlow heat fourier
timestep     0.01
neighbor     0.0 bin
thermo       100
dump         traj all h5md 20 lattice.h5 x theta
run          400
"""


@pytest.fixture(scope="session")
def binary():
    """gendpde's executable; tests needing it skip when none is found, and fail when
    $GENDPDE names one that does not exist (scripts/test.sh sets it)."""
    if os.environ.get("GENDPDE"):
        return gendpde.find_binary()
    try:
        return gendpde.find_binary()
    except FileNotFoundError as e:
        pytest.skip(str(e))


def _scene(binary, factory, name, text):
    d = factory.mktemp(name)
    (d / f"in.{name}").write_text(text)
    return d, gendpde.run(f"in.{name}", cwd=d, binary=binary)


@pytest.fixture(scope="session")
def fluid(binary, tmp_path_factory):
    """(directory, Run) of FLUID."""
    return _scene(binary, tmp_path_factory, "fluid", FLUID)


@pytest.fixture(scope="session")
def lattice(binary, tmp_path_factory):
    """(directory, Run) of LATTICE."""
    return _scene(binary, tmp_path_factory, "lattice", LATTICE)
