//! `velocity` and `set` beside the reference LAMMPS (issue 17, item 7): the random
//! velocities of every `loop` and `dist`, the styles set/scale/ramp/zero with sum, rot,
//! temp and units, and the set keywords (type/fraction picks LAMMPS's particles) give
//! LAMMPS's per-particle values to round-off; the same on 1 and 3 ranks; errors name
//! the line.

use crate::common;

use common::lammps::{expect_success, parse_dump, run_lammps, DumpSnapshot};
use common::{expect_errors, gendpde, mpirun, random_data_file, tempdir};
use std::path::{Path, PathBuf};

fn stage(name: &str, script: &str) -> PathBuf {
    let dir = tempdir(name);
    std::fs::write(dir.join("in.x"), script).unwrap();
    std::fs::write(dir.join("data.v"), random_data_file(60, &[1.0, 2.5, 0.7], true, 88172645463325252)).unwrap();
    dir
}

fn dump(path: &Path) -> DumpSnapshot {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    parse_dump(&text).pop().expect("a snapshot")
}

/// Runs `script` (which writes `out.dump` and `out.data`) in gendpde and LAMMPS; returns
/// the largest difference of every dump column and of the data files' dpdTheta.
fn compare(name: &str, script: &str) -> Vec<(String, f64)> {
    let dg = stage(&format!("{name}-gendpde"), script);
    let out = gendpde(&dg, &["run", "in.x", "-log", "none"]);
    assert!(out.status.success(), "gendpde failed on {name}:\n{}", String::from_utf8_lossy(&out.stderr));
    let dl = stage(&format!("{name}-lammps"), script);
    expect_success("LAMMPS", &run_lammps(&dl, "in.x", &[]));
    let (g, l) = (dump(&dg.join("out.dump")), dump(&dl.join("out.dump")));
    assert_eq!(g.columns, l.columns);
    assert_eq!(g.atoms.len(), 60);
    let mut diffs: Vec<(String, f64)> = g.columns
        .iter()
        .enumerate()
        .map(|(c, name)| {
            let worst = g.atoms.iter().zip(&l.atoms).map(|((tg, rg), (tl, rl))| {
                assert_eq!(tg, tl);
                (rg[c] - rl[c]).abs()
            });
            (name.clone(), worst.fold(0.0, f64::max))
        })
        .collect();
    let theta = |dir: &Path| -> Vec<f64> {
        let text = std::fs::read_to_string(dir.join("out.data")).unwrap();
        let atoms = text.split("Atoms").nth(1).unwrap().split("Velocities").next().unwrap();
        let mut rows: Vec<(u64, f64)> = atoms.lines().filter_map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (w.len() >= 6).then(|| (w[0].parse().unwrap(), w[2].parse().unwrap()))
        }).collect();
        rows.sort_by_key(|r| r.0);
        rows.into_iter().map(|r| r.1).collect()
    };
    let (tg, tl) = (theta(&dg), theta(&dl));
    assert_eq!(tg.len(), 60);
    diffs.push(("dpdTheta".into(), tg.iter().zip(&tl).map(|(a, b)| ((a - b) / b).abs()).fold(0.0, f64::max)));
    diffs
}

const HEAD: &str = "units lj\natom_style dpd\nread_data data.v\n";
const OUT: &str = "write_dump all custom out.dump id type x y z ix iy iz vx vy vz modify format float %.17g\nwrite_data out.data\n";

fn assert_round_off(name: &str, diffs: &[(String, f64)]) {
    for (col, d) in diffs {
        assert!(*d < 1e-14, "{name}: column {col} differs from LAMMPS by {d:e}");
    }
}

#[test]
fn velocity_create_loops_match_lammps() {
    for lp in ["all", "local", "geom"] {
        for dist in ["uniform", "gaussian"] {
            let script = format!("{HEAD}velocity all create 1.5 4928459 loop {lp} dist {dist}\n{OUT}");
            assert_round_off(&format!("loop {lp} dist {dist}"), &compare(&format!("loop-{lp}-{dist}"), &script));
        }
    }
}

