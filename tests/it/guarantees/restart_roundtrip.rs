//! Restarts keep everything a continuation needs: for every example and every LAMMPS
//! parity script, 2k steps in one run equal k steps, `write_restart`, a new process with
//! `read_restart` and k more steps, bit for bit: every thermo row at full precision (the
//! continuation's set-up row included) and the final per-particle state, written and
//! read on 1 and on 2 ranks, and written on 2 and read on 1 or 3.
#![cfg(feature = "mpi")]

use crate::common;

use std::path::{Path, PathBuf};

/// A script reduced to a fast scene: its `-var`s, the thermo interval and k.
struct Case {
    script: &'static str,
    vars: &'static [(&'static str, &'static str)],
    every: u64,
    k: u64,
}

const CASES: &[Case] = &[
    Case { script: "examples/vdw-equilibrium/in.vdw-equilibrium", vars: &[("n", "11"), ("rc", "3.0")], every: 5, k: 10 },
    Case { script: "examples/distributions/in.distributions", vars: &[("n", "11"), ("rc", "3.0"), ("equil", "5"), ("dump", "5")], every: 5, k: 10 },
    Case { script: "examples/dpde-classic/in.dpde-classic", vars: &[("n", "8")], every: 5, k: 10 },
    Case { script: "examples/flash-heating/in.flash-heating", vars: &[("n", "11"), ("rc", "3.0"), ("equil", "5")], every: 5, k: 10 },
    Case { script: "examples/heat-gradient/in.heat-gradient", vars: &[("L", "6"), ("w", "2"), ("ny", "9")], every: 5, k: 10 },
    Case { script: "examples/heat-mixture/in.heat-mixture", vars: &[], every: 5, k: 10 },
    Case { script: "examples/momentum-noise/in.momentum-noise", vars: &[("noise", "harmonic 1.5"), ("equil", "5"), ("dump", "5")], every: 5, k: 10 },
    Case { script: "examples/heat-only/in.heat-only", vars: &[], every: 5, k: 10 },
    Case { script: "examples/isothermal/in.isothermal", vars: &[("n", "11"), ("rc", "3.0"), ("equil", "5")], every: 5, k: 10 },
    Case { script: "examples/lj-fluid/in.lj-fluid", vars: &[("n", "11"), ("rc", "3.0"), ("equil", "5")], every: 5, k: 10 },
    Case { script: "examples/lth-argon/in.lth-argon", vars: &[("n", "10"), ("equil", "5")], every: 5, k: 10 },
    Case { script: "examples/sdpd-vdw/in.sdpd-vdw", vars: &[("kB", "0.05")], every: 5, k: 10 },
    Case { script: "examples/vapour-liquid/in.vapour-liquid", vars: &[("lx", "16"), ("ly", "14"), ("lz", "14"), ("rc", "3.0"), ("dump", "5")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpde-deterministic", vars: &[], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpde-metal", vars: &[], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpde-shardlow", vars: &[("equil", "5")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.mdpd-deterministic", vars: &[], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.mdpd-liquid", vars: &[("equil", "5")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpd-isothermal", vars: &[], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpd-fdt", vars: &[], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpde-vv-lj", vars: &[("equil", "5")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpd-vv", vars: &[], every: 5, k: 10 },
    // fix nph: the box, omega, omega_dot, the chain, V0, T0 and the fixed point
    Case { script: "scripts/lammps/in.nph", vars: &[("sigma", "1.0"), ("kappa", "1.0"), ("baro", "aniso 20.0 20.0 1.0")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.edpd-gradient", vars: &[], every: 5, k: 10 },
    // per-pair coefficients, cutoffs and kernels, boxes under 4 (cutoff + skin)
    Case { script: "scripts/lammps/in.mix-dpd", vars: &[("T", "1.0")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.mix-mdpd", vars: &[], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpd-basic", vars: &[], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.table-lj", vars: &[("tstyle", "spline")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.table-water", vars: &[("gamma", "10.0")], every: 5, k: 10 },
    // dpd/ext with noise; the thermostats at a fixed T (a ramp spans its own run, as in
    // LAMMPS, so a run cut in two ramps differently)
    Case { script: "scripts/lammps/in.dpd-ext", vars: &[("T", "1.0")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpd-tstat", vars: &[("T", "300.0")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.dpdext-tstat", vars: &[("T", "300.0")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.multi-lucy-parity", vars: &[("tstyle", "lookup")], every: 5, k: 10 },
    Case { script: "scripts/lammps/in.sdpd-taitwater", vars: &[("T", "300.0"), ("every", "5")], every: 5, k: 10 },
];

/// Commands of the original script a continuation repeats: the output settings (the
/// restart holds the box, particles, groups, styles and fixes).
const REPEATED: &[&str] = &["variable", "thermo", "thermo_style", "thermo_modify", "compute"];

const FINAL_DUMP: &str = "write_dump all custom final.dump id type x y z ix iy iz px py pz u theta\n";

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The script's lines up to its last `run` (comments dropped) and the repeated ones.
fn split(script: &str) -> (String, String) {
    let lines: Vec<&str> = script.lines().map(|l| l.split('#').next().unwrap_or("").trim_end()).collect();
    let last_run = lines.iter().rposition(|l| l.split_whitespace().next() == Some("run")).expect("the script has a run");
    let before = lines[..last_run].join("\n") + "\n";
    let repeated: Vec<&str> = lines[..last_run]
        .iter()
        .copied()
        .filter(|l| {
            let mut w = l.split_whitespace();
            let cmd = w.next().unwrap_or("");
            REPEATED.contains(&cmd) || (cmd == "fix" && w.nth(2) == Some("ave/time"))
        })
        .collect();
    (before, repeated.join("\n") + "\n")
}

fn gendpde(np: usize, dir: &Path, script: &str, vars: &[(&str, &str)]) -> String {
    let mut args = vec!["run", script, "-log", "none"];
    for (k, v) in vars {
        args.extend(["-var", k, v]);
    }
    let out = common::ranks::mpirun(np, dir, &args);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{script} on {np} ranks in {}: {}\n{stdout}", dir.display(), String::from_utf8_lossy(&out.stderr));
    stdout
}

/// The numeric thermo rows of the last run in `stdout`.
fn last_run_rows(stdout: &str) -> Vec<String> {
    let runs: Vec<&str> = stdout.split("Setting up").collect();
    runs.last().unwrap().lines().filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit() || c == '-')).map(String::from).collect()
}

fn check(case: &Case, np_write: usize, np_read: usize) {
    let src = root().join(case.script);
    let name = src.file_name().unwrap().to_string_lossy().into_owned();
    let dir = std::env::temp_dir().join(format!("gendpde-rt-{name}-{np_write}{np_read}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for entry in std::fs::read_dir(src.parent().unwrap()).unwrap() {
        let p = entry.unwrap().path();
        if p.is_file() {
            std::fs::copy(&p, dir.join(p.file_name().unwrap())).unwrap();
        }
    }
    let (before, repeated) = split(&std::fs::read_to_string(&src).unwrap());
    let precise = format!("thermo {}\nthermo_modify format float %.17g\n", case.every);
    let k = case.k;
    std::fs::write(dir.join("in.straight"), format!("{before}{precise}run {}\n{FINAL_DUMP}", 2 * k).replace("final.dump", "straight.dump")).unwrap();
    std::fs::write(dir.join("in.first"), format!("{before}{precise}run {k}\nwrite_restart half.h5\n")).unwrap();
    std::fs::write(dir.join("in.second"), format!("read_restart half.h5\n{repeated}{precise}run {k}\n{FINAL_DUMP}")).unwrap();

    let straight = last_run_rows(&gendpde(1, &dir, "in.straight", case.vars));
    let first = last_run_rows(&gendpde(np_write, &dir, "in.first", case.vars));
    let second = last_run_rows(&gendpde(np_read, &dir, "in.second", case.vars));
    let what = format!("{} written on {np_write} rank(s), read on {np_read}", case.script);
    assert!(!first.is_empty() && !second.is_empty(), "{what}: no thermo rows");
    assert_eq!(second[0], *first.last().unwrap(), "{what}: the continuation's set-up row differs from the row the restart was written at");
    let joined: Vec<String> = first.iter().chain(&second[1..]).cloned().collect();
    assert_eq!(joined, straight, "{what}: the continued thermo rows differ from the uninterrupted run");
    let (a, b) = (std::fs::read(dir.join("straight.dump")).unwrap(), std::fs::read(dir.join("final.dump")).unwrap());
    assert!(a == b, "{what}: the final particles differ from the uninterrupted run");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Scenes that run on one rank only (pair voronoi/fv), checked written and read on one.
const ONE_RANK_CASES: &[Case] = &[
    Case { script: "examples/voronoi-vdw/in.voronoi-vdw", vars: &[("k", "4")], every: 5, k: 10 },
    Case { script: "examples/voronoi-coexistence/in.voronoi-coexistence", vars: &[("k", "4"), ("V", "40"), ("dump", "5")], every: 5, k: 10 },
];

fn all(np_write: usize, np_read: usize) {
    let mut failed = Vec::new();
    let cases: Vec<&Case> = CASES.iter().chain(ONE_RANK_CASES.iter().filter(|_| np_write == 1 && np_read == 1)).collect();
    for case in cases.iter().copied() {
        if let Err(e) = std::panic::catch_unwind(|| check(case, np_write, np_read)) {
            let msg = e.downcast_ref::<String>().cloned().unwrap_or_default();
            failed.push(msg.lines().take(12).collect::<Vec<_>>().join("\n"));
        }
    }
    assert!(failed.is_empty(), "{} of {} scripts do not continue bit-identically:\n{}", failed.len(), cases.len(), failed.join("\n\n"));
}

#[test]
fn restarts_continue_bit_identically_on_one_rank() {
    all(1, 1);
}

#[test]
fn restarts_continue_bit_identically_on_two_ranks() {
    all(2, 2);
}

#[test]
fn restarts_written_on_two_ranks_continue_on_one() {
    all(2, 1);
}

#[test]
fn restarts_written_on_two_ranks_continue_on_three() {
    all(2, 3);
}
