//! The language's long tail (issue 38, part 3, item 2): `clear`, the variable styles and
//! math functions, thermo keywords and `thermo_modify`, unit systems and the small
//! commands (`comm_modify`, `shell`, `write_coeff`, ...), each beside the reference LAMMPS
//! (22 Jul 2025) on a script of its own.

use crate::common;

use common::lammps::{expect_success, parse_thermo_blocks, run_gendpde, run_lammps, ThermoBlock};
use common::tempdir;
use std::path::PathBuf;

/// Writes `script` as `in.x` into a fresh directory `NAME-SIDE`, with the `files` (name,
/// text) beside it.
fn stage(name: &str, side: &str, script: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = tempdir(&format!("{name}-{side}"));
    std::fs::write(dir.join("in.x"), script).unwrap();
    for (f, text) in files {
        std::fs::write(dir.join(f), text).unwrap();
    }
    dir
}

/// Runs `script` in both codes (each must succeed); returns the directories and standard
/// outputs, LAMMPS's first.
fn both(name: &str, script: &str, files: &[(&str, &str)]) -> ((PathBuf, String), (PathBuf, String)) {
    let (dl, dg) = (stage(name, "lammps", script, files), stage(name, "gendpde", script, files));
    let l = expect_success("LAMMPS", &run_lammps(&dl, "in.x", &[]));
    let g = run_gendpde(&dg, "in.x", &[]);
    assert!(g.status.success(), "gendpde failed on {name}:\n{}", String::from_utf8_lossy(&g.stderr));
    ((dl, l), (dg, String::from_utf8_lossy(&g.stdout).into_owned()))
}

/// Runs `script` in gendpde, which must fail with a message containing `expected`.
fn expect_error(name: &str, script: &str, expected: &str) {
    let out = run_gendpde(&stage(name, "gendpde", script, &[]), "in.x", &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "accepted:\n{script}");
    assert!(stderr.contains(expected), "expected '{expected}', got {stderr}\nfor:\n{script}");
}

/// The thermo blocks of both outputs, which must have the same headings and row counts;
/// returns them and the largest relative difference of their values.
fn thermo_parity(lammps: &str, gendpde: &str) -> (Vec<ThermoBlock>, f64) {
    let (bl, bg) = (parse_thermo_blocks(lammps, "Step"), parse_thermo_blocks(gendpde, "Step"));
    assert_eq!(bl.len(), bg.len(), "thermo blocks:\n{lammps}\n---\n{gendpde}");
    let mut worst: f64 = 0.0;
    for (l, g) in bl.iter().zip(&bg) {
        assert_eq!(l.header, g.header, "headings");
        assert_eq!(l.rows.len(), g.rows.len(), "rows of {:?}", l.header);
        for (x, y) in l.rows.iter().flatten().zip(g.rows.iter().flatten()) {
            worst = worst.max((x - y).abs() / x.abs().max(1.0));
        }
    }
    eprintln!("largest relative thermo difference from LAMMPS over {} blocks: {worst:e}", bl.len());
    (bl, worst)
}

/// The printed lines (`print`) of an output that start with `prefix`.
fn printed<'a>(out: &'a str, prefix: &str) -> Vec<&'a str> {
    out.lines().filter(|l| l.starts_with(prefix)).collect()
}

/// `clear` deletes the box and every setting (units back to lj: timestep 0.005, thermo
/// normalised; the region ID free again) and keeps the variables; a second system is set
/// up after it. Thermo of both systems as LAMMPS's, to round-off.
#[test]
fn clear_restores_defaults_and_keeps_variables() {
    let system = |units: &str, lattice: &str, n: u32, t: &str, cut: &str| {
        format!(
            "units {units}\nlattice {lattice}\nregion box block 0 {n} 0 {n} 0 {n}\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
             velocity all create {t} 4928459 loop geom\ncomm_modify vel yes\npair_style dpd {t} {cut} 123\npair_coeff 1 1 25.0 0.0\n\
             fix 1 all nve\nthermo_style custom step dt temp pe press\nthermo_modify format float %.17g\nrun 5\n"
        )
    };
    let script = format!(
        "variable a equal 2.5\n{}clear\nprint \"after clear a=${{a}}\"\n{}",
        system("metal", "sc 1.0", 7, "300.0", "1.0"),
        system("lj", "fcc 0.8442", 4, "1.0", "1.5").replace("units lj\n", "")
    );
    let ((_, l), (_, g)) = both("clear", &script, &[]);
    let (blocks, worst) = thermo_parity(&l, &g);
    assert_eq!(blocks.len(), 2);
    assert_eq!(blocks[1].column("Dt")[0], 0.005, "lj's timestep after clear");
    assert!(blocks[1].column("PotEng")[1] != 0.0, "a pair energy to compare");
    assert!(worst < 1e-12, "thermo differs from LAMMPS's by {worst:e}");
    assert_eq!(printed(&g, "after clear"), ["after clear a=2.5"]);
}

