//! LAMMPS scripts run unchanged (issue 17, part 2): compute chunk/atom and fix ave/chunk
//! (scripts/lammps/in.dpde-profile), compute msd (in.dpde-msd), compute ke/atom, pe/atom
//! and reduce (in.dpde-reduce) beside the reference
//! LAMMPS (../shared/lammps), with their error messages and their independence of the rank
//! count.

use crate::common;

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
        ("fix a all ave/chunk 1 1 1 c c_pe", "in.x:5: fix: value 'c_pe': not a per-atom compute"),
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

/// Runs `input` in LAMMPS and gendpde; asserts the same thermo rows (`rows` of them, the
/// step `moved` column positive at the end) to 1e-9 relative, the trajectories' own
/// agreement, and returns the worst relative difference.
fn same_thermo_as_lammps(name: &str, input: &str, rows: usize) -> f64 {
    let (dl, dg) = (tempdir(&format!("{name}-lammps")), tempdir(&format!("{name}-gendpde")));
    stage_inputs(&dl, input);
    stage_inputs(&dg, input);
    let l = parse_thermo(&expect_success("LAMMPS", &run_lammps(&dl, input, &[])), "Step");
    let out = gendpde(&dg, &["run", input, "-log", "none"]);
    assert!(out.status.success(), "gendpde failed:\n{}", stderr(&out));
    let g = parse_thermo(&String::from_utf8_lossy(&out.stdout), "Step");
    assert_eq!(g.len(), rows);
    assert_eq!(g.len(), l.len());
    let mut worst: f64 = 0.0;
    for (a, b) in g.iter().zip(&l) {
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(b) {
            // msd at step 0 with com yes: LAMMPS's round-off leaves 4e-29, gendpde's exact sums 0
            assert!((x - y).abs() <= 1e-9 * x.abs().max(y.abs()) + 1e-20, "{input}: step {}: {x} vs LAMMPS {y}", a[0]);
            if x.abs().max(y.abs()) > 1e-20 {
                worst = worst.max((x - y).abs() / x.abs().max(y.abs()));
            }
        }
    }
    worst
}

/// compute msd with and without `com yes`, of all particles and of a group, and compute
/// com of the group, over 100 steps of the deterministic scene in which particles cross
/// the boundaries: the same values as LAMMPS's.
#[test]
fn msd_and_com_match_lammps() {
    let worst = same_thermo_as_lammps("msd", MSD, 11);
    eprintln!("msd: worst relative difference from LAMMPS {worst:.1e}");
}

const REDUCE: &str = "in.dpde-reduce";

/// compute reduce in every mode over ke/atom, pe/atom (pairwise: half pair energies),
/// positions, velocities and forces, of all particles and of a group, with thermo_modify
/// norm yes: the same values as LAMMPS's.
#[test]
fn reduce_of_per_atom_computes_matches_lammps() {
    let worst = same_thermo_as_lammps("reduce", REDUCE, 6);
    eprintln!("reduce: worst relative difference from LAMMPS {worst:.1e}");
}

/// For GenDPDE, whose pe is the sum of the internal energies, pe/atom is u: its sum is pe.
#[test]
fn pe_atom_of_gendpde_sums_to_pe() {
    let dir = tempdir("pe-atom-gendpde");
    let script = "units lj\nlattice sc 0.5\nregion box block 0 14 0 14 0 14\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
                  velocity all create 1.5 4928459 dist gaussian\nset group all theta 1.5\npair_style gendpde 4.0 4928459\npair_coeff * * 4.5 1.0\n\
                  fix eos all eos/vdw 60.0 2.4682 1.4142 excess\nfix rev all nve/gendpde\nfix ssa all shardlow\ntimestep 0.01\n\
                  compute pe all pe/atom\ncompute s all reduce sum c_pe\ncompute ke all ke/atom\ncompute k all reduce sum c_ke\n\
                  thermo 5\nthermo_style custom step pe c_s ke c_k\nthermo_modify norm no format float %.17g\nrun 10\n";
    std::fs::write(dir.join("in.x"), script).unwrap();
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows = parse_thermo(&String::from_utf8_lossy(&out.stdout), "Step");
    assert_eq!(rows.len(), 3);
    for r in rows {
        assert!((r[1] - r[2]).abs() <= 1e-12 * r[1].abs(), "pe {} vs sum of pe/atom {}", r[1], r[2]);
        assert!((r[3] - r[4]).abs() <= 1e-12 * r[3].abs(), "ke {} vs sum of ke/atom {}", r[3], r[4]);
    }
}

/// The msd and reduce values do not depend on the number of ranks.
#[cfg(feature = "mpi")]
#[test]
fn msd_and_reduce_are_rank_independent() {
    for input in [MSD, REDUCE] {
        same_on_1_2_3_ranks("thermo-ranks", input, |_, out| parse_thermo(&String::from_utf8_lossy(&out.stdout), "Step").iter().map(|r| format!("{r:?}\n")).collect());
    }
}

#[test]
fn reduce_errors_name_the_line() {
    let k = "compute ke all ke/atom\ncompute t all temp\n";
    for (line, expected) in [
        ("compute r all reduce total c_ke", "in.x:6: compute: mode 'total': expected sum, sumsq, sumabs, min, max, ave, avesq or aveabs"),
        ("compute r all reduce sum", "in.x:6: compute: missing argument: expected inputs (x, y, z, vx, vy, vz, fx, fy, fz, c_ID, v_name)"),
        ("compute r all reduce sum c_nope", "in.x:6: compute: Compute ID nope for compute reduce does not exist"),
        ("compute r all reduce sum c_t", "in.x:6: compute: Compute reduce compute t does not calculate per-atom values"),
        ("compute r all reduce sum mass", "in.x:6: compute: input 'mass': expected x, y, z, vx, vy, vz, fx, fy, fz, c_ID of a per-atom compute or v_name of an atom-style variable"),
        ("compute r all reduce max c_ke replace 1 2", "in.x:6: compute: keyword replace is not supported"),
        ("compute p all pe/atom angle kspace charge", "in.x:6: compute: unknown keyword 'charge'; known: pair, bond, angle, dihedral, improper, kspace, fix"),
        ("compute p nogroup ke/atom", "in.x:6: compute: no group 'nogroup'"),
    ] {
        expect_error(&format!("{k}{line}"), expected);
    }
}

#[test]
fn msd_errors_name_the_line() {
    for (line, expected) in [
        ("compute m all msd com maybe", "in.x:4: compute: expected yes or no for com, got 'maybe'"),
        ("compute m all msd average yes", "in.x:4: compute: keyword average: only the default, average no, is supported"),
        ("compute m all msd start 0", "in.x:4: compute: unknown keyword 'start'; known: com"),
        ("compute m none msd", "in.x:4: compute: no group 'none'"),
        ("compute c none com", "in.x:4: compute: no group 'none'"),
        ("compute c all com extra", "in.x:4: compute: unexpected argument"),
    ] {
        expect_error(line, expected);
    }
    let dir = tempdir("msd-nobox");
    std::fs::write(dir.join("in.x"), "units lj\ncompute m all msd\n").unwrap();
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    assert!(stderr(&out).contains("in.x:2: compute: compute msd before the box exists"), "{}", stderr(&out));
}
