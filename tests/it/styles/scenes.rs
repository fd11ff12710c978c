//! Reduced variants of the 2019 paper's LJ scenes (examples/lj-fluid, flash-heating):
//! the virial pressure against the Kolafa-Nezbeda EOS pressure, and kinetic against
//! internal temperature, at rest and after a flash heating. Full-size runs:
//! scripts/validation/, results in docs/VALIDATION.md.
//!
//! The LJ EOS runs through the table of scripts/validation (errors below 1e-6 in theta
//! and 5e-5 in pi/n^2, docs/commands/fix_eos.md): the analytic model costs five times as
//! much per step.

use crate::common;

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

/// Samples (T_kin, T_int, P, E, P_mf) every `every` steps over `steps` steps, where
/// P_mf = rho T_kin + rho^2 <pi_i/n_i^2> is the particle EOS averaged over the particles'
/// own states: the virial with each particle's weight-gradient sum m_i = -sum_j r_ij
/// w'(r_ij)/3 replaced by its mean-field value rho.
fn sample(it: &mut gendpde::Interpreter, steps: u64, every: u64) -> [Vec<f64>; 5] {
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let mut out: [Vec<f64>; 5] = Default::default();
    for k in 1..=steps {
        physics.advance(sys).unwrap();
        if k % every == 0 {
            let o = Observables::measure(sys);
            let rho = o.atoms / o.volume;
            let pn2 = &sys.store.pn2[..sys.store.nlocal];
            let p_mf = rho * o.temperature(1.0) + rho * rho * pn2.iter().sum::<f64>() / pn2.len().max(1) as f64;
            for (v, x) in out.iter_mut().zip([o.temperature(1.0), o.theta / o.atoms, o.pressure(), o.energy(), p_mf]) {
                v.push(x);
            }
        }
    }
    out
}

/// Means and standard errors of one LJ run (`lj_state`).
struct LjState {
    /// Virial pressure and its SEM.
    p: f64,
    p_err: f64,
    /// The EOS pressure at rho and the measured <T_int>.
    p_eos: f64,
    /// <P - P_mf> over paired samples and its SEM (see `sample`).
    p_minus_mf: f64,
    p_minus_mf_err: f64,
    tk: f64,
    tk_err: f64,
    ti: f64,
}

/// One LJ state at rho = 0.5 with density cutoff `rc` and friction `gamma` in a box of n^3
/// sites.
fn lj_state(t: &str, n: &str, rc: &str, gamma: &str, steps: u64) -> LjState {
    let vars = [("T", t), ("n", n), ("rc", rc), ("gamma", gamma), ("eos", TABLE), ("equil", "400"), ("steps", "0")];
    let mut it = common::run_example("lj-fluid", &vars);
    let [tk, ti, p, _, p_mf] = sample(&mut it, steps, 5);
    let diff: Vec<f64> = p.iter().zip(&p_mf).map(|(a, b)| a - b).collect();
    let ((tk, tk_err), (ti, _), (p, p_err), (d, d_err)) = (mean_sem(&tk), mean_sem(&ti), mean_sem(&p), mean_sem(&diff));
    let p_eos = LennardJones::new(60.0).pressure(ti, 0.5);
    eprintln!(
        "LJ T = {t}, rho = 0.5, rc = {rc}, gamma = {gamma}: P = {p:.5} +- {p_err:.5}, EOS P({ti:.4}) = {p_eos:.5} ({:+.2} %), P - P_mf = {d:.5} +- {d_err:.5}; <T_kin> = {tk:.5} +- {tk_err:.5} ({:+.3} % from <T_int>)",
        100.0 * (p / p_eos - 1.0),
        100.0 * (tk / ti - 1.0)
    );
    LjState { p, p_err, p_eos, p_minus_mf: d, p_minus_mf_err: d_err, tk, tk_err, ti }
}