/// The variable styles of one partition (world, universe, uloop, getenv, file, atomfile,
/// format, timer) and LAMMPS's math and feature functions, printed and in thermo columns
/// over a `run N start A stop B` (ramp, vdisplace, swiggle, cwiggle, stride, logfreq,
/// stagger): every printed line and thermo value as LAMMPS's.
#[test]
fn variable_styles_and_functions() {
    const SCRIPT: &str = r#"variable w world hello
print "W ${w}"
variable e getenv HOME
variable e getenv NOPE_NOT_SET
print "E [${e}]"
variable x equal 2.0/3
variable fx format x %.3f
variable fy format x %10.4e
print "X ${fx} [${fy}] $(v_fx*2)"
variable f file values.txt
label lf
print "F ${f}"
next f
jump SELF lf
variable u universe a b c
variable ul uloop 3 pad
label lu
print "U ${u} ${ul}"
next u ul
jump SELF lu
variable t timer
print "T $(v_t-v_t) $(v_t >= 0)"
print "FN $(round(-2.5)) $(round(0.5)) $(sign(-3)) $(sign(0)) $(ternary(0,2,3)) $(1|^1) $(1|^0||0) $(version) $(yes+off+true)"
print "FS $(stagger(100,10)) $(logfreq(10,2,10)) $(logfreq2(10,4,10)) $(logfreq3(10,5,1000)) $(stride(0,100,10)) $(stride2(0,1000,100,200,300,10))"
print "FW $(is_file(values.txt)) $(is_file(nope.txt)) $(extract_setting(dimension)) $(extract_setting(bigint)) $(extract_setting(tagint)) $(extract_setting(box_exist))"
units lj
atom_modify map yes
lattice fcc 0.8442
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
mass 1 1.0
print "FB $(extract_setting(box_exist)) $(extract_setting(ntypes)) $(extract_setting(world_size)) $(ramp(1,3)) $(vdisplace(1,2))"
velocity all create 1.0 87287 loop geom
comm_modify vel yes
pair_style dpd 1.0 1.5 123
pair_coeff 1 1 25.0 0.0
fix 1 all nve
variable a atomfile af.txt
compute s all reduce sum v_a
variable ra equal ramp(1,3)
variable vd equal vdisplace(1,2)
variable sw equal swiggle(1,2,0.02)
variable cw equal cwiggle(1,2,0.02)
variable st equal stride(2,20,3)
variable lf equal logfreq(1,2,3)
variable sg equal stagger(4,1)
thermo 1
thermo_style custom step v_ra v_vd v_sw v_cw v_st v_lf v_sg c_s
thermo_modify format float %.17g
run 10 start 0 stop 20
next a
run 2
print "FE $(ramp(1,3)) $(vdisplace(1,2)) $(extract_setting(nlocal))"
"#;
    let files = [
        ("values.txt", "# values\n1.5\n\n  two  words\n3e2 # c\n"),
        ("af.txt", "# snapshot 1\n3\n1 1.5\n2 -2.0\n5 4.25\n2\n1 10\n3 0.5\n"),
    ];
    let ((_, l), (_, g)) = both("variables", SCRIPT, &files);
    let lines = |out: &str| -> Vec<String> {
        let tagged = |l: &&str| l.starts_with("Increment") || l.split_once(' ').is_some_and(|(tag, _)| (1..=2).contains(&tag.len()) && tag.chars().all(|c| c.is_ascii_uppercase()));
        out.lines().filter(tagged).map(String::from).collect()
    };
    assert_eq!(lines(&g), lines(&l));
    assert!(lines(&g).len() > 15, "{:?}", lines(&g));
    let (blocks, worst) = thermo_parity(&l, &g);
    assert_eq!(blocks.iter().map(|b| b.rows.len()).collect::<Vec<_>>(), [11, 3]);
    assert!(worst < 1e-15, "thermo differs from LAMMPS's by {worst:e}");
}

