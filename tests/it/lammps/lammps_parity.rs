//! Parity with the reference LAMMPS (22 Jul 2025, installed by ../shared/lammps/setup.sh):
//! the same input scripts (scripts/lammps/) run unchanged in both codes.
//! 1. deterministic (noise and dissipation off): per-particle positions and momenta agree
//!    to 1e-9 relative after 100 steps, for DPDE (conservative a0 force) and MDPD;
//! 2. statistical: time averages agree within 3 combined standard errors (block averages
//!    over 10 blocks of the production run);
//! 3. speed: atom-steps/s of both on the same script, reported (not asserted);
//! 4. LAMMPS's own DPDE example in metal units runs unchanged and conserves energy;
//! 5. two-type mixtures with coefficients and cutoffs per type pair (dpd, mdpd): forces
//!    at step 0 to round-off, particles after 100 (dpd) or 50 (mdpd) steps as in 1.;
//!    the mixture's `write_data pair ij` file of each code read by the other;
//! 6. DPD-BASIC's dpd/ext (two-type mixture) and the thermostats dpd/tstat, dpd/ext/tstat
//!    overlaid on a spline table (real units) with the noise off (T = 0): forces at step
//!    0 to round-off, thermo rows and particles after a few steps as in 1.

use crate::common;

use common::lammps::{agree_within, block_average, compare_dumps, expect_success, parse_thermo, parse_thermo_blocks, read_dump_snapshot, run_both, run_gendpde, run_lammps, stage_inputs, ThermoBlock};
use std::path::Path;

#[test]
fn dpde_conservative_dynamics_matches_lammps_per_particle() {
    let ((dl, _), (dg, _)) = run_both("dpde-det", "in.dpde-deterministic", &[], &[]);
    let (dr, dp) = compare_dumps(&dl.join("dpde-det.dump"), &dg.join("dpde-det.dump"));
    eprintln!("DPDE after 100 steps: max |dr|/L = {dr:.2e}, max |dp|/|p| = {dp:.2e}");
    assert!(dr < 1e-9 && dp < 1e-9, "dr {dr:e}, dp {dp:e}");
}

#[test]
fn mdpd_conservative_dynamics_matches_lammps_per_particle() {
    let ((dl, _), (dg, _)) = run_both("mdpd-det", "in.mdpd-deterministic", &[], &[]);
    let (dr, dp) = compare_dumps(&dl.join("mdpd-det.dump"), &dg.join("mdpd-det.dump"));
    eprintln!("MDPD after 100 steps: max |dr|/L = {dr:.2e}, max |dp|/|p| = {dp:.2e}");
    assert!(dr < 1e-9 && dp < 1e-9, "dr {dr:e}, dp {dp:e}");
}

/// Largest |f_gendpde - f_lammps| over particles and components, relative to the largest
/// |f_lammps|, between two dumps of `id fx fy fz`.
fn compare_forces(a: &Path, b: &Path) -> f64 {
    let (a, b) = (read_dump_snapshot(a), read_dump_snapshot(b));
    assert_eq!(a.atoms.len(), b.atoms.len());
    let scale = a.atoms.iter().flat_map(|(_, v)| v.iter()).fold(0.0f64, |m, x| m.max(x.abs()));
    let mut worst = 0.0f64;
    for ((ia, va), (ib, vb)) in a.atoms.iter().zip(&b.atoms) {
        assert_eq!(ia, ib);
        for (x, y) in va.iter().zip(vb) {
            worst = worst.max((x - y).abs() / scale);
        }
    }
    assert!(scale > 1.0, "the forces are trivial (largest {scale})");
    worst
}

