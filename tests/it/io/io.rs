//! Files users rely on: restarts continue bit-identically, H5MD snapshots follow the
//! H5MD 1.1 layout (checked here and read by h5py), a killed run leaves readable
//! frames and checkpoints, and damaged inputs give clear errors.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn gendpde(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gendpde")).args(args).current_dir(dir).output().expect("gendpde runs")
}

fn tempdir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gendpde-io-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The vdW example (reduced) with a checkpoint every 50 steps and a final dump.
fn straight_script(dir: &Path) {
    let script = std::fs::read_to_string(common::example("vdw-equilibrium")).unwrap().replace(
        "run          ${steps}",
        "checkpoint 50 ck.*.h5\nrun ${steps}\nwrite_dump all custom straight.dump id type x y z ix iy iz px py pz u theta",
    );
    std::fs::write(dir.join("in.straight"), script).unwrap();
    std::fs::write(
        dir.join("in.continue"),
        "read_restart ck.50.h5\nthermo_style custom step time temp tint press pe ke etotal edrift\nrun 50\nwrite_dump all custom continued.dump id type x y z ix iy iz px py pz u theta\n",
    )
    .unwrap();
}

const VARS: [&str; 8] = ["-var", "n", "11", "-var", "rc", "3.0", "-var", "steps"];

