//! Running the gendpde binary under mpirun, and the full-precision thermo rows of its output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

/// `mpirun -np NP gendpde ARGS...` in `dir` (oversubscribed, allowed as root). Each
/// launch has its own session directory: OpenMPI 4.1 fails a launch whose shared one
/// (/tmp/ompi.HOST.UID) another launch creates at the same moment. Idle ranks yield the
/// core (`mpi_yield_when_idle`): with more ranks than cores, busy-waiting ranks starve
/// the working ones (docs/PERFORMANCE.md: 4 ranks on 2 cores 862 s against 7.6 s).
pub fn mpirun(np: usize, dir: &Path, args: &[&str]) -> Output {
    static LAUNCHES: AtomicUsize = AtomicUsize::new(0);
    let session = std::env::temp_dir().join(format!("gendpde-ompi-{}-{}", std::process::id(), LAUNCHES.fetch_add(1, Ordering::Relaxed)));
    let out = Command::new("mpirun")
        .args(["--oversubscribe", "-np", &np.to_string(), env!("CARGO_BIN_EXE_gendpde")])
        .args(args)
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_orte_tmpdir_base", &session)
        .env("OMPI_MCA_mpi_yield_when_idle", "1")
        .current_dir(dir)
        .output()
        .expect("mpirun runs (scripts/test.sh installs OpenMPI)");
    let _ = std::fs::remove_dir_all(&session);
    out
}

/// A fresh, empty directory for test `name` of this process. Each call has its own (the
/// count of calls in its name): the tests of every area share one process, and two of
/// them may pick the same name (multi_lucy's and table_parity's error cases do).
pub fn tempdir(name: &str) -> PathBuf {
    static DIRS: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!("gendpde-mpi-{name}-{}-{}", std::process::id(), DIRS.fetch_add(1, Ordering::Relaxed)));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Thermo lines of a run (its numeric rows).
pub fn thermo_rows(stdout: &[u8]) -> Vec<String> {
    // every word a number ("162 atoms in group hot" is no row)
    let numeric = |l: &str| l.trim_start().starts_with(|c: char| c.is_ascii_digit()) && l.split_whitespace().all(|w| w.parse::<f64>().is_ok());
    String::from_utf8_lossy(stdout).lines().filter(|l| numeric(l)).map(String::from).collect()
}
