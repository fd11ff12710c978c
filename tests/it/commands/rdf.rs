//! `compute rdf` with `fix ave/time ... mode vector`:
//! 1. an ideal gas (uniform random positions) gives g(r) = 1 within 4 standard errors;
//! 2. the same data file gives LAMMPS's output file (22 Jul 2025) to round-off;
//! 3. after free flight with list rebuilds, the counts equal a brute-force O(N^2) count;
//! 4. bad input names the file and line;
//! 5. (MPI) 1, 2 and 3 ranks write the same file.

use crate::common;

use common::lammps::{expect_success, run_lammps};
use gendpde::{Interpreter, Mode, Output};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gendpde-rdf-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// SplitMix64 uniform numbers in [0, 1).
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) as f64 / 2f64.powi(64)
    }
}

/// A data file of `n` uniform random particles in a cube of side `l`; `dpd` adds the
/// particle temperature column (atom_style dpd: id type theta x y z).
fn write_data(path: &Path, n: usize, l: f64, seed: u64, dpd: bool) {
    let mut rng = Rng(seed);
    let style = if dpd { "dpd" } else { "atomic" };
    let mut s = format!("random gas\n\n{n} atoms\n1 atom types\n\n0 {l} xlo xhi\n0 {l} ylo yhi\n0 {l} zlo zhi\n\nAtoms # {style}\n\n");
    for i in 1..=n {
        let theta = if dpd { " 1.0" } else { "" };
        let r: Vec<String> = (0..3).map(|_| format!("{:.12}", rng.uniform() * l)).collect();
        s += &format!("{i} 1{theta} {}\n", r.join(" "));
    }
    std::fs::write(path, s).unwrap();
}

/// Blocks of an ave/time vector file: (step, rows of values without the row index).
fn read_blocks(path: &Path) -> Vec<(u64, Vec<Vec<f64>>)> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let mut blocks = Vec::new();
    while let Some(head) = lines.next() {
        let w: Vec<u64> = head.split_whitespace().map(|x| x.parse().unwrap()).collect();
        let rows = (0..w[1]).map(|_| lines.next().unwrap().split_whitespace().skip(1).map(|x| x.parse().unwrap()).collect()).collect();
        blocks.push((w[0], rows));
    }
    blocks
}

/// The free ideal gas: GenDPDE with a density-independent EOS (no conservative force)
/// and no dissipation; rdf cutoff 2.5 beyond the pair cutoff 1.0 (wider cells).
fn ideal_script(steps: u64) -> String {
    format!(
        "units lj\natom_style dpd\nread_data ideal.data\nmass 1 1.0\nvelocity all create 1.0 4928 dist gaussian\n\
         pair_style gendpde 1.0 4928\nfix eos all eos/cv 10.0\nfix nve all nve/gendpde\ntimestep 0.01\n\
         compute g all rdf 25 cutoff 2.5\nfix out all ave/time 10 1 10 c_g[*] file ideal.rdf mode vector format \" %.17g\"\n\
         run {steps}\nwrite_dump all custom final.dump id x y z\n"
    )
}

const IDEAL: (usize, f64) = (3456, 12.0);

fn ideal_setup(name: &str, steps: u64) -> PathBuf {
    let d = dir(name);
    write_data(&d.join("ideal.data"), IDEAL.0, IDEAL.1, 17, true);
    std::fs::write(d.join("in.ideal"), ideal_script(steps)).unwrap();
    d
}

fn gendpde_run(d: &Path, np: usize) {
    let exe = env!("CARGO_BIN_EXE_gendpde");
    let out = if np == 1 {
        Command::new(exe).current_dir(d).args(["run", "in.ideal", "-log", "none"]).output().unwrap()
    } else {
        Command::new("mpirun")
            .args(["--oversubscribe", "-np", &np.to_string(), exe, "run", "in.ideal", "-log", "none"])
            .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
            .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
            .current_dir(d)
            .output()
            .expect("mpirun runs")
    };
    assert!(out.status.success(), "gendpde on {np} ranks failed:\n{}", String::from_utf8_lossy(&out.stderr));
}

/// Fraction of the box volume in bin k of width dr.
fn shell_fraction(k: usize, dr: f64, volume: f64) -> f64 {
    4.0 * PI / 3.0 * (((k + 1) as f64 * dr).powi(3) - (k as f64 * dr).powi(3)) / volume
}