/// Thermo keywords nbuild, ndanger (every 2 delay 4: every build is dangerous), evdwl,
/// ecoul, epair, emol and the other molecular energies (0), cpuremain (0 at a run's first
/// line; a wall-clock estimate, not compared); `thermo_modify lost, lost/bond, warn,
/// line one, flush`; `thermo_style one`, and LAMMPS's default columns (`one`) for pair dpd
/// with no thermo_style, after `clear`. Every thermo value as LAMMPS's to round-off.
#[test]
fn thermo_keywords_and_default_columns() {
    const SCRIPT: &str = r#"lattice fcc 3.0
region box block 0 5 0 5 0 5
create_box 2 box
create_atoms 1 box
mass * 1.0
set type 1 type/fraction 2 0.5 1234
velocity all create 2.0 87287 loop geom
comm_modify vel yes
pair_style dpd 1.0 1.0 123
pair_coeff * * 25.0 0.0
pair_coeff 1 2 40.0 0.0
fix 1 all nve
timestep 0.02
thermo 10
thermo_style custom step nbuild ndanger evdwl ecoul epair emol elong ebond eangle edihed eimp cpuremain
thermo_modify format float %.17g lost ignore lost/bond warn warn 10 line one flush yes
run 50
neigh_modify every 2 delay 4 check yes
run 50
thermo_style one
thermo_modify format float %.17g
run 10
clear
lattice fcc 3.0
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
mass * 1.0
velocity all create 2.0 87287 loop geom
comm_modify vel yes
pair_style dpd 1.0 1.0 123
pair_coeff * * 25.0 0.0
fix 1 all nve
thermo_modify format float %.17g
run 10
"#;
    let ((_, l), (_, g)) = both("thermo", SCRIPT, &[]);
    // headings and row counts checked; CPULeft (wall clock) is compared apart
    thermo_parity(&l, &g);
    let (mut bl, mut bg) = (parse_thermo_blocks(&l, "Step"), parse_thermo_blocks(&g, "Step"));
    assert_eq!(bl.len(), 4);
    let mut worst: f64 = 0.0;
    for (a, b) in bl.iter_mut().zip(bg.iter_mut()) {
        if let Some(k) = a.column_index("CPULeft") {
            assert_eq!((a.rows[0][k], b.rows[0][k]), (0.0, 0.0), "CPULeft at a run's first line");
            assert!(b.rows.iter().all(|r| r[k] >= 0.0));
            a.rows.iter_mut().chain(b.rows.iter_mut()).for_each(|r| r[k] = 0.0);
        }
        for (x, y) in a.rows.iter().flatten().zip(b.rows.iter().flatten()) {
            worst = worst.max((x - y).abs() / x.abs().max(1.0));
        }
    }
    assert_eq!(bg[1].column("Ndanger"), [0.0, 2.0, 5.0, 7.0, 10.0, 12.0]);
    assert_eq!(bg[0].column("Nbuild"), bl[0].column("Nbuild"));
    assert_eq!(bg[3].header, ["Step", "Temp", "E_pair", "E_mol", "TotEng", "Press"]);
    // 110 steps of a chaotic fluid: round-off grows to ~1e-12
    eprintln!("thermo keywords: largest relative difference from LAMMPS {worst:e}");
    assert!(worst < 1e-10, "thermo differs from LAMMPS's by {worst:e}");
}

