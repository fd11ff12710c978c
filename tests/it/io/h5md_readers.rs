//! H5MD files of runs open in MDAnalysis with the recipe of the README
//! (`Universe.empty(N, trajectory=True)` then `load_new(FILE, format="H5MD")`,
//! `convert_units=False` for unitless lj files): positions, velocities, the box, the time
//! and the step of every frame equal h5py's values, and the observables the thermo rows.

use crate::common;

use common::lammps::{parse_thermo, stage_with};
use std::path::{Path, PathBuf};
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gendpde-h5md-readers-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs scripts/lammps/`input` with `dump` before its run; returns gendpde's stdout.
fn run_with_dump(dir: &Path, input: &str, dump: &str) -> String {
    stage_with(dir, input, "in.h5md", &format!("{dump}\n"), "");
    let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(dir).args(["run", "in.h5md", "-log", "none"]).output().unwrap();
    assert!(out.status.success(), "gendpde failed:\n{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

const CHECK: &str = r#"
import sys
import h5py, numpy as np
import MDAnalysis as mda
path, convert = sys.argv[1], sys.argv[2] == "yes"
with h5py.File(path, "r") as f:
    p = f["particles/all"]
    pos, vel = p["position/value"][()], p["velocity/value"][()]
    edges, steps, times = p["box/edges/value"][()], p["position/step"][()], p["position/time"][()]
    obs = {k: f["observables"][k]["value"][()] for k in f["observables"]}
u = mda.Universe.empty(pos.shape[1], trajectory=True)
u.load_new(path, format="H5MD", convert_units=convert)
assert len(u.trajectory) == len(pos) == len(steps), (len(u.trajectory), len(pos))
for k, ts in enumerate(u.trajectory):
    assert np.array_equal(ts.positions, pos[k].astype(np.float32)), f"frame {k}: positions"
    assert np.array_equal(ts.velocities, vel[k].astype(np.float32)), f"frame {k}: velocities"
    assert np.array_equal(ts.dimensions, np.array([*edges[k], 90, 90, 90], dtype=np.float32)), f"frame {k}: box {ts.dimensions}"
    assert ts.time == np.float32(times[k]) or ts.time == times[k], f"frame {k}: time {ts.time} {times[k]}"
    assert ts.data["step"] == steps[k], f"frame {k}: step"
    for name, v in obs.items():
        assert ts.data[name] == v[k] or (np.isnan(v[k]) and np.isnan(ts.data[name])), f"frame {k}: {name}"
        print("OBS", steps[k], name, repr(float(ts.data[name])))
print("FRAMES", len(u.trajectory), "UNITS", u.trajectory.units["length"], u.trajectory.units["velocity"])
"#;

/// Runs the MDAnalysis check on `file`; returns its output (None without MDAnalysis).
fn mdanalysis(file: &Path, convert_units: bool) -> Option<String> {
    let probe = Command::new("python3").args(["-c", "import MDAnalysis, h5py"]).output();
    if !probe.is_ok_and(|o| o.status.success()) {
        eprintln!("SKIPPED: MDAnalysis or h5py is missing (pip install MDAnalysis h5py; scripts/test.sh installs them)");
        return None;
    }
    let yes = if convert_units { "yes" } else { "no" };
    let out = Command::new("python3").args(["-c", CHECK, file.to_str().unwrap(), yes]).output().unwrap();
    assert!(out.status.success(), "MDAnalysis on {}:\n{}", file.display(), String::from_utf8_lossy(&out.stderr));
    Some(String::from_utf8(out.stdout).unwrap())
}

#[test]
fn mdanalysis_reads_lj_frames_with_convert_units_false() {
    let d = dir("lj");
    let stdout = run_with_dump(&d, "in.dpde-deterministic", "dump h all h5md 10 traj.h5 position velocity species id mass");
    let Some(out) = mdanalysis(&d.join("traj.h5"), false) else { return };
    assert!(out.contains("FRAMES 11 UNITS None None"), "{out}");
    // the observables are the thermo rows (printed with %.17g by this scene)
    let rows = parse_thermo(&stdout, "Step");
    assert_eq!(rows.len(), 11);
    let header = stdout.lines().find(|l| l.trim_start().starts_with("Step")).unwrap();
    let names = ["temp", "press", "pe", "ke", "c_dpdU[1]", "c_dpdU[2]", "c_dpdU[4]", "v_totEnergy"];
    let headings: Vec<&str> = header.split_whitespace().collect();
    let mut seen = 0;
    for line in out.lines().filter_map(|l| l.strip_prefix("OBS ")) {
        let w: Vec<&str> = line.split(' ').collect();
        let (step, name, value): (f64, &str, f64) = (w[0].parse().unwrap(), w[1], w[2].parse().unwrap());
        let row = rows.iter().find(|r| r[0] == step).unwrap_or_else(|| panic!("no thermo row at step {step}"));
        let k = names.iter().position(|n| *n == name).unwrap_or_else(|| panic!("observable {name}"));
        let col = headings.iter().position(|h| *h == ["Temp", "Press", "PotEng", "KinEng", "c_dpdU[1]", "c_dpdU[2]", "c_dpdU[4]", "v_totEnergy"][k]).unwrap();
        assert_eq!(value, row[col], "step {step}: {name}");
        seen += 1;
    }
    assert_eq!(seen, 11 * names.len());
}

#[test]
fn mdanalysis_reads_metal_units() {
    let d = dir("metal");
    run_with_dump(&d, "in.dpde-metal", "dump h all h5md 25 traj.h5 x v\ndump_modify h author \"A. User\" email a.user@example.org");
    let Some(out) = mdanalysis(&d.join("traj.h5"), true) else { return };
    assert!(out.contains("FRAMES 5 UNITS Angstrom Angstrom/ps"), "{out}");
    let s = gendpde_io::check_h5md(&d.join("traj.h5")).unwrap();
    assert_eq!(s.author, "A. User");
}
