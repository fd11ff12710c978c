//! `pair_style multi/lucy` (DPD-REACT) against the reference LAMMPS (22 Jul 2025), on
//! scripts/lammps/in.multi-lucy-parity run unchanged by both codes: two types, a table per
//! type pair (RSQ spacing used as given, R spacing splined with its own cutoff, FP end
//! slopes with a positive inner density), lookup and linear, 20 steps of fix nve.
//! Per-particle forces at step 0 agree to 1e-12 of the largest, every thermo row (temp,
//! press and its diagonal, pe, ke, etotal) to 1e-11 relative, the positions after 20
//! steps to 1e-10 of the box. And the errors of bad input.

use crate::common;

use common::lammps::{compare_with_lammps, run_gendpde, scripts_dir};

const TABLE: [&str; 1] = ["multi-lucy.table"];

/// The line of `pair_style` in in.multi-lucy-parity.
const PAIR_LINE: usize = 21;

#[test]
fn multi_lucy_linear_forces_and_energies_match_lammps() {
    compare_with_lammps("multi-lucy-linear", "in.multi-lucy-parity", "multi-lucy.dump", &[("tstyle", "linear")], &TABLE);
}

#[test]
fn multi_lucy_lookup_forces_and_energies_match_lammps() {
    compare_with_lammps("multi-lucy-lookup", "in.multi-lucy-parity", "multi-lucy.dump", &[("tstyle", "lookup")], &TABLE);
}

/// Runs 2 steps of the parity scene with its pair lines replaced by `pair`, next to two
/// more tables of narrow density ranges: low.table (ML_LOW, rho in [0, 0.0025]) and
/// high.table (ML_HIGH, rho in [0.01, 0.02]). Returns stderr and whether gendpde succeeded.
fn run_with(name: &str, pair: &str) -> (String, bool) {
    let d = common::tempdir(name);
    common::lammps::stage_inputs(&d, "in.multi-lucy-parity");
    std::fs::copy(scripts_dir().join(TABLE[0]), d.join(TABLE[0])).unwrap();
    let section = |key: &str, lo: f64, hi: f64| {
        let mut s = format!("{key}\nN 10 R {lo} {hi}\n\n");
        for i in 0..10 {
            s += &format!("{} {} 0.0 0.01\n", i + 1, lo + (hi - lo) * i as f64 / 9.0);
        }
        s
    };
    std::fs::write(d.join("low.table"), section("ML_LOW", 0.0, 0.0025)).unwrap();
    std::fs::write(d.join("high.table"), section("ML_HIGH", 0.01, 0.02)).unwrap();
    let text = std::fs::read_to_string(d.join("in.multi-lucy-parity")).unwrap();
    let (start, end) = (text.find("\npair_style").unwrap() + 1, text.find("\nneighbor").unwrap());
    assert_eq!(text[..start].lines().count() + 1, PAIR_LINE, "the pair_style line of in.multi-lucy-parity");
    std::fs::write(d.join("in.test"), format!("{}{pair}{}", &text[..start], &text[end..])).unwrap();
    let out = run_gendpde(&d, "in.test", &[("steps", "2")]);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{name}: {err}");
    (err, out.status.success())
}

#[test]
fn bad_styles_tables_and_densities_are_refused_naming_the_line() {
    let cases = [
        ("spline", "pair_style multi/lucy spline 400\n", "in.test:21: pair_style: unknown table style 'spline': pair multi/lucy has lookup and linear"),
        ("extra", "pair_style multi/lucy linear 400 5.0\n", "in.test:21: pair_style"),
        ("n", "pair_style multi/lucy linear 1\n", "illegal number of pair table entries: 1"),
        ("keyword", "pair_style multi/lucy linear 400\npair_coeff * * multi-lucy.table NOPE\n", "in.test:22: pair_coeff: multi-lucy.table: did not find keyword NOPE"),
        ("unset", "pair_style multi/lucy linear 400\npair_coeff 1 1 multi-lucy.table ML_R 12.0\n", "all pair coeffs are not set: types 1 2 have no table"),
        ("shardlow", "pair_style multi/lucy linear 400\npair_coeff * * multi-lucy.table ML_R 12.0\nfix 2 all shardlow\n", "fix 2 does not work with pair multi/lucy"),
        // the densities of the scene (about 0.0046) lie above rho_hi = 0.0025 of ML_LOW...
        (
            "outer",
            "pair_style multi/lucy linear 400\npair_coeff * * multi-lucy.table ML_R 12.0\npair_coeff 2 2 low.table ML_LOW 12.0\n",
            "> table outer bound 0.0025",
        ),
        // ...and below rho_lo = 0.01 of ML_HIGH
        ("inner", "pair_style multi/lucy lookup 400\npair_coeff * * high.table ML_HIGH 12.0\n", "< table inner bound 0.01"),
    ];
    for (name, pair, expected) in cases {
        let (err, ok) = run_with(name, pair);
        assert!(!ok, "{name}: the script should fail");
        assert!(err.contains(expected), "{name}: expected '{expected}' in:\n{err}");
    }
    let (err, ok) = run_with("ok", "pair_style multi/lucy linear 400\npair_coeff * * multi-lucy.table ML_R 12.0\n");
    assert!(ok, "the same scene with one table runs: {err}");
}