/// `units si, cgs, electron, nano, micro`: LAMMPS's constants (k_B, mvv2e, nktv2p, mv2d)
/// and defaults, through temp, pe, ke, etotal, press, density and pxx of a dpd fluid at
/// k_B T = 2 over 10 steps, relative to each value. Electron units agree to ~1e-9 only:
/// LAMMPS's ftm2v there is not 1/mvv2e (their product is 1 + 5.3e-9), and gendpde
/// integrates with 1/mvv2e.
#[test]
fn unit_styles_match_lammps_constants() {
    for (units, kb, tolerance) in
        [("si", 1.3806504e-23, 1e-12), ("cgs", 1.3806504e-16, 1e-12), ("nano", 0.013806504, 1e-12), ("micro", 1.3806504e-8, 1e-12), ("electron", 3.16681534e-6, 1e-8)]
    {
        let t = 2.0 / kb;
        let script = format!(
            "units {units}\nlattice fcc 1.2\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 2.0\n\
             velocity all create {t:?} 87287 loop geom\ncomm_modify vel yes\npair_style dpd {t:?} 1.0 123\npair_coeff 1 1 25.0 0.0\n\
             neighbor 0.3 bin\nfix 1 all nve\ntimestep 0.01\nthermo 5\nthermo_style custom step temp pe ke etotal press density pxx\n\
             thermo_modify format float %.17g\nrun 10\n"
        );
        let ((_, l), (_, g)) = both(&format!("units-{units}"), &script, &[]);
        let (bl, bg) = (parse_thermo_blocks(&l, "Step"), parse_thermo_blocks(&g, "Step"));
        assert_eq!(bl.iter().map(|b| (&b.header, b.rows.len())).collect::<Vec<_>>(), bg.iter().map(|b| (&b.header, b.rows.len())).collect::<Vec<_>>());
        let worst = bl[0].rows.iter().flatten().zip(bg[0].rows.iter().flatten()).map(|(x, y)| if *x == 0.0 { y.abs() } else { ((x - y) / x).abs() }).fold(0.0, f64::max);
        eprintln!("units {units}: largest relative thermo difference from LAMMPS {worst:e}");
        assert!(worst < tolerance, "units {units}: thermo differs from LAMMPS's by {worst:e}");
    }
}

/// `shell` (LAMMPS's cd, mkdir -p, mv into a directory, rm with and without -f, rmdir of a
/// tree, putenv read back by getenv, with LAMMPS's warning for a failed rm), `timer`
/// (LAMMPS's settings line), `comm_modify mode single cutoff vel`, `newton`,
/// `write_coeff` (the file byte for byte as LAMMPS's) and `info`; partition and the
/// refused keywords fail naming what is not supported.
#[test]
fn shell_timer_comm_modify_and_write_coeff() {
    const SCRIPT: &str = r#"shell mkdir sub1 sub2/deep
shell putenv FOO=bar
variable foo getenv FOO
print "FOO=${foo} $(is_file(sub2/deep))"
shell mv f.txt sub1
shell cd sub1
print "cd $(is_file(f.txt))"
shell cd ..
shell mv sub1/f.txt moved.txt
print "moved $(is_file(moved.txt)) $(is_file(sub1/f.txt))"
shell rm moved.txt nonexist.txt
shell rm -f nonexist.txt
shell rmdir sub1 sub2
print "gone $(is_file(moved.txt)) $(is_file(sub2/deep))"
timer off
timer full sync every 10
lattice fcc 3.0
region box block 0 3 0 3 0 3
create_box 2 box
create_atoms 1 box
mass * 1.0
comm_modify vel yes cutoff 3.0 mode single
newton on
pair_style dpd 1.0 1.0 123
pair_coeff * * 25.0 4.5
pair_coeff 1 2 40.123456789 4.5 0.8
write_coeff coeffs.txt
info system variables
"#;
    let ((dl, l), (dg, g)) = both("session", SCRIPT, &[("f.txt", "x\n")]);
    let lines = |out: &str| -> Vec<String> {
        let keep = ["FOO=", "cd ", "moved ", "gone ", "WARNING: Shell", "New timer"];
        out.lines().filter(|l| keep.iter().any(|k| l.starts_with(k))).map(|l| l.split(" (src/").next().unwrap_or_default().to_string()).collect()
    };
    assert_eq!(lines(&g), lines(&l));
    assert_eq!(lines(&g).len(), 7, "{g}");
    for d in [&dl, &dg] {
        assert!(!d.join("sub1").exists() && !d.join("sub2").exists() && !d.join("moved.txt").exists(), "{}", d.display());
    }
    let read = |d: &PathBuf| std::fs::read_to_string(d.join("coeffs.txt")).unwrap();
    assert_eq!(read(&dg), read(&dl));
    assert!(g.contains("System information:") && g.contains("Units         = lj"), "{g}");
}

