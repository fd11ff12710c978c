//! eDPD (LAMMPS DPD-MESO: atom_style edpd, pair edpd, fix mvv/edpd, fix edpd/source,
//! compute edpd/temp/atom) against the reference LAMMPS, on the inputs of scripts/lammps/:
//! 1. per-particle forces at step 0 with the noise separated out (F(dt) = D + N/sqrt(dt),
//!    the same N in both runs of a code: 2 F(4) - F(1) = D), per-type coefficients and the
//!    power/kappa keywords, to round-off; the same for the pressure and its diagonal
//!    (kinetic part and virial, LAMMPS's conventions) and the energies;
//! 2. the heat conduction of the pair flux Q, with particles frozen for one step (the same
//!    separation on (T1 - T0) C_V / dt), to round-off;
//! 3. the heat sources (cuboid, sphere, region, a group), deterministic: T after 10 steps,
//!    to the bit;
//! 4. LAMMPS's examples in.edpd and in.edpd-region run unchanged (shortened to 2 x 10
//!    steps) and heat the source half.
//!
//! The temperature profile of in.edpd over several seeds: scripts/validation/edpd_profile.py.

use crate::common;

use common::lammps::{expect_success, parse_thermo, read_dump_snapshot, run_lammps, stage_inputs, DumpSnapshot};
use std::path::{Path, PathBuf};
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gendpde-edpd-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn gendpde(dir: &Path, input: &str, vars: &[(&str, &str)]) -> String {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_gendpde"));
    cmd.current_dir(dir).args(["-in", input, "-log", "none"]);
    for (k, v) in vars {
        cmd.args(["-var", k, v]);
    }
    let out = cmd.output().expect("gendpde runs");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "gendpde failed on {input}:\n{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    stdout
}

/// Dumps of `input` from both codes for each value of `dt` (LAMMPS and gendpde name the
/// temperature column c_t and edpd_temp: variable `tcol`).
fn both(name: &str, input: &str, vars: &[(&str, &str)], dts: &[&str]) -> Vec<(DumpSnapshot, DumpSnapshot)> {
    let d = dir(name);
    stage_inputs(&d, input);
    dts.iter()
        .map(|dt| {
            let (l, g) = (format!("l{dt}.dump"), format!("g{dt}.dump"));
            let mut lv = vec![("dt", *dt), ("out", l.as_str()), ("tcol", "c_t")];
            lv.extend_from_slice(vars);
            expect_success("LAMMPS", &run_lammps(&d, input, &lv));
            let mut gv = vec![("dt", *dt), ("out", g.as_str()), ("tcol", "edpd_temp")];
            gv.extend_from_slice(vars);
            gendpde(&d, input, &gv);
            (read_dump_snapshot(&d.join(l)), read_dump_snapshot(&d.join(g)))
        })
        .collect()
}

/// Value `c` of every particle (sorted by id).
fn column(s: &DumpSnapshot, c: usize) -> Vec<f64> {
    s.atoms.iter().map(|(_, v)| v[c]).collect()
}

/// Largest |a - b| over the particles and the largest |a|.
fn worst(a: &[f64], b: &[f64]) -> (f64, f64) {
    a.iter().zip(b).fold((0.0f64, 0.0f64), |(d, m), (x, y)| (d.max((x - y).abs()), m.max(x.abs())))
}

/// The particles' (T, C_V) of data.edpd-small, in id order.
fn data_temperatures() -> Vec<(f64, f64)> {
    let text = std::fs::read_to_string(common::lammps::scripts_dir().join("data.edpd-small")).unwrap();
    let atoms = text.split("Atoms # edpd").nth(1).unwrap().split("Velocities").next().unwrap();
    let mut rows: Vec<(u64, f64, f64)> = atoms
        .lines()
        .filter_map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (w.len() >= 7).then(|| (w[0].parse().unwrap(), w[2].parse().unwrap(), w[3].parse().unwrap()))
        })
        .collect();
    rows.sort_by_key(|r| r.0);
    rows.into_iter().map(|(_, t, cv)| (t, cv)).collect()
}

#[test]
fn edpd_forces_at_step_0_match_lammps_without_the_noise() {
    for case in ["types", "poly"] {
        let runs = both(&format!("forces-{case}"), "in.edpd-forces", &[("case", case)], &["1.0", "4.0"]);
        for k in 0..3 {
            let det = |a: &DumpSnapshot, b: &DumpSnapshot| column(a, k).iter().zip(column(b, k)).map(|(f1, f4)| 2.0 * f4 - f1).collect::<Vec<_>>();
            let (l, g) = (det(&runs[0].0, &runs[1].0), det(&runs[0].1, &runs[1].1));
            let (diff, max) = worst(&l, &g);
            // the noise is not the same in the two codes: the raw forces differ
            let (raw, _) = worst(&column(&runs[0].0, k), &column(&runs[0].1, k));
            eprintln!("{case}, f{}: conservative + dissipative max |dF| = {diff:.2e} of max |F| = {max:.1} (raw forces differ by {raw:.1})", ["x", "y", "z"][k]);
            assert!(diff < 1e-11 * max, "{case}: forces differ by {diff:e}");
            assert!(raw > 1e-3 * max, "{case}: the noise was expected to differ between the codes");
        }
    }
}

