import shutil

import h5py
import numpy as np
import pytest

import gendpde


def test_frames_match_h5py(fluid):
    d, _ = fluid
    with h5py.File(d / "traj.h5", "r") as f:
        part = f["particles/all"]
        names = {k for k in part if k != "box"}
        steps = part["position/step"][()]
        times = part["position/time"][()]
        values = {k: part[f"{k}/value"][()] for k in names}
        edges = part["box/edges/value"][()]
        observables = {k: f[f"observables/{k}/value"][()] for k in f["observables"]}
    with gendpde.read_h5md(d / "traj.h5") as frames:
        assert len(frames) == len(steps) == 5  # steps 0, 50, ..., 200
        assert set(frames[0].keys()) == names
        for k, frame in enumerate(frames):
            assert frame.step == steps[k] and frame.time == times[k]
            np.testing.assert_array_equal(frame.box, edges[k])
            np.testing.assert_array_equal(frame.offset, np.zeros(3))
            for name in names:
                np.testing.assert_array_equal(frame[name], values[name][k])
        last = frames[-1]
        assert last.position.shape == (3375, 3) and last.temperature.shape == (3375,)
        np.testing.assert_array_equal(frames.array("temperature"), values["temperature"])
        assert frames.boundary == ["periodic"] * 3
        obs = frames.observables()
        assert list(obs.index) == list(steps) and set(obs.columns) == set(observables)
        for k, v in observables.items():
            np.testing.assert_array_equal(obs[k].to_numpy(), v)


def test_frames_match_the_text_dump(fluid):
    """The last H5MD frame and write_dump at the same step hold the same numbers."""
    d, _ = fluid
    (dump,) = gendpde.read_dump(d / "final.dump")
    with gendpde.read_h5md(d / "traj.h5") as frames:
        last = frames[-1]
    assert dump.attrs["step"] == last.step == 200
    np.testing.assert_array_equal(dump.attrs["box"], last.box)
    np.testing.assert_array_equal(dump["id"], last.id)
    np.testing.assert_array_equal(dump["type"], last.species)
    np.testing.assert_array_equal(dump[["vx", "vy", "vz"]].to_numpy(), last.velocity)
    np.testing.assert_array_equal(dump[["px", "py", "pz"]].to_numpy(), last.momentum)
    np.testing.assert_array_equal(dump[["ix", "iy", "iz"]].to_numpy(), last.image)
    np.testing.assert_array_equal(dump["theta"], last.temperature)
    np.testing.assert_array_equal(dump["u"], last.internal_energy)
    np.testing.assert_array_equal(dump["n"], last.density)
    # positions are wrapped at neighbour-list builds, so some lie just outside the box
    x = dump[["x", "y", "z"]].to_numpy()
    np.testing.assert_array_equal(x, last.position)
    np.testing.assert_allclose(dump[["xu", "yu", "zu"]].to_numpy(), x + last.image * last.box, rtol=1e-15)


def rewrite(src, dst):
    """A copy of `src` as other writers lay it out: box edges growing by 1 % per frame,
    mass as a time-independent dataset, and observables of their own."""
    shutil.copy(src, dst)
    with h5py.File(dst, "r+") as f:
        part = f["particles/all"]
        edges = part["box/edges/value"][0]
        steps = part["position/step"][()]
        del part["box/edges"]
        g = part["box"].create_group("edges")
        g["value"] = np.array([edges * (1 + 0.01 * k) for k in range(len(steps))])
        g["step"] = steps
        g["time"] = part["position/time"][()]
        mass = part["mass/value"][0]
        del part["mass"]
        part["mass"] = mass
        del f["observables"]
        obs = f.create_group("observables")
        for name, v in [("temperature", np.arange(len(steps), dtype=float)),
                        ("pressure_tensor", np.arange(3 * len(steps), dtype=float).reshape(-1, 3))]:
            o = obs.create_group(name)
            o["value"], o["step"] = v, steps
    return edges, steps


def test_time_dependent_box_and_fixed_elements(fluid, tmp_path):
    d, _ = fluid
    edges, steps = rewrite(d / "traj.h5", tmp_path / "copy.h5")
    with gendpde.read_h5md(tmp_path / "copy.h5") as frames:
        assert len(frames) == len(steps)
        for k, frame in enumerate(frames):
            np.testing.assert_allclose(frame.box, edges * (1 + 0.01 * k))
            np.testing.assert_array_equal(frame.mass, np.ones(3375))
        obs = frames.observables()
        assert list(obs.index) == list(steps)
        assert list(obs.columns) == ["pressure_tensor[0]", "pressure_tensor[1]", "pressure_tensor[2]", "temperature"]
        assert obs["pressure_tensor[2]"].iloc[1] == 5.0


def test_incomplete_frame_is_left_out(fluid, tmp_path):
    """A writer killed between the values and the step of a frame: the frame is not read."""
    d, _ = fluid
    shutil.copy(d / "traj.h5", tmp_path / "killed.h5")
    with h5py.File(tmp_path / "killed.h5", "r+") as f:
        step = f["particles/all/position/step"]  # one dataset, hard-linked in every element
        step.resize((len(step) - 1,))
    with gendpde.read_h5md(tmp_path / "killed.h5") as frames:
        assert len(frames) == 4 and frames[-1].step == 150
        assert frames.array("position").shape == (4, 3375, 3)
        with pytest.raises(IndexError):
            frames[4]


def test_fixed_box_dataset(fluid, tmp_path):
    """Writers that store the box edges once, as a plain dataset (H5MD allows both)."""
    d, _ = fluid
    shutil.copy(d / "traj.h5", tmp_path / "fixed.h5")
    with h5py.File(tmp_path / "fixed.h5", "r+") as f:
        box = f["particles/all/box"]
        edges = box["edges/value"][0]
        del box["edges"]
        box["edges"] = edges
    with gendpde.read_h5md(tmp_path / "fixed.h5") as frames:
        for frame in frames:
            np.testing.assert_array_equal(frame.box, edges)


def test_not_h5md(tmp_path):
    with h5py.File(tmp_path / "plain.h5", "w") as f:
        f["x"] = [1.0]
    with pytest.raises(ValueError, match="not an H5MD file"):
        gendpde.read_h5md(tmp_path / "plain.h5")
