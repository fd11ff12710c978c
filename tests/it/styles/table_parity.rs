//! `pair_style table` and `hybrid/overlay` against the reference LAMMPS (22 Jul 2025), on
//! inputs of scripts/lammps/ run unchanged by both codes:
//! - in.table-lj: two types, a table per type pair (RSQ spacing used as given, R spacing
//!   with an explicit cutoff, r from the file with FPRIME), lookup, linear and spline;
//! - in.table-water: hybrid/overlay of LAMMPS's coarse-grained water table and pair dpd
//!   with gamma = 0 (deterministic), real units.
//!
//! Per-particle forces at step 0 agree to round-off (1e-12 of the largest force), every
//! thermo row (temp, press, pe, ke, etotal and the sum, sum of squares, min and max of
//! compute pe/atom, so the per-particle energies) to 1e-11 relative, and the positions
//! after 20-50 steps of fix nve to 1e-10 of the box. The errors name the line.

use crate::common;

use common::lammps::{compare_with_lammps, run_gendpde, scripts_dir};
use std::path::PathBuf;

/// The potential files the inputs read.
const POTENTIALS: [&str; 2] = ["table-lj.pot", "cg_spce_table.pot"];

fn dir(name: &str) -> PathBuf {
    let d = common::tempdir(name);
    for pot in POTENTIALS {
        std::fs::copy(scripts_dir().join(pot), d.join(pot)).unwrap();
    }
    d
}


#[test]
fn table_linear_forces_and_energies_match_lammps() {
    compare_with_lammps("table-linear", "in.table-lj", "table-lj.dump", &[("tstyle", "linear")], &POTENTIALS);
}

#[test]
fn table_lookup_forces_and_energies_match_lammps() {
    compare_with_lammps("table-lookup", "in.table-lj", "table-lj.dump", &[("tstyle", "lookup")], &POTENTIALS);
}

#[test]
fn table_spline_forces_and_energies_match_lammps() {
    compare_with_lammps("table-spline", "in.table-lj", "table-lj.dump", &[("tstyle", "spline")], &POTENTIALS);
}

#[test]
fn hybrid_overlay_of_table_and_dpd_matches_lammps() {
    compare_with_lammps("table-water", "in.table-water", "table-water.dump", &[], &POTENTIALS);
}

/// A directory with a two-particle scene at distance `r` (types 1 and 1): data.pair and
/// in.test with the lines `rest` after read_data.
fn pair_scene(name: &str, r: f64, rest: &str) -> PathBuf {
    let d = dir(name);
    let data = format!(
        "two particles\n\n2 atoms\n2 atom types\n\n0 12 xlo xhi\n0 12 ylo yhi\n0 12 zlo zhi\n\nAtoms # atomic\n\n\
         1 1 5 5 5\n2 1 {} 5 5\n",
        5.0 + r
    );
    std::fs::write(d.join("data.pair"), data).unwrap();
    let script = format!("units lj\natom_style atomic\nread_data data.pair\nmass * 1.0\n{rest}neighbor 0.3 bin\nfix 1 all nve\nrun 1\n");
    std::fs::write(d.join("in.test"), script).unwrap();
    d
}

fn expect_error(name: &str, rest: &str, expected: &str) {
    let d = pair_scene(name, 1.0, rest);
    let out = run_gendpde(&d, "in.test", &[]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{name}: the script should fail");
    assert!(err.contains(expected), "{name}: expected '{expected}' in:\n{err}");
    assert!(!err.contains("panicked"), "{name}: {err}");
}

#[test]
fn a_pair_inside_the_inner_cutoff_stops_the_run_naming_both_particles() {
    let coeff = "pair_style table linear 400\npair_coeff * * table-lj.pot LJ_R\n";
    let out = run_gendpde(&pair_scene("inner", 0.7, coeff), "in.test", &[]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("pair distance 7.000000000e-1 to particle 2 < table inner cutoff 0.8 (types 1 1)"), "{err}");
    assert!(err.contains("particle 1 "), "{err}");
    // the same pair at 0.9 runs
    let out = run_gendpde(&pair_scene("inner-ok", 0.9, coeff), "in.test", &[]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn bad_tables_and_styles_are_refused_naming_the_line() {
    let with = |coeff: &str| coeff.to_string();
    let cases: &[(&str, String, &str)] = &[
        ("bitmap", with("pair_style table bitmap 12\n"), "in.test:5: pair_style: table style bitmap is not supported: use lookup, linear or spline"),
        ("n", with("pair_style table linear 1\n"), "illegal number of pair table entries: 1 (2 to 16777216)"),
        ("keyword", with("pair_style table linear 100\npair_coeff * * table-lj.pot NOPE\n"), "in.test:6: pair_coeff: table-lj.pot: did not find keyword NOPE"),
        ("file", with("pair_style table linear 100\npair_coeff * * missing.pot LJ_R\n"), "cannot open table file missing.pot"),
        ("cut", with("pair_style table linear 100\npair_coeff * * table-lj.pot LJ_R 3.0\n"), "pair table cutoff 3 is outside of the table (0.8, 2.5]"),
        ("unset", with("pair_style table linear 100\npair_coeff 1 1 table-lj.pot LJ_R\n"), "all pair coeffs are not set: types 1 2 have no table"),
        ("hybrid", with("pair_style hybrid table linear 100 dpd 1.0 1.0 5\n"), "pair_style hybrid (one sub-style per type pair) is not supported: use hybrid/overlay"),
        (
            "gendpde",
            with("pair_style hybrid/overlay table linear 100 gendpde 1.0 5\n"),
            "pair gendpde is many-body (densities and EOS): it cannot be combined in hybrid/overlay",
        ),
        ("mdpd", with("pair_style hybrid/overlay table linear 100 mdpd 1.0 1.0 5\n"), "many-body DPD combines only as"),
        (
            "substyle",
            with("pair_style hybrid/overlay table linear 100 dpd 1.0 1.0 5\npair_coeff * * dpd/fdt 1.0 1.0\n"),
            "'dpd/fdt' is not a sub-style of this pair_style hybrid/overlay",
        ),
        ("shardlow", with("pair_style table linear 100\npair_coeff * * table-lj.pot LJ_R\nfix 2 all shardlow\n"), "fix 2 does not work with pair table: shardlow is not one of its fixes (nve; overlay dpd/fdt for fix shardlow)"),
    ];
    for (name, script, expected) in cases {
        expect_error(name, script, expected);
    }
    // a damaged section names the file and its line
    let d = pair_scene("damaged", 1.0, "pair_style table linear 100\npair_coeff * * bad.pot LJ_RSQ\n");
    let text = std::fs::read_to_string(scripts_dir().join("table-lj.pot")).unwrap().replacen("\n3 ", "\n3 x", 1);
    std::fs::write(d.join("bad.pot"), text).unwrap();
    let err = String::from_utf8_lossy(&run_gendpde(&d, "in.test", &[]).stderr).into_owned();
    assert!(err.contains("in.test:6: pair_coeff: bad.pot:9: expected 'index r e f', got '3 x"), "{err}");
}