/// The pressure of pair edpd (kinetic part with LAMMPS's 3N - 3 degrees of freedom, the
/// virial of the conservative, dissipative and random forces) and the energies at step 0:
/// the noise separated as for the forces (P(dt) = P_D + P_N / sqrt(dt)), to round-off. The
/// random virial alone moves an instantaneous Press of LAMMPS's in.edpd by about 1.5, so
/// that example's thermo Press can only agree on average.
#[test]
fn edpd_pressure_and_energies_at_step_0_match_lammps_without_the_noise() {
    for case in ["types", "poly"] {
        let d = dir(&format!("press-{case}"));
        stage_inputs(&d, "in.edpd-forces");
        let rows = ["1.0", "4.0"].map(|dt| {
            let vars = [("dt", dt), ("case", case), ("out", "p.dump")];
            let l = expect_success("LAMMPS", &run_lammps(&d, "in.edpd-forces", &vars));
            let g = gendpde(&d, "in.edpd-forces", &vars);
            let row = |text: &str| parse_thermo(text, "Step").into_iter().next().expect("a thermo row at step 0");
            (row(&l), row(&g))
        });
        let det = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p1, p4)| 2.0 * p4 - p1).collect::<Vec<f64>>();
        let (l, g) = (det(&rows[0].0, &rows[1].0), det(&rows[0].1, &rows[1].1));
        // step temp pe ke press pxx pyy pzz
        for (k, name) in ["temp", "pe", "ke", "press", "pxx", "pyy", "pzz"].iter().enumerate().map(|(k, n)| (k + 1, n)) {
            let rel = (l[k] - g[k]).abs() / l[k].abs();
            eprintln!("{case}: {name} {:.12} (LAMMPS) vs {:.12}, relative {rel:.1e}; raw {:.6} vs {:.6}", l[k], g[k], rows[0].0[k], rows[0].1[k]);
            assert!(rel < 1e-12, "{case}: deterministic {name} differs: {} vs {}", l[k], g[k]);
        }
    }
}

#[test]
fn edpd_heat_conduction_matches_lammps_without_the_noise() {
    let runs = both("heat", "in.edpd-heat", &[], &["1.0", "4.0"]);
    let t0 = data_temperatures();
    // y = (T1 - T0) C_V / dt = Q_c + noise / sqrt(dt); Q_c = 2 y(4) - y(1)
    let conduction = |one: &DumpSnapshot, four: &DumpSnapshot| {
        let y = |s: &DumpSnapshot, dt: f64| column(s, 0).iter().zip(&t0).map(|(t1, (t, cv))| (t1 - t) * cv / dt).collect::<Vec<_>>();
        y(four, 4.0).iter().zip(y(one, 1.0)).map(|(a, b)| 2.0 * a - b).collect::<Vec<_>>()
    };
    let (l, g) = (conduction(&runs[0].0, &runs[1].0), conduction(&runs[0].1, &runs[1].1));
    let (diff, max) = worst(&l, &g);
    let total: f64 = g.iter().sum();
    eprintln!("heat conduction: max |dQ| = {diff:.2e} of max |Q| = {max:.2e}; sum of Q = {total:.1e}");
    assert!(diff < 1e-10 * max, "conduction differs by {diff:e}");
    assert!(max > 1e-3, "no conduction to compare");
    assert!(total.abs() < 1e-10 * max * l.len() as f64, "conduction does not conserve heat: {total:e}");
}

#[test]
fn edpd_sources_match_lammps_to_the_bit() {
    let d = dir("sources");
    stage_inputs(&d, "in.edpd-sources");
    expect_success("LAMMPS", &run_lammps(&d, "in.edpd-sources", &[("out", "l.dump")]));
    gendpde(&d, "in.edpd-sources", &[("out", "g.dump"), ("tcol", "edpd_temp")]);
    let (l, g) = (column(&read_dump_snapshot(&d.join("l.dump")), 0), column(&read_dump_snapshot(&d.join("g.dump")), 0));
    let t0 = data_temperatures();
    let heated = l.iter().zip(&t0).filter(|(t, (t0, _))| *t != t0).count();
    eprintln!("sources: {heated} of {} particles heated or cooled", l.len());
    assert!(heated > 100, "the sources should reach many particles, reached {heated}");
    assert_eq!(l, g, "per-particle temperatures after the sources differ");
}

