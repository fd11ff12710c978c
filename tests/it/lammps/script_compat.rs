//! LAMMPS scripts run unchanged (issue 17, part 1): create_atoms random, compute temp,
//! run_style, atom_modify, the LAMMPS command line, units and thermo keywords, the lines
//! of a LAMMPS log and the messages of misplaced commands; each beside the reference
//! LAMMPS (../shared/lammps) where a number comes out.

use crate::common;

use common::{gendpde, tempdir};
use common::lammps::{expect_success, parse_dump, parse_thermo_blocks, run_lammps, scripts_dir, DumpSnapshot, ThermoBlock};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh directory holding `script` as `in.x` and the data files of scripts/lammps/.
fn stage(name: &str, script: &str) -> PathBuf {
    let dir = tempdir(name);
    std::fs::write(dir.join("in.x"), script).unwrap();
    for entry in std::fs::read_dir(scripts_dir()).unwrap() {
        let name = entry.unwrap().file_name();
        if name.to_string_lossy().starts_with("data.") {
            std::fs::copy(scripts_dir().join(&name), dir.join(&name)).unwrap();
        }
    }
    dir
}

/// Runs `gendpde run in.x` on `script` in a fresh directory.
fn run_script(name: &str, script: &str) -> (PathBuf, Output) {
    let dir = stage(name, script);
    let out = gendpde(&dir, &["run", "in.x", "-log", "none"]);
    (dir, out)
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs `script`, which must fail with a message containing `expected`.
fn expect_error(name: &str, script: &str, expected: &str) {
    let (_, out) = run_script(name, script);
    assert!(!out.status.success(), "accepted:\n{script}");
    assert!(stderr(&out).contains(expected), "expected '{expected}', got {}\nfor:\n{script}", stderr(&out));
}

/// Runs `script` in gendpde (which must succeed) and in LAMMPS; returns both directories
/// and standard outputs.
fn both(name: &str, script: &str) -> ((PathBuf, String), (PathBuf, String)) {
    let (dg, g) = run_script(&format!("{name}-gendpde"), script);
    assert!(g.status.success(), "gendpde failed on {name}:\n{}", stderr(&g));
    let dl = stage(&format!("{name}-lammps"), script);
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
write_dump all custom rand.dump id type x y z modify format float %.17g
";

/// The positions LAMMPS draws for the same seeds, to the last bit, per tag: type 1 fills
/// the box, type 2 the slab 2 <= x <= 5, 1 <= z <= 3.
#[test]
fn create_atoms_random_fills_the_region_as_lammps() {
    let ((dg, _), (dl, _)) = both("random", RANDOM);
    let (g, l) = (dump(&dg.join("rand.dump")), dump(&dl.join("rand.dump")));
    assert_eq!(g.atoms.len(), 800);
    assert_eq!(g.columns, l.columns);
    assert_eq!(g.atoms, l.atoms, "gendpde's positions differ from LAMMPS's");
    let limits = [(1, 500, [0.0, 0.0, 0.0], [10.0, 8.0, 6.0]), (2, 300, [2.0, 0.0, 1.0], [5.0, 8.0, 3.0])];
    for (c, (t, n, lo, hi)) in census(&g).iter().zip(limits) {
        assert_eq!((c.0, c.1), (t, n));
        assert!((0..3).all(|d| c.2[d] >= lo[d] && c.3[d] <= hi[d]), "type {t}: {c:?}");
    }
}

/// Syntax and errors of create_atoms random.
#[test]
fn create_atoms_random_errors_name_the_line() {
    let head = "units lj\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\n";
    for (line, expected) in [
        ("create_atoms 1 random 10 0 NULL", "in.x:4: create_atoms: Illegal create_atoms random seed 0"),
        ("create_atoms 1 random 10 5", "in.x:4: create_atoms: missing argument: expected a region ID or NULL"),
        ("create_atoms 1 random ten 5 NULL", "in.x:4: create_atoms: expected the number of particles (a non-negative integer), got 'ten'"),
        ("create_atoms 1 random 10 5 nowhere", "in.x:4: create_atoms: no region with ID 'nowhere'"),
        ("create_atoms 1 random 10 5 NULL overlap 0", "in.x:4: create_atoms: Illegal create_atoms overlap value: 0"),
        ("create_atoms 1 random 10 5 NULL subset 3 7", "in.x:4: create_atoms: create_atoms keyword 'subset' is not supported"),
        ("create_atoms 1 box overlap 0.5", "in.x:4: create_atoms: Create_atoms overlap can only be used with random style"),
        ("region far block 10 12 0 1 0 1 units box\ncreate_atoms 1 random 10 5 far", "in.x:5: create_atoms: No overlap of box and region for create_atoms"),
        ("create_atoms 2 random 10 5 NULL", "in.x:4: create_atoms: type 2 is outside 1..1"),
    ] {
        expect_error("random-errors", &format!("{head}{line}\n"), expected);
    }
    expect_error("random-nobox", "create_atoms 1 random 10 5 NULL\n", "in.x:1: create_atoms: create_atoms before the box exists");
}

/// Every rank replays the whole stream: the same particles on 1, 2 and 3 ranks.
#[cfg(feature = "mpi")]
#[test]
fn create_atoms_random_is_rank_independent() {
    let dir = tempdir("random-ranks");
    std::fs::write(dir.join("in.x"), RANDOM).unwrap();
    let mut first: Option<String> = None;
    for np in [1, 2, 3] {
        let out = common::mpirun(np, &dir, &["run", "in.x", "-log", "none"]);
        assert!(out.status.success(), "{np} ranks: {}", stderr(&out));
        let text = std::fs::read_to_string(dir.join("rand.dump")).unwrap();
        assert_eq!(parse_dump(&text)[0].atoms.len(), 800);
        match &first {
            None => first = Some(text),
            Some(f) => assert!(*f == text, "{np} ranks differ from 1 rank"),
        }
    }
}

/// The last thermo block of a log or screen output.
fn last_block(text: &str) -> ThermoBlock {
    parse_thermo_blocks(text, "Step").pop().expect("a thermo block")
}

/// Every column of every row of two thermo blocks agrees to `rel` relative (of the
/// column's largest magnitude); returns the largest relative difference.
fn compare_blocks(g: &ThermoBlock, l: &ThermoBlock, rel: f64) -> f64 {
    assert_eq!(g.header, l.header);
    assert_eq!(g.rows.len(), l.rows.len());
    let mut worst: f64 = 0.0;
    for (c, name) in g.header.iter().enumerate() {
        let scale = l.rows.iter().map(|r| r[c].abs()).fold(0.0, f64::max).max(1e-300);
        for (rg, rl) in g.rows.iter().zip(&l.rows) {
            let d = (rg[c] - rl[c]).abs() / scale;
            assert!(d <= rel, "{name} at step {}: gendpde {} LAMMPS {}", rl[0], rg[c], rl[c]);
            worst = worst.max(d);
        }
    }
    worst
}

/// The deterministic DPDE scene of scripts/lammps/in.dpde-deterministic (conservative
/// force only) with a temperature of half the box: `thermo_modify temp` makes temp, ke,
/// etotal and the pressure's kinetic part those of the group, as in LAMMPS.
const TEMP: &str = "units lj
atom_style dpd
comm_modify vel yes
read_data data.dpde-small
mass 1 1.0
pair_style dpd/fdt/energy 1.0 34387
pair_coeff 1 1 25.0 0.0 0.0 1.0
neighbor 0.3 bin
neigh_modify every 1 delay 0 check no
timestep 0.01
region half block 0 4.5 INF INF INF INF units box
group half region half
compute th half temp
compute tall all temp
compute_modify tall extra/dof 0
variable t equal temp
thermo 10
thermo_style custom step temp c_th c_tall ke etotal press pxx pzz v_t
thermo_modify temp th norm no format float %.17g
fix 1 all shardlow
fix 2 all nve
fix 3 all eos/cv 10.0
run 50
";

#[test]
fn compute_temp_of_a_group_matches_lammps() {
    let ((_, g), (_, l)) = both("temp", TEMP);
    let (g, l) = (last_block(&g), last_block(&l));
    let worst = compare_blocks(&g, &l, 1e-9);
    eprintln!("compute temp of a group: largest relative difference to LAMMPS {worst:.2e} over {} rows", l.rows.len());
    // the group's temperature is not the whole box's
    let (t, tall) = (g.column_index("Temp").unwrap(), g.column_index("c_tall").unwrap());
    assert!((g.rows[0][t] - g.rows[0][tall]).abs() > 1e-3 * g.rows[0][t]);
}

#[test]
fn compute_temp_errors_name_the_line() {
    let head = "units lj\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncompute d all dpd\n";
    for (line, expected) in [
        ("thermo_modify temp nope", "in.x:5: thermo_modify: no compute with ID 'nope'"),
        ("thermo_modify temp d", "in.x:5: thermo_modify: compute d does not compute a temperature (compute temp)"),
        ("compute t nogroup temp", "in.x:5: compute: no group"),
        ("compute t all temp extra", "in.x:5: compute: unexpected argument 'extra'"),
        ("compute_modify d extra/dof 0 foo 1", "in.x:5: compute_modify: Compute d dpd does not support compute_modify foo command"),
        ("compute t all temp\ncompute_modify t extra/dof", "in.x:6: compute_modify: missing argument: expected the extra degrees of freedom"),
        ("compute t all temp\ncompute_modify t dynamic/dof maybe", "in.x:6: compute_modify: expected yes or no for dynamic/dof, got 'maybe'"),
    ] {
        expect_error("temp-errors", &format!("{head}{line}\n"), expected);
    }
}

/// `cmd` run in `dir` with standard input from `stdin` (or none).
fn run_with(cmd: &mut Command, dir: &Path, stdin: Option<&str>) -> Output {
    use std::io::Write;
    let mut child = cmd
        .current_dir(dir)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("starts");
    let mut pipe = child.stdin.take().unwrap();
    pipe.write_all(stdin.unwrap_or("").as_bytes()).unwrap();
    drop(pipe);
    child.wait_with_output().unwrap()
}

/// The deterministic scene of [`TEMP`] with `run_style verlet`, `atom_modify` and a
/// variable step count, for the command line.
fn cli_scene() -> String {
    TEMP.replace("units lj\n", "units lj\natom_modify map array sort 0 0.0\nvariable steps index 50\n")
        .replace("mass 1 1.0\n", "mass 1 1.0\nrun_style verlet\n")
        .replace("run 50", "run ${steps}")
}

/// LAMMPS's command line, with the same arguments in both codes: `-in`, `-var`, `-log`,
/// `-screen none`, `-nocite`; the logs hold the same thermo lines.
#[test]
fn lammps_command_line_runs_the_same_script_as_lammps() {
    let script = cli_scene();
    let args = ["-in", "in.x", "-var", "steps", "20", "-log", "log.x", "-screen", "none", "-nocite"];
    let dg = stage("cli-gendpde", &script);
    let out = run_with(Command::new(env!("CARGO_BIN_EXE_gendpde")).args(args), &dg, None);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(String::from_utf8_lossy(&out.stdout), "", "-screen none leaves the screen empty");
    let dl = stage("cli-lammps", &script);
    let lmp = run_with(Command::new(common::lammps::lmp()).args(args), &dl, None);
    assert!(lmp.status.success(), "{}", String::from_utf8_lossy(&lmp.stdout));
    let read = |d: &Path| last_block(&std::fs::read_to_string(d.join("log.x")).unwrap());
    let (g, l) = (read(&dg), read(&dl));
    assert_eq!(l.rows.last().unwrap()[0], 20.0);
    let worst = compare_blocks(&g, &l, 1e-9);
    eprintln!("command line: thermo of both logs agree to {worst:.1e}");
}

/// `-i`, `-v` with several values, `-echo screen`, standard input, the default log file
/// log.lammps, and LAMMPS options gendpde does not implement.
#[test]
fn lammps_command_line_forms() {
    let script = "variable a index 3 4\nprint \"a=$a\"\nunits lj\n";
    let dir = stage("cli-forms", script);
    let gendpde = || Command::new(env!("CARGO_BIN_EXE_gendpde"));
    let stdout = |o: &Output| String::from_utf8_lossy(&o.stdout).into_owned();
    let out = run_with(gendpde().args(["-i", "in.x", "-v", "a", "7", "8", "-echo", "screen"]), &dir, None);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stdout(&out).contains("a=7"), "{}", stdout(&out));
    assert!(stdout(&out).contains("units lj"), "-echo screen echoes commands: {}", stdout(&out));
    let log = std::fs::read_to_string(dir.join("log.lammps")).expect("LAMMPS's default log file");
    assert!(log.contains("a=7"));
    // the script on standard input, with and without options
    for args in [&[][..], &["-log", "none"][..]] {
        let out = run_with(gendpde().args(args), &dir, Some(script));
        assert!(out.status.success(), "{}", stderr(&out));
        assert!(stdout(&out).contains("a=3") && !stdout(&out).contains("units lj"), "{}", stdout(&out));
    }
    let out = run_with(gendpde().args(["-in", "in.x", "-log", "none", "-echo", "none"]), &dir, None);
    assert!(!stdout(&out).contains("units lj"));
    for (args, expected) in [
        (&["-in", "in.x", "-sf", "omp"][..], "ERROR: LAMMPS option -sf is not supported"),
        (&["-pk", "omp", "2", "-in", "in.x"][..], "ERROR: LAMMPS option -pk is not supported"),
        (&["-k", "on", "-in", "in.x"][..], "ERROR: LAMMPS option -k is not supported"),
        (&["-in", "in.x", "-bogus"][..], "ERROR: unknown command-line option '-bogus'"),
        (&["-in"][..], "ERROR: option -in needs a value"),
        (&["-in", "in.x", "-var", "a"][..], "ERROR: -var a needs at least one value"),
        (&["-in", "in.x", "-screen", "out.txt"][..], "ERROR: -screen out.txt: only -screen none is supported"),
        (&["-in", "missing.in"][..], "ERROR: cannot open input script 'missing.in'"),
    ] {
        let out = run_with(gendpde().args(args), &dir, None);
        assert!(!out.status.success(), "{args:?} accepted");
        assert!(stderr(&out).starts_with(expected), "{args:?}: expected {expected}, got {}", stderr(&out));
    }
    // the subcommands keep working
    let out = run_with(gendpde().args(["run", "in.x", "-log", "none", "-var", "a", "5"]), &dir, None);
    assert!(stdout(&out).contains("a=5"), "{}", stdout(&out));
}

#[test]
fn run_style_and_atom_modify() {
    let head = "units lj\n";
    for ok in ["run_style verlet", "atom_modify map array", "atom_modify map hash sort 1000 0.0", "atom_modify id yes map yes"] {
        let (_, out) = run_script("settings", &format!("{head}{ok}\n"));
        assert!(out.status.success(), "{ok}: {}", stderr(&out));
    }
    for (line, expected) in [
        ("run_style respa 2 2", "in.x:2: run_style: run style 'respa' is not supported (only verlet)"),
        ("run_style verlet extra", "in.x:2: run_style: unexpected argument 'extra'"),
        ("atom_modify map list", "in.x:2: atom_modify: expected map array, hash or yes, got 'list'"),
        ("atom_modify sort 100", "in.x:2: atom_modify: missing argument: expected the sort bin size"),
        ("atom_modify id no", "in.x:2: atom_modify: id no is not supported"),
        ("atom_modify", "in.x:2: atom_modify: missing argument: expected map, sort or id"),
    ] {
        expect_error("settings-errors", &format!("{head}{line}\n"), expected);
    }
}

/// Box keywords (and density, in g/cm^3 in real and metal) in every unit system, in
/// thermo and in an equal-style variable; the positions are random (they differ from
/// LAMMPS's), the keywords do not depend on them.
const BOX: &str = "units UNITS
region box block -2 13 1.5 15 -3 12 units box
create_box 1 box
create_atoms 1 random 200 99 NULL
mass 1 2.5
comm_modify vel yes
pair_style dpd 1.0 1.0 3421
pair_coeff 1 1 25.0 4.5
fix 1 all nve
variable w equal xhi-xlo+yhi*ylo-zlo/zhi+lx*ly*lz/vol+cella+cellb+cellc+density
thermo_style custom step atoms vol density lx ly lz xlo xhi ylo yhi zlo zhi cella cellb cellc v_w
thermo_modify format float %.15g
run 0
";

/// LAMMPS's DPDE example data (metal: 1000 particles at 300 K, conservative force at step
/// 0): temperature, pressure (bar in metal, atm in real), energies and enthalpy.
const DPDE: &str = "units UNITS
atom_style dpd
read_data data.dpde
comm_modify vel yes
mass 1 100.0
pair_style dpd/fdt/energy 10.0 245455
pair_coeff 1 1 0.075 0.022 3.2E-5 10.00
neighbor 2.0 bin
timestep 0.001
variable p equal press
variable h equal enthalpy
thermo_style custom step temp press pxx pyy pzz pe ke etotal enthalpy density v_p v_h
thermo_modify format float %.15g
fix 1 all shardlow
fix 2 all nve
fix 3 all eos/cv 0.05
run 0
";

/// The clock keywords over a run (time in ps in metal, fs in real, tau in lj; the default
/// timestep of each units).
const CLOCK: &str = "units UNITS
region box block 0 20 0 20 0 20 units box
create_box 1 box
create_atoms 1 random 100 5 NULL
mass 1 1.0
comm_modify vel yes
pair_style dpd 1.0 1.0 3421
pair_coeff 1 1 25.0 4.5
fix 1 all nve
thermo 10
thermo_style custom step elapsed time dt atoms vol
thermo_modify format float %.15g
run 20
run 10
";

#[test]
fn thermo_keywords_in_every_unit_system_match_lammps() {
    for u in ["lj", "real", "metal"] {
        let ((_, g), (_, l)) = both(&format!("clock-{u}"), &CLOCK.replace("UNITS", u));
        let (g, l) = (parse_thermo_blocks(&g, "Step"), parse_thermo_blocks(&l, "Step"));
        assert_eq!(g.len(), 2);
        for (g, l) in g.iter().zip(&l) {
            compare_blocks(g, l, 1e-12);
        }
    }
    for (scene, text, units) in [("box", BOX, &["lj", "real", "metal"][..]), ("dpde", DPDE, &["real", "metal"][..])] {
        for u in units {
            let ((_, g), (_, l)) = both(&format!("{scene}-{u}"), &text.replace("UNITS", u));
            let (g, l) = (last_block(&g), last_block(&l));
            let worst = compare_blocks(&g, &l, 1e-12);
            eprintln!("{scene} in {u} units: {} columns agree with LAMMPS to {worst:.1e}", g.header.len());
        }
    }
}

/// Everything after the thermo block of a run, and the memory line before it.
fn summary_lines(text: &str) -> (String, String) {
    let memory = text.lines().find(|l| l.starts_with("Per MPI rank memory allocation")).expect("the memory line").to_string();
    let perf = text.lines().find(|l| l.starts_with("Performance:")).expect("the Performance line").to_string();
    (memory, perf)
}

/// The words (not the numbers) of the lines around a run are LAMMPS's: the memory line just
/// before the heading, `Loop time of`, `Performance:` in tau/day (lj) or ns/day and hours/ns
/// (real, metal), and `Total wall time: h:mm:ss` at the end.
#[test]
fn run_summary_lines_follow_lammps() {
    let words = |l: &str| l.split_whitespace().filter(|w| w.parse::<f64>().is_err() && *w != "|").map(String::from).collect::<Vec<_>>();
    for u in ["lj", "metal", "real"] {
        let ((_, g), (_, l)) = both(&format!("summary-{u}"), &BOX.replace("UNITS", u).replace("run 0", "run 20"));
        let ((gm, gp), (lm, lp)) = (summary_lines(&g), summary_lines(&l));
        assert_eq!(words(&gm), words(&lm));
        let (gp, lp) = (words(&gp), words(&lp));
        // the prefix of atom-step/s follows the rate
        assert_eq!(gp[..gp.len() - 1], lp[..lp.len() - 1], "{gp:?} vs {lp:?}");
        assert!(gp.last().unwrap().ends_with("atom-step/s"));
        for out in [&g, &l] {
            let heading = out.lines().skip_while(|l| !l.starts_with("Per MPI rank memory")).nth(1).unwrap();
            assert!(heading.trim_start().starts_with("Step"), "{heading}");
            let wall = out.lines().last().unwrap();
            let hms: Vec<&str> = wall.strip_prefix("Total wall time: ").expect(wall).split(':').collect();
            assert!(hms.len() == 3 && hms[1].len() == 2 && hms[2].len() == 2, "{wall}");
        }
        let loop_line = g.lines().find(|l| l.starts_with("Loop time of")).unwrap();
        assert!(loop_line.ends_with("on 1 procs for 20 steps with 200 atoms"), "{loop_line}");
    }
}

/// tpcpu and spcpu: 0 at the first line of a run, then simulated time and steps per CPU
/// second since the previous line (tpcpu = spcpu dt); cpu grows.
#[test]
fn cpu_keywords_measure_the_run() {
    let script = BOX.replace("UNITS", "lj").replace("thermo_style custom step", "thermo 50\nthermo_style custom step cpu tpcpu spcpu").replace("run 0", "run 200");
    let (_, out) = run_script("cpu", &script);
    assert!(out.status.success(), "{}", stderr(&out));
    let b = last_block(&String::from_utf8_lossy(&out.stdout));
    let (cpu, tp, sp) = (b.column_index("CPU").unwrap(), b.column_index("T/CPU").unwrap(), b.column_index("S/CPU").unwrap());
    assert_eq!(b.rows.len(), 5);
    assert_eq!((b.rows[0][tp], b.rows[0][sp]), (0.0, 0.0));
    for w in b.rows.windows(2) {
        assert!(w[1][cpu] > w[0][cpu]);
        assert!(w[1][sp] > 0.0 && (w[1][tp] - 0.005 * w[1][sp]).abs() <= 1e-6 * w[1][tp], "{:?}", w[1]);
        // 50 steps in the CPU time between the lines
        let expected = 50.0 / (w[1][cpu] - w[0][cpu]);
        assert!((w[1][sp] - expected).abs() <= 1e-3 * expected, "{} vs {expected}", w[1][sp]);
    }
}

/// The lammps-logfile package (scripts/requirements.txt) reads a gendpde log of two runs:
/// the thermo columns of both, with the values gendpde printed.
#[test]
fn lammps_logfile_reads_a_gendpde_log() {
    let script = TEMP.replace("run 50", "run 20\nrun 30");
    let dir = stage("logfile", &script);
    let out = gendpde(&dir, &["-in", "in.x", "-log", "log.x", "-screen", "none"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let read = "import sys, lammps_logfile\n\
                log = lammps_logfile.File(sys.argv[1])\n\
                print(log.get_num_partial_logs())\n\
                print(' '.join(log.get_keywords()))\n\
                print(' '.join(repr(float(x)) for x in log.get('Step')))\n\
                print(repr(float(log.get('c_th', run_num=0)[-1])))\n";
    let py = Command::new("python3").args(["-c", read, "log.x"]).current_dir(&dir).output().expect("python3 runs");
    assert!(py.status.success(), "lammps-logfile failed (pip install -r scripts/requirements.txt):\n{}", String::from_utf8_lossy(&py.stderr));
    let text = String::from_utf8_lossy(&py.stdout).into_owned();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "2", "{text}");
    assert_eq!(lines[1], "KinEng Press Pxx Pzz Step Temp TotEng c_tall c_th v_t", "sorted by lammps-logfile");
    assert_eq!(lines[2], "0.0 10.0 20.0 20.0 30.0 40.0 50.0", "the steps of both runs: {text}");
    let log = std::fs::read_to_string(dir.join("log.x")).unwrap();
    let first = parse_thermo_blocks(&log, "Step").remove(0);
    let th = first.rows.last().unwrap()[first.column_index("c_th").unwrap()];
    assert_eq!(lines[3].parse::<f64>().unwrap(), th);
}

/// Misplaced commands and missing files: one prefix, the script's file:line, the right
/// complaint first.
#[test]
fn messages_name_the_line_once() {
    let head = "units lj\natom_style dpd\n";
    for (lines, expected) in [
        ("read_data nofile.data", "ERROR: in.x:3: read_data: cannot open data file 'nofile.data'"),
        ("read_data data.dpde-small\nread_data data.dpde-small", "ERROR: in.x:4: read_data: the box exists already\n"),
        ("read_data data.dpde-small\nread_restart x.h5", "ERROR: in.x:4: read_restart: the box exists already\n"),
        ("create_atoms 1 box", "ERROR: in.x:3: create_atoms: create_atoms before the box exists"),
        ("pair_style dpd 1.0 1.0 1\npair_coeff 1 1 25 4.5", "ERROR: in.x:4: pair_coeff: pair_coeff before the box exists"),
        ("read_data data.dpde-small\nfix 1 all bogus", "ERROR: in.x:4: fix: unknown fix style 'bogus'"),
        ("read_data data.dpde-small\nfix 1 nogroup nve", "ERROR: in.x:4: fix: no group 'nogroup'"),
        ("read_data data.dpde-small\ngroup g type 1\nfix 1 g bogus", "ERROR: in.x:5: fix: unknown fix style 'bogus'"),
        ("read_data data.dpde-small\ngroup g type 1\nfix 1 g nve", "ERROR: in.x:5: fix: group 'g': fix nve acts on group all"),
    ] {
        expect_error("messages", &format!("{head}{lines}\n"), expected);
    }
}

/// `neigh_modify one`, `page` and `binsize` as LAMMPS takes them: the bounds of its
/// neighbour pages bound nothing in gendpde's growing lists (the trajectory is LAMMPS's),
/// and page < 10 one is refused with LAMMPS's words; `exclude` is refused.
#[test]
fn neigh_modify_pages_and_bins_run_as_in_lammps() {
    let script = TEMP.replace("neigh_modify every 1 delay 0 check no", "neigh_modify every 1 delay 0 check no one 100 page 1000 binsize 0.5").replace("run 50", "run 20");
    let ((_, g), (_, l)) = both("neigh-pages", &script);
    let worst = compare_blocks(&last_block(&g), &last_block(&l), 1e-9);
    eprintln!("neigh_modify one/page/binsize: agree with LAMMPS to {worst:.1e}");
    let head = "units lj\natom_style dpd\n";
    for (line, expected) in [
        ("neigh_modify one 100 page 500", "ERROR: in.x:3: neigh_modify: Neighbor page size must be >= 10x the one atom setting"),
        ("neigh_modify page 5", "ERROR: in.x:3: neigh_modify: Neighbor page size must be >= 10x the one atom setting"),
        ("neigh_modify one 0", "ERROR: in.x:3: neigh_modify: neigh_modify one must be positive"),
        ("neigh_modify exclude type 1 1", "ERROR: in.x:3: neigh_modify: keyword exclude is not supported"),
    ] {
        expect_error("neigh-pages-bad", &format!("{head}{line}\n"), expected);
    }
}

/// `variable NAME internal VALUE` (LAMMPS's internal style) reads as a number in
/// expressions and thermo, as in LAMMPS.
#[test]
fn internal_variables_match_lammps() {
    let script = TEMP
        .replace("variable t equal temp\n", "variable t equal temp\nvariable a internal 1.5\nvariable a internal 2.25\nvariable b equal v_a*temp\n")
        .replace("pxx pzz v_t", "pxx pzz v_t v_a v_b")
        .replace("run 50", "run 20");
    let ((_, g), (_, l)) = both("internal", &script);
    let (g, l) = (last_block(&g), last_block(&l));
    assert!(g.column_index("v_b").is_some(), "v_b printed");
    let worst = compare_blocks(&g, &l, 1e-9);
    eprintln!("internal variables: agree with LAMMPS to {worst:.1e}");
}

/// `pair_style` before `read_data` and a region in lattice units without a lattice
/// (LAMMPS's default lattice of spacing 1) run as in LAMMPS.
#[test]
fn lammps_orders_and_defaults_are_accepted() {
    let script = TEMP
        .replace("pair_style dpd/fdt/energy 1.0 34387\n", "")
        .replace("atom_style dpd\n", "atom_style dpd\npair_style dpd/fdt/energy 1.0 34387\n")
        .replace("region half block 0 4.5 INF INF INF INF units box", "region half block 0 4.5 INF INF INF INF")
        .replace("run 50", "run 20");
    let ((_, g), (_, l)) = both("orders", &script);
    let worst = compare_blocks(&last_block(&g), &last_block(&l), 1e-9);
    eprintln!("pair_style before read_data, region in default lattice units: agree to {worst:.1e}");
}

/// Regions of every style and side, in lattice and box units, filled on an fcc lattice
/// (6 types, one a region): the same particles as LAMMPS, ID by ID.
const REGIONS: &str = "units lj
lattice fcc 0.8442
region box block 0 8 0 8 0 8
create_box 6 box
region s sphere 4 4 4 2.5
region c cylinder z 2 3 1.5 1 6
region cy cylinder x 6 6 1.2 INF INF units lattice
region b block 0.5 3 0.5 3 5 8 side in
region o sphere 4 4 4 3.7 side out
region sb cylinder y 10.0 10.0 4.0 INF EDGE units box side out
create_atoms 1 region s
create_atoms 2 region c
create_atoms 3 region cy
create_atoms 4 region b
create_atoms 5 region o
create_atoms 6 region sb
mass * 1.0
write_dump all custom regions.dump id type x y z modify sort id format float %.17g
";

/// The particles of two dumps agree ID by ID (type and position to 1e-12); returns the
/// count per type.
fn same_particles(g: &DumpSnapshot, l: &DumpSnapshot) -> Vec<usize> {
    assert_eq!(g.atoms.len(), l.atoms.len(), "particle counts");
    let (t, x) = (l.column_index("type").unwrap(), l.column_index("x").unwrap());
    let mut per_type = Vec::new();
    for ((ig, rg), (il, rl)) in g.atoms.iter().zip(&l.atoms) {
        assert_eq!((ig, rg[t]), (il, rl[t]));
        for d in 0..3 {
            assert!((rg[x + d] - rl[x + d]).abs() <= 1e-12, "particle {ig}: {rg:?} vs {rl:?}");
        }
        let k = rl[t] as usize;
        per_type.resize(per_type.len().max(k), 0);
        per_type[k - 1] += 1;
    }
    per_type
}

#[test]
fn regions_of_every_style_fill_as_lammps() {
    let ((dg, _), (dl, _)) = both("regions", REGIONS);
    let counts = same_particles(&dump(&dg.join("regions.dump")), &dump(&dl.join("regions.dump")));
    eprintln!("regions: particles per type as LAMMPS {counts:?}");
    assert_eq!(counts, [249, 153, 168, 108, 1161, 1576]);
}

#[test]
fn region_errors_name_the_line() {
    let head = "units lj\n";
    for (line, expected) in [
        ("region s sphere 0 0 0 -1", "in.x:2: region: the radius must be positive, got -1"),
        ("region s sphere 0 0 0", "in.x:2: region: missing argument: expected the radius"),
        ("region c cylinder w 0 0 1 0 1", "in.x:2: region: expected the axis x, y or z, got 'w'"),
        ("region c cylinder z 0 0 1 2 1", "in.x:2: region: each upper bound must exceed its lower bound"),
        ("region b block 0 1 0 1 0 1 side up", "in.x:2: region: expected side in or out, got 'up'"),
        ("region b block 0 1 0 1 0 1 move v_x NULL NULL", "in.x:2: region: unknown keyword 'move'; known: side, units"),
        ("region p prism 0 1 0 1 0 1 0 0 0", "in.x:2: region: unknown region style 'prism'; known: block, sphere, cylinder"),
        ("region s sphere 1 1 1 1\ncreate_box 1 s", "in.x:3: create_box: region 's': a box needs a block region (side in)"),
        ("region b block 0 1 0 1 0 1 side out\ncreate_box 1 b", "in.x:3: create_box: region 'b': a box needs a block region (side in)"),
    ] {
        expect_error("region-errors", &format!("{head}{line}\n"), expected);
    }
}

/// create_atoms random in a sphere, a cylinder and outside a sphere: every particle in its
/// region, counts as LAMMPS's, and the fraction in each half of the region's bounding
/// box near 1/2 (uniform).
#[test]
fn create_atoms_random_in_curved_regions() {
    let script = "units lj
region box block 0 10 0 10 0 10
create_box 3 box
region s sphere 5 5 5 3
region c cylinder z 3 7 2 INF INF
region o sphere 5 5 5 4 side out
create_atoms 1 random 1000 11 s
create_atoms 2 random 1000 12 c
create_atoms 3 random 1000 13 o
mass * 1.0
write_dump all custom rand.dump id type x y z modify format float %.17g
";
    let ((dg, _), (dl, _)) = both("random-curved", script);
    for (who, d) in [("gendpde", &dg), ("LAMMPS", &dl)] {
        let s = dump(&d.join("rand.dump"));
        let (t, x) = (s.column_index("type").unwrap(), s.column_index("x").unwrap());
        let mut n = [0usize; 3];
        let mut upper = [0usize; 3];
        for (_, r) in &s.atoms {
            let k = r[t] as usize - 1;
            let p = [r[x], r[x + 1], r[x + 2]];
            let dist = |c: [f64; 3], dims: &[usize]| dims.iter().map(|&d| (p[d] - c[d]).powi(2)).sum::<f64>().sqrt();
            let inside = match k {
                0 => dist([5.0; 3], &[0, 1, 2]) <= 3.0 + 1e-6,
                1 => dist([3.0, 7.0, 0.0], &[0, 1]) <= 2.0 + 1e-6,
                _ => dist([5.0; 3], &[0, 1, 2]) >= 4.0 - 1e-6,
            };
            assert!(inside, "{who}: type {} at {p:?}", k + 1);
            n[k] += 1;
            upper[k] += usize::from(p[0] > [5.0, 3.0, 5.0][k]);
        }
        assert_eq!(n, [1000; 3], "{who}");
        // binomial(1000, 1/2): sd 15.8; 4 sd
        for k in 0..3 {
            assert!((upper[k] as f64 - 500.0).abs() < 64.0, "{who}: type {}: {} of 1000 in the upper half", k + 1, upper[k]);
        }
    }
}

/// Lattices fcc, bcc, hcp, diamond and sc with origin, orient and spacing, in lj units
/// (SCALE = density) and metal units (SCALE = lattice constant), filling a box and a
/// sphere in lattice units: the same particles as LAMMPS, ID by ID.
#[test]
fn lattices_with_origin_and_orient_match_lammps() {
    for (units, lattice) in [
        ("lj", "fcc 0.8442 orient x 1 1 1 orient y -1 1 0 orient z -1 -1 2 origin 0.1 0.2 0.3"),
        ("metal", "bcc 3.3 orient x 1 1 0 orient y -1 1 0 orient z 0 0 1 origin 0.5 0 0.25"),
        ("lj", "hcp 0.9 origin 0.2 0.1 0.05"),
        ("metal", "diamond 5.43 orient x 1 -1 0 orient y 1 1 1 orient z -1 -1 2"),
        ("real", "hcp 2.9"),
        ("lj", "sc 0.5 spacing 1 2 1"),
    ] {
        let script = format!(
            "units {units}\nlattice {lattice}\nregion box block 0 4 0 3 -1 2\ncreate_box 2 box\nregion s sphere 2 1.5 0.5 1.2\n\
             create_atoms 1 box\ncreate_atoms 2 region s\nmass * 1.0\n\
             write_dump all custom lat.dump id type x y z modify sort id format float %.17g\n"
        );
        let ((dg, _), (dl, _)) = both("lattice", &script);
        let counts = same_particles(&dump(&dg.join("lat.dump")), &dump(&dl.join("lat.dump")));
        eprintln!("{units} lattice {lattice}: {counts:?} particles as LAMMPS");
        assert!(counts.len() == 2 && counts.iter().all(|&n| n > 0));
    }
}

#[test]
fn lattice_errors_name_the_line() {
    for (line, expected) in [
        ("lattice fcc 0.8 orient x 1 1 0", "in.x:2: lattice: the orient vectors are not orthogonal"),
        ("lattice fcc 0.8 orient z 0 0 -1", "in.x:2: lattice: the orient vectors are not right-handed"),
        ("lattice fcc 0.8 orient x 1 0.5 0", "in.x:2: lattice: expected an integer component of the orient vector, got '0.5'"),
        ("lattice fcc 0.8 origin 0 0 1", "in.x:2: lattice: each origin fraction must lie in [0, 1)"),
        ("lattice fcc -1", "in.x:2: lattice: the reduced density must be positive, got -1"),
        ("lattice sq 1.0", "in.x:2: lattice: unknown lattice style 'sq'; known: none, sc, bcc, fcc, hcp, diamond"),
        ("lattice fcc 0.8 basis 0 0 0", "in.x:2: lattice: unknown keyword 'basis'; known: origin, orient, spacing"),
        ("lattice none 2.0 origin 0 0 0", "in.x:2: lattice: unexpected argument 'origin'"),
        (
            "lattice none 2.0\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 box",
            "in.x:5: create_atoms: create_atoms needs a lattice with points",
        ),
    ] {
        expect_error("lattice-errors", &format!("units lj\n{line}\n"), expected);
    }
}

/// A DPD fluid whose thermostat ramps (dpd/tstat 1 -> 2), so that `start`/`stop` show.
const RAMP: &str = "units lj\natom_style atomic\ncomm_modify vel yes\nlattice fcc 3.0\nregion box block 0 3 0 3 0 3\n\
create_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\nvelocity all create 1.0 87287\n\
pair_style dpd/tstat 1.0 2.0 1.0 34387\npair_coeff * * 4.5\nfix 1 all nve\n\
thermo 5\nthermo_style custom step elapsed elaplong\n";

/// `run N upto|start|stop|pre|post|every` and LAMMPS's quoting: quoted text waits for the
/// command that reads it (print, the commands of `run every`), a `string` variable is
/// substituted when defined. The printed lines, the Step/Elapsed/Elaplong columns of every
/// thermo block and the count of summaries are LAMMPS's.
#[test]
fn run_keywords_and_quoting_match_lammps() {
    let script = format!(
        "{RAMP}variable x equal 2\nvariable s string \"x was ${{x}}\"\nvariable x equal 3\n\
         print \"q: $x ${{s}} 'kept $x' $(step)\"\nprint 'q: single $x'\n\
         run 10 start 0 stop 40\n\
         run 25 upto start 0 stop 40 pre no post no\n\
         run 15 start 0 stop 40 every 5 \"print 'q: at $(step) elaplong $(elaplong)'\" \"print 'q: done'\"\n\
         run 0 post no\n"
    );
    let ((_, g), (_, l)) = both("run-keywords", &script);
    let printed = |t: &str| t.lines().filter(|l| l.starts_with("q:")).map(String::from).collect::<Vec<_>>();
    assert_eq!(printed(&g), printed(&l));
    assert!(printed(&g).contains(&"q: 3 x was 2 'kept $x' 0".to_string()), "{:?}", printed(&g));
    let clock = |t: &str| {
        parse_thermo_blocks(t, "Step").iter().map(|b| ["Step", "Elapsed", "Elaplong"].map(|c| b.column(c))).collect::<Vec<_>>()
    };
    assert_eq!(clock(&g), clock(&l));
    assert_eq!(clock(&g).len(), 6, "one block per run and per part of every");
    let count = |t: &str, what: &str| t.lines().filter(|l| l.starts_with(what)).count();
    for what in ["Loop time of", "Performance:"] {
        assert_eq!(count(&g, what), count(&l, what), "{what}");
    }
}

#[test]
fn run_keyword_errors_name_the_line() {
    let cases = [
        ("run 10\nrun 5 upto\n", "in.x:16: run: run 5 upto: the current step 10 is already past it"),
        ("run 10\nrun 5 start 11\n", "run start 11 is after the start of the run (step 10)"),
        ("run 10 stop 9\n", "run stop 9 is before the end of the run (step 10)"),
        ("run 10 every 0 NULL\n", "the number of steps must be positive"),
        ("run 10 every 5\n", "expected the commands of run every"),
        ("run 10 pre maybe\n", "expected yes or no for pre, got 'maybe'"),
        ("run 10 sideways\n", "unknown run keyword 'sideways'"),
        ("run 10 every 5 \"nonsense 1\"\n", "(run every):1: nonsense: unknown command 'nonsense'"),
    ];
    for (k, (tail, expected)) in cases.iter().enumerate() {
        expect_error(&format!("run-error-{k}"), &format!("{RAMP}{tail}"), expected);
    }
}

/// `if ... then ... elif ... else`, a `jump` out of a loop from inside `if`, string
/// comparisons, `|^`, and `quit`: the printed lines are LAMMPS's and `quit 3` ends the
/// script with status 3 after the line before it.
#[test]
fn if_jump_and_quit_follow_lammps() {
    let script = format!(
        "{RAMP}variable s equal step\nvariable name index lj/cut\nlabel loop\nvariable a loop 10\nrun 5 post no\n\
         if \"$s >= 15\" then \"print 'q: out at $s a=$a'\" \"jump SELF break\" elif \"$a == 2\" \"print 'q: a is 2'\" else \"print 'q: not yet $a'\"\n\
         next a\njump SELF loop\nlabel break\nprint \"q: done a=$a\"\n\
         if \"${{name}} == lj/cut && !(1 > 2)\" then \"print 'q: string ok'\"\n\
         if \"(1 > 0) |^ (2 > 1)\" then \"print 'q: xor wrong'\" else \"print 'q: xor ok'\"\n\
         if \"$a > 2\" then \"print 'q: quitting'\" \"quit 3\"\nprint \"q: not reached\"\n"
    );
    let (_, g) = run_script("if-quit-gendpde", &script);
    let dl = stage("if-quit-lammps", &script);
    let l = run_lammps(&dl, "in.x", &[]);
    let printed = |o: &Output| String::from_utf8_lossy(&o.stdout).lines().filter(|l| l.starts_with("q:")).map(String::from).collect::<Vec<_>>();
    assert_eq!(printed(&g), printed(&l), "gendpde stderr: {}", stderr(&g));
    assert_eq!(printed(&g), ["q: not yet 1", "q: a is 2", "q: out at 15 a=3", "q: done a=3", "q: string ok", "q: xor ok", "q: quitting"]);
    assert_eq!((g.status.code(), l.status.code()), (Some(3), Some(3)));
    for (k, (tail, expected)) in [
        ("if \"1 < 2\"\n", "missing argument: expected then"),
        ("if \"1 < 2\" than \"print x\"\n", "expected 'then'"),
        ("if \"1 < 2\" then\n", "need at least one command"),
        ("if \"abc < 2\" then \"print x\"\n", "cannot compare a number with a string"),
        ("if \"1 < 2\" then \"print x\" else \"print y\" elif \"1\" \"print z\"\n", "elif after else"),
        ("quit 256\n", "the exit status 256 is not in 0..255"),
    ]
    .iter()
    .enumerate()
    {
        expect_error(&format!("if-error-{k}"), &format!("{RAMP}{tail}"), expected);
    }
}