#[test]
fn a_run_continued_from_a_restart_is_bit_identical() {
    let dir = tempdir("restart");
    straight_script(&dir);
    let mut args = vec!["run", "in.straight", "-log", "none"];
    args.extend(VARS);
    args.push("100");
    let out = gendpde(&args, &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = gendpde(&["run", "in.continue", "-log", "none"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (a, b) = (std::fs::read(dir.join("straight.dump")).unwrap(), std::fs::read(dir.join("continued.dump")).unwrap());
    assert!(a == b, "the continued run differs from the straight one");
    // and the thermo at step 100 is the same line
    let last = |o: &Output| String::from_utf8_lossy(&o.stdout).lines().filter(|l| l.trim_start().starts_with("100 ")).last().map(String::from);
    let straight = gendpde(&args, &dir);
    assert_eq!(last(&straight), last(&out));
}

#[test]
fn h5md_snapshots_follow_the_standard_and_h5py_reads_them() {
    let dir = tempdir("h5md");
    let script = std::fs::read_to_string(common::example("heat-only"))
        .unwrap()
        .replace("run          ${steps}", "dump traj all h5md 10 traj.h5 x p u theta id type\nrun ${steps}");
    std::fs::write(dir.join("in.test"), script).unwrap();
    let out = gendpde(&["run", "in.test", "-log", "none", "-var", "steps", "30", "-var", "n", "10"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary = gendpde_io::check_h5md(&dir.join("traj.h5")).unwrap_or_else(|e| panic!("not H5MD 1.1: {}", e.0));
    assert_eq!(summary.particles, 1000);
    assert_eq!(summary.frames, 4, "frames at steps 0, 10, 20, 30");
    // an independent reader: h5py (scripts/test.sh installs scripts/requirements.txt)
    let check = r#"
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
p = f["particles/all"]
assert p["position/value"].shape == (4, 1000, 3), p["position/value"].shape
assert p["momentum/value"].shape == (4, 1000, 3)
assert p["internal_energy/value"].shape == (4, 1000)
assert p["temperature/value"].shape == (4, 1000)
assert list(p["position/step"][:]) == [0, 10, 20, 30]
assert np.allclose(p["position/time"][:], [0.0, 0.1, 0.2, 0.3])
ids = p["id/value"][3]
assert list(ids) == list(range(1, 1001)), "rows sorted by id"
u = p["internal_energy/value"][0]
assert np.allclose(u, 7.5), "u = C_V theta = 7.5 at step 0"
assert tuple(f["h5md"].attrs["version"]) == (1, 1)
print("h5py ok")
"#;
    let py = Command::new("python3").args(["-c", check, dir.join("traj.h5").to_str().unwrap()]).output().expect("python3 runs");
    assert!(
        py.status.success(),
        "h5py check failed (scripts/test.sh installs h5py from scripts/requirements.txt):\n{}",
        String::from_utf8_lossy(&py.stderr)
    );
}

#[test]
fn a_run_killed_during_output_leaves_frames_and_checkpoints_that_load() {
    let dir = tempdir("kill");
    let script = std::fs::read_to_string(common::example("vdw-equilibrium")).unwrap().replace(
        "run          ${steps}",
        "dump traj all h5md 1 traj.h5 x p u theta n\ncheckpoint 20 ck.*.h5\nrun ${steps}",
    );
    std::fs::write(dir.join("in.test"), script).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_gendpde"))
        .args(["run", "in.test", "-log", "none", "-var", "n", "11", "-var", "rc", "3.0", "-var", "steps", "100000"])
        .current_dir(&dir)
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // wait until two checkpoints exist, then kill -9 in the middle of the output stream
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    while !dir.join("ck.40.h5").exists() && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(137));
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let summary = gendpde_io::check_h5md(&dir.join("traj.h5")).unwrap_or_else(|e| panic!("killed file unreadable: {}", e.0));
    assert!(summary.frames >= 41, "frames up to step 40 at least, got {}", summary.frames);
    let newest = (1..).map(|k| 20 * k).take_while(|s| dir.join(format!("ck.{s}.h5")).exists()).last().unwrap();
    std::fs::write(dir.join("in.load"), format!("read_restart ck.{newest}.h5\nrun 2\n")).unwrap();
    let out = gendpde(&["run", "in.load", "-log", "none"], &dir);
    assert!(out.status.success(), "the last checkpoint ck.{newest}.h5 does not load: {}", String::from_utf8_lossy(&out.stderr));
}

/// The bytes of the checkpoint a reduced vdW run writes at step 50 in `dir`.
fn checkpoint_at_50(dir: &Path) -> Vec<u8> {
    straight_script(dir);
    let mut args = vec!["run", "in.straight", "-log", "none"];
    args.extend(VARS);
    args.push("50");
    assert!(gendpde(&args, dir).status.success());
    std::fs::read(dir.join("ck.50.h5")).unwrap()
}

#[test]
fn damaged_restart_and_data_files_give_clear_errors() {
    let dir = tempdir("damaged");
    let good = checkpoint_at_50(&dir);
    for (k, cut) in [0, 100, good.len() / 3, good.len() - 100].iter().enumerate() {
        std::fs::write(dir.join(format!("bad{k}.h5")), &good[..*cut]).unwrap();
        std::fs::write(dir.join("in.bad"), format!("read_restart bad{k}.h5\nrun 1\n")).unwrap();
        let out = gendpde(&["run", "in.bad", "-log", "none"], &dir);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "truncated restart at {cut} bytes accepted");
        assert!(err.contains("in.bad:1: read_restart:") && err.contains(&format!("bad{k}.h5")), "{err}");
        assert!(!err.contains("internal error") && !err.contains("HDF5-DIAG"), "{err}");
    }
    std::fs::write(dir.join("data.bad"), "title\n\n3 atoms\n1 atom types\n0 5 xlo xhi\n0 5 ylo yhi\n0 5 zlo zhi\n\nAtoms # dpd\n\n1 1 1.5 0 0 0\n2 1 1.5 1 1\n3 1 1.5 2 2 2\n").unwrap();
    std::fs::write(dir.join("in.data"), "atom_style dpd\nread_data data.bad\n").unwrap();
    let out = gendpde(&["run", "in.data", "-log", "none"], &dir);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("data.bad:12: Atoms: expected 6 columns"), "{err}");
}

#[test]
fn a_full_disk_during_output_stops_cleanly_with_earlier_frames_intact() {
    let dir = tempdir("full");
    let script = std::fs::read_to_string(common::example("heat-only"))
        .unwrap()
        .replace("run          ${steps}", "dump traj all h5md 1 traj.h5 x p u theta\nrun ${steps}");
    std::fs::write(dir.join("in.test"), script).unwrap();
    // a file-size limit of 600 KiB stands for the full disk (SIGXFSZ ignored: writes fail)
    let cmd = format!("trap '' XFSZ; ulimit -f 600; exec {} run in.test -log none -var steps 100", env!("CARGO_BIN_EXE_gendpde"));
    let out = Command::new("bash").args(["-c", &cmd]).current_dir(&dir).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "the run must stop when the disk is full");
    assert!(err.contains("in.test:32: run: dump traj: traj.h5") && err.contains("File too large"), "{err}");
    assert!(!err.contains("internal error"), "{err}");
    // the file's recorded end lies past the bytes the disk took: once there is space
    // again, repair_h5md (or `h5clear -s -i`) makes it whole, with every earlier frame
    let path = dir.join("traj.h5");
    gendpde_io::h5md::repair_h5md(&path).unwrap_or_else(|e| panic!("repair failed: {}", e.0));
    let summary = gendpde_io::check_h5md(&path).unwrap_or_else(|e| panic!("earlier frames lost: {}", e.0));
    assert!(summary.frames >= 3, "frames before the disk filled: {}", summary.frames);
}

/// Single-bit flips anywhere in a checkpoint written by a run: `read_restart` either
/// refuses the file with a message naming it, or continues exactly as from the intact
/// file; it never panics and never runs on silently changed data.
#[test]
fn flipped_bits_in_a_restart_are_refused_or_harmless() {
    use proptest::prelude::*;
    let dir = tempdir("flips");
    let good = checkpoint_at_50(&dir);
    std::fs::write(dir.join("in.flip"), "read_restart flip.h5\nthermo_modify format float %.17g\nrun 2\n").unwrap();
    std::fs::write(dir.join("flip.h5"), &good).unwrap();
    let reference = gendpde(&["run", "in.flip", "-log", "none"], &dir);
    assert!(reference.status.success());
    let rows = |o: &Output| String::from_utf8_lossy(&o.stdout).lines().filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit())).map(String::from).collect::<Vec<_>>();
    let (refused, harmless) = (std::cell::Cell::new(0), std::cell::Cell::new(0));
    let config = ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() };
    proptest!(config, |(at in 0..good.len(), bit in 0u8..8)| {
        let mut bytes = good.clone();
        bytes[at] ^= 1 << bit;
        std::fs::write(dir.join("flip.h5"), &bytes).unwrap();
        let out = gendpde(&["run", "in.flip", "-log", "none"], &dir);
        let err = String::from_utf8_lossy(&out.stderr);
        prop_assert!(out.status.code() == Some(0) || out.status.code() == Some(1), "byte {at} bit {bit}: exit {:?}: {err}", out.status);
        if out.status.success() {
            prop_assert_eq!(rows(&out), rows(&reference), "byte {} bit {}: accepted with changed results", at, bit);
            harmless.set(harmless.get() + 1);
        } else {
            prop_assert!(err.contains("in.flip:1: read_restart:") && err.contains("flip.h5"), "byte {at} bit {bit}: {err}");
            prop_assert!(!err.contains("panicked") && !err.contains("HDF5-DIAG"), "byte {at} bit {bit}: {err}");
            refused.set(refused.get() + 1);
        }
    });
    eprintln!("{} flips refused, {} harmless", refused.get(), harmless.get());
}

