//! LAMMPS scripts run unchanged (issue 17, part 1): create_atoms random, compute temp,
//! run_style, atom_modify, the LAMMPS command line, units and thermo keywords, the lines
//! of a LAMMPS log and the messages of misplaced commands; each beside the reference
//! LAMMPS (../shared/lammps) where a number comes out.

mod common;

use common::lammps::{expect_success, parse_dump, run_lammps, DumpSnapshot};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn tempdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gendpde-script-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn gendpde(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gendpde")).args(args).current_dir(dir).output().expect("gendpde runs")
}

/// Writes `script` as `in.x` in a fresh directory and runs `gendpde run in.x`.
fn run_script(name: &str, script: &str) -> (PathBuf, Output) {
    let dir = tempdir(name);
    std::fs::write(dir.join("in.x"), script).unwrap();
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    (dir, out)
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs `script` in gendpde (which must succeed) and in LAMMPS; returns both directories
/// and standard outputs.
fn both(name: &str, script: &str) -> ((PathBuf, String), (PathBuf, String)) {
    let (dg, g) = run_script(&format!("{name}-gendpde"), script);
    assert!(g.status.success(), "gendpde failed on {name}:\n{}", stderr(&g));
    let dl = tempdir(&format!("{name}-lammps"));
    std::fs::write(dl.join("in.x"), script).unwrap();
    let l = expect_success("LAMMPS", &run_lammps(&dl, "in.x", &[]));
    ((dg, String::from_utf8_lossy(&g.stdout).into_owned()), (dl, l))
}

/// The last snapshot of a text dump.
fn dump(path: &Path) -> DumpSnapshot {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    parse_dump(&text).pop().expect("a snapshot")
}

/// Per-type count and the bounds of x, y, z of a dump: (type, count, [lo; 3], [hi; 3]).
fn census(s: &DumpSnapshot) -> Vec<(u64, usize, [f64; 3], [f64; 3])> {
    let (ct, cx) = (s.column_index("type").unwrap(), s.column_index("x").unwrap());
    let mut out: Vec<(u64, usize, [f64; 3], [f64; 3])> = Vec::new();
    for (_, row) in &s.atoms {
        let t = row[ct] as u64;
        let i = match out.iter().position(|c| c.0 == t) {
            Some(i) => i,
            None => {
                out.push((t, 0, [f64::INFINITY; 3], [f64::NEG_INFINITY; 3]));
                out.len() - 1
            }
        };
        out[i].1 += 1;
        for d in 0..3 {
            out[i].2[d] = out[i].2[d].min(row[cx + d]);
            out[i].3[d] = out[i].3[d].max(row[cx + d]);
        }
    }
    out.sort_by_key(|c| c.0);
    out
}

const RANDOM: &str = "units lj
region box block 0 10 0 8 0 6
create_box 2 box
region slab block 2 5 INF INF 1 3 units box
create_atoms 1 random 500 4321 NULL
create_atoms 2 random 300 777 slab
mass * 1.0
write_dump all custom rand.dump id type x y z
";

/// Counts per type and bounds as LAMMPS's (the positions differ: another generator):
/// type 1 fills the box, type 2 the slab 2 <= x <= 5, 1 <= z <= 3.
#[test]
fn create_atoms_random_fills_the_region_as_lammps() {
    let ((dg, _), (dl, _)) = both("random", RANDOM);
    let (g, l) = (census(&dump(&dg.join("rand.dump"))), census(&dump(&dl.join("rand.dump"))));
    eprintln!("gendpde {g:?}\nLAMMPS  {l:?}");
    let limits = [(1, 500, [0.0, 0.0, 0.0], [10.0, 8.0, 6.0]), (2, 300, [2.0, 0.0, 1.0], [5.0, 8.0, 3.0])];
    for census in [&g, &l] {
        assert_eq!(census.len(), 2);
        for (c, (t, n, lo, hi)) in census.iter().zip(limits) {
            assert_eq!((c.0, c.1), (t, n));
            for d in 0..3 {
                let len = hi[d] - lo[d];
                // N points reach within a few L/N of each face
                assert!(c.2[d] >= lo[d] && c.2[d] < lo[d] + 0.05 * len, "type {t} lower bound {d}: {c:?}");
                assert!(c.3[d] <= hi[d] && c.3[d] > hi[d] - 0.05 * len, "type {t} upper bound {d}: {c:?}");
            }
        }
    }
}

/// Syntax and errors of create_atoms random.
#[test]
fn create_atoms_random_errors_name_the_line() {
    let head = "units lj\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\n";
    for (line, expected) in [
        ("create_atoms 1 random 10 0 NULL", "in.x:4: create_atoms: the random seed must be positive"),
        ("create_atoms 1 random 10 5", "in.x:4: create_atoms: missing argument: expected a region ID or NULL"),
        ("create_atoms 1 random ten 5 NULL", "in.x:4: create_atoms: expected the number of particles (a non-negative integer), got 'ten'"),
        ("create_atoms 1 random 10 5 nowhere", "in.x:4: create_atoms: no region with ID 'nowhere'"),
        ("create_atoms 1 random 10 5 NULL overlap 0.5", "in.x:4: create_atoms: create_atoms random: keyword 'overlap' is not supported"),
        ("region far block 10 12 0 1 0 1 units box\ncreate_atoms 1 random 10 5 far", "in.x:5: create_atoms: the region does not overlap the box"),
        ("create_atoms 2 random 10 5 NULL", "in.x:4: create_atoms: type 2 is outside 1..1"),
    ] {
        let (_, out) = run_script("random-errors", &format!("{head}{line}\n"));
        assert!(!out.status.success(), "{line} was accepted");
        assert!(stderr(&out).contains(expected), "{line}: expected '{expected}', got {}", stderr(&out));
    }
    let (_, out) = run_script("random-nobox", "create_atoms 1 random 10 5 NULL\n");
    assert!(stderr(&out).contains("in.x:1: create_atoms: create_atoms before the box exists"), "{}", stderr(&out));
}

/// Every rank replays the whole stream: the same particles on 1, 2 and 3 ranks.
#[cfg(feature = "mpi")]
#[test]
fn create_atoms_random_is_rank_independent() {
    let dir = tempdir("random-ranks");
    std::fs::write(dir.join("in.x"), RANDOM).unwrap();
    let mut first: Option<String> = None;
    for np in [1, 2, 3] {
        let out = Command::new("mpirun")
            .args(["--oversubscribe", "-np", &np.to_string(), env!("CARGO_BIN_EXE_gendpde"), "run", "in.x", "-log", "none"])
            .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
            .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
            .current_dir(&dir)
            .output()
            .expect("mpirun runs");
        assert!(out.status.success(), "{np} ranks: {}", stderr(&out));
        let text = std::fs::read_to_string(dir.join("rand.dump")).unwrap();
        assert_eq!(parse_dump(&text)[0].atoms.len(), 800);
        match &first {
            None => first = Some(text),
            Some(f) => assert!(*f == text, "{np} ranks differ from 1 rank"),
        }
    }
}