/// LAMMPS's example with its runs shortened to `steps`, in gendpde; the profile file.
fn example(name: &str, steps: u64) -> String {
    let d = dir(name);
    let text = std::fs::read_to_string(common::lammps::scripts_dir().join(name)).unwrap();
    let text = text.replace("run                 500", &format!("run                 {steps}")).replace("ave/chunk 1 500 500", &format!("ave/chunk 1 {steps} {steps}"));
    std::fs::write(d.join(name), text).unwrap();
    gendpde(&d, name, &[]);
    std::fs::read_to_string(d.join("temp.profile")).unwrap()
}

#[test]
fn lammps_edpd_examples_run_unchanged_and_heat_the_source_half() {
    for name in ["in.edpd", "in.edpd-region"] {
        let profile = example(name, 10);
        let rows: Vec<Vec<f64>> =
            profile.lines().filter(|l| !l.starts_with('#')).map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect()).filter(|r: &Vec<f64>| r.len() == 5).collect();
        assert_eq!(rows.len(), 20, "{name}: 20 bins of y");
        let mean = |upper: bool| {
            let r: Vec<&Vec<f64>> = rows.iter().filter(|r| (r[1] > 0.0) == upper).collect();
            r.iter().map(|r| r[3]).sum::<f64>() / r.len() as f64
        };
        let (hot, cold) = (mean(true), mean(false));
        // 20 steps of +-0.01 per time unit (0.011 in the region variant): about +-0.002
        eprintln!("{name}: mean T of the heated half {hot:.5}, of the cooled half {cold:.5}");
        assert!(hot - cold > 0.002 && hot - cold < 0.006, "{name}: heated half {hot}, cooled half {cold}");
    }
}

#[test]
fn bad_edpd_input_is_refused_naming_the_line() {
    let d = dir("errors");
    let head = "units lj\natom_style edpd\nregion b block 0 8 0 8 0 8\ncreate_box 2 b\ncreate_atoms 1 random 100 7 NULL\nmass * 1.0\n";
    let pair = "pair_style edpd 1.58 9872598\npair_coeff * * 18.75 4.5 0.41 1.58 1.41E-5 2.0 1.58\n";
    let cases = [
        (format!("{head}pair_style edpd 1.58 9872598\npair_coeff * * 18.75 4.5 0.41 1.58\n"), "in.bad:8: pair_coeff: missing argument"),
        (format!("{head}pair_style edpd 1.58 9872598\npair_coeff * * 18.75 4.5 0.41 1.58 1.41E-5 2.0 1.58 power 1 2 3\n"), "in.bad:8: pair_coeff: missing argument"),
        (format!("{head}pair_style edpd 1.58 9872598\npair_coeff * * 18.75 4.5 0.41 1.58 1.41E-5 2.0 1.58 slope 1 2 3 4\n"), "in.bad:8: pair_coeff: unknown keyword 'slope'"),
        (format!("{head}pair_style edpd 1.58 0\n"), "in.bad:7: pair_style: the random seed must be positive"),
        (format!("{head}set atom * edpd/temp -1.0\n"), "in.bad:7: set:"),
        (format!("{head}{pair}fix s all edpd/source region nowhere 0.1\n"), "in.bad:9: fix: region nowhere for fix edpd/source does not exist"),
        (format!("{head}{pair}fix s all edpd/source cube 0 0 0 1 0.1\n"), "in.bad:9: fix: expected sphere, cuboid or region, got 'cube'"),
        (format!("{head}{pair}run 0\n"), "in.bad:9: run: pair edpd integrates with fix mvv/edpd"),
        (format!("{head}pair_style edpd 1.58 9872598\npair_coeff 1 1 18.75 4.5 0.41 1.58 1.41E-5 2.0 1.58\nfix 1 all mvv/edpd\nrun 0\n"), "in.bad:10: run: pair edpd: no coefficients for types 1 2"),
        (format!("{head}{pair}fix 1 all nve\nrun 0\n"), "in.bad:10: run: fix 1 does not work with pair edpd: nve is not one of its fixes (mvv/edpd, edpd/source)"),
        ("units lj\natom_style atomic\nregion b block 0 8 0 8 0 8\ncreate_box 1 b\ncreate_atoms 1 random 10 7 NULL\nset atom * edpd/cv 2.0\n".to_string(), "in.bad:6: set: set edpd/cv needs atom_style edpd"),
    ];
    for (script, expected) in cases {
        std::fs::write(d.join("in.bad"), &script).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).current_dir(&d).args(["-in", "in.bad", "-log", "none"]).output().unwrap();
        let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        assert!(!out.status.success(), "accepted:\n{script}");
        assert!(text.contains(expected), "expected '{expected}' for\n{script}\ngot:\n{text}");
        assert!(!text.contains("panicked"), "panic for\n{script}\n{text}");
    }
}
