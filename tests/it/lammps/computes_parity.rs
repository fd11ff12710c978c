//! Computes and output fixes beside the reference LAMMPS (issue 38): temp/partial,
//! temp/com, temp/region, gyration, count/type, vacf, msd, property/atom, reduce and
//! reduce/region, coord/atom of a group, ke/atom; fix ave/time (scalar and vector modes,
//! ave running, c_ID[*], f_ID in thermo), fix ave/histo, fix ave/atom (f_ID in dumps),
//! fix print, fix vector; cluster/atom and coord/atom with type columns; thermo_modify temp of a temp/partial;
//! the group functions of variables (count, mass, xcm, vcm, fcm, bound, gyration, ke, with
//! and without a region).
//! A deterministic pair dpd scene (gamma 0): every thermo value to round-off, the files
//! to their printed digits, and the same on 1 and 3 ranks.

use crate::common;
use common::lammps::{expect_success, parse_dump, parse_thermo_blocks, run_gendpde, run_lammps};
use common::{mpirun, tempdir};
use std::path::{Path, PathBuf};

/// Runs `script` as in.x in both codes, each in a fresh directory; returns both
/// directories and standard outputs.
fn both(name: &str, script: &str) -> ((PathBuf, String), (PathBuf, String)) {
    let stage = |side: &str| {
        let d = tempdir(&format!("{name}-{side}"));
        std::fs::write(d.join("in.x"), script).unwrap();
        d
    };
    let (dl, dg) = (stage("lammps"), stage("gendpde"));
    let l = expect_success("LAMMPS", &run_lammps(&dl, "in.x", &[]));
    let out = run_gendpde(&dg, "in.x", &[]);
    assert!(out.status.success(), "gendpde failed:\n{}", String::from_utf8_lossy(&out.stderr));
    ((dl, l), (dg, String::from_utf8_lossy(&out.stdout).into_owned()))
}

/// The deterministic two-type pair dpd scene (gamma 0) the parity scenes start from.
macro_rules! scene_head {
    () => {
        "units lj
comm_modify vel yes
lattice fcc 3.0
region box block 0 4 0 4 0 4
create_box 2 box
create_atoms 1 box
region half block 0 2 INF INF INF INF
set region half type 2
mass * 1.0
mass 2 2.0
pair_style dpd 1.0 1.0 4928
pair_coeff * * 25.0 0.0
fix nve all nve
velocity all create 1.0 87287 loop geom
"
    };
}

const SCENE: &str = concat!(
    scene_head!(),
    "group one type 1
group two type 2
region slab block 1 3 INF INF INF INF
compute tp all temp/partial 1 0 1
compute tc two temp/com
compute tr all temp/region slab
compute g one gyration
compute ct all count/type atom
compute vacf two vacf
compute m one msd com yes
compute pa all property/atom vx xu
compute r1 all reduce sum c_pa[1]
compute r2 two reduce/region slab ave c_pa[2] vy
compute co all coord/atom cutoff 0.9 group two
compute rc all reduce max c_co
compute rs all reduce sum c_co
compute ke all ke/atom
compute rke one reduce sum c_ke
variable gx equal c_g[1]+c_g[4]
variable n equal count(two)
variable nr equal count(two,slab)
variable ms equal mass(two)
variable xc equal xcm(one,x)
variable vc equal vcm(two,y,slab)
variable fc equal fcm(two,z)
variable bx equal bound(two,xmax)
variable bn equal bound(one,ymin,slab)
variable gy equal gyration(one)
variable k equal ke(two)
fix at all ave/time 2 5 10 c_tp c_g v_gx c_ct[*] file ave.txt
fix ar all ave/time 1 4 10 c_tc c_vacf[4] ave running
fix av all ave/time 5 2 10 c_m mode vector file avec.txt
fix pr all print 10 \"step $(step) tp $(c_tp:%.10f) f ${gx}\" file print.txt screen no
thermo_style custom step temp c_tp c_tp[1] c_tc[4] c_tc c_tr c_g c_g[1] c_g[4] c_ct[1] c_ct[2] c_vacf[4] c_m[4] c_r1 c_r2[1] c_r2[2] c_rc c_rs c_rke f_at[1] f_at[2] f_at[3] f_ar[2] pxx press v_n v_nr v_ms v_xc v_vc v_fc v_bx v_bn v_gy v_k
thermo_modify format float %.17g norm yes
thermo 10
run 30
thermo_modify temp tp
run 10
"
);

