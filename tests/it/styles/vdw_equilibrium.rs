//! The van der Waals scene of examples/vdw-equilibrium (2019 paper, sec 5.1) at reduced
//! size and cutoff: temperatures with and without a reservoir, and the distribution of
//! the internal energy against eq. 90.

use crate::common;

use common::stats::{chi_square_equiprobable, gamma_quantile_edges, mean, variance};
use gendpde::Observables;

const T: f64 = 1.5;
const CV: f64 = 60.0;
const A: f64 = 2.4682;
const RHO: f64 = 0.5;

/// N = 11^3 = 1331 at rho = 0.5 (box 13.9), rc = 3: the smallest box of 4 cells.
fn scene(extra: &str) -> gendpde::Interpreter {
    let mut it = common::run_example("vdw-equilibrium", &[("n", "11"), ("rc", "3.0"), ("steps", "0")]);
    if !extra.is_empty() {
        it.execute_str("extra.in", extra).unwrap();
    }
    it
}

struct Averages {
    t_kin: Vec<f64>,
    t_int: Vec<f64>,
    last_u: Vec<f64>,
    u: Vec<f64>,
}

fn sample(it: &mut gendpde::Interpreter, equilibrate: u64, steps: u64, every: u64) -> Averages {
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let mut a = Averages { t_kin: vec![], t_int: vec![], last_u: vec![], u: vec![] };
    for k in 1..=equilibrate + steps {
        physics.advance(sys).unwrap();
        if k > equilibrate && k % every == 0 {
            let o = Observables::measure(sys);
            a.t_kin.push(o.temperature(1.0));
            a.t_int.push(o.theta / o.atoms);
            if k % 500 == 0 {
                a.u.extend_from_slice(&sys.store.u[..sys.store.nlocal]);
            }
        }
    }
    a.last_u = sys.store.u[..sys.store.nlocal].to_vec();
    a
}

#[test]
fn reservoir_holds_both_temperatures_and_u_follows_eq_90() {
    // a strong reservoir (relaxation time ~3 time units) keeps the statistical error of
    // <T_int> near 0.15 %; at dt = 0.01, <T_kin> sits ~0.6 % below T (0.07 % at dt = 0.005)
    let mut it = scene("fix bath all heat/reservoir 1.5 50.0 777\n");
    let a = sample(&mut it, 2000, 2000, 10);
    let (tk, ti) = (mean(&a.t_kin), mean(&a.t_int));
    eprintln!("reservoir: <T_kin> = {tk:.5}, <T_int> = {ti:.5} (T = {T})");
    assert!((tk - T).abs() < 0.01 * T, "<T_kin> = {tk}");
    assert!((ti - T).abs() < 0.01 * T, "<T_int> = {ti}");

    // eq 90 with the mean-field density n = rho: u + a rho ~ Gamma(shape C_V, scale T).
    // One snapshot: internal energies are independent given the positions.
    let shifted: Vec<f64> = a.last_u.iter().map(|u| u + A * RHO).collect();
    let edges = gamma_quantile_edges(CV, T, 20);
    let (chi2, dof, p) = chi_square_equiprobable(&shifted, &edges);
    eprintln!("eq 90: chi2 = {chi2:.2} with {dof} dof over {} particles, p = {p:.4}", shifted.len());
    assert!(p > 1e-3, "u histogram rejected against eq 90: chi2 = {chi2}, p = {p}");
    // the pooled moments over 4 snapshots: mean C_V T - a rho, variance C_V T^2
    let (m, v) = (mean(&a.u), variance(&a.u));
    eprintln!("pooled u: mean {m:.4} (eq 90: {:.4}), variance {v:.3} (eq 90: {:.3})", CV * T - A * RHO, CV * T * T);
    assert!((m - (CV * T - A * RHO)).abs() < 0.01 * CV * T);
    assert!((v / (CV * T * T) - 1.0).abs() < 0.05);
}

#[test]
fn without_reservoir_kinetic_and_internal_temperatures_agree() {
    let mut it = scene("");
    let a = sample(&mut it, 1000, 2000, 10);
    let (tk, ti) = (mean(&a.t_kin), mean(&a.t_int));
    eprintln!("NVE: <T_kin> = {tk:.5}, <T_int> = {ti:.5}, difference {:.3} %", 100.0 * (tk / ti - 1.0));
    assert!((tk / ti - 1.0).abs() < 0.01, "<T_kin> = {tk}, <T_int> = {ti}");
}
