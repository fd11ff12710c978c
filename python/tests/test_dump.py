import numpy as np
import pytest

import gendpde

# two frames as LAMMPS writes them: `dump custom` with dump_modify time yes, units yes, a
# triclinic box (bounding box, then the tilts) and scaled coordinates; the second frame cut
# off by a killed writer
FRAME = """ITEM: UNITS
metal
ITEM: TIME
{time}
ITEM: TIMESTEP
{step}
ITEM: NUMBER OF ATOMS
3
ITEM: BOX BOUNDS xy xz yz pp pp fm
-1.0 11.0 1.0
0.0 10.0 0.0
0.0 20.0 0.0
ITEM: ATOMS id type xs ys zs dpdTheta
3 2 0.5 0.5 0.5 300.5
1 1 0.0 0.25 0.75 299
2 1 0.99 0.1 0.2 301.25
"""
LAMMPS_DUMP = FRAME.format(time=0.5, step=500) + FRAME.format(time=0.6, step=600)[:-40]


@pytest.mark.parametrize("cut", [40, 10])  # rows missing; the last row short of columns
def test_lammps_dump(tmp_path, cut):
    (tmp_path / "lmp.dump").write_text(FRAME.format(time=0.5, step=500) + FRAME.format(time=0.6, step=600)[:-cut])
    frames = gendpde.read_dump(tmp_path / "lmp.dump")
    assert len(frames) == 1
    (df,) = frames
    a = df.attrs
    assert (a["step"], a["time"], a["units"], a["natoms"]) == (500, 0.5, "metal", 3)
    assert a["boundary"] == ["pp", "pp", "fm"]
    np.testing.assert_array_equal(a["tilt"], [1.0, 0.0, 0.0])
    np.testing.assert_array_equal(a["box"], [11.0, 10.0, 20.0])  # bounding box less the tilt
    np.testing.assert_array_equal(a["offset"], [-1.0, 0.0, 0.0])
    assert list(df.columns) == ["id", "type", "xs", "ys", "zs", "dpdTheta"]
    assert df["id"].tolist() == [3, 1, 2] and df["id"].dtype == np.int64
    assert df["dpdTheta"].tolist() == [300.5, 299.0, 301.25]


def test_write_dump_against_a_plain_read(fluid):
    """read_dump of gendpde's write_dump against numpy's own reading of the rows."""
    d, _ = fluid
    path = d / "final.dump"
    (df,) = gendpde.read_dump(path)
    lines = path.read_text().splitlines()
    assert lines[8].split()[2:] == list(df.columns)
    rows = np.loadtxt(lines[9:])
    assert rows.shape == (3375, 21) == df.shape
    np.testing.assert_array_equal(df.to_numpy(float), rows)
    assert df.attrs["step"] == int(lines[1]) == 200
    lo_hi = np.array([[float(w) for w in lines[k].split()] for k in (5, 6, 7)])
    np.testing.assert_array_equal(df.attrs["bounds"], lo_hi)
    np.testing.assert_array_equal(df.attrs["box"], lo_hi[:, 1] - lo_hi[:, 0])
    assert df.attrs["boundary"] == ["pp", "pp", "pp"] and df.attrs["time"] is None


@pytest.mark.parametrize("name", ["theta", "vx"])
def test_profile_of_scaled_coordinates(tmp_path, name):
    """xs columns count as positions lo + xs * L; the wrapped image of 0.99 is the last bin."""
    (tmp_path / "lmp.dump").write_text(LAMMPS_DUMP)
    frames = gendpde.read_dump(tmp_path / "lmp.dump")
    if name == "theta":
        x, mean, _ = gendpde.profile(frames, "x", 4, "theta")
        np.testing.assert_allclose(x, -1.0 + 11.0 / 8 * np.array([1, 3, 5, 7]))
        np.testing.assert_array_equal(mean, [299.0, np.nan, 300.5, 301.25])
    else:
        with pytest.raises(KeyError, match="vx"):
            gendpde.profile(frames, "x", 4, "vx")
