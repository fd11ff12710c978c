//! LAMMPS scripts run unchanged (issue 17, part 2): compute chunk/atom and fix ave/chunk
//! (scripts/lammps/in.dpde-profile) and compute msd (in.dpde-msd) beside the reference
//! LAMMPS (../shared/lammps), with their error messages and their independence of the rank
//! count.

mod common;

use common::lammps::{expect_success, parse_thermo, run_lammps, stage_inputs};
use common::{gendpde, tempdir};
use std::path::Path;
use std::process::Output;

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

const PROFILE: &str = "in.dpde-profile";
const PROFILE_FILES: [&str; 4] = ["prof-all.txt", "prof-sample.txt", "prof-none.txt", "prof-window.txt"];

/// One unit in the last digit `token` prints (`0.969616` -> 1e-6, `193.25` -> 0.01).
fn last_digit(token: &str) -> f64 {
    let (mantissa, exp) = token.split_once(['e', 'E']).map_or((token, 0), |(m, e)| (m, e.parse::<i32>().unwrap()));
    let decimals = mantissa.split_once('.').map_or(0, |(_, f)| f.len() as i32);
    10f64.powi(exp - decimals)
}

/// Asserts that two fix ave/chunk files have the same layout (lines, words) and the same
/// numbers to the last digit LAMMPS prints; returns the number of differing lines.
fn same_profile(what: &str, g: &str, l: &str) -> usize {
    let (gl, ll): (Vec<&str>, Vec<&str>) = (g.lines().collect(), l.lines().collect());
    assert_eq!(gl.len(), ll.len(), "{what}: {} lines in gendpde, {} in LAMMPS", gl.len(), ll.len());
    let mut differing = 0;
    for (n, (a, b)) in gl.iter().zip(&ll).enumerate() {
        if a == b {
            continue;
        }
        differing += 1;
        let (aw, bw): (Vec<&str>, Vec<&str>) = (a.split_whitespace().collect(), b.split_whitespace().collect());
        assert_eq!(aw.len(), bw.len(), "{what}:{}: '{a}' vs LAMMPS '{b}'", n + 1);
        for (x, y) in aw.iter().zip(&bw) {
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(u), Ok(v)) => assert!((u - v).abs() <= last_digit(y).max(last_digit(x)) * 1.000001, "{what}:{}: {x} vs LAMMPS {y}", n + 1),
                _ => assert_eq!(x, y, "{what}:{}", n + 1),
            }
        }
    }
    differing
}