/// A mixture scene of scripts/lammps (`in.mix-NAME`): step-0 forces and the particles after
/// `steps` steps against LAMMPS (the driven MDPD mixture heats fast, and round-off grows
/// with it).
fn mixture_matches_lammps(name: &str, steps: &str) {
    let ((dl, _), (dg, _)) = run_both(&format!("mix-{name}"), &format!("in.mix-{name}"), &[("steps", steps)], &[]);
    let f0 = format!("mix-{name}-f0.dump");
    let df = compare_forces(&dl.join(&f0), &dg.join(&f0));
    let end = format!("mix-{name}.dump");
    let (dr, dp) = compare_dumps(&dl.join(&end), &dg.join(&end));
    eprintln!("{name} mixture: step-0 forces max |df|/max|f| = {df:.2e}; after {steps} steps max |dr|/L = {dr:.2e}, max |dp|/|p| = {dp:.2e}");
    assert!(df < 1e-12, "forces at step 0 differ by {df:e}");
    assert!(dr < 1e-9 && dp < 1e-9, "dr {dr:e}, dp {dp:e}");
}

#[test]
fn dpd_mixture_with_per_pair_coefficients_and_cutoffs_matches_lammps() {
    mixture_matches_lammps("dpd", "100");
}

#[test]
fn mdpd_mixture_with_per_pair_coefficients_cutoffs_and_kernels_matches_lammps() {
    mixture_matches_lammps("mdpd", "50");
}

/// `pair_style` naming the style in force again keeps the coefficients and resets every
/// cutoff to the new global one, as LAMMPS does: forces before and after, against LAMMPS.
#[test]
fn pair_style_named_again_keeps_coefficients_as_lammps() {
    let ((dl, _), (dg, _)) = run_both("mix-restyle", "in.mix-dpd-restyle", &[], &[]);
    for f in ["restyle-f0.dump", "restyle-f1.dump"] {
        let df = compare_forces(&dl.join(f), &dg.join(f));
        assert!(df < 1e-12, "{f}: forces differ by {df:e}");
    }
    // the cutoffs did change: the forces after differ from those before
    let (a, b) = (read_dump_snapshot(&dg.join("restyle-f0.dump")), read_dump_snapshot(&dg.join("restyle-f1.dump")));
    assert!(a.atoms.iter().zip(&b.atoms).any(|((_, x), (_, y))| x != y), "the new global cutoff changed nothing");
}

/// A DPD-BASIC scene of scripts/lammps with T = 0 (sigma = 0; the friction acts on the
/// velocities of `velocity create`): step-0 forces `DUMP-f0.dump`, the thermo rows and the
/// particles `DUMP.dump` after the script's steps.
fn dpd_basic_matches_lammps(input: &str, dump: &str, extra: &[&str]) {
    let ((dl, l), (dg, g)) = run_both(dump, input, &[], extra);
    let f0 = format!("{dump}-f0.dump");
    let df = compare_forces(&dl.join(&f0), &dg.join(&f0));
    let end = format!("{dump}.dump");
    let (dr, dp) = compare_dumps(&dl.join(&end), &dg.join(&end));
    let (rl, rg) = (parse_thermo_blocks(&l, "Step"), parse_thermo_blocks(&g, "Step"));
    let rows = |b: &[ThermoBlock]| b.iter().flat_map(|b| b.rows.clone()).collect::<Vec<_>>();
    let (rl, rg) = (rows(&rl), rows(&rg));
    assert_eq!(rl.len(), rg.len(), "{input}: thermo rows");
    let worst = rl.iter().zip(&rg).flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs() / x.abs().max(1.0))).fold(0.0, f64::max);
    eprintln!("{input}: step-0 forces max |df|/max|f| = {df:.2e}; thermo rows max rel. diff {worst:.2e}; at the end max |dr|/L = {dr:.2e}, max |dp|/|p| = {dp:.2e}");
    assert!(df < 1e-12, "{input}: forces at step 0 differ by {df:e}");
    assert!(worst < 1e-10, "{input}: thermo rows differ by {worst:e}");
    assert!(dr < 1e-12 && dp < 1e-10, "{input}: dr {dr:e}, dp {dp:e}");
}

#[test]
fn dpd_ext_mixture_without_noise_matches_lammps() {
    dpd_basic_matches_lammps("in.dpd-ext", "dpd-ext", &[]);
}

#[test]
fn dpd_tstat_and_dpd_ext_tstat_over_a_table_without_noise_match_lammps() {
    dpd_basic_matches_lammps("in.dpd-tstat", "tstat", &["cg_spce_table.pot"]);
    dpd_basic_matches_lammps("in.dpdext-tstat", "dpdext-tstat", &["cg_spce_table.pot"]);
}

