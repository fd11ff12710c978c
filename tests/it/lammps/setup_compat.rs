//! Set-up commands as the reference LAMMPS runs them (issue 38, part 3): create_atoms
//! random's positions and keywords, the static group styles, boxes shorter than two list
//! radii, and `gendpde check` evaluating what a run evaluates at set-up.

use crate::common;

use common::lammps::{expect_success, parse_dump, run_lammps, DumpSnapshot};
use common::{gendpde, tempdir};
use std::path::PathBuf;
use std::process::Output;

/// A fresh directory `name` holding `script` as `in.x`.
fn stage(name: &str, script: &str) -> PathBuf {
    let dir = tempdir(name);
    std::fs::write(dir.join("in.x"), script).unwrap();
    dir
}

fn text(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr)
}

/// Runs `script` in LAMMPS (which must succeed); returns its directory and screen output.
fn lammps(name: &str, script: &str) -> (PathBuf, String) {
    let dir = stage(&format!("{name}-lammps"), script);
    let out = expect_success("LAMMPS", &run_lammps(&dir, "in.x", &[]));
    (dir, out)
}

/// Runs `script` in gendpde on `np` ranks (which must succeed); returns its directory and
/// screen output.
fn gendpde_on(np: usize, name: &str, script: &str) -> (PathBuf, String) {
    let dir = stage(&format!("{name}-gendpde-{np}"), script);
    let args = ["run", "in.x", "-log", "none"];
    let out = if np == 1 { gendpde(&dir, &args) } else { common::mpirun(np, &dir, &args) };
    assert!(out.status.success(), "gendpde on {np} ranks failed:\n{}", text(&out));
    (dir, text(&out))
}

/// The only snapshot of the dump `name` in `dir`.
fn snapshot(dir: &std::path::Path, name: &str) -> DumpSnapshot {
    let path = dir.join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    parse_dump(&text).pop().expect("a snapshot")
}

/// Runs `script` (which must fail) in gendpde; its message must contain `expected`.
fn expect_error(name: &str, script: &str, expected: &str) {
    let dir = stage(name, script);
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    assert!(!out.status.success(), "accepted:\n{script}");
    assert!(text(&out).contains(expected), "expected '{expected}', got {}\nfor:\n{script}", text(&out));
}

/// create_atoms random with a sphere, `overlap` against earlier particles and its own
/// (in lattice units: scaled by the x spacing 1.25), `maxtry` that leaves some out, and a
/// lattice with `basis` types: LAMMPS's particles, to the last bit, per tag, on 1 and 3
/// ranks.
const CREATE: &str = "units lj
lattice bcc 1.024
region box block 0 4 0 3 0 3
create_box 3 box
create_atoms 1 box basis 2 2
region ball sphere 6 4 3 2.5 units box
region slab block 1 3 INF INF 0.5 2.5 units box
lattice none 1.25
create_atoms 3 random 150 99 ball overlap 0.5 maxtry 40
create_atoms 2 random 40 1234 slab overlap 0.3 units box
create_atoms 1 random 20 7 NULL maxtry 1
mass * 1.0
write_dump all custom create.dump id type x y z modify format float %.17g
";

#[test]
fn create_atoms_draws_lammps_particles() {
    let (dl, out) = lammps("create", CREATE);
    assert!(out.contains("WARNING: Only inserted"), "maxtry 40 should leave some out:\n{out}");
    let l = snapshot(&dl, "create.dump");
    let created: Vec<usize> = (1..=3).map(|t| l.atoms.iter().filter(|(_, r)| r[0] == t as f64).count()).collect();
    // 36 + 20 of type 1, 36 + 40 of type 2 (the basis), fewer than 150 of type 3
    assert!(created[0] == 56 && created[1] == 76 && created[2] > 0 && created[2] < 150, "{created:?}");
    for np in [1, 3] {
        let (dg, out) = gendpde_on(np, "create", CREATE);
        assert!(out.contains("Only inserted"), "{out}");
        let g = snapshot(&dg, "create.dump");
        assert_eq!(g.columns, l.columns);
        assert_eq!(g.atoms.len(), l.atoms.len(), "{np} ranks");
        for (a, b) in g.atoms.iter().zip(&l.atoms) {
            assert_eq!(a, b, "{np} ranks: particle {} differs", b.0);
        }
    }
}

