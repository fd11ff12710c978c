import shutil

import numpy as np
import pytest

import gendpde
from conftest import FLUID, ROOT


def test_outputs(fluid):
    d, r = fluid
    assert [p.name for p in r.outputs] == ["final.dump", "log.gendpde", "traj.h5"]
    assert r.wall_s > 0 and r.command[1:4] == ["run", "in.fluid", "-log"]
    assert [df.attrs["last_step"] for df in r.logs] == [100, 200]


def test_error_carries_the_script_message(binary, tmp_path):
    """The default example (fix shardlow) in a box under 2 (cutoff + skin): gendpde's
    message (LAMMPS's for fix shardlow), with the script's file and line, becomes the
    exception's."""
    script = ROOT / "examples" / "vdw-equilibrium" / "in.vdw-equilibrium"
    with pytest.raises(gendpde.GendpdeError) as e:
        gendpde.run(script, vars={"n": 6, "steps": 10}, cwd=tmp_path, binary=binary)
    msg = str(e.value)
    assert msg.startswith(f"ERROR: {script}:36: run: Shardlow algorithm requires sub-domain length > 2*(rcut+skin)")
    assert "rcut= 8.8" in msg and "\n" not in msg
    assert e.value.returncode != 0 and msg in e.value.stderr


def test_error_of_an_unknown_command(binary, tmp_path):
    (tmp_path / "in.bad").write_text("units lj\nfrobnicate all 3\n")
    with pytest.raises(gendpde.GendpdeError, match=r"^ERROR: .*in\.bad:2: .*frobnicate"):
        gendpde.run(tmp_path / "in.bad", cwd=tmp_path, binary=binary, log=None)


def test_binary_from_environment(monkeypatch, tmp_path):
    monkeypatch.setenv("GENDPDE", str(tmp_path / "missing"))
    with pytest.raises(FileNotFoundError, match="GENDPDE="):
        gendpde.run("in.x", cwd=tmp_path)


@pytest.mark.skipif(shutil.which("mpirun") is None, reason="no mpirun")
def test_two_ranks_print_the_same_thermo(fluid, binary, tmp_path):
    """np=2 runs under mpirun: thermo output is bit-identical for every rank count."""
    _, serial = fluid
    (tmp_path / "in.fluid").write_text(FLUID)
    r = gendpde.run(tmp_path / "in.fluid", vars={"steps": 60}, np=2, cwd=tmp_path, binary=binary, log=None)
    assert [df.attrs["nprocs"] for df in r.logs] == [2, 2]
    first = serial.logs[0]
    np.testing.assert_array_equal(r.logs[0].to_numpy(), first[first["Step"] <= 60].to_numpy())