/// A restart file of an earlier gendpde (tests/data/restart-before-octant.h5: 64 particles
/// of examples/dpde-classic at n = 4, written at step 10 by the build before the octant
/// column of the list order, 94556ca) is read: the run after it warns that it sets up
/// afresh, and its set-up row (step, temp, tint, pe, ke, etotal: functions of the stored
/// positions, momenta and energies) is the one that build prints when it continues from
/// the file (keeping its stored forces).
#[test]
fn a_restart_of_the_build_before_the_octant_column_loads_and_sets_up_afresh() {
    let dir = tempdir("restart-before-octant");
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/restart-before-octant.h5");
    std::fs::copy(&data, dir.join("old.h5")).unwrap();
    std::fs::write(dir.join("in.continue"), "read_restart old.h5\nthermo_modify format float %.17g\nrun 5\n").unwrap();
    let out = gendpde(&["run", "in.continue", "-log", "none"], &dir);
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("written before the particle columns [\"octant\"]"), "no warning: {stderr}");
    let rows: Vec<&str> = stdout.lines().filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit())).collect();
    // printed by 94556ca continuing from the file (the columns before press)
    let written = "10  1.5060666312367323 1.4991042239814514 14.991042239814515 2.2238015101854876 17.214843750000004";
    assert!(rows.first().is_some_and(|r| r.trim_start().starts_with(written)), "set-up row {:?}", rows.first());
    assert_eq!(rows.len(), 2, "rows at steps 10 and 15");
}
