//! Helpers shared by the integration tests: running example scripts with variables
//! overridden, and the statistics the physics tests need.
#![allow(dead_code)]

pub mod lammps;
pub mod ranks;
pub mod stats;
// checks of the statistics helpers
mod statistics_helpers;

use gendpde::{Interpreter, Mode, Output};
use std::path::{Path, PathBuf};
use std::process::Command;

#[allow(unused_imports)] // not every test file launches mpirun
pub use ranks::{mpirun, tempdir};

/// Runs the gendpde program with `args` in `dir`.
pub fn gendpde(dir: &Path, args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_gendpde")).args(args).current_dir(dir).output().expect("gendpde runs")
}

pub fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples").join(name).join(format!("in.{name}"))
}

/// An interpreter that has executed `examples/NAME/in.NAME` with the given `-var`s.
pub fn run_example(name: &str, vars: &[(&str, &str)]) -> Interpreter {
    let mut it = Interpreter::new(Mode::Run, Output::new(false));
    for (k, v) in vars {
        it.vars.set_command_line(k, vec![v.to_string()]);
    }
    if let Err(e) = it.execute_file(&example(name)) {
        panic!("example {name} failed: {e}");
    }
    it
}

/// An interpreter that has executed `text`.
pub fn run_script(text: &str) -> Interpreter {
    let mut it = Interpreter::new(Mode::Run, Output::new(false));
    if let Err(e) = it.execute_str("test.in", text) {
        panic!("script failed: {e}");
    }
    it
}

/// Largest |E(t) - E(0)|/|E(0)| of the total energy over `steps` steps of the interpreter's
/// dynamics.
pub fn worst_energy_error(it: &mut Interpreter, steps: u64) -> f64 {
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let e0 = gendpde::Observables::measure(sys).energy();
    let mut worst: f64 = 0.0;
    for _ in 0..steps {
        physics.advance(sys).unwrap();
        worst = worst.max(((gendpde::Observables::measure(sys).energy() - e0) / e0).abs());
    }
    worst
}

/// A LAMMPS data file of `n` particles (types alternating 2, 1, 2, ...) at pseudo-random
/// positions with 6 decimals (so LAMMPS and gendpde read the same doubles) in the box
/// [0, 5] x [-1, 4] x [0, 6]; one type per mass; `dpd`: atom style dpd (dpdTheta 1).
pub fn random_data_file(n: usize, masses: &[f64], dpd: bool, seed: u64) -> String {
    let mut state = seed.max(1);
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut s = format!("test\n\n{n} atoms\n{} atom types\n\n0 5 xlo xhi\n-1 4 ylo yhi\n0 6 zlo zhi\n\nMasses\n\n", masses.len());
    for (t, m) in masses.iter().enumerate() {
        s += &format!("{} {m}\n", t + 1);
    }
    s += if dpd { "\nAtoms # dpd\n\n" } else { "\nAtoms # atomic\n\n" };
    for i in 1..=n {
        let (x, y, z) = (5.0 * next(), -1.0 + 5.0 * next(), 6.0 * next());
        let theta = if dpd { " 1.0" } else { "" };
        s += &format!("{i} {}{theta} {x:.6} {y:.6} {z:.6}\n", 1 + i % 2);
    }
    s
}

/// Runs `head` followed by each case's lines in the directory `stage` makes of a script;
/// each must fail with its expected text and the location of its last line.
pub fn expect_errors(head: &str, cases: &[(&str, &str)], stage: impl Fn(&str) -> PathBuf) {
    for (lines, expected) in cases {
        let script = format!("{head}{lines}\n");
        let dir = stage(&script);
        let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
        let err = String::from_utf8_lossy(&out.stderr);
        let n = script.lines().count();
        assert!(!out.status.success(), "accepted: {lines}");
        assert!(err.contains(&format!("in.x:{n}:")) && err.contains(expected), "{lines}: expected 'in.x:{n}: ... {expected}', got {err}");
    }
}