#[test]
fn create_atoms_keywords_are_checked_as_lammps() {
    let head = "units lj\nlattice sc 1.0\nregion box block 0 4 0 4 0 4\ncreate_box 2 box\n";
    for (line, expected) in [
        ("create_atoms 1 box basis 2 1", "in.x:5: create_atoms: Out of range basis setting '2 1' in create_atoms command"),
        ("create_atoms 1 box basis 1 3", "in.x:5: create_atoms: Out of range basis setting '1 3' in create_atoms command"),
        ("create_atoms 1 region box maxtry 5", "in.x:5: create_atoms: Create_atoms maxtry can only be used with random style"),
        ("create_atoms 1 random 5 3 NULL maxtry 0", "in.x:5: create_atoms: create_atoms maxtry must be positive"),
        ("create_atoms 1 random 5 3 NULL units cell", "in.x:5: create_atoms: Unknown create_atoms units option cell"),
        ("create_atoms 1 random 5 3 NULL mol w 4", "in.x:5: create_atoms: create_atoms keyword 'mol' is not supported"),
        ("create_atoms 1 box ratio 0.5 4", "in.x:5: create_atoms: create_atoms keyword 'ratio' is not supported"),
        ("create_atoms 1 box spin 4", "in.x:5: create_atoms: Illegal create_atoms command option spin"),
    ] {
        expect_error("create-keywords", &format!("{head}{line}\n"), expected);
    }
}

/// Every static group style, on types set by region: LAMMPS's "N atoms in group ID"
/// lines, in order, on 1 and 3 ranks (subtract also takes out the group's own earlier
/// members that are in the other groups, as LAMMPS does).
const GROUPS: &str = "units lj
lattice sc 1.0
region box block 0 4 0 4 0 4
create_box 3 box
create_atoms 1 box
region left block 0 1.5 INF INF INF INF
region right block 2.5 4 INF INF INF INF
set region left type 2
set region right type 3
group one region left
group two type 2 3
group three id 1:40:3 50 52:55
group four id <> 10 20
group five type != 1
group s subtract all one two
group u union one two
group i intersect two five three
group e empty
variable v atom x>2.5&&y<1.5
group var variable v
group three clear
group three id 60:64
group one type 1
group s subtract s five
group two union two e
group t id >= 60
group t intersect t three
group t type 1:3:2
group all region left
group s delete
group s static
group neg id -5:-1
";

/// The "N atoms in group ID" lines of a screen output.
fn group_lines(out: &str) -> Vec<&str> {
    out.lines().filter(|l| l.contains(" atoms in group ")).collect()
}

#[test]
fn group_styles_select_lammps_members() {
    let (_, l) = lammps("groups", GROUPS);
    let expected = group_lines(&l);
    assert_eq!(expected.len(), 20, "{l}");
    assert!(expected.contains(&"15 atoms in group i") && expected.contains(&"8 atoms in group var"), "{expected:?}");
    for np in [1, 3] {
        let (_, g) = gendpde_on(np, "groups", GROUPS);
        assert_eq!(group_lines(&g), expected, "{np} ranks");
    }
}

