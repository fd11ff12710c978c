//! `change_box` against the reference LAMMPS (22 Jul 2025): every orthogonal operation
//! (final, delta, scale, volume, set, remap of a group, units lattice and box) gives the same
//! box to the last bit and the same particles after 20 steps of deterministic DPD
//! (scripts/lammps/in.change-box, unchanged in both codes); bad input stops with the line.

use crate::common;

use common::lammps::{expect_success, parse_thermo_blocks, read_dump_snapshot, run_lammps, stage_inputs};
use std::path::PathBuf;
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gendpde-change-box-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn gendpde(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(dir).args(args).output().expect("gendpde runs")
}

#[test]
fn change_box_matches_lammps_box_and_particles() {
    let (dl, dg) = (dir("lammps"), dir("gendpde"));
    stage_inputs(&dl, "in.change-box");
    stage_inputs(&dg, "in.change-box");
    let l = expect_success("LAMMPS", &run_lammps(&dl, "in.change-box", &[]));
    let out = gendpde(&dg, &["run", "in.change-box", "-log", "none"]);
    assert!(out.status.success(), "gendpde: {}", String::from_utf8_lossy(&out.stderr));
    let (lb, gb) = (parse_thermo_blocks(&l, "Step").pop().unwrap(), parse_thermo_blocks(&String::from_utf8_lossy(&out.stdout), "Step").pop().unwrap());
    for c in ["Volume", "Lx", "Ly", "Lz", "Cella", "Cellb", "Cellc", "Xlo", "Xhi", "Ylo", "Yhi", "Zlo", "Zhi"] {
        let (a, b) = (lb.column(c), gb.column(c));
        assert_eq!(a, b, "{c}: LAMMPS {a:?} vs gendpde {b:?}");
    }
    let (a, b) = (lb.column("PotEng")[0], gb.column("PotEng")[0]);
    assert!((a - b).abs() <= 1e-10 * a.abs(), "step-0 pair energy: LAMMPS {a} vs gendpde {b}");
    let (a, b) = (read_dump_snapshot(&dl.join("change-box.dump")), read_dump_snapshot(&dg.join("change-box.dump")));
    assert_eq!(a.atoms.len(), b.atoms.len());
    let mut worst: f64 = 0.0;
    for ((ia, va), (ib, vb)) in a.atoms.iter().zip(&b.atoms) {
        assert_eq!(ia, ib);
        for c in ["x", "y", "z", "vx", "vy", "vz"] {
            worst = worst.max((va[a.column_index(c).unwrap()] - vb[b.column_index(c).unwrap()]).abs());
        }
    }
    eprintln!("change_box + 20 steps: largest per-particle difference {worst:.2e}");
    assert!(worst < 1e-10, "particles differ by {worst:e}");
}

#[test]
fn change_box_bad_input_names_the_line() {
    let base = "units lj\natom_style dpd\nlattice sc 3.0\nregion box block 0 6 0 6 0 6\ncreate_box 1 box\n";
    let cases = [
        ("change_box all x volume\n", "in.bad:6: change_box: x volume: it follows the x, y or z change it compensates"),
        ("change_box all x final 2 1\n", "in.bad:6: change_box: the box would be empty along x"),
        ("change_box all xy final 0.5\n", "in.bad:6: change_box: xy: only orthogonal boxes are supported"),
        ("change_box all boundary p f p\n", "in.bad:6: change_box: boundary 'f' along y: only periodic (p) is supported"),
        ("change_box all x scale 1.1 units cubits\n", "in.bad:6: change_box: units: expected lattice or box, got 'cubits'"),
        ("change_box nogroup x scale 1.1\n", "in.bad:6: change_box: no group 'nogroup'"),
        ("change_box all units box\n", "in.bad:6: change_box: nothing to change"),
    ];
    let d = dir("bad");
    for (line, expect) in cases {
        std::fs::write(d.join("in.bad"), format!("{base}{line}")).unwrap();
        let out = gendpde(&d, &["check", "in.bad"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(expect), "{line}: expected '{expect}' in:\n{err}");
        assert!(!err.contains("internal error"), "{line}: a panic reached the user:\n{err}");
    }
}
