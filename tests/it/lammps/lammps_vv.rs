//! Velocity-Verlet DPD and DPDE against the reference LAMMPS (22 Jul 2025): `pair
//! dpd/fdt` + `fix nve` and `pair dpd/fdt/energy` + `fix dpd/energy` + `fix nve` without
//! `fix shardlow` (friction, noise and the energy rates in the pair pass). The inputs
//! (scripts/lammps/) run unchanged in both codes.
//! 1. deterministic (sigma = kappa = 0): per-particle positions and momenta after 100
//!    steps, and the thermo rows (uCond and uMech sums, mean theta) at every output;
//! 2. statistical: Temp, Press, uMech and theta averages over three seeds agree within 3
//!    combined standard errors, and so do the drift rates of pe + ke + uCond + uMech;
//! 3. LAMMPS's dpd-vv and dpde-vv examples (metal units) run unchanged: the same step-0
//!    state, and energy conserved as well as LAMMPS conserves it.

use crate::common;

use common::lammps::{agree_within, block_average, compare_dumps, expect_success, parse_thermo_blocks, run_lammps, stage_inputs, ThermoBlock};
use std::path::PathBuf;
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gendpde-vv-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `input` with `vars` in both codes (each in its own directory); returns the
/// directories and the last thermo block of each.
fn both(name: &str, input: &str, vars: &[(&str, &str)]) -> ((PathBuf, ThermoBlock), (PathBuf, ThermoBlock)) {
    let (dl, dg) = (dir(&format!("{name}-lammps")), dir(&format!("{name}-gendpde")));
    stage_inputs(&dl, input);
    stage_inputs(&dg, input);
    let l = expect_success("LAMMPS", &run_lammps(&dl, input, vars));
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_gendpde"));
    cmd.current_dir(&dg).args(["run", input, "-log", "none"]);
    for (k, v) in vars {
        cmd.args(["-var", k, v]);
    }
    let out = cmd.output().expect("gendpde runs");
    assert!(out.status.success(), "gendpde failed on {input}:\n{}", String::from_utf8_lossy(&out.stderr));
    let last = |t: &str| parse_thermo_blocks(t, "Step").pop().expect("a thermo block");
    ((dl, last(&l)), (dg, last(&String::from_utf8_lossy(&out.stdout))))
}

fn value(b: &ThermoBlock, row: usize, c: &str) -> f64 {
    b.rows[row][b.column_index(c).unwrap_or_else(|| panic!("no column {c}"))]
}

#[test]
fn vv_dpde_without_noise_matches_lammps_per_particle() {
    let vars = [("sigma", "0.0"), ("kappa", "0.0"), ("equil", "0"), ("steps", "100")];
    let ((dl, l), (dg, g)) = both("det", "in.dpde-vv-lj", &vars);
    let (dr, dp) = compare_dumps(&dl.join("dpde-vv.dump"), &dg.join("dpde-vv.dump"));
    eprintln!("VV DPDE, sigma = kappa = 0, after 100 steps: max |dr|/L = {dr:.2e}, max |dp|/|p| = {dp:.2e}");
    assert!(dr < 1e-10 && dp < 1e-9, "per-particle state differs: |dr|/L {dr:e}, |dp|/|p| {dp:e}");
    assert_eq!(l.rows.len(), g.rows.len());
    for c in ["Temp", "Press", "PotEng", "KinEng", "c_dpdU[1]", "c_dpdU[2]", "c_dpdU[4]", "v_totEnergy"] {
        for k in 0..l.rows.len() {
            let (a, b) = (value(&l, k, c), value(&g, k, c));
            assert!((a - b).abs() <= 1e-9 * a.abs().max(1.0), "row {k} {c}: LAMMPS {a} vs gendpde {b}");
        }
    }
}

/// Mean and standard error of `column` over the concatenated runs (5 blocks per run).
fn average(runs: &[ThermoBlock], column: &str) -> (f64, f64) {
    let series: Vec<f64> = runs.iter().flat_map(|b| b.rows.iter().map(|r| r[b.column_index(column).unwrap()])).collect();
    block_average(&series, 5 * runs.len())
}

/// Drift rate of `column` per unit time: the slopes over 5 blocks of each run, averaged.
fn drift(runs: &[ThermoBlock], column: &str, dt: f64) -> (f64, f64) {
    let slopes: Vec<f64> = runs
        .iter()
        .flat_map(|b| {
            let k = b.column_index(column).unwrap();
            let len = b.rows.len() / 5;
            (0..5).map(move |i| {
                let (first, last) = (&b.rows[i * len], &b.rows[(i + 1) * len - 1]);
                (last[k] - first[k]) / ((last[0] - first[0]) * dt)
            })
        })
        .collect();
    block_average(&slopes, slopes.len())
}

#[test]
fn vv_dpde_statistics_agree_with_lammps_over_seeds() {
    let (mut l, mut g) = (Vec::new(), Vec::new());
    for seed in ["11", "12", "13"] {
        let vars = [("seed", seed), ("equil", "200"), ("steps", "1000")];
        let ((_, a), (_, b)) = both(&format!("stat-{seed}"), "in.dpde-vv-lj", &vars);
        l.push(a);
        g.push(b);
    }
    for c in ["Temp", "Press", "c_dpdU[2]", "c_dpdU[4]"] {
        let (a, b) = (average(&l, c), average(&g, c));
        eprintln!("VV DPDE {c}: LAMMPS {:.5} +- {:.5}, gendpde {:.5} +- {:.5}", a.0, a.1, b.0, b.1);
        assert!(agree_within(a, b, 3.0), "{c}: LAMMPS {a:?} vs gendpde {b:?}");
    }
    let (a, b) = (drift(&l, "v_totEnergy", 0.01), drift(&g, "v_totEnergy", 0.01));
    eprintln!("VV DPDE energy drift per unit time: LAMMPS {:.3e} +- {:.3e}, gendpde {:.3e} +- {:.3e}", a.0, a.1, b.0, b.1);
    assert!(agree_within(a, b, 3.0), "energy drift: LAMMPS {a:?} vs gendpde {b:?}");
}

#[test]
fn lammps_vv_examples_run_unchanged() {
    for (name, energy) in [("in.dpd-vv", None), ("in.dpde-vv", Some("v_totEnergy"))] {
        let ((_, l), (_, g)) = both(name, name, &[("steps", "200")]);
        // identical initial state: the same step-0 temperature and pair energy
        for c in ["Temp", "PotEng"] {
            let (a, b) = (value(&l, 0, c), value(&g, 0, c));
            assert!((a - b).abs() <= 1e-9 * a.abs(), "{name} step 0 {c}: LAMMPS {a} vs gendpde {b}");
        }
        let t = |b: &ThermoBlock| block_average(&b.rows.iter().map(|r| r[b.column_index("Temp").unwrap()]).collect::<Vec<_>>(), 4);
        eprintln!("{name}: <Temp> LAMMPS {:?}, gendpde {:?}", t(&l), t(&g));
        if let Some(c) = energy {
            let change = |b: &ThermoBlock| (value(b, b.rows.len() - 1, c) - value(b, 0, c)) / value(b, 0, c);
            let (a, b) = (change(&l), change(&g));
            eprintln!("{name}: relative change of pe + ke + u over 200 steps: LAMMPS {a:.2e}, gendpde {b:.2e}");
            // the examples' noise changes the energy by a random walk of about 1e-5
            assert!(a.abs() < 3e-5 && b.abs() < 3e-5, "{name}: energy changed by {b:e} (LAMMPS {a:e})");
        }
    }
}
