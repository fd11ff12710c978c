"""gendpde's readers on the reference LAMMPS's own output (skipped without LAMMPS)."""
import os
import shutil
import subprocess

import numpy as np
import pytest

import gendpde
from conftest import ROOT


@pytest.fixture(scope="module")
def lmp():
    path = os.environ.get("LMP")
    if not path:
        setup = os.environ.get("LAMMPS_SETUP", str(ROOT.parent / "shared" / "lammps" / "setup.sh"))
        if not os.path.isfile(setup):
            pytest.skip("no reference LAMMPS (set LMP or LAMMPS_SETUP)")
        r = subprocess.run(["bash", setup], capture_output=True, text=True)
        if r.returncode != 0:
            pytest.skip(f"reference LAMMPS setup failed: {r.stderr[-300:]}")
        path = r.stdout.strip().splitlines()[-1]
    return path


def test_lammps_log_and_dump(lmp, tmp_path):
    src = ROOT / "scripts" / "lammps"
    shutil.copy(src / "in.dpde-deterministic", tmp_path)
    shutil.copy(src / "data.dpde-small", tmp_path)
    r = subprocess.run([lmp, "-in", "in.dpde-deterministic", "-log", "log.lammps"], cwd=tmp_path,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout[-2000:]
    (log,) = gendpde.read_log(tmp_path / "log.lammps")
    assert log["Step"].tolist() == list(range(0, 101, 10))
    assert log.attrs["natoms"] == 2197 and log.attrs["units"] == "lj" and log.attrs["complete"]
    assert gendpde.parse_log(r.stdout)[0].equals(log)
    (frame,) = gendpde.read_dump(tmp_path / "dpde-det.dump")
    lines = (tmp_path / "dpde-det.dump").read_text().splitlines()
    np.testing.assert_array_equal(frame.to_numpy(float), np.loadtxt(lines[9:]))
    assert frame.attrs["step"] == 100 and list(frame.columns) == ["id", "x", "y", "z", "vx", "vy", "vz"]
    x, n, _ = gendpde.profile([frame], "x", 4, "density")
    assert np.sum(n) * np.prod(frame.attrs["box"]) / 4 == pytest.approx(2197)