#[test]
fn group_errors_are_lammps_messages() {
    let head = "units lj\nlattice sc 1.0\nregion box block 0 4 0 4 0 4\ncreate_box 2 box\ncreate_atoms 1 box\ngroup one id 1:9\nvariable e equal 2\n";
    for (line, expected) in [
        ("group q union", "in.x:8: group: Illegal group union command: missing argument(s)"),
        ("group q subtract one", "in.x:8: group: Illegal group subtract command: missing argument(s)"),
        ("group q intersect one", "in.x:8: group: Illegal group intersect command: missing argument(s)"),
        ("group q subtract one xx", "in.x:8: group: Group ID xx does not exist"),
        ("group q molecule 1", "in.x:8: group: Group molecule command requires atom attribute molecule"),
        ("group q include molecule", "in.x:8: group: Group include molecule command requires atom attribute molecule"),
        ("group q variable nov", "in.x:8: group: Variable name nov for group does not exist"),
        ("group q variable e", "in.x:8: group: Variable e for group is invalid style"),
        ("group all clear", "in.x:8: group: Cannot clear group all"),
        ("group all delete", "in.x:8: group: Cannot delete group all"),
        ("group nn clear", "in.x:8: group: Could not find group clear group ID nn"),
        ("group nn delete", "in.x:8: group: Could not find group delete group ID nn"),
        ("group q empty x", "in.x:8: group: Illegal group empty command"),
        ("group q region nor", "in.x:8: group: Region nor for group region does not exist"),
        ("group q type 1*2", "in.x:8: group: Incorrect range string '1*2': Not a valid integer number: '1*2'"),
        ("group q type 1:x", "in.x:8: group: Incorrect range string '1:x': Syntax error"),
        ("group q type 1:3:0", "in.x:8: group: Illegal range increment value"),
        ("group q type <= 2.5", "in.x:8: group: Expected integer parameter instead of '2.5' in input script or data file"),
        ("group q id < 6 7", "in.x:8: group: Illegal group command"),
        ("group q dynamic all region box", "in.x:8: group: group dynamic is not supported"),
        ("group q xxx", "in.x:8: group: Illegal group command: unknown style 'xxx'"),
    ] {
        expect_error("group-errors", &format!("{head}{line}\n"), expected);
    }
    expect_error("group-nobox", "group q empty\n", "in.x:1: group: Group command before simulation box is defined");
}

/// LAMMPS's dpd with velocity Verlet in a box of 10 with `neighbor 5.0 bin` (cutoff +
/// skin = 6 > 10 / 2): gendpde lists with a shorter skin. No noise (T = 0), so thermo
/// and positions agree with LAMMPS to round-off over 50 steps; bit-identical on 1 and 3
/// ranks.
const SMALL_BOX: &str = "units lj
comm_modify vel yes
region box block 0 10 0 10 0 10
create_box 1 box
create_atoms 1 random 3000 4321 NULL
mass 1 1.0
velocity all create 1.0 87287 loop geom
pair_style dpd 0.0 1.0 34387
pair_coeff 1 1 25.0 4.5
neighbor 5.0 bin
neigh_modify one 4000 page 40000
timestep 0.01
fix 1 all nve
thermo 10
thermo_style custom step temp pe ke etotal press pxx pyy
thermo_modify format float %.17g
run 50
write_dump all custom small.dump id x y z vx vy vz modify format float %.17g
";

#[test]
fn small_box_runs_as_lammps() {
    let (dl, l) = lammps("small-box", SMALL_BOX);
    let (dg, g) = gendpde_on(1, "small-box", SMALL_BOX);
    assert!(g.contains("neighbor skin 5 does not fit the box"), "{g}");
    let (tl, tg) = (common::lammps::parse_thermo(&l, "Step"), common::lammps::parse_thermo(&g, "Step"));
    assert_eq!((tl.len(), tg.len()), (6, 6));
    let mut worst: f64 = 0.0;
    for (a, b) in tl.iter().zip(&tg) {
        for (x, y) in a.iter().zip(b) {
            worst = worst.max((x - y).abs() / x.abs().max(1e-300));
        }
    }
    let (dr, dv) = common::lammps::compare_dumps(&dg.join("small.dump"), &dl.join("small.dump"));
    eprintln!("thermo {worst:.1e}, positions {dr:.1e} of the box, velocities {dv:.1e}");
    assert!(worst < 1e-12 && dr < 1e-12 && dv < 1e-11, "thermo {worst:.1e}, positions {dr:.1e}, velocities {dv:.1e}");
    let (d3, g3) = gendpde_on(3, "small-box", SMALL_BOX);
    assert_eq!(common::lammps::parse_thermo(&g3, "Step"), tg, "3 ranks");
    assert!(std::fs::read(d3.join("small.dump")).unwrap() == std::fs::read(dg.join("small.dump")).unwrap(), "3 ranks: another dump");
}