/// `write_data pair ij` of either code, read by the other with only `pair_style` in the
/// script (in.mix-dpd-data), gives the step-0 row of the script that set the coefficients.
#[test]
fn pairij_data_files_round_trip_between_gendpde_and_lammps() {
    let ((dl, l), (dg, g)) = run_both("mix-data", "in.mix-dpd", &[("steps", "0")], &[]);
    let first = |out: &str| parse_thermo(out, "Step")[0].clone();
    let expect = first(&l);
    assert!(agree(&expect, &first(&g)), "in.mix-dpd step 0: LAMMPS {expect:?}, gendpde {:?}", first(&g));
    let text = std::fs::read_to_string(dg.join("mix-dpd-ij.data")).unwrap();
    assert!(text.contains("PairIJ Coeffs # dpd\n\n1 1 25.0 4.5 1.2\n1 2 30.0 3.0 1.3\n2 2 20.0 6.0 1.0\n"), "{text}");
    // each code reads the other's file
    std::fs::copy(dg.join("mix-dpd-ij.data"), dl.join("from-gendpde.data")).unwrap();
    std::fs::copy(dl.join("mix-dpd-ij.data"), dg.join("from-lammps.data")).unwrap();
    stage_inputs(&dl, "in.mix-dpd-data");
    stage_inputs(&dg, "in.mix-dpd-data");
    let l2 = expect_success("LAMMPS", &run_lammps(&dl, "in.mix-dpd-data", &[("data", "from-gendpde.data")]));
    let out = run_gendpde(&dg, "in.mix-dpd-data", &[("data", "from-lammps.data")]);
    assert!(out.status.success(), "gendpde failed:\n{}", String::from_utf8_lossy(&out.stderr));
    let g2 = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(agree(&expect, &first(&l2)), "LAMMPS reading gendpde's file: {:?}", first(&l2));
    assert!(agree(&expect, &first(&g2)), "gendpde reading LAMMPS's file: {:?}", first(&g2));
}

/// Thermo rows equal to 1e-12 relative.
fn agree(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * x.abs().max(1.0))
}

/// The production block (the last thermo block) of a run.
fn production(text: &str) -> ThermoBlock {
    parse_thermo_blocks(text, "Step").pop().expect("a thermo block")
}

fn rate(text: &str) -> f64 {
    // "Loop time of T on P procs for S steps with N atoms"
    let line = text.lines().filter(|l| l.starts_with("Loop time of")).last().expect("a Loop time line");
    let w: Vec<&str> = line.split_whitespace().collect();
    let (t, s, n): (f64, f64, f64) = (w[3].parse().unwrap(), w[8].parse().unwrap(), w[11].parse().unwrap());
    s * n / t
}

/// Block averages of `columns` in both runs, asserted to agree within 3 combined SE.
fn compare_averages(what: &str, l: &ThermoBlock, g: &ThermoBlock, columns: &[&str]) {
    for c in columns {
        let series = |b: &ThermoBlock| b.rows.iter().map(|r| r[b.column_index(c).unwrap()]).collect::<Vec<f64>>();
        let (a, b) = (block_average(&series(l), 10), block_average(&series(g), 10));
        eprintln!("{what} {c}: LAMMPS {:.5} +- {:.5}, gendpde {:.5} +- {:.5}", a.0, a.1, b.0, b.1);
        assert!(agree_within(a, b, 3.0), "{what} {c}: LAMMPS {a:?} vs gendpde {b:?}");
    }
}

/// Energy drift rate: slope of the total energy per block, block-averaged.
fn drift(b: &ThermoBlock, column: &str) -> (f64, f64) {
    let k = b.column_index(column).unwrap();
    let rows = &b.rows;
    let blocks = 10;
    let len = rows.len() / blocks;
    let slopes: Vec<f64> = (0..blocks)
        .map(|i| {
            let (first, last) = (&rows[i * len], &rows[(i + 1) * len - 1]);
            (last[k] - first[k]) / (last[0] - first[0])
        })
        .collect();
    block_average(&slopes, blocks)
}

