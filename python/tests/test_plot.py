import subprocess
import sys

import numpy as np
import pytest

import gendpde

pytest.importorskip("matplotlib")
from gendpde import plot  # noqa: E402


@pytest.mark.parametrize("name", ["traj.h5", "final.dump"])
def test_profile_command(fluid, tmp_path, name):
    d, _ = fluid
    out = tmp_path / "p.png"
    r = subprocess.run([sys.executable, "-m", "gendpde.plot", "profile", str(d / name), "--axis", "y",
                        "--bins", "8", "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    frames = 5 if name == "traj.h5" else 1
    assert r.stdout.strip() == f"{out}: density, theta along y, {frames} frames"
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_profile_figure_axes(fluid):
    d, _ = fluid
    frames = plot.load_frames(d / "traj.h5", start=100)
    assert [f.step for f in frames] == [100, 150, 200]
    fig = plot.profile_figure(frames, "z", 6, ("density", "theta", "vx"))
    axes = fig.axes
    assert [a.get_xlabel() for a in axes] == ["z [σ, reduced units]"] * 3
    assert [a.get_ylabel() for a in axes] == ["number density [σ⁻³, reduced units]",
                                              "particle temperature θ [ε/k_B, reduced units]",
                                              "velocity vx [(ε/m)^½, reduced units]"]
    x, theta, err = gendpde.profile(frames, "z", 6, "theta")
    line = axes[1].lines[0]
    np.testing.assert_array_equal(line.get_xdata(), x)
    np.testing.assert_array_equal(line.get_ydata(), theta)
    assert plot.label("theta", "metal") == "particle temperature θ [K]"


def test_no_frame_after_start(fluid, tmp_path):
    d, _ = fluid
    r = subprocess.run([sys.executable, "-m", "gendpde.plot", "profile", str(d / "traj.h5"), "--start", "999",
                        "-o", str(tmp_path / "p.png")], capture_output=True, text=True)
    assert r.returncode == 1 and "no frame at or after step 999" in r.stderr
