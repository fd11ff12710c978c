//! Helpers shared by the integration tests: running example scripts with variables
//! overridden, and the statistics the physics tests need.
#![allow(dead_code)]

pub mod lammps;
pub mod ranks;
pub mod stats;

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
        physics.step(sys).unwrap();
        worst = worst.max(((gendpde::Observables::measure(sys).energy() - e0) / e0).abs());
    }
    worst
}
