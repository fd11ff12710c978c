//! Heat-flow scenes of the 2021 PRE (validation scenes V4 and V5; examples/heat-gradient
//! and examples/heat-mixture).
//!
//! Conductivity: fixed particles on a simple cubic lattice between a hot and a cold
//! reservoir. The steady flux J comes from the reservoirs' energy tallies, the gradient
//! from a linear fit of the time-averaged theta profile in the middle of the conduction
//! zones; lambda = -J / (dtheta/dx). The prediction is the exact lattice sum
//! lambda = (1/2V) sum_{i != j} kappa_ij x_ij^2 (the 2021 eqs 66-67 with the continuum
//! integral replaced by the sum over the actual configuration), divided by T^2 for the
//! original model. Error bars: jackknife over time blocks of the ratio of the summed
//! flux and the summed slope.

use crate::common;

use gendpde_integrators::System;

/// Geometry of examples/heat-gradient (its defaults, kept in step with the script).
const L: f64 = 12.0;
const W: f64 = 3.0;
const NY: f64 = 10.0;
const RC: f64 = 2.2;
const BLOCKS: usize = 10;

struct Measured {
    lambda: f64,
    error: f64,
    /// Exact lattice-sum prediction (kappa = 1) and the mean theta of the fitted layers.
    lattice: f64,
    t_mid: f64,
}

/// (1/2V) sum_{i != j} (1 - r/rc)^2 x_ij^2 over the configuration (minimum image).
fn lattice_sum(sys: &System) -> f64 {
    let s = &sys.store;
    let len = sys.domain.len();
    let mut sum = 0.0;
    for i in 0..s.nlocal {
        for j in 0..s.nlocal {
            let d: Vec<f64> = (0..3).map(|k| {
                let x = s.r[i][k] - s.r[j][k];
                x - len[k] * (x / len[k]).round()
            }).collect();
            let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if i != j && r < RC {
                sum += (1.0 - r / RC).powi(2) * d[0] * d[0];
            }
        }
    }
    sum / (2.0 * sys.domain.volume())
}

fn tally(sys: &System, id: &str) -> f64 {
    match sys.fixes.get(id) {
        Some(&gendpde_integrators::FixRecord::Reservoir(e)) => e,
        _ => 0.0,
    }
}

/// Slope of the least-squares line through (x, y).
fn slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// Runs the gradient scene; `equil` steps to the steady state, then `BLOCKS` blocks of
/// `block` steps.
fn conductivity(heat: &str, t: f64, dt_rel: f64, seed: u64, equil: u64, block: u64) -> Measured {
    let time_step = 2.0;
    let (ts, dts, dt, seed) = (t.to_string(), dt_rel.to_string(), time_step.to_string(), seed.to_string());
    let vars = [("heat", heat), ("T", &ts), ("dT", &dts), ("dt", &dt), ("seed", &seed), ("steps", "0")];
    let mut it = common::run_example("heat-gradient", &vars);
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let lattice = lattice_sum(sys);
    let lx = sys.domain.len()[0];
    let centre = 0.5 * (W - 1.0);
    // distance from the hot slab's centre along the periodic x axis: layers of the two
    // zones fold onto each other
    let layer: Vec<usize> = (0..sys.store.nlocal)
        .map(|i| {
            let d = (sys.store.r[i][0] - centre).rem_euclid(lx);
            d.min(lx - d).round() as usize
        })
        .collect();
    let layers = (lx / 2.0).round() as usize + 1;
    // layers at least rc inside the zone [W/2, W/2 + L] (in d)
    let inside = |d: usize| d as f64 - 0.5 * W >= RC - 1e-9 && 0.5 * W + L - d as f64 >= RC - 1e-9;
    let fit: Vec<usize> = (0..layers).filter(|&d| inside(d)).collect();
    for _ in 0..equil {
        physics.advance(sys).unwrap();
    }
    let (mut flux, mut grad, mut level) = (Vec::new(), Vec::new(), Vec::new());
    let area = NY * NY;
    for _ in 0..BLOCKS {
        let e0 = tally(sys, "hot") - tally(sys, "cold");
        let (mut sum, mut count) = (vec![0.0; layers], vec![0.0; layers]);
        for step in 1..=block {
            physics.advance(sys).unwrap();
            if step % 10 == 0 {
                for (i, &d) in layer.iter().enumerate() {
                    sum[d] += sys.store.theta[i];
                    count[d] += 1.0;
                }
            }
        }
        let power = 0.5 * (tally(sys, "hot") - tally(sys, "cold") - e0) / (block as f64 * time_step);
        flux.push(power / (2.0 * area));
        let x: Vec<f64> = fit.iter().map(|&d| d as f64).collect();
        let y: Vec<f64> = fit.iter().map(|&d| sum[d] / count[d]).collect();
        grad.push(slope(&x, &y));
        level.push(y.iter().sum::<f64>() / y.len() as f64);
    }
    let (sj, sg) = (flux.iter().sum::<f64>(), grad.iter().sum::<f64>());
    let lambda = -sj / sg;
    let jack: Vec<f64> = (0..BLOCKS).map(|b| -(sj - flux[b]) / (sg - grad[b])).collect();
    let mj = jack.iter().sum::<f64>() / BLOCKS as f64;
    let nb = BLOCKS as f64;
    let error = ((nb - 1.0) / nb * jack.iter().map(|l| (l - mj).powi(2)).sum::<f64>()).sqrt();
    let t_mid = level.iter().sum::<f64>() / nb;
    Measured { lambda, error, lattice, t_mid }
}

