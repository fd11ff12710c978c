//! A run stopped by SIGTERM, SIGINT or SIGUSR1 (what batch systems send before the wall
//! time), on 1 rank and through mpirun on 2: the log holds the thermo rows printed so far,
//! the H5MD file is readable without repair, the text dump is whole, the state is saved
//! (the checkpoint's file, else interrupted.restart.h5) and continues, and gendpde exits
//! with 128 + the signal's number.

use crate::common;

use common::lammps::{parse_dump, parse_thermo, stage_with};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gendpde-signals-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The deterministic DPDE scene, `steps` long, with an H5MD and a text dump and `extra`
/// before its run, as in.sig.
fn scene(dir: &Path, extra: &str) {
    let dumps = "dump h all h5md 20 traj.h5 x v\ndump c all custom 20 c.dump id x y z\n";
    stage_with(dir, "in.dpde-deterministic", "in.sig", &format!("{dumps}{extra}"), "write_dump all custom final.dump id x y z vx vy vz\n");
}

fn gendpde(dir: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_gendpde"));
    c.current_dir(dir);
    c
}

fn mpirun(np: usize, dir: &Path) -> Command {
    let mut c = Command::new("mpirun");
    c.args(["--oversubscribe", "-np", &np.to_string(), env!("CARGO_BIN_EXE_gendpde")])
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .current_dir(dir);
    c
}

/// Starts `cmd` (a run of in.sig), waits until its log holds `rows` thermo rows, sends
/// `signal`; returns the exit status and stderr.
fn stop(mut cmd: Command, dir: &Path, rows: usize, signal: &str) -> (Option<i32>, String) {
    let child: Child = cmd.args(["run", "in.sig", "-var", "steps", "1000000"]).stdout(Stdio::null()).stderr(Stdio::piped()).spawn().unwrap();
    let start = Instant::now();
    // the rows reach the log as they are printed
    while parse_thermo(&std::fs::read_to_string(dir.join("log.gendpde")).unwrap_or_default(), "Step").len() < rows {
        assert!(start.elapsed() < Duration::from_secs(120), "no {rows} thermo rows in the log after 120 s");
        std::thread::sleep(Duration::from_millis(20));
    }
    let kill = Command::new("kill").args([&format!("-{signal}"), &child.id().to_string()]).status().unwrap();
    assert!(kill.success());
    let out = child.wait_with_output().unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The step the run stopped after, from its message.
fn stopped_at(stderr: &str, signal: &str) -> u64 {
    let at = stderr.find(&format!("run stopped by {signal} after step ")).unwrap_or_else(|| panic!("no stop message in:\n{stderr}"));
    stderr[at..].split_whitespace().nth(6).unwrap().trim_end_matches(':').parse().unwrap()
}

/// What a stopped run leaves: the log's rows up to the step, a clean H5MD file, a whole
/// text dump, the saved state; returns the state's file.
fn check_left(dir: &Path, step: u64, signal: &str, state: &str) {
    let log = std::fs::read_to_string(dir.join("log.gendpde")).unwrap();
    let rows = parse_thermo(&log, "Step");
    assert!(rows.len() >= 3 && rows.last().unwrap()[0] <= step as f64, "log rows {:?}", rows.last());
    assert!(log.contains(&format!("run stopped by {signal} after step {step}: the state is in {state}")), "log ends:\n{}", &log[log.len().saturating_sub(400)..]);
    let h5 = gendpde_io::check_h5md(&dir.join("traj.h5")).unwrap();
    assert!(h5.clean, "the H5MD file needs a repair");
    assert_eq!(h5.steps.last().copied(), Some((step / 20 * 20) as i64));
    let dump = parse_dump(&std::fs::read_to_string(dir.join("c.dump")).unwrap());
    assert_eq!(dump.len(), h5.frames, "text dump frames");
    assert!(dir.join(state).exists(), "{state} not written");
}

/// Continues from `state` on one rank for 30 steps; returns the final dump.
fn continue_from(dir: &Path, state: &str) -> String {
    std::fs::write(dir.join("in.continue"), format!("read_restart {state}\nrun 30\nwrite_dump all custom continued.dump id x y z vx vy vz\n")).unwrap();
    let out = gendpde(dir).args(["run", "in.continue", "-log", "none"]).output().unwrap();
    assert!(out.status.success(), "continuing from {state}:\n{}", String::from_utf8_lossy(&out.stderr));
    std::fs::read_to_string(dir.join("continued.dump")).unwrap()
}

/// Stops a run of in.sig by `signal` (TERM, INT, USR1), which gendpde sees as `seen`,
/// and checks what it left; returns the step it stopped after and the file of its state.
fn interrupt(cmd: Command, dir: &Path, signal: &str, seen: &str, exit: impl Fn(Option<i32>) -> bool, checkpoint: bool) -> (u64, String) {
    let (code, stderr) = stop(cmd, dir, 3, signal);
    assert!(exit(code), "exit status {code:?}; stderr:\n{stderr}");
    let name = format!("SIG{seen}");
    let step = stopped_at(&stderr, &name);
    let state = if checkpoint { format!("ck.{step}.h5") } else { "interrupted.restart.h5".to_string() };
    check_left(dir, step, &name, &state);
    (step, state)
}

#[test]
fn sigterm_on_one_rank_saves_the_checkpoint_and_closes_the_outputs() {
    let d = dir("term");
    scene(&d, "checkpoint 1000000 ck.*.h5\n");
    let (step, state) = interrupt(gendpde(&d), &d, "TERM", "TERM", |c| c == Some(143), true);
    // the checkpoint continues as the uninterrupted run does, to the bit
    let continued = continue_from(&d, &state);
    let straight = dir("term-straight");
    scene(&straight, "");
    let out = gendpde(&straight).args(["run", "in.sig", "-log", "none", "-var", "steps", &(step + 30).to_string()]).output().unwrap();
    assert!(out.status.success());
    assert_eq!(continued, std::fs::read_to_string(straight.join("final.dump")).unwrap(), "continuation differs");
}

#[test]
fn sigint_without_a_checkpoint_writes_interrupted_restart() {
    let d = dir("int");
    scene(&d, "");
    let (_, state) = interrupt(gendpde(&d), &d, "INT", "INT", |c| c == Some(130), false);
    continue_from(&d, &state);
}

#[test]
fn sigterm_sigusr1_and_sigint_through_mpirun_stop_both_ranks_at_one_step() {
    // mpirun forwards them; stopped by SIGTERM or SIGINT itself, it exits non-zero
    let term = |c: Option<i32>| c.is_some_and(|c| c != 0);
    let usr1 = |c: Option<i32>| c == Some(138);
    // Ctrl-C (SIGINT) to mpirun reaches the ranks as SIGTERM
    for (signal, seen, exit) in [("TERM", "TERM", &term as &dyn Fn(Option<i32>) -> bool), ("USR1", "USR1", &usr1), ("INT", "TERM", &term)] {
        let d = dir(&format!("mpi-{signal}"));
        scene(&d, "checkpoint 1000000 ck.*.h5\n");
        let (step, state) = interrupt(mpirun(2, &d), &d, signal, seen, exit, true);
        let continued = continue_from(&d, &state);
        assert!(continued.contains(&format!("ITEM: TIMESTEP\n{}\n", step + 30)));
    }
}
