//! Checks of the statistics helpers the physics tests rely on.

use crate::common;

use common::stats::*;

#[test]
fn incomplete_gamma_matches_known_values() {
    // P(1, x) = 1 - e^-x; chi-square with 2 dof at 5.991 has p = 0.05
    assert!((gamma_p(1.0, 2.0) - (1.0 - (-2.0f64).exp())).abs() < 1e-12);
    assert!((1.0 - gamma_p(1.0, 5.991 / 2.0) - 0.05).abs() < 1e-4);
    // chi-square 19 dof, 30.144 -> p = 0.05
    assert!((1.0 - gamma_p(9.5, 30.144 / 2.0) - 0.05).abs() < 1e-4);
    // Gamma(60, 1.5) median ~ k s (1 - 1/(3k))... CDF at mean is slightly above 1/2
    let c = gamma_cdf(90.0, 60.0, 1.5);
    assert!(c > 0.5 && c < 0.54, "{c}");
}

#[test]
fn chi_square_accepts_its_own_distribution_and_rejects_another() {
    // Gamma(5, 1.5) samples as sums of exponentials from a fixed LCG
    let mut state: u64 = 99;
    let mut unif = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    let samples: Vec<f64> = (0..5000).map(|_| (0..5).map(|_| -1.5 * unif().ln()).sum()).collect();
    let edges = gamma_quantile_edges(5.0, 1.5, 20);
    let (_, _, p) = chi_square_equiprobable(&samples, &edges);
    assert!(p > 1e-3, "p = {p}");
    let wrong = gamma_quantile_edges(5.0, 1.6, 20);
    let (_, _, p) = chi_square_equiprobable(&samples, &wrong);
    assert!(p < 1e-3, "a 7 % scale error must be rejected, p = {p}");
}
