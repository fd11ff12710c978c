//! The command line: reproducible output, and `gendpde check` naming the bad line.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

fn gendpde(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gendpde")).args(args).current_dir(dir).output().expect("gendpde runs")
}

/// Thermo output without the wall-clock lines.
fn thermo(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter(|l| !["Loop time", "Performance", "Comm time", "Total wall time"].iter().any(|t| l.starts_with(t)))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn same_seed_same_input_gives_identical_thermo() {
    let dir = tempdir("repro");
    let ex = common::example("vdw-equilibrium");
    let ex = ex.to_str().unwrap();
    let args = ["run", ex, "-var", "n", "11", "-var", "rc", "3.0", "-var", "steps", "100", "-log", "none"];
    let (a, b) = (gendpde(&args, &dir), gendpde(&args, &dir));
    assert!(a.status.success(), "{}", String::from_utf8_lossy(&a.stderr));
    assert_eq!(thermo(&a), thermo(&b));
    assert!(thermo(&a).lines().count() >= 3);
    // a different seed changes the trajectory
    let mut other = args.to_vec();
    other.extend(["-var", "seed", "17"]);
    assert_ne!(thermo(&a), thermo(&gendpde(&other, &dir)));
}

#[test]
fn run_writes_a_log_with_the_thermo_lines() {
    let dir = tempdir("log");
    let ex = common::example("heat-only");
    let out = gendpde(&["run", ex.to_str().unwrap(), "-var", "steps", "20", "-log", "my.log"], &dir);
    assert!(out.status.success());
    let log = std::fs::read_to_string(dir.join("my.log")).unwrap();
    let screen = thermo(&out);
    let last = screen.lines().filter(|l| l.trim_start().starts_with("20 ")).last().unwrap();
    assert!(log.contains(last), "log lacks the last thermo line {last}");
    assert!(log.contains("fix ssa all shardlow heat fourier"), "commands are echoed to the log");
}

const GOOD: &str = "units lj
lattice sc 0.5
region box block 0 12 0 12 0 12
create_box 1 box
create_atoms 1 box
mass 1 1.0
pair_style gendpde 3.0 123
pair_coeff * * 4.5 1.0
fix eos all eos/vdw 60.0 2.4682 1.4142
fix ssa all shardlow
run 10
";

fn check(script: &str) -> (bool, String) {
    let dir = tempdir("check");
    std::fs::write(dir.join("in.test"), script).unwrap();
    let out = gendpde(&["check", "in.test"], &dir);
    (out.status.success(), String::from_utf8_lossy(&out.stderr).into_owned())
}

#[test]
fn check_accepts_a_valid_script() {
    let (ok, err) = check(GOOD);
    assert!(ok, "{err}");
}

#[test]
fn check_names_the_line_of_each_error() {
    let cases = [
        ("unknown command", GOOD.replace("mass 1 1.0", "mass 1 1.0\nfrobnicate 3"), "in.test:7: frobnicate: unknown command"),
        ("missing argument", GOOD.replace("pair_coeff * * 4.5 1.0", "pair_coeff * * 4.5"), "in.test:8: pair_coeff: missing argument"),
        ("negative mass", GOOD.replace("mass 1 1.0", "mass 1 -1.0"), "in.test:6: mass: the mass must be positive"),
        ("density cap", GOOD.replace("lattice sc 0.5", "lattice sc 0.8"), "in.test:9: fix: mean number density"),
        ("small box", GOOD.replace("0 12 0 12 0 12", "0 12 0 12 0 3"), "in.test:11: run: Shardlow algorithm requires sub-domain length > 2*(rcut+skin)"),
        ("non-number", GOOD.replace("timestep", "x").replace("run 10", "timestep abc\nrun 10"), "in.test:11: timestep: expected the timestep (a number), got 'abc'"),
    ];
    for (what, script, expect) in cases {
        let (ok, err) = check(&script);
        assert!(!ok, "{what}: check accepted the script");
        assert!(err.contains(expect), "{what}: expected '{expect}' in:\n{err}");
        assert!(!err.contains("internal error"), "{what}: a panic reached the user:\n{err}");
    }
}

/// A fresh directory for each call (tests run in parallel).
fn tempdir(name: &str) -> std::path::PathBuf {
    static COUNT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("gendpde-cli-{name}-{}-{k}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_non_positive_temperature_stops_the_run_naming_the_particle() {
    let dir = tempdir("theta");
    let script = GOOD.replace("run 10", "set atom 7 u -200.0\nrun 10");
    std::fs::write(dir.join("in.test"), script).unwrap();
    let out = gendpde(&["run", "in.test", "-log", "none"], &dir);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("in.test:12: run: particle 7 at step 0: particle temperature is not positive"), "{err}");
    assert!(err.contains("u = -2.000000000e2") && err.contains("theta = -"), "{err}");
}

#[test]
fn a_blow_up_during_the_run_names_step_and_particle() {
    let dir = tempdir("blowup");
    // C_V close to k_B and a huge timestep drive some internal energy negative
    let script = GOOD.replace("60.0 2.4682", "1.05 2.4682").replace("pair_coeff * * 4.5 1.0", "pair_coeff * * 4.5 50.0")
        .replace("run 10", "set group all theta 1.5\ntimestep 0.5\nrun 50");
    std::fs::write(dir.join("in.test"), script).unwrap();
    let out = gendpde(&["run", "in.test", "-log", "none"], &dir);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "the run should stop");
    assert!(err.contains("run stopped: particle ") && err.contains(" during step "), "{err}");
    assert!(!err.contains("internal error"), "{err}");
    // the last good state was written and loads
    assert!(err.contains("the last good state (step ") && err.contains("failed.restart.h5"), "{err}");
    std::fs::write(dir.join("in.load"), "read_restart failed.restart.h5\nrun 0\n").unwrap();
    let out = gendpde(&["run", "in.load", "-log", "none"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn label_next_jump_loop_like_lammps() {
    let dir = tempdir("loop");
    std::fs::write(
        dir.join("in.loop"),
        "variable a loop 3\nlabel top\nprint \"iteration ${a}\"\nnext a\njump SELF top\nprint done\njump SELF nowhere\n",
    )
    .unwrap();
    let out = gendpde(&["run", "in.loop", "-log", "none"], &dir);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(stdout.lines().take(4).collect::<Vec<_>>(), ["iteration 1", "iteration 2", "iteration 3", "done"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("in.loop:7: jump: no line 'label nowhere' in in.loop"), "{err}");
}

#[test]
fn an_endless_jump_loop_stops_with_a_clear_message() {
    let dir = tempdir("endless");
    std::fs::write(dir.join("in.loop"), "variable a equal 1\nlabel top\nprint \"$a\" screen no\njump SELF top\n").unwrap();
    let out = gendpde(&["run", "in.loop", "-log", "none"], &dir);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("in.loop:4: jump: 1000000 jumps without a run or a next in between"), "{err}");
    // a loop that advances with next is not endless, however long
    std::fs::write(dir.join("in.next"), "variable i loop 3\nlabel top\nnext i\njump SELF top\nprint done\n").unwrap();
    let out = gendpde(&["run", "in.next", "-log", "none"], &dir);
    assert!(out.status.success() && String::from_utf8_lossy(&out.stdout).contains("done"), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn a_tiny_heat_capacity_is_refused_in_a_short_message() {
    let (ok, err) = check("units lj\nlattice sc 0.5\nregion b block 0 5 0 5 0 5\ncreate_box 1 b\nfix e all eos/cv 1e-300\n");
    assert!(!ok);
    assert!(err.contains("C_V = 1e-300 must exceed k_B = 1.0"), "{err}");
    assert!(err.len() < 300, "{err}");
}

#[test]
fn a_full_disk_under_the_log_stops_the_script_naming_the_log() {
    let dir = tempdir("fulllog");
    let script = std::fs::read_to_string(common::example("heat-only")).unwrap().replace("thermo       500", "thermo 1");
    std::fs::write(dir.join("in.test"), script).unwrap();
    // a file-size limit of 4 KiB stands for the full disk (SIGXFSZ ignored: writes fail)
    let cmd = format!("trap '' XFSZ; ulimit -f 4; exec {} run in.test -log log.test -var steps 2000", env!("CARGO_BIN_EXE_gendpde"));
    let out = Command::new("bash").args(["-c", &cmd]).current_dir(&dir).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("log file log.test: File too large"), "{err}");
    assert!(!err.contains("internal error") && !err.contains("panicked"), "{err}");
    // what was written before stays
    let log = std::fs::read_to_string(dir.join("log.test")).unwrap();
    assert!(log.len() >= 3000 && log.contains("pair_style"), "{} bytes", log.len());
}

#[test]
fn a_closed_screen_pipe_stops_the_run_like_sigpipe_without_a_panic() {
    use std::io::{BufRead, BufReader};
    let dir = tempdir("pipe");
    let ex = common::example("vdw-equilibrium");
    let mut child = Command::new(env!("CARGO_BIN_EXE_gendpde"))
        .args(["run", ex.to_str().unwrap(), "-log", "none", "-var", "n", "11", "-var", "rc", "3.0", "-var", "steps", "100000"])
        .current_dir(&dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    for _ in 0..2 {
        lines.next().unwrap().unwrap();
    }
    drop(lines); // like `| head -2`
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(128 + 13), "{err}");
    assert!(err.contains("run stopped by SIGPIPE"), "{err}");
    assert!(!err.contains("internal error") && !err.contains("panicked"), "{err}");
}