/// Density, mass density, temperature, velocity and force profiles in 1d, 2d and reduced
/// bins, with every norm and ave mode, agree with LAMMPS to its printed digits.
#[test]
fn ave_chunk_profiles_match_lammps() {
    let (dl, dg) = (tempdir("chunk-profile-lammps"), tempdir("chunk-profile-gendpde"));
    stage_inputs(&dl, PROFILE);
    stage_inputs(&dg, PROFILE);
    expect_success("LAMMPS", &run_lammps(&dl, PROFILE, &[]));
    let out = gendpde(&dg, &["run", PROFILE, "-log", "none"]);
    assert!(out.status.success(), "gendpde failed:\n{}", stderr(&out));
    for f in PROFILE_FILES {
        let read = |d: &Path| std::fs::read_to_string(d.join(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
        let (g, l) = (read(&dg), read(&dl));
        assert!(g.lines().count() > 20, "{f}: too short:\n{g}");
        let differing = same_profile(f, &g, &l);
        eprintln!("{f}: {} lines, {differing} differ in their last digit", l.lines().count());
    }
}

/// Runs `input` for 40 steps on 1, 2 and 3 ranks and asserts that `result` (of the
/// directory and the output) is the same for each.
#[cfg(feature = "mpi")]
fn same_on_1_2_3_ranks(name: &str, input: &str, result: impl Fn(&Path, &Output) -> String) {
    let dir = tempdir(name);
    stage_inputs(&dir, input);
    let mut first: Option<String> = None;
    for np in [1, 2, 3] {
        let out = common::mpirun(np, &dir, &["run", input, "-log", "none", "-var", "steps", "40"]);
        assert!(out.status.success(), "{np} ranks: {}", stderr(&out));
        let r = result(&dir, &out);
        match &first {
            None => first = Some(r),
            Some(f) => assert!(*f == r, "{input}: {np} ranks differ from 1 rank"),
        }
    }
}

/// The profile files do not depend on the number of ranks.
#[cfg(feature = "mpi")]
#[test]
fn ave_chunk_profiles_are_rank_independent() {
    same_on_1_2_3_ranks("chunk-ranks", PROFILE, |dir, _| PROFILE_FILES.iter().map(|f| std::fs::read_to_string(dir.join(f)).unwrap()).collect());
}

/// Runs `script` (after the deterministic scene's box) and expects an error containing
/// `expected`.
fn expect_error(script: &str, expected: &str) {
    let dir = tempdir("chunk-errors");
    stage_inputs(&dir, PROFILE);
    let text = format!("units lj\natom_style dpd\nread_data data.dpde-small\n{script}\n");
    std::fs::write(dir.join("in.x"), &text).unwrap();
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    assert!(!out.status.success(), "accepted:\n{text}");
    assert!(stderr(&out).contains(expected), "expected '{expected}', got {}\nfor:\n{text}", stderr(&out));
}

#[test]
fn chunk_atom_errors_name_the_line() {
    for (line, expected) in [
        ("compute c all chunk/atom molecule", "in.x:4: compute: chunk style 'molecule': only bin/1d, bin/2d and bin/3d are supported"),
        ("compute c all chunk/atom bin/1d w lower 1", "in.x:4: compute: expected a dimension x, y or z, got 'w'"),
        ("compute c all chunk/atom bin/1d x middle 1", "in.x:4: compute: expected an origin (lower, center, upper or a coordinate), got 'middle'"),
        ("compute c all chunk/atom bin/1d x lower 0", "in.x:4: compute: the bin width must be positive, got 0.0"),
        ("compute c all chunk/atom bin/2d x lower 1 x lower 1", "in.x:4: compute: dimension x is binned twice"),
        ("compute c all chunk/atom bin/1d x lower", "in.x:4: compute: missing argument: expected the bin width"),
        ("compute c all chunk/atom bin/1d x lower 1 units metres", "in.x:4: compute: expected units box, lattice or reduced, got 'metres'"),
        ("compute c all chunk/atom bin/1d x lower 1 discard yes", "in.x:4: compute: unknown keyword 'discard'; known: units"),
        ("compute c nogroup chunk/atom bin/1d x lower 1", "in.x:4: compute: no group 'nogroup'"),
    ] {
        expect_error(line, expected);
    }
}

#[test]
fn ave_chunk_errors_name_the_line() {
    let c = "compute c all chunk/atom bin/1d x lower 1\n";
    for (line, expected) in [
        ("fix a all ave/chunk 1 1 1 nochunk density/number", "in.x:5: fix: no compute chunk/atom with ID 'nochunk'"),
        ("fix a all ave/chunk 2 3 4 c density/number", "in.x:5: fix: Nevery 2, Nrepeat 3, Nfreq 4: all must be positive"),
        ("fix a all ave/chunk 1 1 1 c", "in.x:5: fix: expected values (density/number, density/mass, temp, vx, vy, vz, fx, fy, fz), got nothing"),
        ("fix a all ave/chunk 1 1 1 c c_pe", "in.x:5: fix: value 'c_pe': per-atom computes, fixes and variables are not supported"),
        ("fix a all ave/chunk 1 1 1 c vx norm some", "in.x:5: fix: expected norm all, sample or none, got 'some'"),
        ("fix a all ave/chunk 1 1 1 c vx ave window 0", "in.x:5: fix: ave window M: M must be positive"),
        ("fix a all ave/chunk 1 1 1 c vx ave sometimes", "in.x:5: fix: expected ave one, running or window, got 'sometimes'"),
        ("fix a all ave/chunk 1 1 1 c vx overwrite", "in.x:5: fix: unknown keyword 'overwrite'; known: norm, ave, adof, cdof, file, format, title1, title2, title3"),
        ("fix a all ave/chunk 1 1 1 c vx format %g%g", "in.x:5: fix: bad format: format '%g%g' has more than one conversion"),
        ("fix a nogroup ave/chunk 1 1 1 c vx", "in.x:5: fix: no group 'nogroup'"),
        ("fix a all ave/chunk 1 1 1 c vx file /nonexistent/dir/p.txt\nmass 1 1\npair_style dpd 1 1 5\npair_coeff 1 1 25 4.5\nfix 1 all nve\nrun 0", "fix a ave/chunk: writing /nonexistent/dir/p.txt: No such file"),
        ("fix a all nve\nfix a all ave/chunk 1 1 1 c vx", "in.x:6: fix: fix ID 'a' is in use by another style (unfix it first)"),
        ("fix a all ave/chunk 1 1 1 c vx\nfix a all nve", "in.x:6: fix: fix ID 'a' is in use by another style (unfix it first)"),
    ] {
        expect_error(&format!("{c}{line}"), expected);
    }
}

/// unfix removes a fix ave/chunk: the file stops growing.
#[test]
fn unfix_stops_ave_chunk() {
    let dir = tempdir("chunk-unfix");
    stage_inputs(&dir, PROFILE);
    let script = "units lj\natom_style dpd\nread_data data.dpde-small\nmass 1 1.0\npair_style dpd/fdt/energy 1.0 5\npair_coeff 1 1 25.0 0.0 0.0 1.0\n\
                  fix 1 all shardlow\nfix 2 all nve\nfix 3 all eos/cv 10.0\ncompute c all chunk/atom bin/3d x lower 3 y lower 3 z lower 3 units box\n\
                  fix a all ave/chunk 5 1 5 c density/number file p.txt\nrun 10\nunfix a\nrun 10\n";
    std::fs::write(dir.join("in.x"), script).unwrap();
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(dir.join("p.txt")).unwrap();
    assert!(text.starts_with("# Chunk-averaged data for fix a and group all\n# Timestep Number-of-chunks Total-count\n# Chunk Coord1 Coord2 Coord3 Ncount density/number\n"), "{text}");
    let steps: Vec<&str> = text.lines().filter(|l| !l.starts_with(' ') && !l.starts_with('#')).collect();
    assert_eq!(steps, ["0 64 2197", "5 64 2197", "10 64 2197"]);
}

const MSD: &str = "in.dpde-msd";

/// compute msd with and without `com yes`, of all particles and of a group, over 100 steps
/// of the deterministic scene in which particles cross the boundaries: the same values as
/// LAMMPS's to 1e-9 relative (the trajectories' own agreement).
#[test]
fn msd_matches_lammps() {
    let (dl, dg) = (tempdir("msd-lammps"), tempdir("msd-gendpde"));
    stage_inputs(&dl, MSD);
    stage_inputs(&dg, MSD);
    let l = parse_thermo(&expect_success("LAMMPS", &run_lammps(&dl, MSD, &[])), "Step");
    let out = gendpde(&dg, &["run", MSD, "-log", "none"]);
    assert!(out.status.success(), "gendpde failed:\n{}", stderr(&out));
    let g = parse_thermo(&String::from_utf8_lossy(&out.stdout), "Step");
    assert_eq!(g.len(), 11);
    assert_eq!(g.len(), l.len());
    assert!(g[10][4] > 0.5, "the particles hardly moved: <dr^2> = {}", g[10][4]);
    let mut worst: f64 = 0.0;
    for (a, b) in g.iter().zip(&l) {
        for (x, y) in a.iter().zip(b) {
            // step 0 with com yes: LAMMPS's round-off leaves 4e-29, gendpde's exact sums 0
            assert!((x - y).abs() <= 1e-9 * x.abs().max(y.abs()) + 1e-20, "step {}: {x} vs LAMMPS {y}", a[0]);
            if x.abs().max(y.abs()) > 1e-20 {
                worst = worst.max((x - y).abs() / x.abs().max(y.abs()));
            }
        }
    }
    eprintln!("msd: worst relative difference from LAMMPS {worst:.1e}");
}

/// The msd values do not depend on the number of ranks.
#[cfg(feature = "mpi")]
#[test]
fn msd_is_rank_independent() {
    same_on_1_2_3_ranks("msd-ranks", MSD, |_, out| parse_thermo(&String::from_utf8_lossy(&out.stdout), "Step").iter().map(|r| format!("{r:?}\n")).collect());
}

#[test]
fn msd_errors_name_the_line() {
    for (line, expected) in [
        ("compute m all msd com maybe", "in.x:4: compute: expected yes or no for com, got 'maybe'"),
        ("compute m all msd average yes", "in.x:4: compute: keyword average: only the default, average no, is supported"),
        ("compute m all msd start 0", "in.x:4: compute: unknown keyword 'start'; known: com"),
        ("compute m none msd", "in.x:4: compute: no group 'none'"),
    ] {
        expect_error(line, expected);
    }
    let dir = tempdir("msd-nobox");
    std::fs::write(dir.join("in.x"), "units lj\ncompute m all msd\n").unwrap();
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    assert!(stderr(&out).contains("in.x:2: compute: compute msd before the box exists"), "{}", stderr(&out));
}