/// LJ at the paper's parameters, T = 1.5, rho = 0.5, rc = 4, gamma = 4.5 (N = 14^3):
/// <T_kin> within 0.5 % of <T_int>.
#[test]
fn lj_kinetic_and_internal_temperatures_agree() {
    let s = lj_state("1.5", "14", "4.0", "4.5", 3000);
    assert!(s.tk_err < 0.0015 * s.ti, "the run is too short to test 0.5 %: SEM {}", s.tk_err);
    assert!((s.tk / s.ti - 1.0).abs() < 0.005);
}

/// LJ, T = 1.5, rho = 0.5, rc = 4 (N = 14^3): the virial pressure lies 7 % above the EOS
/// pressure, not within the 2 % the issue asked for, and the test shows why. The particle
/// EOS averaged over the particles' own states (P_mf of `sample`) accounts for most of the
/// excess: at rc = 4 the local densities fluctuate by 15 % (the counting noise of about 47
/// independent neighbours) and pi(n)/n^2 is curved, so the mean of the particle pressures is
/// not the EOS at the mean density; the rest is the correlation of n_i with the weight
/// gradient sum m_i, a fluctuation term of the same order. The excess falls as 1/rc^3:
/// +1.8 % at rc = 6 and +0.2 % at rc = 7 (docs/VALIDATION.md, Figs 4 and 5, runs too long
/// for the suite). At T = 3, where pi(n)/n^2 is nearly linear, the virial is within 2 % of the EOS
/// at rc = 4. The friction is 0.45, not 4.5: the pressure is the same at both (0.4523 +-
/// 0.0016 at 0.45, N = 2744; 0.4525 +- 0.0008 at 4.5, N = 27000; pressure.py), and with 4.5
/// the local densities that carry it decorrelate ten times more slowly, too slowly for a
/// short run to have an honest error bar.
#[test]
fn lj_virial_pressure_excess_comes_from_the_local_density_fluctuations() {
    let s = lj_state("1.5", "14", "4.0", "0.45", 4000);
    let excess = s.p - s.p_eos;
    assert!(excess > 4.0 * s.p_err, "no excess: P = {} +- {}, EOS {}", s.p, s.p_err, s.p_eos);
    assert!(
        s.p_minus_mf.abs() + 4.0 * s.p_minus_mf_err < 0.5 * excess,
        "the particle EOS over the local densities misses most of the excess {excess}: P - P_mf = {} +- {}",
        s.p_minus_mf,
        s.p_minus_mf_err
    );
    let s = lj_state("3.0", "14", "4.0", "0.45", 1500);
    assert!(s.p_err < 0.005 * s.p_eos, "the run is too short to test 2 %: SEM {}", s.p_err);
    assert!((s.p / s.p_eos - 1.0).abs() < 0.02, "T = 3: P = {} +- {}, EOS {}", s.p, s.p_err, s.p_eos);
}

/// Flash heating (examples/flash-heating, N = 14^3): half of the particles heated to
/// T = 5; after relaxing, <T_kin> within 0.5 % of <T_int>, and the total energy drifts
/// by less than 1e-5 relative over the run.
#[test]
fn flash_heating_relaxes_to_equal_temperatures_and_keeps_energy() {
    let vars = [("n", "14"), ("eos", FLASH_TABLE), ("equil", "300"), ("steps", "0")];
    let mut it = common::run_example("flash-heating", &vars);
    let [_, _, _, e0, _] = sample(&mut it, 1, 1);
    let [tk, ti, _, e, _] = sample(&mut it, 3000, 5);
    let half = tk.len() / 3;
    let ((tk, tk_err), (ti, _)) = (mean_sem(&tk[half..]), mean_sem(&ti[half..]));
    let drift = e.iter().map(|x| (x / e0[0] - 1.0).abs()).fold(0.0, f64::max);
    eprintln!("flash heating: <T_kin> = {tk:.5} +- {tk_err:.5}, <T_int> = {ti:.5} ({:+.3} %), max |dE/E| = {drift:.2e}", 100.0 * (tk / ti - 1.0));
    assert!(ti > 2.5, "the slab was not heated: T_int = {ti}");
    assert!(tk_err < 0.0015 * ti, "the run is too short to test 0.5 %: SEM {tk_err}");
    assert!((tk / ti - 1.0).abs() < 0.005);
    assert!(drift < 1e-5);
}