#[test]
fn ideal_gas_has_unit_g_within_four_standard_errors() {
    let d = ideal_setup("ideal", 0);
    gendpde_run(&d, 1);
    let blocks = read_blocks(&d.join("ideal.rdf"));
    let (n, l) = (IDEAL.0 as f64, IDEAL.1);
    let (pairs, dr) = (n * (n - 1.0) / 2.0, 0.1);
    // In a periodic box the indicators of pairs (i, j) and (i, k) are independent, so the
    // number X of pairs in a shell of volume fraction p has variance M p (1 - p), M = N(N-1)/2,
    // and g = X / (M p): sigma_g = sqrt((1 - p) / (M p)).
    let (mut chi2, mut total, mut worst) = (0.0, 0.0, 0.0f64);
    let rows = &blocks[0].1;
    assert_eq!((blocks[0].0, rows.len()), (0, 25));
    for (k, row) in rows.iter().enumerate() {
        let p = shell_fraction(k, dr, l * l * l);
        let sigma = ((1.0 - p) / (pairs * p)).sqrt();
        let z = (row[1] - 1.0) / sigma;
        assert!((row[0] - (k as f64 + 0.5) * dr).abs() < 1e-12);
        assert!(z.abs() < 4.0, "bin {k} (r = {}): g = {} is {z:.2} sigma from 1", row[0], row[1]);
        (chi2, total, worst) = (chi2 + z * z, total + row[1] * p * pairs, worst.max(z.abs()));
    }
    let p_all = 4.0 * PI / 3.0 * 2.5f64.powi(3) / (l * l * l);
    let z_all = (total / (pairs * p_all) - 1.0) / ((1.0 - p_all) / (pairs * p_all)).sqrt();
    eprintln!("ideal gas N = {n}: chi2 = {chi2:.1} over 25 bins, largest |z| = {worst:.2}, all pairs within 2.5: z = {z_all:.2}");
    assert!(z_all.abs() < 4.0);
    // coord(Rc) is the mean number of neighbours within Rc
    let coord = rows[24][2];
    assert!((coord - 2.0 * total / n).abs() < 1e-9 * coord, "coord {coord}");
}

#[test]
fn counts_after_free_flight_match_a_brute_force_count() {
    let d = ideal_setup("flight", 100);
    gendpde_run(&d, 1);
    let blocks = read_blocks(&d.join("ideal.rdf"));
    assert_eq!(blocks.iter().map(|b| b.0).collect::<Vec<_>>(), (0..=100).step_by(10).collect::<Vec<_>>());
    let dump = std::fs::read_to_string(d.join("final.dump")).unwrap();
    let lines: Vec<&str> = dump.lines().collect();
    let start = lines.iter().position(|l| l.starts_with("ITEM: ATOMS")).unwrap() + 1;
    let r: Vec<[f64; 3]> = lines[start..]
        .iter()
        .map(|l| {
            let w: Vec<f64> = l.split_whitespace().skip(1).map(|x| x.parse().unwrap()).collect();
            [w[0], w[1], w[2]]
        })
        .collect();
    let (n, l, dr) = (IDEAL.0 as f64, IDEAL.1, 0.1);
    let mut brute = [0u64; 25];
    for i in 0..r.len() {
        for j in 0..i {
            let d2: f64 = (0..3).map(|a| {
                let x = r[i][a] - r[j][a];
                let x = x - l * (x / l).round();
                x * x
            }).sum();
            let k = (d2.sqrt() / dr) as usize;
            if k < 25 {
                brute[k] += 2;
            }
        }
    }
    let last = &blocks.last().unwrap().1;
    for (k, row) in last.iter().enumerate() {
        let counted = row[1] * shell_fraction(k, dr, l * l * l) * (n - 1.0) * n;
        assert!((counted - brute[k] as f64).abs() < 1e-6 * counted.max(1.0), "bin {k}: rdf counts {counted}, brute force {}", brute[k]);
    }
}

