//! Per type-pair coefficients of LAMMPS's pairwise styles (issue 17, item 5): the
//! messages of pair_coeff with type ranges, of unset pairs (LAMMPS's "All pair coeffs are
//! not set"), and of pair coefficient sections in data files, each naming its line.
//! The numbers (forces, data file round trips) are checked against LAMMPS in
//! tests/it/lammps/lammps_parity.rs.

use crate::common;

use common::{gendpde, tempdir};

/// Runs `script` as in.x beside data.mix-dpd (and `data`, as data.x), expecting an
/// error containing `expected`.
fn expect_error(name: &str, script: &str, data: Option<&str>, expected: &str) {
    let dir = tempdir(name);
    std::fs::copy(common::lammps::scripts_dir().join("data.mix-dpd"), dir.join("data.mix-dpd")).unwrap();
    std::fs::write(dir.join("in.x"), script).unwrap();
    if let Some(d) = data {
        std::fs::write(dir.join("data.x"), d).unwrap();
    }
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{name}: the script should fail");
    assert!(stderr.contains(expected), "{name}: expected '{expected}' in:\n{stderr}");
    assert!(!stderr.contains("panicked"), "{name}: {stderr}");
}

const HEAD: &str = "units lj\natom_style atomic\ncomm_modify vel yes\nread_data data.mix-dpd\nmass * 1.0\n";

#[test]
fn pair_coeff_ranges_and_unset_pairs_are_clear_errors() {
    let dpd = "pair_style dpd 1.0 1.0 4928459\n";
    for (lines, expected) in [
        ("pair_coeff 2* 1 25.0 4.5\n", "in.x:7: pair_coeff: the types '2* 1' hold no pair I <= J"),
        ("pair_coeff 3 1 25.0 4.5\n", "in.x:7: pair_coeff: expected a particle type or range within 1..2, got '3'"),
        ("pair_coeff * * 25.0 4.5 1.0 9\n", "in.x:7: pair_coeff: unexpected argument '9'"),
        ("pair_coeff 1 1 25.0 4.5\nfix 1 all nve\nrun 0\n", "in.x:9: run: All pair coeffs are not set: no pair_coeff for types 1 2"),
        // 2 1 is the pair 1 2: the pair 2 2 is the one left
        ("pair_coeff 1 1 25.0 4.5\npair_coeff 2 1 25.0 4.5\nfix 1 all nve\nrun 0\n", "in.x:10: run: All pair coeffs are not set: no pair_coeff for types 2 2"),
    ] {
        expect_error("pair-coeff-ranges", &format!("{HEAD}{dpd}{lines}"), None, expected);
    }
    let mdpd = "pair_style hybrid/overlay mdpd/rhosum mdpd 1.0 1.0 9872598\n";
    expect_error(
        "mdpd-rd",
        &format!("{HEAD}{mdpd}pair_coeff * * mdpd -40 25 4.5 0.7 0.75\n"),
        None,
        "in.x:7: pair_coeff: the cutoff 0.7 must not be shorter than that of the repulsive term 0.75",
    );
    expect_error(
        "mdpd-rhosum-unset",
        &format!("{HEAD}{mdpd}pair_coeff * * mdpd -40 25 4.5 1.0 0.75\npair_coeff 1 1 mdpd/rhosum 0.75\nfix 1 all mvv/dpd\nrun 0\n"),
        None,
        "in.x:10: run: All pair mdpd/rhosum coeffs are not set: no pair_coeff for types 1 2",
    );
}

#[test]
fn pair_coeff_sections_of_data_files_are_checked_at_their_lines() {
    let data = |section: &str| {
        format!("title\n\n1 atoms\n2 atom types\n\n0 6 xlo xhi\n0 6 ylo yhi\n0 6 zlo zhi\n\n{section}\nAtoms # atomic\n\n1 1 1.0 1.0 1.0\n")
    };
    let script = "units lj\natom_style atomic\npair_style dpd 1.0 1.0 4928459\nread_data data.x\n";
    expect_error("data-no-style", "units lj\natom_style atomic\nread_data data.x\n", Some(&data("Pair Coeffs\n\n1 25 4.5\n2 25 4.5\n")), "has a Pair Coeffs section: define the pair style (pair_style) before read_data");
    // the values are the pair style's: a bad one names the data file's line
    expect_error("data-bad-value", script, Some(&data("PairIJ Coeffs # dpd\n\n1 1 25 4.5\n1 2 25 x\n2 2 25 4.5\n")), "data.x:13: pair_coeff: expected gamma (a number), got 'x'");
    expect_error("data-bad-type", script, Some(&data("Pair Coeffs\n\n1 25 4.5\n3 25 4.5\n")), "data.x:13: Pair Coeffs: atom type 3 is outside 1..2");
    // Pair Coeffs sets I I only: the mixture is incomplete, as in LAMMPS
    expect_error(
        "data-ii-only",
        &format!("{script}mass * 1.0\nfix 1 all nve\nrun 0\n"),
        Some(&data("Pair Coeffs\n\n1 25 4.5\n2 25 4.5\n")),
        "in.x:7: run: All pair coeffs are not set: no pair_coeff for types 1 2",
    );
}