/// Fix shardlow keeps LAMMPS's refusal of a box shorter than 2 (cutoff + skin); a box
/// shorter than two cutoffs says what LAMMPS would do.
#[test]
fn small_box_refusals_say_why() {
    let head = "units lj\natom_style dpd\ncomm_modify vel yes\nregion box block 0 10 0 10 0 10\ncreate_box 1 box\n\
                create_atoms 1 random 300 4321 NULL\nmass 1 1.0\ntimestep 0.01\n";
    let shardlow = "pair_style dpd/fdt 1.0 1.0 34387\npair_coeff 1 1 25.0 4.5 1.0\nneighbor 5.0 bin\nfix 1 all shardlow\nfix 2 all nve\nrun 5\n";
    expect_error(
        "small-shardlow",
        &format!("{head}{shardlow}"),
        "in.x:14: run: Shardlow algorithm requires sub-domain length > 2*(rcut+skin). Either reduce the number of processors \
         requested, or change the cutoff/skin: rcut= 12 bbx= 10 bby= 10 bbz= 10",
    );
    let short = head.replace("block 0 10 0 10 0 10", "block 0 1.5 0 10 0 10");
    expect_error(
        "small-cutoff",
        &format!("{short}pair_style dpd 1.0 1.0 34387\npair_coeff 1 1 25.0 4.5\nneighbor 0.3 bin\nfix 2 all nve\nrun 5\n"),
        "in.x:13: run: box length 1.5 is shorter than 2 x cutoff = 2: LAMMPS runs such a box",
    );
}

/// `gendpde check` evaluates the set-up's thermo line as the run does: a thermo variable
/// naming an unknown keyword, or one that fails at step 0, fails both with the same
/// message; a sound line passes both.
#[test]
fn check_evaluates_the_setup_thermo_line() {
    let script = |vars: &str| {
        format!(
            "units lj\ncomm_modify vel yes\nregion box block 0 5 0 5 0 5\ncreate_box 1 box\ncreate_atoms 1 random 100 7 NULL\n\
             mass 1 1.0\npair_style dpd 1.0 1.0 3\npair_coeff 1 1 25.0 4.5\nfix 1 all nve\n{vars}\
             thermo_style custom step temp v_a\nrun 5\n"
        )
    };
    let outcome = |name: &str, text: &str, mode: &str| {
        let dir = stage(name, text);
        let out = if mode == "run" { gendpde(&dir, &["run", "in.x", "-log", "none"]) } else { gendpde(&dir, &["check", "in.x"]) };
        (out.status.success(), String::from_utf8_lossy(&out.stderr).lines().find(|l| l.starts_with("ERROR")).unwrap_or_default().to_string())
    };
    for (vars, expected) in [
        ("variable a equal pxy\n", "ERROR: in.x:12: run: thermo keyword v_a: unknown identifier 'pxy' in expression"),
        ("variable a equal 1.0/step\n", "ERROR: in.x:12: run: thermo keyword v_a: division by zero"),
        ("variable a equal v_b\n", "ERROR: in.x:12: run: thermo keyword v_a: "),
    ] {
        let text = script(vars);
        let (run_ok, run_err) = outcome("check-run", &text, "run");
        let (check_ok, check_err) = outcome("check-check", &text, "check");
        assert!(!run_ok && !check_ok, "{vars}: run {run_ok}, check {check_ok}");
        assert!(run_err.starts_with(expected), "{vars}: {run_err}");
        assert_eq!(check_err, run_err, "{vars}");
    }
    let text = script("variable a equal 2*temp\n");
    assert_eq!((outcome("check-ok", &text, "run").0, outcome("check-ok", &text, "check").0), (true, true));
}

/// `create_atoms single`, in lattice and box units, outside the box (none created) and
/// remapped into it: LAMMPS's particles and tags.
#[test]
fn create_atoms_single_places_lammps_particles() {
    let script = "units lj\nlattice sc 0.5\nregion box block 0 4 0 4 0 4\ncreate_box 2 box\n\
                  create_atoms 1 single 1.5 2.25 0.5\ncreate_atoms 2 single 5.5 -1.0 0.5 remap yes\n\
                  create_atoms 2 single 5.5 1.0 0.5\ncreate_atoms 1 single 3.0 3.0 3.0 units box\n\
                  create_atoms 1 single 9.0 -1.0 7.9 units box remap yes\nmass * 1.0\n\
                  write_dump all custom s.dump id type x y z modify format float %.17g\n";
    let (dl, _) = lammps("single", script);
    let (dg, _) = gendpde_on(1, "single", script);
    let (g, l) = (snapshot(&dg, "s.dump"), snapshot(&dl, "s.dump"));
    assert_eq!(l.atoms.len(), 4);
    assert_eq!(g.atoms, l.atoms);
}