/// The atomfile variable (summed by compute reduce), nbuild, ndanger and the step functions
/// give the same thermo rows on 1 and 3 ranks, bit for bit (CPULeft, a wall-clock
/// estimate, left out).
#[test]
fn new_keywords_are_rank_count_independent() {
    let script = "atom_modify map yes\nlattice fcc 3.0\nregion box block 0 5 0 5 0 5\ncreate_box 1 box\ncreate_atoms 1 box\nmass * 1.0\n\
                  velocity all create 2.0 87287 loop geom\ncomm_modify vel yes\npair_style dpd 1.0 1.0 123\npair_coeff * * 25.0 0.0\nfix 1 all nve\n\
                  timestep 0.02\nneigh_modify every 2 delay 4 check yes\nvariable a atomfile af.txt\ncompute s all reduce sum v_a\n\
                  variable r equal ramp(1,3)+swiggle(0,1,0.1)\nthermo 5\nthermo_style custom step nbuild ndanger epair v_r c_s cpuremain\n\
                  thermo_modify format float %.17g\nrun 40\nnext a\nrun 10\n";
    let rows = |np: usize| {
        let dir = stage("ranks", &np.to_string(), script, &[("af.txt", "2\n1 1.5\n400 -2.0\n1\n7 3.0\n")]);
        let out = if np == 1 { run_gendpde(&dir, "in.x", &[]) } else { common::mpirun(np, &dir, &["run", "in.x", "-log", "none"]) };
        assert!(out.status.success(), "{np} ranks: {}", String::from_utf8_lossy(&out.stderr));
        let rows = common::ranks::thermo_rows(&out.stdout);
        rows.iter().map(|r| r.split_whitespace().take(6).collect::<Vec<_>>().join(" ")).collect::<Vec<_>>()
    };
    let one = rows(1);
    assert_eq!(one.len(), 9 + 3);
    assert!(one.last().is_some_and(|r| r.ends_with(" 0.0060000000000000001")), "{one:?}");
    assert_eq!(rows(3), one);
}

/// What gendpde does not do is refused naming the command and why, or worded as LAMMPS's
/// message where LAMMPS refuses it too.
#[test]
fn refusals_name_what_is_not_supported() {
    for (name, script, expected) in [
        ("clear-args", "clear all\n", "unexpected argument 'all'"),
        ("variables-world", "variable w world a b\n", "World variable count doesn't match # of partitions"),
        ("variables-format", "variable x equal 1\nvariable f format x %d\n", "Incorrect conversion in format string"),
        ("variables-file", "variable f file nope.txt\n", "Cannot open file variable file nope.txt"),
        ("variables-next", "variable a index 1 2\nvariable b loop 2\nnext a b\n", "All variables in next command must have same style"),
        ("variables-random", "print $(random(0,1,5))\n", "random() is not supported"),
        ("thermo-multi", "thermo_style multi\n", "thermo style 'multi' is not supported"),
        ("thermo-line", "thermo_modify line yaml\n", "thermo_modify line yaml is not supported"),
        ("thermo-lost", "thermo_modify lost sometimes\n", "Unknown thermo_modify lost argument: sometimes"),
        ("session-shell", "shell ls\n", "shell ls: only LAMMPS's built-in sub-commands"),
        ("session-partition", "partition yes 1 print hi\n", "partition is not supported"),
        ("session-timeout", "timer timeout 1:00:00\n", "timer timeout 1:00:00 is not supported"),
        ("session-comm", "comm_modify mode multi\n", "comm_modify mode multi needs LAMMPS's multi neighbor lists"),
        ("session-comm-key", "comm_modify speed 2\n", "Unknown comm_modify keyword: speed"),
        ("session-newton", "newton maybe\n", "Expected boolean parameter instead of 'maybe'"),
        ("session-coeff", "write_coeff c.txt\n", "write_coeff command before simulation box is defined"),
        ("units-bad", "units planck\n", "units planck: known are lj, real, metal, si, cgs, electron, micro, nano"),
    ] {
        expect_error(name, script, expected);
    }
}
