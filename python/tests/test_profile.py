import numpy as np
import pytest

import gendpde


def test_lattice_density_is_flat(lattice):
    """Fixed particles on the sc lattice (10 planes per side): with 5 bins, two planes per
    bin, the density is N/V exactly in every bin, frame and direction."""
    d, _ = lattice
    with gendpde.read_h5md(d / "lattice.h5") as frames:
        frames = list(frames)
    box = frames[0].box
    assert len(frames) == 21
    for axis in "xyz":
        x, mean, err = gendpde.profile(frames, axis, 5, "density")
        np.testing.assert_allclose(x, (np.arange(5) + 0.5) * box[0] / 5)
        np.testing.assert_allclose(mean, 1000 / np.prod(box), rtol=1e-12)
        np.testing.assert_allclose(err, 0.0, atol=1e-12)


def test_lattice_theta(lattice):
    """Heat exchange only, u = C_V theta: theta fluctuates, but the total energy is
    conserved, so the bins (200 particles each) average to T = 1.5 in every frame."""
    d, _ = lattice
    with gendpde.read_h5md(d / "lattice.h5") as frames:
        frames = list(frames)[5:]
    x, mean, err = gendpde.profile(frames, "x", 5, "theta")
    assert np.all(err > 0) and np.all(np.abs(mean - 1.5) > 1e-4)
    assert np.mean(mean) == pytest.approx(1.5, rel=1e-10)
    # the same mean computed by hand: per frame, the particles with 2 <= x/a < 4
    a = frames[0].box[0] / 10
    by_hand = [f.temperature[(np.rint(f.position[:, 0] / a) % 10 // 2) == 1].mean() for f in frames]
    assert mean[1] == pytest.approx(np.mean(by_hand), rel=1e-12)
    assert err[1] == pytest.approx(np.std(by_hand, ddof=1) / np.sqrt(len(frames)), rel=1e-9)


def test_fluid_profiles(fluid):
    d, _ = fluid
    with gendpde.read_h5md(d / "traj.h5") as frames:
        frames = list(frames)
    box = frames[0].box
    for axis in "xyz":
        x, n, n_err = gendpde.profile(frames, axis, 6, "density")
        # every particle in one bin of each frame: the bins hold N on average
        assert np.sum(n) * np.prod(box) / 6 == pytest.approx(3375, rel=1e-12)
        assert np.all(np.abs(n - 3375 / np.prod(box)) < 5 * n_err + 1e-12)
    _, vx, vx_err = gendpde.profile(frames, "x", 6, "vx")
    _, px, _ = gendpde.profile(frames, "x", 6, "px")
    np.testing.assert_array_equal(vx, px)  # mass 1
    assert np.all(np.abs(vx) < 5 * vx_err)


def test_dump_and_h5md_frames_give_one_profile(fluid):
    d, _ = fluid
    dump = gendpde.read_dump(d / "final.dump")
    with gendpde.read_h5md(d / "traj.h5") as frames:
        last = [frames[-1]]
    for field in ("density", "theta", "u", "n", "vy"):
        a, b = gendpde.profile(dump, "y", 7, field), gendpde.profile(last, "y", 7, field)
        for u, v in zip(a, b):
            np.testing.assert_array_equal(u, v)
    assert np.all(np.isnan(a[2]))  # one frame: no error estimate


def test_unknown_field(fluid):
    d, _ = fluid
    with gendpde.read_h5md(d / "traj.h5") as frames:
        with pytest.raises(KeyError, match="nonsense"):
            gendpde.profile(frames, "x", 4, "nonsense")