/// A lattice region outside the box creates no particle, as in LAMMPS; a random one is
/// LAMMPS's error.
#[test]
fn create_atoms_outside_the_box() {
    let head = "units lj\nlattice sc 1.0\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\nregion far block 10 12 0 1 0 1 units box\n";
    let lattice = format!("{head}create_atoms 1 region far\ncreate_atoms 1 box\nmass 1 1.0\nwrite_dump all custom far.dump id x y z\n");
    let (dl, _) = lammps("far", &lattice);
    let (dg, _) = gendpde_on(1, "far", &lattice);
    assert_eq!((snapshot(&dg, "far.dump").atoms.len(), snapshot(&dl, "far.dump").atoms.len()), (64, 64));
    expect_error("far-random", &format!("{head}create_atoms 1 random 5 3 far\n"), "in.x:6: create_atoms: No overlap of box and region for create_atoms");
}

/// delete_atoms of a region (compress yes: LAMMPS's renumbering) and of a group that
/// empties one rank's part of the box (compress no), then a run: LAMMPS's particles, IDs
/// and thermo; the same on 3 ranks, one of which owns no particle.
const DELETE: &str = "units lj
comm_modify vel yes
lattice fcc 3.0
region box block 0 4 0 4 0 4
create_box 2 box
create_atoms 1 box
region half block 0 2 INF INF INF INF
set region half type 2
mass * 1.0
region hole sphere 2 2 2 1.0
delete_atoms region hole
region slab block 3 4 INF INF INF INF
group s region slab
delete_atoms group s compress no
pair_style dpd 1.0 1.0 4928
pair_coeff * * 25.0 0.0
fix nve all nve
velocity all create 1.0 87287 loop geom
thermo_style custom step atoms temp press
thermo_modify format float %.17g
run 20
write_dump all custom del.dump id type x y z vx vy vz modify format float %.17g
";

#[test]
fn delete_atoms_removes_and_renumbers_as_lammps() {
    let (dl, l) = lammps("delete", DELETE);
    let (dg, g) = gendpde_on(1, "delete", DELETE);
    for line in ["Deleted 19 atoms, new total = 237", "Deleted 63 atoms, new total = 174"] {
        assert!(l.contains(line) && g.contains(line), "{line}");
    }
    let (tl, tg) = (common::lammps::parse_thermo(&l, "Step"), common::lammps::parse_thermo(&g, "Step"));
    assert_eq!(tl.len(), tg.len());
    for (a, b) in tl.iter().zip(&tg) {
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= 1e-12 * x.abs().max(1.0), "thermo: LAMMPS {a:?} gendpde {b:?}");
        }
    }
    let (sl, sg) = (snapshot(&dl, "del.dump"), snapshot(&dg, "del.dump"));
    assert_eq!(sl.atoms.len(), 174);
    for ((il, vl), (ig, vg)) in sl.atoms.iter().zip(&sg.atoms) {
        assert_eq!((il, vl[0]), (ig, vg[0]), "IDs and types");
        for (x, y) in vl.iter().zip(vg) {
            assert!((x - y).abs() <= 1e-10 * x.abs().max(1.0), "particle {il}: LAMMPS {vl:?} gendpde {vg:?}");
        }
    }
    let (d3, g3) = gendpde_on(3, "delete", DELETE);
    assert_eq!(common::lammps::parse_thermo(&g3, "Step"), tg, "3 ranks");
    assert!(std::fs::read(d3.join("del.dump")).unwrap() == std::fs::read(dg.join("del.dump")).unwrap(), "3 ranks: another dump");
    let head = "units lj\nlattice fcc 3.0\nregion box block 0 2 0 2 0 2\ncreate_box 1 box\ncreate_atoms 1 box\n";
    expect_error("delete-nogroup", &format!("{head}delete_atoms group nope\n"), "in.x:6: delete_atoms: Could not find delete_atoms group ID nope");
    expect_error("delete-overlap", &format!("{head}delete_atoms overlap 0.5 all all\n"), "delete_atoms overlap is not supported");
    expect_error("delete-msd", &format!("{head}compute m all msd\ndelete_atoms region box\n"), "compute m msd, which holds values by particle ID");
}