/// fix ave/histo of per-atom keywords, per-atom computes (beyond extra, ave running),
/// a global vector and global scalars (beyond end, ave window).
const HISTO: &str = concat!(
    scene_head!(),
    "group two type 2
compute ke all ke/atom
compute g all gyration
variable t equal temp
fix h1 all ave/histo 2 3 10 -2.0 2.0 8 vx vy file h1.txt mode vector
fix h2 two ave/histo 5 2 10 0.0 3.0 6 c_ke beyond extra file h2.txt ave running mode vector
fix h3 all ave/histo 1 1 10 -0.5 2.0 5 c_g mode vector file h3.txt
fix h4 all ave/histo 1 5 10 0.0 1.0 3 c_g[1] c_g[2] v_t beyond end ave window 2 file h4.txt
thermo_style custom step temp f_h1[1] f_h1[2] f_h1[3] f_h1[4] f_h2[1] f_h2[3] f_h3[1] f_h4[1] f_h4[3] f_h4[4]
thermo 10
thermo_modify format float %.17g
run 40
"
);

/// fix ave/atom of a per-atom keyword, a per-atom compute and an atom-style variable on a
/// group, and of a force on all, in a dump.
const AVE_ATOM: &str = concat!(
    scene_head!(),
    "group two type 2
compute ke all ke/atom
variable e atom vx*vx+x
fix aa two ave/atom 2 3 10 vx c_ke v_e
fix ab all ave/atom 5 1 5 fz
dump d all custom 10 aa.dump id f_aa[1] f_aa[2] f_aa[3] f_ab
dump_modify d sort id format float %.17g
thermo 10
run 30
"
);

/// compute cluster/atom of a group and of all, and coord/atom, on LAMMPS's random
/// positions (create_atoms random draws LAMMPS's).
const CLUSTERS: &str = "units lj
comm_modify vel yes
region box block 0 6 0 6 0 6
create_box 2 box
create_atoms 1 random 150 4821 NULL
create_atoms 2 random 60 771 NULL
mass * 1.0
pair_style dpd 1.0 1.0 4928
pair_coeff * * 25.0 0.0
fix nve all nve
group two type 2
compute cl two cluster/atom 0.8
compute cla all cluster/atom 0.6
compute co all coord/atom cutoff 0.95 1 2
dump d all custom 10 cl.dump id c_cl c_cla c_co[1] c_co[2]
dump_modify d sort id
run 0
";

/// fix vector of a compute's scalar and of an equal-style variable over two runs (the
/// second run's set-up step is not stored twice), read back by print.
const VECTOR: &str = concat!(
    scene_head!(),
    "compute g all gyration
variable t equal temp
fix v1 all vector 5 c_g
fix v2 all vector 5 v_t
thermo 5
run 20
print \"n $(f_v2[1]) $(f_v2[2]) $(f_v2[4]) $(f_v2[5]) $(f_v1[1]) $(f_v1[5])\"
run 5
print \"n $(f_v2[6]) $(f_v1[6])\"
"
);

/// The numbers of a text file, line by line.
fn numbers(path: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines().filter(|l| !l.starts_with('#')).map(|l| l.split_whitespace().filter_map(|w| w.parse().ok()).collect()).collect()
}

#[test]
fn computes_and_output_fixes_match_lammps() {
    let ((dl, l), (dg, g)) = both("computes", SCENE);
    let worst = same_thermo(&l, &g, 1e-12);
    eprintln!("thermo: worst relative difference {worst:.2e}");
    // %g values: to their 6 digits
    same_files(&dl, &dg, &["ave.txt", "avec.txt", "print.txt"], 1e-9);
}

