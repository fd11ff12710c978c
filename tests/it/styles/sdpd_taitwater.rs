//! Isothermal Tait-water SDPD (LAMMPS DPD-SMOOTH: atom_style sph, pair
//! sdpd/taitwater/isothermal, fix sph) against the reference LAMMPS, on
//! scripts/lammps/in.sdpd-taitwater (512 particles of two types, per-pair kernels):
//! 1. with the noise below round-off (T = 1e-300 K), per-particle positions, velocities,
//!    forces, densities and density rates over 5 steps and the thermo temperature and
//!    pressure, to round-off;
//! 2. at T = 300 K over several seeds, the mean kinetic temperature and pressure, within
//!    their standard errors;
//! 3. bad input is refused naming the line.
//! Rank independence: tests/it/guarantees/guarantees.rs; restarts: tests/it/guarantees/restart_roundtrip.rs.

use crate::common;

use common::lammps::{expect_success, parse_dump, parse_thermo_blocks, run_lammps, stage_inputs, DumpSnapshot};
use std::path::{Path, PathBuf};
use std::process::Command;

const SCRIPT: &str = "in.sdpd-taitwater";

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gendpde-taitwater-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The script as LAMMPS runs it: its dump custom reads rho and drho through compute
/// property/atom.
fn lammps_variant(d: &Path) -> &'static str {
    let text = std::fs::read_to_string(d.join(SCRIPT)).unwrap();
    let text = text
        .replace("fx fy fz rho drho", "fx fy fz c_p[1] c_p[2]")
        .replace("\ndump ", "\ncompute p all property/atom rho drho\ndump ");
    assert!(text.contains("c_p[2]") && text.contains("property/atom"), "the dump line of {SCRIPT} changed");
    std::fs::write(d.join("in.lammps"), text).unwrap();
    "in.lammps"
}

fn gendpde(d: &Path, vars: &[(&str, &str)]) -> String {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_gendpde"));
    cmd.current_dir(d).args(["-in", SCRIPT, "-log", "none"]);
    for (k, v) in vars {
        cmd.args(["-var", k, v]);
    }
    let out = cmd.output().expect("gendpde runs");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "gendpde failed:\n{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    stdout
}

/// Both codes' stdout and dump snapshots for `vars`.
fn both(name: &str, vars: &[(&str, &str)]) -> ((String, Vec<DumpSnapshot>), (String, Vec<DumpSnapshot>)) {
    let d = dir(name);
    stage_inputs(&d, SCRIPT);
    let input = lammps_variant(&d);
    let mut lv = vec![("out", "l.dump")];
    lv.extend_from_slice(vars);
    let l = expect_success("LAMMPS", &run_lammps(&d, input, &lv));
    let mut gv = vec![("out", "g.dump")];
    gv.extend_from_slice(vars);
    let g = gendpde(&d, &gv);
    let read = |f: &str| parse_dump(&std::fs::read_to_string(d.join(f)).unwrap());
    let out = ((l, read("l.dump")), (g, read("g.dump")));
    let _ = std::fs::remove_dir_all(&d);
    out
}

/// The rows of the last thermo block (after the script's `run 0`).
fn last_block(stdout: &str) -> common::lammps::ThermoBlock {
    parse_thermo_blocks(stdout, "Step").pop().expect("a thermo block")
}

#[test]
fn forces_densities_and_trajectory_match_lammps_without_the_noise() {
    let ((lout, lsnaps), (gout, gsnaps)) = both("deterministic", &[("T", "1e-300"), ("steps", "5")]);
    assert_eq!(lsnaps.len(), 6, "steps 0-5 dumped");
    assert_eq!(gsnaps.len(), lsnaps.len());
    let lammps_names = ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "c_p[1]", "c_p[2]"];
    let ours = ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "rho", "drho"];
    for (l, g) in lsnaps.iter().zip(&gsnaps) {
        assert_eq!(l.timestep, g.timestep);
        let mut line = Vec::new();
        for (ln, gn) in lammps_names.iter().zip(ours) {
            let (kl, kg) = (l.column_index(ln).unwrap(), g.column_index(gn).unwrap());
            let (mut diff, mut max) = (0.0f64, 0.0f64);
            for ((il, vl), (ig, vg)) in l.atoms.iter().zip(&g.atoms) {
                assert_eq!(il, ig);
                diff = diff.max((vl[kl] - vg[kg]).abs());
                max = max.max(vl[kl].abs());
            }
            line.push(format!("{gn} {:.1e}", diff / max));
            assert!(max > 0.0, "step {}: {gn} is zero everywhere", l.timestep);
            assert!(diff <= 1e-13 * max, "step {}: {gn} differs by {diff:e} of max {max:e}", l.timestep);
        }
        eprintln!("step {}: max |d|/max |value|: {}", l.timestep, line.join(", "));
    }
    let (lt, gt) = (last_block(&lout), last_block(&gout));
    for col in ["Temp", "Press"] {
        for (a, b) in lt.column(col).iter().zip(gt.column(col)) {
            assert!((a - b).abs() <= 1e-12 * a.abs(), "thermo {col}: LAMMPS {a}, gendpde {b}");
        }
    }
}

