//! The language's long tail (issue 38, part 3, item 2): `clear`, the variable styles and
//! math functions, thermo keywords and `thermo_modify`, unit systems and the small
//! commands (`comm_modify`, `shell`, `write_coeff`, ...), each beside the reference LAMMPS
//! (22 Jul 2025) on a script of its own.

use crate::common;

use common::lammps::{expect_success, parse_thermo_blocks, run_gendpde, run_lammps, ThermoBlock};
use common::tempdir;
use std::path::PathBuf;

/// Writes `script` as `in.x` into a fresh directory `NAME-SIDE`, with the `files` (name,
/// text) beside it.
fn stage(name: &str, side: &str, script: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = tempdir(&format!("{name}-{side}"));
    std::fs::write(dir.join("in.x"), script).unwrap();
    for (f, text) in files {
        std::fs::write(dir.join(f), text).unwrap();
    }
    dir
}

/// Runs `script` in both codes (each must succeed); returns the directories and standard
/// outputs, LAMMPS's first.
fn both(name: &str, script: &str, files: &[(&str, &str)]) -> ((PathBuf, String), (PathBuf, String)) {
    let (dl, dg) = (stage(name, "lammps", script, files), stage(name, "gendpde", script, files));
    let l = expect_success("LAMMPS", &run_lammps(&dl, "in.x", &[]));
    let g = run_gendpde(&dg, "in.x", &[]);
    assert!(g.status.success(), "gendpde failed on {name}:\n{}", String::from_utf8_lossy(&g.stderr));
    ((dl, l), (dg, String::from_utf8_lossy(&g.stdout).into_owned()))
}

/// Runs `script` in gendpde, which must fail with a message containing `expected`.
fn expect_error(name: &str, script: &str, expected: &str) {
    let out = run_gendpde(&stage(name, "gendpde", script, &[]), "in.x", &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "accepted:\n{script}");
    assert!(stderr.contains(expected), "expected '{expected}', got {stderr}\nfor:\n{script}");
}

/// The thermo blocks of both outputs, which must have the same headings and row counts;
/// returns them and the largest relative difference of their values.
fn thermo_parity(lammps: &str, gendpde: &str) -> (Vec<ThermoBlock>, f64) {
    let (bl, bg) = (parse_thermo_blocks(lammps, "Step"), parse_thermo_blocks(gendpde, "Step"));
    assert_eq!(bl.len(), bg.len(), "thermo blocks:\n{lammps}\n---\n{gendpde}");
    let mut worst: f64 = 0.0;
    for (l, g) in bl.iter().zip(&bg) {
        assert_eq!(l.header, g.header, "headings");
        assert_eq!(l.rows.len(), g.rows.len(), "rows of {:?}", l.header);
        for (x, y) in l.rows.iter().flatten().zip(g.rows.iter().flatten()) {
            worst = worst.max((x - y).abs() / x.abs().max(1.0));
        }
    }
    (bl, worst)
}

/// The printed lines (`print`) of an output that start with `prefix`.
fn printed<'a>(out: &'a str, prefix: &str) -> Vec<&'a str> {
    out.lines().filter(|l| l.starts_with(prefix)).collect()
}

/// `clear` deletes the box and every setting (units back to lj: timestep 0.005, thermo
/// normalised; the region ID free again) and keeps the variables; a second system is set
/// up after it. Thermo of both systems as LAMMPS's, to round-off.
#[test]
fn clear_restores_defaults_and_keeps_variables() {
    let system = |units: &str, lattice: &str, n: u32, t: &str, cut: &str| {
        format!(
            "units {units}\nlattice {lattice}\nregion box block 0 {n} 0 {n} 0 {n}\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
             velocity all create {t} 4928459 loop geom\ncomm_modify vel yes\npair_style dpd {t} {cut} 123\npair_coeff 1 1 25.0 0.0\n\
             fix 1 all nve\nthermo_style custom step dt temp pe press\nthermo_modify format float %.17g\nrun 5\n"
        )
    };
    let script = format!(
        "variable a equal 2.5\n{}clear\nprint \"after clear a=${{a}}\"\n{}",
        system("metal", "sc 1.0", 7, "300.0", "1.0"),
        system("lj", "fcc 0.8442", 4, "1.0", "1.5").replace("units lj\n", "")
    );
    let ((_, l), (_, g)) = both("clear", &script, &[]);
    let (blocks, worst) = thermo_parity(&l, &g);
    assert_eq!(blocks.len(), 2);
    assert_eq!(blocks[1].column("Dt")[0], 0.005, "lj's timestep after clear");
    assert!(blocks[1].column("PotEng")[1] != 0.0, "a pair energy to compare");
    assert!(worst < 1e-12, "thermo differs from LAMMPS's by {worst:e}");
    assert_eq!(printed(&g, "after clear"), ["after clear a=2.5"]);
    expect_error("clear-args", "clear all\n", "clear");
}