/// The thermo blocks of two runs agree to `rel` of each column's largest magnitude; returns
/// the worst relative difference.
fn same_thermo(l: &str, g: &str, rel: f64) -> f64 {
    let (bl, bg) = (parse_thermo_blocks(l, "Step"), parse_thermo_blocks(g, "Step"));
    assert_eq!(bl.len(), bg.len());
    let mut worst: f64 = 0.0;
    for (tl, tg) in bl.iter().zip(&bg) {
        assert_eq!(tl.header, tg.header);
        assert_eq!(tl.rows.len(), tg.rows.len());
        for (c, name) in tl.header.iter().enumerate() {
            let scale = tl.rows.iter().map(|r| r[c].abs()).fold(0.0, f64::max).max(1e-300);
            for (rl, rg) in tl.rows.iter().zip(&tg.rows) {
                let d = (rl[c] - rg[c]).abs() / scale;
                assert!(d < rel, "{name} at step {}: gendpde {} LAMMPS {}", rl[0], rg[c], rl[c]);
                worst = worst.max(d);
            }
        }
    }
    worst
}

/// The files of two runs hold the same headings and numbers (to `rel` of 1 or more).
fn same_files(dl: &Path, dg: &Path, files: &[&str], rel: f64) {
    for file in files {
        let (nl, ng) = (numbers(&dl.join(file)), numbers(&dg.join(file)));
        assert_eq!(nl.len(), ng.len(), "{file}: lines");
        for (a, b) in nl.iter().zip(&ng) {
            assert_eq!(a.len(), b.len(), "{file}: {a:?} vs {b:?}");
            for (x, y) in a.iter().zip(b) {
                assert!((x - y).abs() <= rel * x.abs().max(1.0), "{file}: LAMMPS {a:?} gendpde {b:?}");
            }
        }
        let heads = |d: &Path| std::fs::read_to_string(d.join(file)).unwrap().lines().filter(|l| l.starts_with('#')).map(String::from).collect::<Vec<_>>();
        assert_eq!(heads(dl), heads(dg), "{file}");
    }
}

#[test]
fn ave_histo_matches_lammps() {
    let ((dl, l), (dg, g)) = both("histo", HISTO);
    let worst = same_thermo(&l, &g, 1e-12);
    eprintln!("thermo: worst relative difference {worst:.2e}");
    same_files(&dl, &dg, &["h1.txt", "h2.txt", "h3.txt", "h4.txt"], 1e-12);
}

#[test]
fn ave_atom_matches_lammps() {
    let ((dl, _), (dg, _)) = both("ave-atom", AVE_ATOM);
    let read = |d: &Path| parse_dump(&std::fs::read_to_string(d.join("aa.dump")).unwrap());
    let (fl, fg) = (read(&dl), read(&dg));
    assert_eq!(fl.len(), 4);
    assert_eq!(fl.len(), fg.len());
    let mut worst: f64 = 0.0;
    for (a, b) in fl.iter().zip(&fg) {
        assert_eq!((a.timestep, &a.columns), (b.timestep, &b.columns));
        for ((ia, va), (ib, vb)) in a.atoms.iter().zip(&b.atoms) {
            assert_eq!(ia, ib);
            for (x, y) in va.iter().zip(vb) {
                let d = (x - y).abs() / x.abs().max(1.0);
                assert!(d < 1e-12, "step {} atom {ia}: LAMMPS {va:?} gendpde {vb:?}", a.timestep);
                worst = worst.max(d);
            }
        }
    }
    eprintln!("fix ave/atom: worst relative difference {worst:.2e}");
}

#[test]
fn fix_vector_matches_lammps() {
    let ((_, l), (_, g)) = both("vector", VECTOR);
    let lines = |t: &str| t.lines().filter(|l| l.starts_with("n ")).map(|l| l.split_whitespace().skip(1).map(|w| w.parse::<f64>().unwrap()).collect::<Vec<_>>()).collect::<Vec<_>>();
    let (nl, ng) = (lines(&l), lines(&g));
    assert_eq!(nl.len(), 2);
    assert_eq!(nl.len(), ng.len());
    for (a, b) in nl.iter().zip(&ng) {
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= 1e-13 * x.abs().max(1.0), "LAMMPS {a:?} gendpde {b:?}");
        }
    }
}

#[test]
fn clusters_and_coordination_match_lammps() {
    let ((dl, _), (dg, _)) = both("clusters", CLUSTERS);
    let read = |d: &Path| parse_dump(&std::fs::read_to_string(d.join("cl.dump")).unwrap()).remove(0);
    let (l, g) = (read(&dl), read(&dg));
    assert_eq!(l.columns, g.columns);
    assert_eq!(l.atoms, g.atoms);
    let labels: std::collections::HashSet<u64> = l.atoms.iter().map(|a| a.1[1] as u64).collect();
    assert!(labels.len() > 20 && labels.len() < 200, "a scene of many clusters: {}", labels.len());
}