#[test]
fn output_matches_lammps() {
    let d = dir("lammps");
    write_data(&d.join("data.rdf"), 500, 7.0, 5, false);
    // static particles (no force, no velocity): ave/time averages identical samples
    let script = "units lj\natom_style atomic\nread_data data.rdf\nmass 1 1.0\ncomm_modify vel yes\n\
                  pair_style dpd 1.0 1.2 4928\npair_coeff * * 0.0 0.0\nfix 1 all nve\n\
                  compute a all rdf 30\ncompute b all rdf 8 cutoff 0.8\n\
                  fix fa all ave/time 5 1 5 c_a[*] file a.rdf mode vector format \" %.17g\"\n\
                  fix fb all ave/time 2 3 10 c_b[3] c_b[2] file b.rdf mode vector format \" %.17g\"\n\
                  run 20\n";
    let (dl, dg) = (d.join("lammps"), d.join("gendpde"));
    for sub in [&dl, &dg] {
        std::fs::create_dir_all(sub).unwrap();
        std::fs::copy(d.join("data.rdf"), sub.join("data.rdf")).unwrap();
        std::fs::write(sub.join("in.rdf"), script).unwrap();
    }
    expect_success("LAMMPS", &run_lammps(&dl, "in.rdf", &[]));
    let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(&dg).args(["run", "in.rdf", "-log", "none"]).output().unwrap();
    assert!(out.status.success(), "gendpde failed:\n{}", String::from_utf8_lossy(&out.stderr));
    for file in ["a.rdf", "b.rdf"] {
        let (tl, tg) = (std::fs::read_to_string(dl.join(file)).unwrap(), std::fs::read_to_string(dg.join(file)).unwrap());
        let heads = |t: &str| t.lines().filter(|l| l.starts_with('#')).map(String::from).collect::<Vec<_>>();
        assert_eq!(heads(&tl), heads(&tg), "{file}: heading lines");
        let (bl, bg) = (read_blocks(&dl.join(file)), read_blocks(&dg.join(file)));
        assert_eq!(bl.iter().map(|b| b.0).collect::<Vec<_>>(), bg.iter().map(|b| b.0).collect::<Vec<_>>(), "{file}: block steps");
        let mut worst = 0.0f64;
        for ((_, rl), (_, rg)) in bl.iter().zip(&bg) {
            assert_eq!(rl.len(), rg.len());
            for (a, b) in rl.iter().flatten().zip(rg.iter().flatten()) {
                worst = worst.max((a - b).abs() / a.abs().max(1e-300));
            }
        }
        eprintln!("{file}: {} blocks, identical text: {}, largest relative difference {worst:.1e}", bl.len(), tl == tg);
        assert!(worst < 1e-14, "{file}: largest relative difference {worst:e}");
    }
}

/// The error of running `text` (as file `in.bad`).
fn error_of(text: &str) -> String {
    let mut it = Interpreter::new(Mode::Check, Output::new(false));
    match it.execute_str("in.bad", text) {
        Ok(()) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_input_names_the_line() {
    let head = "units lj\nregion b block 0 8 0 8 0 8 units box\ncreate_box 1 b\n";
    let cases = [
        ("compute g all rdf 0\n", "in.bad:4:", "Nbin"),
        ("compute g all rdf ten\n", "in.bad:4:", "the number of bins Nbin"),
        ("compute g all rdf 10 1 2\n", "in.bad:4:", "all-all"),
        ("compute g all rdf 10 cutoff -1\n", "in.bad:4:", "cutoff Rc must be positive"),
        ("compute g all rdf 10\nfix f all ave/time 1 1 1 c_h[*] file x mode vector\n", "in.bad:5:", "Invalid fix ave/time argument: c_h[*]"),
        ("compute g all rdf 10\nfix f all ave/time 1 1 1 c_g[4] file x mode vector\n", "in.bad:5:", "Fix ave/time compute g array is accessed out-of-range"),
        ("compute g all rdf 10\nfix f all ave/time 2 1 5 c_g[*] file x mode vector\n", "in.bad:5:", "multiple of Nevery"),
        ("compute g all rdf 10\nfix f all ave/time 1 1 1 c_g[*] file x\n", "in.bad:5:", "Invalid fix ave/time argument: c_g[*]"),
        ("compute g all rdf 10\nfix f mobile ave/time 1 1 1 c_g[*] file x mode vector\n", "in.bad:5:", "Could not find fix group ID mobile"),
        ("compute g mobile rdf 10\n", "in.bad:4:", "group mobile"),
    ];
    for (tail, line, what) in cases {
        let e = error_of(&format!("{head}{tail}"));
        assert!(e.contains(line) && e.contains(what), "error for {tail:?} lacks {line} or {what:?}: {e}");
    }
    // a cutoff whose cells do not fit the box
    let scene = "mass 1 1.0\nlattice sc 1.0\ncreate_atoms 1 box\npair_style dpd 1.0 1.0 1\npair_coeff * * 25 4.5\nfix n all nve\n";
    let e = error_of(&format!("{head}{scene}compute g all rdf 10 cutoff 4.5\nfix f all ave/time 1 1 1 c_g[*] file x mode vector\nrun 0\n"));
    assert!(e.contains("in.bad:12:") && e.contains("compute g rdf: cutoff + skin"), "{e}");
}

#[cfg(feature = "mpi")]
#[test]
fn one_two_and_three_ranks_write_the_same_file() {
    let mut reference = None;
    for np in [1, 2, 3] {
        let d = ideal_setup(&format!("mpi{np}"), 100);
        gendpde_run(&d, np);
        let text = std::fs::read_to_string(d.join("ideal.rdf")).unwrap();
        match &reference {
            None => reference = Some(text),
            Some(r) => assert!(*r == text, "{np} ranks write another file than 1 rank"),
        }
        eprintln!("ideal gas, 100 steps: {np} ranks identical to 1 rank");
    }
}
