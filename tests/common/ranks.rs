//! Running the gendpde binary under mpirun, and the full-precision thermo rows of its output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `mpirun -np NP gendpde ARGS...` in `dir` (oversubscribed, allowed as root).
pub fn mpirun(np: usize, dir: &Path, args: &[&str]) -> Output {
    Command::new("mpirun")
        .args(["--oversubscribe", "-np", &np.to_string(), env!("CARGO_BIN_EXE_gendpde")])
        .args(args)
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .current_dir(dir)
        .output()
        .expect("mpirun runs (scripts/test.sh installs OpenMPI)")
}

/// A fresh directory for one test of this process.
pub fn tempdir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gendpde-mpi-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Thermo lines of a run (its numeric rows).
pub fn thermo_rows(stdout: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(stdout).lines().filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit())).map(String::from).collect()
}