#[cfg(feature = "mpi")]
#[test]
fn computes_and_output_fixes_do_not_depend_on_the_rank_count() {
    for (scene, files) in [(SCENE, &["ave.txt", "avec.txt", "print.txt"][..]), (HISTO, &["h1.txt", "h2.txt", "h3.txt", "h4.txt"][..]), (AVE_ATOM, &["aa.dump"][..]), (CLUSTERS, &["cl.dump"][..])] {
        let dir = tempdir("computes-ranks");
        std::fs::write(dir.join("in.x"), scene).unwrap();
        let mut first: Option<Vec<String>> = None;
        for np in [1, 3] {
            let out = mpirun(np, &dir, &["run", "in.x", "-log", "none"]);
            assert!(out.status.success(), "{np} ranks: {}", String::from_utf8_lossy(&out.stderr));
            let thermo: Vec<String> = parse_thermo_blocks(&String::from_utf8_lossy(&out.stdout), "Step").iter().flat_map(|b| b.rows.iter().map(|r| format!("{r:?}"))).collect();
            let all: Vec<String> = thermo.into_iter().chain(files.iter().map(|f| std::fs::read_to_string(dir.join(f)).unwrap())).collect();
            match &first {
                None => first = Some(all),
                Some(f) => assert!(*f == all, "{np} ranks differ from 1 rank"),
            }
        }
    }
}

#[test]
fn compute_and_output_fix_errors_name_the_line() {
    let head = "units lj\nlattice fcc 3.0\nregion box block 0 3 0 3 0 3\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\nvariable a atom x\ncompute k all ke/atom\ncompute t all temp\n";
    let stage = |script: &str| {
        let dir = tempdir("compute-errors");
        std::fs::write(dir.join("in.x"), script).unwrap();
        dir
    };
    common::expect_errors(
        head,
        &[
            ("compute p all temp/partial 1 2 0", "Illegal compute temp/partial command"),
            ("compute p all temp/region nope", "Region nope for compute temp/region does not exist"),
            ("compute p all count/type foo", "Invalid compute count/type keyword foo"),
            ("compute p all coord/atom cutoff 2.0 group nope", "Group ID nope requested by compute coord/atom does not exist"),
            ("compute p all property/atom foo", "Invalid keyword foo for compute property/atom command"),
            ("compute r all reduce sum c_k[2]", "Compute reduce compute k does not calculate a per-atom array"),
            ("compute p all property/atom x vx\ncompute r all reduce sum c_p", "Compute reduce compute p does not calculate a per-atom vector"),
            ("compute p all property/atom x vx\ncompute r all reduce sum c_p[3]", "Compute reduce compute p array is accessed out-of-range"),
            ("compute_modify t foo 1", "Compute t temp does not support compute_modify foo command"),
            ("fix f all ave/time 1 1 1 c_nope", "Compute ID nope for fix ave/time does not exist"),
            ("fix f all ave/time 1 1 1 v_nope", "Variable name nope for fix ave/time does not exist"),
            ("fix f all ave/time 1 1 1 v_a", "Fix ave/time variable a is atom-style"),
            ("fix f all ave/time 1 1 1 c_t[7]", "Fix ave/time compute does not calculate a vector"),
            ("fix f all ave/time 1 1 1 c_k", "Fix ave/time compute does not calculate a scalar"),
            ("fix f all ave/time 1 1 1 c_t off 2", "Invalid fix ave/time off column 2"),
            ("fix f all ave/time 1 1 1 c_t mode array", "mode array (expected scalar or vector)"),
            ("fix f all ave/time 2 1 3 c_t", "Nfreq a multiple of Nevery"),
            ("fix f all print 0 hello", "Illegal fix print nevery value 0; must be > 0"),
            ("fix f all print 10 hello title", "missing argument"),
            ("pair_style dpd 1.0 1.0 1\npair_coeff * * 25 0\nfix nve all nve\nfix f all ave/time 10 1 10 c_t\nthermo_style custom step f_f\nthermo 5\nrun 10", "Thermo fix f not computed at compatible time"),
        ],
        stage,
    );
}
