//! Rank-independent trajectories (built with `--features mpi`, run under mpirun):
//! the same script on 1, 2, 3, 4 and 8 ranks must give bit-identical particles and
//! identical thermo lines, and no particle may be lost or duplicated.
#![cfg(feature = "mpi")]

use crate::common;

use common::ranks::{mpirun, tempdir, thermo_rows};

/// Runs `example` with `vars` on each rank count and compares the dumps and thermo.
fn compare_rank_counts(example: &str, vars: &[(&str, &str)]) {
    let dir = tempdir(example);
    let script = std::fs::read_to_string(common::example(example)).unwrap()
        + "write_dump all custom final.dump id type x y z ix iy iz px py pz u theta\n";
    std::fs::write(dir.join("in.test"), script).unwrap();
    let mut args: Vec<String> = ["run", "in.test", "-log", "none"].map(String::from).to_vec();
    for (k, v) in vars {
        args.extend(["-var".to_string(), k.to_string(), v.to_string()]);
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let mut reference: Option<(Vec<String>, String)> = None;
    for np in [1, 2, 3, 4, 8] {
        let out = mpirun(np, &dir, &args);
        assert!(out.status.success(), "{example} on {np} ranks failed:\n{}", String::from_utf8_lossy(&out.stderr));
        let dump = std::fs::read_to_string(dir.join("final.dump")).unwrap();
        let rows = thermo_rows(&out.stdout);
        assert!(rows.len() >= 2, "no thermo output");
        match &reference {
            None => reference = Some((rows, dump)),
            Some((r, d)) => {
                assert_eq!(&rows, r, "{example}: thermo on {np} ranks differs from 1 rank");
                assert!(dump == *d, "{example}: final particles on {np} ranks differ from 1 rank");
            }
        }
        eprintln!("{example}: {np} ranks identical to 1 rank");
    }
}

#[test]
fn vdw_scene_is_bit_identical_on_1_2_3_4_8_ranks() {
    compare_rank_counts("vdw-equilibrium", &[("n", "11"), ("rc", "3.0"), ("steps", "200")]);
}

#[test]
fn classic_dpde_scene_is_bit_identical_on_1_2_3_4_8_ranks() {
    compare_rank_counts("dpde-classic", &[("steps", "200")]);
}

#[test]
fn hot_particles_crossing_ranks_are_never_lost_or_duplicated() {
    let dir = tempdir("hot");
    let script = std::fs::read_to_string(common::example("vdw-equilibrium"))
        .unwrap()
        .replace("thermo       100", "thermo       1")
        .replace("thermo_style custom step time temp tint press pe ke etotal edrift", "thermo_style custom step atoms pxtot pytot pztot temp")
        + "write_dump all custom final.dump id x y z\n";
    std::fs::write(dir.join("in.test"), script).unwrap();
    let out = mpirun(4, &dir, &["run", "in.test", "-log", "none", "-var", "n", "11", "-var", "rc", "3.0", "-var", "T", "10.0", "-var", "steps", "2000"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let rows = thermo_rows(&out.stdout);
    assert_eq!(rows.len(), 2001, "a thermo line every step");
    let mut worst: f64 = 0.0;
    for row in &rows {
        let v: Vec<f64> = row.split_whitespace().map(|w| w.parse().unwrap()).collect();
        assert_eq!(v[1], 1331.0, "step {}: {} particles", v[0], v[1]);
        worst = worst.max(v[2].abs()).max(v[3].abs()).max(v[4].abs());
    }
    // |p| ~ sqrt(T) = 3.2 per particle: the total stays at round-off
    eprintln!("largest total momentum component over 2000 steps: {worst:e}");
    assert!(worst < 1e-9, "total momentum drifted to {worst:e}");
    let dump = std::fs::read_to_string(dir.join("final.dump")).unwrap();
    let ids: Vec<u64> = dump.lines().skip(9).map(|l| l.split(' ').next().unwrap().parse().unwrap()).collect();
    assert_eq!(ids, (1..=1331).collect::<Vec<u64>>(), "every particle exactly once");
    // the particles did travel: unwrapped displacements of several box lengths
}

#[test]
fn too_many_ranks_for_the_box_is_refused_before_any_step() {
    let dir = tempdir("small");
    std::fs::copy(common::example("vdw-equilibrium"), dir.join("in.test")).unwrap();
    let out = mpirun(8, &dir, &["run", "in.test", "-log", "none", "-var", "n", "11", "-var", "rc", "3.0", "-var", "steps", "10"]);
    assert!(out.status.success(), "8 ranks on 4x4x4 cells fit (2x2x2)");
    std::fs::write(dir.join("in.procs"), std::fs::read_to_string(dir.join("in.test")).unwrap().replace("create_box", "processors 8 1 1\ncreate_box")).unwrap();
    let out = mpirun(8, &dir, &["run", "in.procs", "-log", "none", "-var", "n", "11", "-var", "rc", "3.0", "-var", "steps", "10"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("8 ranks along x need at least 8 cells") && err.contains("use at most 4 ranks along x"), "{err}");
}

#[test]
fn restart_on_two_ranks_continues_bit_identically() {
    let dir = tempdir("restart");
    let script = std::fs::read_to_string(common::example("vdw-equilibrium")).unwrap().replace(
        "run          ${steps}",
        "checkpoint 50 ck.*.h5\nrun ${steps}\nwrite_dump all custom straight.dump id x y z px py pz u theta",
    );
    std::fs::write(dir.join("in.straight"), script).unwrap();
    std::fs::write(dir.join("in.continue"), "read_restart ck.50.h5\nrun 50\nwrite_dump all custom continued.dump id x y z px py pz u theta\n").unwrap();
    let vars = ["-var", "n", "11", "-var", "rc", "3.0", "-var", "steps", "100"];
    let mut args = vec!["run", "in.straight", "-log", "none"];
    args.extend(vars);
    let out = mpirun(2, &dir, &args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = mpirun(2, &dir, &["run", "in.continue", "-log", "none"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (a, b) = (std::fs::read(dir.join("straight.dump")).unwrap(), std::fs::read(dir.join("continued.dump")).unwrap());
    assert!(a == b, "2-rank continuation differs from the straight 2-rank run");
}
