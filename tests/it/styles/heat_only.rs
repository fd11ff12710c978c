//! Fixed particles exchanging heat only (2021 PRE, Fig. 2; examples/heat-only):
//! u must follow Gamma(shape C_V/k_B, scale T) with C_V = 5, T = 1.5 (2021 eq 65), and
//! the pair updates must conserve the total internal energy.

use crate::common;

use common::stats::{mean, variance};

const T: f64 = 1.5;
const CV: f64 = 5.0;

/// Runs the heat-only example and samples u every 100 steps after 1000 steps (both models relax within 300).
fn sample(heat: &str) -> (Vec<f64>, Vec<f64>, f64) {
    let mut it = common::run_example("heat-only", &[("heat", heat), ("steps", "0"), ("n", "12")]);
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let u0: f64 = sys.store.u[..sys.store.nlocal].iter().sum();
    let (mut u, mut inv_tau) = (Vec::new(), Vec::new());
    let mut worst: f64 = 0.0;
    for step in 1..=3500 {
        physics.advance(sys).unwrap();
        let s = &sys.store;
        let total: f64 = s.u[..s.nlocal].iter().sum();
        worst = worst.max(((total - u0) / u0).abs());
        if step >= 1000 && step % 100 == 0 {
            u.extend_from_slice(&s.u[..s.nlocal]);
            inv_tau.extend(s.theta[..s.nlocal].iter().map(|th| (1.0 - 1.0 / CV) / th));
        }
    }
    (u, inv_tau, worst)
}

#[test]
fn fourier_model_gives_gamma_distributed_energy_and_conserves_it() {
    let (u, _, drift) = sample("fourier");
    let (m, v) = (mean(&u), variance(&u));
    eprintln!("fourier: <u> = {m:.5} (7.5), var u = {v:.4} (11.25), max |sum u drift| = {drift:e}, {} samples", u.len());
    assert!((m - CV * T).abs() < 0.01 * CV * T, "<u> = {m}");
    assert!((v - CV * T * T).abs() < 0.05 * CV * T * T, "var u = {v}");
    assert!(drift < 1e-12, "sum u drifted by {drift:e}");
}

#[test]
fn original_model_samples_inverse_dressed_temperature() {
    let (u, inv_tau, drift) = sample("original");
    let m = mean(&inv_tau);
    eprintln!("original: <1/tau> = {m:.5} (1/T = {:.5}), var u = {:.4}, drift {drift:e}", 1.0 / T, variance(&u));
    assert!((m * T - 1.0).abs() < 0.01, "<1/tau> = {m}, 1/T = {}", 1.0 / T);
    assert!(drift < 1e-12);
}
