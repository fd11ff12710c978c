import numpy as np

import gendpde
from conftest import DATA


def stdout_tables(text):
    """Independent reading of the thermo rows printed on stdout: (header, rows) per run."""
    tables = []
    for line in text.splitlines():
        words = line.split()
        if words[:1] == ["Step"]:
            tables.append((words, []))
        elif tables and line.startswith("Loop time"):
            continue
        elif tables and words and words[0].lstrip("-").isdigit() and len(words) == len(tables[-1][0]):
            tables[-1][1].append([float(w) for w in words])
    return tables


def test_gendpde_log_matches_stdout(fluid):
    d, r = fluid
    logs = gendpde.read_log(d / "log.gendpde")
    tables = stdout_tables(r.stdout)
    assert len(logs) == len(tables) == 2
    for df, (header, rows) in zip(logs, tables):
        assert list(df.columns) == header
        np.testing.assert_array_equal(df.to_numpy(float), np.array(rows))
        assert df["Step"].dtype == np.int64
        assert all(df[c].dtype == np.float64 for c in header[1:])
    assert logs[0].attrs["keywords"] == ["Step", "Time", "Temp", "Tint", "Press", "PotEng", "KinEng", "TotEng", "Edrift"]
    assert logs[1].attrs["keywords"] == ["Step", "Temp", "Press"]


def test_gendpde_log_attrs(fluid):
    d, _ = fluid
    first, second = gendpde.read_log(d / "log.gendpde")
    for k, df in enumerate((first, second)):
        a = df.attrs
        assert a["run"] == k and a["complete"]
        assert (a["first_step"], a["last_step"]) == (100 * k, 100 * k + 100)
        assert a["natoms"] == 3375 and a["nprocs"] == 1 and a["steps"] == 100
        assert a["units"] == "lj" and a["timestep"] == 0.01
        assert a["loop_time"] > 0
        assert np.isclose(a["atom_steps_per_s"], 3375 * 100 / a["loop_time"])
        # the Performance line: timesteps/s is steps over the loop time
        assert np.isclose(a["performance"]["timesteps/s"], 100 / a["loop_time"], rtol=1e-3)
        assert a["stats"]["Neighbor list builds"] >= 1
    assert second.attrs["thermo_style"] == "custom step temp press"


def test_killed_run_keeps_its_rows(fluid):
    d, _ = fluid
    text = (d / "log.gendpde").read_text()
    cut = text[: text.index("Loop time")]  # the first run killed before its end
    cut = cut[: cut.rindex("\n", 0, len(cut) - 1) + 20]  # and its last row half written
    (df,) = gendpde.parse_log(cut)
    full = gendpde.parse_log(text)[0]
    assert not df.attrs["complete"] and "loop_time" not in df.attrs
    assert len(df) == len(full) - 1
    np.testing.assert_array_equal(df.to_numpy(), full.to_numpy()[:-1])


def test_lammps_log():
    """log.lammps of scripts/lammps/in.dpde-shardlow (reference LAMMPS, -var equil 30 -var steps 40)."""
    first, second = gendpde.read_log(DATA / "log.lammps")
    assert list(first.columns) == ["Step", "Temp", "Press", "PotEng", "KinEng", "c_dpdU[1]", "c_dpdU[2]",
                                   "c_dpdU[4]", "v_totEnergy"]
    assert first["Step"].tolist() == [0, 30] and second["Step"].tolist() == [0, 10, 20, 30, 40]
    assert second["Temp"].iloc[-1] == 1.675354723 and second["c_dpdU[1]"].iloc[1] == 7.244205236e-15
    assert first.attrs["units"] == "lj" and first.attrs["timestep"] == 0.01
    assert (second.attrs["natoms"], second.attrs["steps"], second.attrs["loop_time"]) == (3000, 40, 0.166092)
    assert second.attrs["performance"] == {"tau/day": 208077.145, "timesteps/s": 240.830, "katom-step/s": 722.490}
    assert first.attrs["stats"]["Dangerous builds"] == 0