const STYLES: &str = "lattice fcc 0.8
region left block 0 2.5 INF INF INF INF units box
group left region left
compute tl left temp
velocity all create 1.5 4928459 loop geom rot yes dist gaussian
velocity left create 0.5 777 loop geom sum yes mom no temp tl
velocity left ramp vx -0.2 0.3 y 0.5 3.5 sum yes
velocity left ramp vz 0.1 0.4 z 1 2 units box
velocity all set NULL 0.25 NULL sum yes
velocity left set NULL NULL 0.1 units box
velocity all zero angular
velocity all scale 2.0
velocity all zero linear
variable vv atom 0.1*x-0.2*mass+0.5*id/60
velocity left set v_vv NULL NULL sum yes
";

#[test]
fn velocity_styles_match_lammps() {
    assert_round_off("velocity styles", &compare("velocity-styles", &format!("{HEAD}{STYLES}{OUT}")));
}

const SET: &str = "region ball sphere 2.5 1.5 3 1.8 units box
velocity all create 1.5 4928459 loop geom
set type 1 type/fraction 3 0.4 12345
set region ball type/fraction 2 0.5 777
variable tt atom 1+(id%3)
variable xx atom x+0.5*y
set atom 1*10 type v_tt
set atom 11*20 x v_xx vz -0.5 image 1 NULL -2
set group all dpd/theta NULL
set atom 40*50 dpd/theta 2.5 vx 0.3
";

#[test]
fn set_matches_lammps() {
    let diffs = compare("set", &format!("{HEAD}{SET}{OUT}"));
    assert_round_off("set", &diffs);
}

/// loop all and geom, and set type/fraction, give the same particles on 1 and 3 ranks.
#[test]
fn velocity_and_set_are_rank_independent() {
    let script = format!("{HEAD}velocity all create 1.5 4928459 loop all\nvelocity all create 0.7 99 loop geom sum yes dist gaussian rot yes\n{SET}write_dump all custom out.dump id type x y z vx vy vz\n");
    let text = |np: usize| {
        let dir = stage(&format!("ranks-{np}"), &script);
        let out = mpirun(np, &dir, &["run", "in.x", "-log", "none"]);
        assert!(out.status.success(), "{np} ranks:\n{}", String::from_utf8_lossy(&out.stderr));
        std::fs::read_to_string(dir.join("out.dump")).unwrap()
    };
    assert_eq!(text(1), text(3));
}

#[test]
fn velocity_and_set_errors_name_the_line() {
    let cases = [
        ("velocity all create 1.0 0", "the random seed must be in 1..2147483647"),
        ("velocity all create 1.0 5 loop sideways", "expected loop all, local or geom, got 'sideways'"),
        ("velocity all create 1.0 5 bias yes", "bias yes"),
        ("velocity all create 1.0 5 temp nope", "no compute with ID 'nope'"),
        ("velocity all spin 1.0", "unknown velocity style 'spin'"),
        ("velocity all ramp vq 0 1 x 0 1", "expected vx, vy or vz, got 'vq'"),
        ("velocity all ramp vx 0 1 x 2 2", "the ramp's coordinates must differ"),
        ("velocity all set v_nope NULL NULL", "unknown variable 'nope'"),
        ("velocity all zero sideways", "expected linear or angular"),
        ("velocity all scale 1.0", "cannot rescale a temperature of 0"),
        ("region far block 10 11 10 11 10 11 units box\ngroup none region far\nvelocity none create 1.0 5", "the group is empty"),
        ("region far block 10 11 10 11 10 11 units box\ngroup none region far\nvelocity none create 1.0 5 mom no", "cannot rescale a temperature of 0"),
        ("set type 1 type/fraction 2 1.5 4", "a fraction in [0, 1]"),
        ("set type 1 mass 2.0", "no per-particle mass"),
        ("set atom 1 image 1 x 0", "expected an integer or NULL, got 'x'"),
        ("set region nowhere x 1.0", "no region with ID 'nowhere'"),
        ("set mol 1 x 1.0", "no molecule IDs"),
        ("set group all dpd/theta NULL", "is not positive"),
        ("set atom 1 type 7", "is not one of 1..3"),
        ("set atom 1 vx fast", "expected the velocity (a number), got 'fast'"),
        ("set atom 1 charge 1.0", "unknown set keyword 'charge'"),
        ("variable s string abc\nset atom 1 x v_s", "variable 's' is string-style"),
    ];
    expect_errors(HEAD, &cases, |script| stage("errors", script));
}