#[test]
fn fourier_conductivity_is_the_lattice_sum_at_two_temperatures() {
    // different seeds: with one seed the Fourier model's trajectories at T and 2T are
    // copies scaled by 2 (every term of eqs 61-62 is homogeneous in theta)
    for (t, seed) in [(1.0, 2021), (2.0, 77)] {
        let m = conductivity("fourier", t, 0.5, seed, 3000, 500);
        let continuum = 2.0 * std::f64::consts::PI * RC.powi(5) / 315.0;
        eprintln!(
            "fourier T = {t}: lambda = {:.4} +- {:.4}, lattice sum {:.4}, continuum {continuum:.4}, <theta> fitted {:.3}",
            m.lambda, m.error, m.lattice, m.t_mid
        );
        assert!((m.lambda - m.lattice).abs() < 3.0 * m.error, "T = {t}: {} +- {} vs {}", m.lambda, m.error, m.lattice);
    }
}

/// The original model (2019 eq 70): lambda = lattice sum / T^2 (2021 eq 66, corrected),
/// so lambda(T = 1) / lambda(T = 2) = 4.
#[test]
fn original_conductivity_scales_as_inverse_square_temperature() {
    let mut at = Vec::new();
    for (t, seed) in [(1.0, 2021), (2.0, 77)] {
        let m = conductivity("original", t, 0.1, seed, 3000, 500);
        let predicted = m.lattice / (m.t_mid * m.t_mid);
        eprintln!("original T = {t}: lambda = {:.4} +- {:.4}, lattice sum / <theta>^2 = {predicted:.4} (<theta> = {:.4})", m.lambda, m.error, m.t_mid);
        assert!((m.lambda - predicted).abs() < 3.0 * m.error, "T = {t}: {} +- {} vs {predicted}", m.lambda, m.error);
        at.push(m);
    }
    let ratio = at[0].lambda / at[1].lambda;
    let error = ratio * ((at[0].error / at[0].lambda).powi(2) + (at[1].error / at[1].lambda).powi(2)).sqrt();
    eprintln!("original: lambda(1)/lambda(2) = {ratio:.3} +- {error:.3} (4)");
    assert!((ratio - 4.0).abs() < 3.0 * error, "ratio {ratio} +- {error}");
}

/// Energy bookkeeping: with gamma = 0 and fixed particles, sum u changes only through the
/// reservoirs, so its change equals the sum of their tallies (f_hot + f_cold) to round-off.
#[test]
fn internal_energy_changes_by_the_reservoir_tallies() {
    let mut it = common::run_example("heat-gradient", &[("steps", "0"), ("ny", "9")]);
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let total = |sys: &System| sys.store.u[..sys.store.nlocal].iter().sum::<f64>();
    let u0 = total(sys);
    let mut worst: f64 = 0.0;
    for _ in 0..2000 {
        physics.advance(sys).unwrap();
        let added = tally(sys, "hot") + tally(sys, "cold");
        worst = worst.max((total(sys) - u0 - added).abs() / u0);
    }
    eprintln!("bookkeeping: f_hot = {:.3}, f_cold = {:.3}, worst |sum u - u0 - tallies| / u0 = {worst:.2e}", tally(sys, "hot"), tally(sys, "cold"));
    assert!(tally(sys, "hot") > 0.0 && tally(sys, "cold") < 0.0);
    assert!(worst < 1e-12, "{worst:e}");
}

/// Mixture of C_V = 5 and 50 (2021 sec. III.C, scene V5): with the Fourier law the mean
/// pair heat flow between the species vanishes, so <theta_s> = T and <u_s> = C_V,s T for
/// both. Error bars: standard error of 20 block means (blocks of 250 steps, ~25
/// relaxation times of the exchange between the species).
#[test]
fn mixture_species_share_the_temperature() {
    const T: f64 = 1.5;
    let mut it = common::run_example("heat-mixture", &[("steps", "0")]);
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    for _ in 0..500 {
        physics.advance(sys).unwrap();
    }
    let (blocks, block) = (20, 250);
    let mut means = vec![Vec::new(), Vec::new()];
    for _ in 0..blocks {
        let (mut sum, mut count) = ([0.0; 2], [0.0; 2]);
        for step in 1..=block {
            physics.advance(sys).unwrap();
            if step % 5 == 0 {
                let s = &sys.store;
                for i in 0..s.nlocal {
                    let k = s.kind[i] as usize - 1;
                    sum[k] += s.theta[i];
                    count[k] += 1.0;
                }
            }
        }
        for k in 0..2 {
            means[k].push(sum[k] / count[k]);
        }
    }
    for (k, (m, cv)) in means.iter().zip([5.0, 50.0]).enumerate() {
        let n = m.len() as f64;
        let mean = m.iter().sum::<f64>() / n;
        let sem = (m.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
        eprintln!("mixture: type {} (C_V = {cv}): <theta> = {mean:.4} +- {sem:.4} (T = {T}), <u> = {:.3} ({:.3})", k + 1, cv * mean, cv * T);
        assert!((mean - T).abs() < 3.0 * sem, "type {}: {mean} +- {sem}", k + 1);
    }
}
