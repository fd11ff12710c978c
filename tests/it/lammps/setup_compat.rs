//! Set-up commands as the reference LAMMPS runs them (issue 38, part 3): create_atoms
//! random's positions and keywords, the static group styles, boxes shorter than two list
//! radii, and `gendpde check` evaluating what a run evaluates at set-up.

use crate::common;

use common::lammps::{expect_success, parse_dump, run_lammps, DumpSnapshot};
use common::{gendpde, tempdir};
use std::path::PathBuf;
use std::process::Output;

/// A fresh directory `name` holding `script` as `in.x`.
fn stage(name: &str, script: &str) -> PathBuf {
    let dir = tempdir(name);
    std::fs::write(dir.join("in.x"), script).unwrap();
    dir
}

fn text(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr)
}

/// Runs `script` in LAMMPS (which must succeed); returns its directory and screen output.
fn lammps(name: &str, script: &str) -> (PathBuf, String) {
    let dir = stage(&format!("{name}-lammps"), script);
    let out = expect_success("LAMMPS", &run_lammps(&dir, "in.x", &[]));
    (dir, out)
}

/// Runs `script` in gendpde on `np` ranks (which must succeed); returns its directory and
/// screen output.
fn gendpde_on(np: usize, name: &str, script: &str) -> (PathBuf, String) {
    let dir = stage(&format!("{name}-gendpde-{np}"), script);
    let args = ["run", "in.x", "-log", "none"];
    let out = if np == 1 { gendpde(&dir, &args) } else { common::mpirun(np, &dir, &args) };
    assert!(out.status.success(), "gendpde on {np} ranks failed:\n{}", text(&out));
    (dir, text(&out))
}

/// The only snapshot of the dump `name` in `dir`.
fn snapshot(dir: &std::path::Path, name: &str) -> DumpSnapshot {
    let path = dir.join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    parse_dump(&text).pop().expect("a snapshot")
}

/// Runs `script` (which must fail) in gendpde; its message must contain `expected`.
fn expect_error(name: &str, script: &str, expected: &str) {
    let dir = stage(name, script);
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    assert!(!out.status.success(), "accepted:\n{script}");
    assert!(text(&out).contains(expected), "expected '{expected}', got {}\nfor:\n{script}", text(&out));
}

/// create_atoms random with a sphere, `overlap` against earlier particles and its own
/// (in lattice units: scaled by the x spacing 1.25), `maxtry` that leaves some out, and a
/// lattice with `basis` types: LAMMPS's particles, to the last bit, per tag, on 1 and 3
/// ranks.
const CREATE: &str = "units lj
lattice bcc 1.024
region box block 0 4 0 3 0 3
create_box 3 box
create_atoms 1 box basis 2 2
region ball sphere 6 4 3 2.5 units box
region slab block 1 3 INF INF 0.5 2.5 units box
lattice none 1.25
create_atoms 3 random 150 99 ball overlap 0.5 maxtry 40
create_atoms 2 random 40 1234 slab overlap 0.3 units box
create_atoms 1 random 20 7 NULL maxtry 1
mass * 1.0
write_dump all custom create.dump id type x y z modify format float %.17g
";

#[test]
fn create_atoms_draws_lammps_particles() {
    let (dl, out) = lammps("create", CREATE);
    assert!(out.contains("WARNING: Only inserted"), "maxtry 40 should leave some out:\n{out}");
    let l = snapshot(&dl, "create.dump");
    let created: Vec<usize> = (1..=3).map(|t| l.atoms.iter().filter(|(_, r)| r[0] == t as f64).count()).collect();
    // 36 + 20 of type 1, 36 + 40 of type 2 (the basis), fewer than 150 of type 3
    assert!(created[0] == 56 && created[1] == 76 && created[2] > 0 && created[2] < 150, "{created:?}");
    for np in [1, 3] {
        let (dg, out) = gendpde_on(np, "create", CREATE);
        assert!(out.contains("Only inserted"), "{out}");
        let g = snapshot(&dg, "create.dump");
        assert_eq!(g.columns, l.columns);
        assert_eq!(g.atoms.len(), l.atoms.len(), "{np} ranks");
        for (a, b) in g.atoms.iter().zip(&l.atoms) {
            assert_eq!(a, b, "{np} ranks: particle {} differs", b.0);
        }
    }
}

#[test]
fn create_atoms_keywords_are_checked_as_lammps() {
    let head = "units lj\nlattice sc 1.0\nregion box block 0 4 0 4 0 4\ncreate_box 2 box\n";
    for (line, expected) in [
        ("create_atoms 1 box basis 2 1", "in.x:5: create_atoms: Out of range basis setting '2 1' in create_atoms command"),
        ("create_atoms 1 box basis 1 3", "in.x:5: create_atoms: Out of range basis setting '1 3' in create_atoms command"),
        ("create_atoms 1 region box maxtry 5", "in.x:5: create_atoms: Create_atoms maxtry can only be used with random style"),
        ("create_atoms 1 random 5 3 NULL maxtry 0", "in.x:5: create_atoms: create_atoms maxtry must be positive"),
        ("create_atoms 1 random 5 3 NULL units cell", "in.x:5: create_atoms: Unknown create_atoms units option cell"),
        ("create_atoms 1 random 5 3 NULL mol w 4", "in.x:5: create_atoms: create_atoms keyword 'mol' is not supported"),
        ("create_atoms 1 box ratio 0.5 4", "in.x:5: create_atoms: create_atoms keyword 'ratio' is not supported"),
        ("create_atoms 1 box spin 4", "in.x:5: create_atoms: Illegal create_atoms command option spin"),
    ] {
        expect_error("create-keywords", &format!("{head}{line}\n"), expected);
    }
}