#[test]
fn dpde_shardlow_statistics_and_speed_agree_with_lammps() {
    let vars = [("equil", "1000"), ("steps", "5000")];
    let ((_, l), (_, g)) = run_both("dpde-stat", "in.dpde-shardlow", &vars, &[]);
    let (lb, gb) = (production(&l), production(&g));
    compare_averages("DPDE", &lb, &gb, &["Temp", "Press", "c_dpdU[4]"]);
    let (dl, dg) = (drift(&lb, "v_totEnergy"), drift(&gb, "v_totEnergy"));
    eprintln!("DPDE energy drift per unit time: LAMMPS {:.3e} +- {:.3e}, gendpde {:.3e} +- {:.3e}", dl.0, dl.1, dg.0, dg.1);
    assert!(agree_within(dl, dg, 3.0), "energy drift: LAMMPS {dl:?} vs gendpde {dg:?}");
    let (rl, rg) = (rate(&l), rate(&g));
    eprintln!("DPDE + shardlow speed: LAMMPS {rl:.0} atom-steps/s, gendpde {rg:.0} atom-steps/s, ratio {:.2}", rg / rl);
}

#[test]
fn mdpd_liquid_statistics_and_speed_agree_with_lammps() {
    let vars = [("equil", "3000"), ("steps", "5000")];
    let ((_, l), (_, g)) = run_both("mdpd-stat", "in.mdpd-liquid", &vars, &[]);
    compare_averages("MDPD", &production(&l), &production(&g), &["Temp", "Press"]);
    let (rl, rg) = (rate(&l), rate(&g));
    eprintln!("MDPD speed: LAMMPS {rl:.0} atom-steps/s, gendpde {rg:.0} atom-steps/s, ratio {:.2}", rg / rl);
}

#[test]
fn lammps_dpde_example_in_metal_units_runs_unchanged() {
    let ((_, l), (_, g)) = run_both("dpde-metal", "in.dpde-metal", &[], &[]);
    let (lb, gb) = (production(&l), production(&g));
    let k = gb.column_index("v_totEnergy").unwrap();
    let (e0, e1) = (gb.rows[0][k], gb.rows.last().unwrap()[k]);
    let kl = lb.column_index("v_totEnergy").unwrap();
    eprintln!(
        "DPDE metal example, total energy step 0 -> 100: LAMMPS {} -> {}, gendpde {e0} -> {e1}",
        lb.rows[0][kl],
        lb.rows.last().unwrap()[kl]
    );
    // identical initial state: same step-0 thermo (temperature, pair energy, energy)
    for c in ["Temp", "PotEng", "v_totEnergy"] {
        let (a, b) = (lb.rows[0][lb.column_index(c).unwrap()], gb.rows[0][gb.column_index(c).unwrap()]);
        assert!((a - b).abs() <= 1e-9 * a.abs().max(1e-12), "step 0 {c}: LAMMPS {a} vs gendpde {b}");
    }
    assert!(((e1 - e0) / e0).abs() < 1e-6, "energy drifted from {e0} to {e1}");
}

/// LAMMPS's DPD-BASIC example in.dpd (a two-type mixture with its own cutoffs in a 5.5 box,
/// 2 cells of cutoff + skin across) runs unchanged; its temperature and pressure after
/// step 1000 agree with LAMMPS's within 3 combined standard errors (10 blocks; one seed
/// each; several seeds: scripts/lammps/in_dpd_seeds.py).
#[test]
fn lammps_dpd_basic_example_runs_unchanged_and_agrees_statistically() {
    let ((_, l), (_, g)) = run_both("dpd-basic", "in.dpd-basic", &[], &[]);
    let after = |b: ThermoBlock| ThermoBlock { header: b.header, rows: b.rows.into_iter().filter(|r| r[0] >= 1000.0).collect() };
    let (lb, gb) = (after(production(&l)), after(production(&g)));
    assert_eq!(gb.rows.len(), 41, "thermo every 100 steps to 5000");
    compare_averages("in.dpd", &lb, &gb, &["Temp", "Press"]);
}