/// Mean and standard error over seeds of the per-run means of `col` after `skip` rows.
fn seed_mean(runs: &[common::lammps::ThermoBlock], col: &str, skip: usize) -> (f64, f64) {
    let means: Vec<f64> = runs.iter().map(|b| {
        let v = b.column(col);
        v[skip..].iter().sum::<f64>() / (v.len() - skip) as f64
    }).collect();
    let n = means.len() as f64;
    let mean = means.iter().sum::<f64>() / n;
    let var = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

#[test]
fn temperature_and_pressure_match_lammps_within_the_noise() {
    const SEEDS: [&str; 4] = ["11", "22", "33", "44"];
    let (mut l, mut g) = (Vec::new(), Vec::new());
    for seed in SEEDS {
        let ((lout, _), (gout, _)) = both(&format!("noise-{seed}"), &[("T", "300.0"), ("seed", seed), ("steps", "300"), ("every", "10")]);
        l.push(last_block(&lout));
        g.push(last_block(&gout));
    }
    // the kinetic temperature relaxes from 192 K within a few steps: rows from step 50
    for col in ["Temp", "Press"] {
        let (a, b) = (seed_mean(&l, col, 5), seed_mean(&g, col, 5));
        let z = (a.0 - b.0) / (a.1 * a.1 + b.1 * b.1).sqrt();
        eprintln!("{col}: LAMMPS {:.5e} +- {:.1e}, gendpde {:.5e} +- {:.1e} ({z:+.2} sigma)", a.0, a.1, b.0, b.1);
        assert!(z.abs() < 4.0, "{col}: LAMMPS {a:?}, gendpde {b:?}");
        assert!(a.1 > 0.0 && b.1 > 0.0, "{col}: no spread between seeds");
    }
    // equipartition (LAMMPS's equipartition-verification example): T_kin near T
    let t = seed_mean(&g, "Temp", 5);
    assert!((t.0 - 300.0).abs() < 0.1 * 300.0, "T_kin {t:?} far from 300 K");
}

#[test]
fn bad_taitwater_input_is_refused_naming_the_line() {
    let head = "units micro\natom_style sph\nregion b block 0 0.8 0 0.8 0 0.8\ncreate_box 2 b\ncreate_atoms 1 random 100 7 NULL\nmass * 0.001\n";
    let pair = "pair_style sdpd/taitwater/isothermal 300 1.0 5\npair_coeff * * 1.0 10.0 0.25";
    let (with_sph, no_fix, with_nve) = (format!("{pair}\nfix 1 all sph\nrun 0"), format!("{pair}\nrun 0"), format!("{pair}\nfix 1 all sph\nfix 2 all nve\nrun 0"));
    let cases = [
        ("pair_style sdpd/taitwater/isothermal 0 1.0", "pair_style: Temperature must be positive"),
        ("pair_style sdpd/taitwater/isothermal 300 -1.0", "pair_style: Viscosity must be positive"),
        ("pair_style sdpd/taitwater/isothermal 300 1.0 5\npair_coeff * * 1.0 10.0", "pair_coeff: missing argument"),
        ("pair_style sdpd/taitwater/isothermal 300 1.0 5\npair_coeff 2 1 1.0 10.0 0.2", "pair_coeff: Incorrect args for pair coefficients"),
        (no_fix.as_str(), "run: pair sdpd/taitwater/isothermal needs fix sph"),
        (with_sph.as_str(), "run: particle 1 at step 0: SPH density 0 is not positive (set sph/rho)"),
        (
            "pair_style sdpd/taitwater/isothermal 300 1.0 5\npair_coeff 1 1 1.0 10.0 0.25\nfix 1 all sph\nrun 0",
            "run: Not all pair sdpd/taitwater/isothermal coeffs are set: no pair_coeff for types 1 2",
        ),
        (with_nve.as_str(), "run: fix 2 does not work with pair sdpd/taitwater/isothermal"),
        ("pair_style dpd 1.0 1.0 5\npair_coeff * * 25 4.5\nfix 1 all sph\nrun 0", "run: fix 1 does not work with pair dpd: sph is not one of its fixes"),
    ];
    let d = dir("errors");
    let stage = |script: &str| {
        std::fs::write(d.join("in.x"), script).unwrap();
        d.clone()
    };
    common::expect_errors(head, &cases, stage);
    let atomic = "units micro\natom_style atomic\nregion b block 0 1 0 1 0 1\ncreate_box 1 b\ncreate_atoms 1 random 10 7 NULL\n";
    common::expect_errors(atomic, &[("set atom * sph/rho 1.0", "set: set sph/rho needs atom_style sph")], stage);
}

/// The id -> (type, rho, x) rows of the `Atoms # sph` section of a data file.
fn sph_atoms(text: &str) -> Vec<(u64, Vec<f64>)> {
    let atoms = text.split("Atoms # sph").nth(1).expect("an Atoms # sph section").split("Velocities").next().unwrap();
    let mut rows: Vec<(u64, Vec<f64>)> = atoms
        .lines()
        .filter_map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (w.len() >= 8).then(|| (w[0].parse().unwrap(), [1, 2, 5].iter().map(|&k| w[k].parse().unwrap()).collect()))
        })
        .collect();
    rows.sort_by_key(|r| r.0);
    rows
}

#[test]
fn sph_data_files_round_trip_the_density() {
    let d = dir("data");
    stage_inputs(&d, SCRIPT);
    std::fs::write(d.join("in.x"), "units micro\natom_style sph\nread_data data.sdpd-taitwater\nwrite_data back.data\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(&d).args(["-in", "in.x", "-log", "none"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let read = |f: &str| sph_atoms(&std::fs::read_to_string(d.join(f)).unwrap());
    let (original, back) = (read("data.sdpd-taitwater"), read("back.data"));
    assert_eq!(original.len(), 512);
    assert_eq!(original, back, "types, densities or positions changed through read_data and write_data");
    let _ = std::fs::remove_dir_all(&d);
}
