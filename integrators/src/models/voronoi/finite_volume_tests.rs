//! The finite-volume model's invariants (reading notes, targets e and f): conservation of
//! M, P, E by every part of the rates, entropy production at k_B = 0, eq 81 for the noise,
//! no force on a uniform state of a disordered configuration, and the stepped trajectory.

use super::finite_volume::*;
use super::tests::{random_points, Lcg};
use gendpde_potentials::cell_energy::{vdw_entropy, VdwCell, WATER_C};
use gendpde_potentials::CellEnergy;

const LO: [f64; 3] = [0.0, -2.0, 1.0];
const LEN: [f64; 3] = [4.0, 4.5, 3.5];
const VDW: VdwCell = VdwCell { c: WATER_C };

/// A disordered vdW configuration: densities 0.6-1.4, temperatures 1.0-1.4, velocities ~0.3.
fn disordered(n: usize, seed: u64) -> (Cells, f64) {
    let r = random_points(n, LO, LEN, seed);
    let vols = super::Tessellation::build(&r, LO, LEN).unwrap().volumes;
    let mut g = Lcg(seed + 100);
    let mut c = Cells { tag: (1..=n as u64).collect(), r, ..Default::default() };
    for k in 0..n {
        let m = (0.6 + 0.8 * g.next()) * vols[k];
        c.m.push(m);
        c.s.push(vdw_entropy(WATER_C, m, vols[k], 1.0 + 0.4 * g.next()));
        c.p.push(std::array::from_fn(|_| m * 0.3 * (g.next() - 0.5)));
    }
    (c, vols.iter().sum())
}

fn sum3(v: &[[f64; 3]]) -> [f64; 3] {
    v.iter().fold([0.0; 3], |a, x| [a[0] + x[0], a[1] + x[1], a[2] + x[2]])
}

/// The largest single term of a rate vector: the scale for its round-off.
fn scale3(v: &[[f64; 3]]) -> f64 {
    v.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()))
}

fn scale1(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

const TR: CellTransport = CellTransport { eta: 0.7, zeta: 0.4, kappa: 1.3, kb: 0.0 };

#[test]
fn reversible_rates_conserve_mass_momentum_energy_and_entropy_eq_75() {
    let (c, _) = disordered(80, 11);
    let f = CellFrame::new(&c, &VDW, LO, LEN).unwrap();
    let r = f.reversible(&c);
    let (dm, ds): (f64, f64) = (r.m.iter().sum(), r.s.iter().sum());
    assert!(dm.abs() < 1e-14 * scale1(&r.m) * 80.0 && scale1(&r.m) > 1e-3, "sum dM/dt = {dm}");
    assert!(ds.abs() < 1e-14 * scale1(&r.s) * 80.0, "sum dS/dt = {ds}");
    let dp = sum3(&r.p);
    assert!(dp.iter().all(|x| x.abs() < 1e-14 * scale3(&r.p) * 80.0), "sum dP/dt = {dp:?}");
    let de = f.energy_rate(&r);
    let work: f64 = (0..c.len()).map(|k| (c.p[k][0] * r.p[k][0] / c.m[k]).abs()).sum();
    assert!(de.abs() < 1e-12 * work, "dE/dt = {de} (scale {work})");
}

#[test]
fn irreversible_rates_conserve_energy_and_produce_entropy_at_kb_zero() {
    let (c, _) = disordered(80, 12);
    let f = CellFrame::new(&c, &VDW, LO, LEN).unwrap();
    let r = f.irreversible(&c, &TR);
    let dp = sum3(&r.p);
    assert!(dp.iter().all(|x| x.abs() < 1e-14 * scale3(&r.p) * 80.0), "sum dP/dt = {dp:?}");
    assert!(r.m.iter().all(|&x| x == 0.0));
    let de = f.energy_rate(&r);
    let heat: f64 = (0..c.len()).map(|k| (f.thermo[k].temperature * r.s[k]).abs()).sum();
    assert!(de.abs() < 1e-12 * heat, "dE/dt = {de} (scale {heat})");
    let ds: f64 = r.s.iter().sum();
    assert!(ds > 1e-3 * heat, "dS/dt = {ds} must be positive");
    // Each mechanism alone produces entropy: viscosity alone, conduction alone.
    for tr in [CellTransport { kappa: 0.0, ..TR }, CellTransport { eta: 0.0, zeta: 0.0, ..TR }] {
        let ds: f64 = f.irreversible(&c, &tr).s.iter().sum();
        assert!(ds > 0.0, "{tr:?}: dS/dt = {ds}");
    }
}

/// Eq 81: v . dP~ + T dS~ summed vanishes and sum dP~ = 0, for every realisation.
#[test]
fn noise_conserves_momentum_and_energy_eq_81() {
    let (c, _) = disordered(60, 13);
    let f = CellFrame::new(&c, &VDW, LO, LEN).unwrap();
    let tr = CellTransport { kb: 1.0, ..TR };
    for step in 0..5 {
        let (dp, ds) = f.noise(&c, &tr, 77, step, 0.01);
        let p = sum3(&dp);
        assert!(p.iter().all(|x| x.abs() < 1e-14 * scale3(&dp) * 60.0), "sum dP~ = {p:?}");
        let de: f64 = (0..c.len()).map(|k| f.v[k][0] * dp[k][0] + f.v[k][1] * dp[k][1] + f.v[k][2] * dp[k][2] + f.thermo[k].temperature * ds[k]).sum();
        let sc: f64 = (0..c.len()).map(|k| (f.thermo[k].temperature * ds[k]).abs()).sum();
        assert!(de.abs() < 1e-12 * sc && sc > 0.0, "sum v.dP~ + T dS~ = {de} (scale {sc})");
    }
    // Keyed by tag: the same cells in reverse order get the same increments.
    let mut rev = c.clone();
    for v in [&mut rev.tag] {
        v.reverse();
    }
    rev.r.reverse();
    rev.p.reverse();
    rev.m.reverse();
    rev.s.reverse();
    let fr = CellFrame::new(&rev, &VDW, LO, LEN).unwrap();
    let (a, _) = f.noise(&c, &tr, 5, 3, 0.01);
    let (b, _) = fr.noise(&rev, &tr, 5, 3, 0.01);
    for k in 0..c.len() {
        for x in 0..3 {
            assert!((a[k][x] - b[c.len() - 1 - k][x]).abs() < 1e-12 * scale3(&a));
        }
    }
}

/// Target f: cells of one density and entropy density (so one p, mu, T) moving together
/// on a disordered configuration: no force, no mass or entropy flow, however irregular
/// the cells.
#[test]
fn a_uniform_state_on_a_disordered_configuration_feels_no_force() {
    let (mut c, _) = disordered(80, 14);
    let vols = super::Tessellation::build(&c.r, LO, LEN).unwrap().volumes;
    let u = [0.3, -0.2, 0.1];
    for k in 0..c.len() {
        c.m[k] = 1.2 * vols[k];
        c.s[k] = vdw_entropy(WATER_C, c.m[k], vols[k], 0.9);
        c.p[k] = [c.m[k] * u[0], c.m[k] * u[1], c.m[k] * u[2]];
    }
    let f = CellFrame::new(&c, &VDW, LO, LEN).unwrap();
    let p0 = f.thermo[0].pressure;
    let tr = CellTransport { kb: 1.0, ..TR };
    let rev = f.reversible(&c);
    let irr = f.irreversible(&c, &tr);
    let amax = f.tess.faces.iter().fold(0.0f64, |a, x| a.max(x.area));
    let vmin = vols.iter().fold(f64::MAX, |a, &x| a.min(x));
    assert!(vmin < 0.3 * vols.iter().fold(0.0f64, |a, &x| a.max(x)), "configuration not disordered enough");
    for k in 0..c.len() {
        for x in 0..3 {
            assert!((rev.p[k][x] + irr.p[k][x]).abs() < 1e-12 * p0.abs() * amax, "cell {k}: force {:?}", rev.p[k]);
        }
        assert!(rev.m[k].abs() < 1e-13 && rev.s[k].abs() < 1e-13);
    }
    // The k_B drift alone moves the entropy (the Ito terms), never the momentum.
    assert!(irr.s.iter().all(|&x| x < 0.0));
}

/// Stepped: mass and momentum to round-off every step, with and without noise; energy
/// drift at k_B = 0 falls as dt^2 (Heun).
#[test]
fn steps_conserve_mass_and_momentum_and_energy_to_second_order() {
    let (c0, _) = disordered(64, 15);
    let drift = |dt: f64, steps: u64, kb: f64| {
        let model = FiniteVolume { energy: VDW, transport: CellTransport { kb, ..TR }, dissipation: CellDissipation::Hydrodynamic, seed: 9 };
        let mut c = c0.clone();
        let e0 = CellFrame::new(&c, &VDW, LO, LEN).unwrap().energy(&c);
        let (m0, p0): (f64, [f64; 3]) = (c.m.iter().sum(), sum3(&c.p));
        for s in 0..steps {
            let f0 = CellFrame::new(&c, &VDW, LO, LEN).unwrap();
            model.step(&mut c, &f0, LO, LEN, dt, s).unwrap();
            let m: f64 = c.m.iter().sum();
            let p = sum3(&c.p);
            assert!((m - m0).abs() < 1e-13 * m0, "step {s}: sum M {m} vs {m0}");
            let pscale: f64 = c.p.iter().flatten().map(|x| x.abs()).sum();
            assert!((0..3).all(|x| (p[x] - p0[x]).abs() < 1e-14 * pscale), "step {s}: sum P {p:?} vs {p0:?}");
        }
        let e1 = CellFrame::new(&c, &VDW, LO, LEN).unwrap().energy(&c);
        (e1 - e0).abs() / e0.abs()
    };
    let coarse = drift(0.02, 10, 0.0);
    let fine = drift(0.01, 20, 0.0);
    assert!(coarse < 1e-4 && fine < coarse / 3.0, "relative energy drift {coarse} at dt 0.02, {fine} at 0.01");
    eprintln!("relative energy drift over t = 0.2: {coarse:.3e} at dt 0.02, {fine:.3e} at dt 0.01");
    // With noise (k_B = 1e-3: cells of ~10^3 molecules), M and P stay exact.
    drift(0.01, 10, 1e-3);
}

/// The virial is the strain derivative of the cell energies at fixed M and S: each
/// diagonal component summed over the cells against central differences of sum E(M, S, V)
/// under a stretch of one axis of the generators and the box (disordered, 60 cells), and
/// per cell its trace is 3 p V.
#[test]
fn virial_is_minus_the_strain_derivative_of_the_cell_energies() {
    let (c, _) = disordered(60, 19);
    let f = CellFrame::new(&c, &VDW, LO, LEN).unwrap();
    let w = f.virial();
    for k in 0..c.len() {
        let pv = 3.0 * f.thermo[k].pressure * f.tess.volumes[k];
        assert!((w[k][0] + w[k][1] + w[k][2] - pv).abs() < 1e-13 * pv.abs(), "cell {k}: trace {:?} vs 3 p V = {pv}", w[k]);
    }
    let stretched = |a: usize, e: f64| {
        let mut s = c.clone();
        let mut len = LEN;
        len[a] *= 1.0 + e;
        for r in &mut s.r {
            r[a] = LO[a] + (1.0 + e) * (r[a] - LO[a]);
        }
        let f = CellFrame::new(&s, &VDW, LO, len).unwrap();
        f.thermo.iter().map(|st| st.energy).sum::<f64>()
    };
    let h = 1e-6;
    for a in 0..3 {
        let fd = -(stretched(a, h) - stretched(a, -h)) / (2.0 * h);
        let wa: f64 = w.iter().map(|x| x[a]).sum();
        assert!((fd - wa).abs() < 1e-8 * wa.abs(), "axis {a}: virial {wa} vs -dU/d epsilon {fd}");
        eprintln!("axis {a}: virial {wa:.10} vs -dU/d epsilon {fd:.10} (relative {:.1e})", (fd - wa) / wa);
    }
}

#[test]
fn a_cell_outside_the_relation_is_an_error_naming_its_tag() {
    let (mut c, _) = disordered(30, 16);
    c.m[4] = -1.0;
    match CellFrame::new(&c, &VDW, LO, LEN) {
        Err(ModelError::State { tag, .. }) => assert_eq!(tag, 5),
        other => panic!("expected a state error, got {other:?}"),
    }
    assert!(VDW.state(1.0, 1.0, 1.0).is_ok());
}

/// With noise a cell of heat capacity C = 3M/2 <= k_B stops the step, naming it; without
/// noise (k_B = 0) the same cell steps.
#[test]
fn a_cell_below_the_noise_models_heat_capacity_stops_the_step() {
    let (mut c, _) = disordered(30, 18);
    c.m[6] = 0.6;
    c.s[6] = vdw_entropy(WATER_C, 0.6, CellFrame::new(&c, &VDW, LO, LEN).unwrap().tess.volumes[6], 1.2);
    for (kb, fails) in [(1.0, true), (0.0, false)] {
        let model = FiniteVolume { energy: VDW, transport: CellTransport { kb, ..TR }, dissipation: CellDissipation::Hydrodynamic, seed: 3 };
        let f0 = CellFrame::new(&c, &VDW, LO, LEN).unwrap();
        match model.step(&mut c.clone(), &f0, LO, LEN, 1e-3, 0) {
            Err(ModelError::State { tag, err }) if fails => assert!(tag == 7 && err.what.contains("C <= k_B"), "{tag}: {err}"),
            Ok(()) if !fails => {}
            other => panic!("k_B {kb}: {other:?}"),
        }
    }
}

/// Eq 10 (fluctuation-dissipation): the irreversible drift at k_B = 0 is M . dS/dx with
/// M = <dx~ dx~^T>/(2 k_B dt); dS/dx is 1 on every entropy, so dP_mu = sum_l <dP~_mu dS~_l>
/// /(2 k_B dt) and T_mu dS_mu = T_mu sum_l <dS~_mu dS~_l>/(2 k_B dt). Estimated over 4000
/// realisations of the noise, every component within 5 standard errors.
#[test]
fn noise_covariance_gives_the_irreversible_drift_eq_10() {
    let (c, _) = disordered(16, 17);
    let f = CellFrame::new(&c, &VDW, LO, LEN).unwrap();
    let drift = f.irreversible(&c, &TR);
    let (worst, samples) = eq_10_deviation(&f, &drift, |step| f.noise(&c, &CellTransport { kb: 0.5, ..TR }, 3, step, 0.01), 0.5, 0.01);
    eprintln!("eq 10 over {samples} realisations: largest deviation {worst:.2} standard errors ({} components)", 4 * c.len());
    // eq_10_deviation asserts each component; the whole set within 5 standard errors too
    assert!(samples > 0 && worst < 5.0, "eq 10: largest deviation {worst:.2} standard errors over {samples} realisations");
}

/// Voronoi DPD (eqs 85-90): at k_B = 0 the irreversible rates conserve E and P and produce
/// entropy; the pair noise satisfies eq 87 in every realisation; and eq 10 holds with eq
/// 88's B times sqrt 2 (the printed B gives half of eq 89's friction and heating).
#[test]
fn voronoi_dpd_conserves_and_its_noise_covariance_gives_eq_89() {
    let (c, _) = disordered(16, 18);
    let f = CellFrame::new(&c, &VDW, LO, LEN).unwrap();
    let (gamma, kappa) = (0.8, 1.3);
    let r = f.irreversible_dpd(&c, gamma, kappa, 0.0);
    let dp = sum3(&r.p);
    assert!(dp.iter().all(|x| x.abs() < 1e-14 * scale3(&r.p) * 16.0), "sum dP/dt = {dp:?}");
    let heat: f64 = (0..c.len()).map(|k| (f.thermo[k].temperature * r.s[k]).abs()).sum();
    assert!(f.energy_rate(&r).abs() < 1e-12 * heat, "dE/dt = {}", f.energy_rate(&r));
    assert!(r.s.iter().sum::<f64>() > 0.0);

    let (worst, samples) = eq_10_deviation(&f, &r, |step| {
        let (dp, ds) = f.noise_dpd(&c, gamma, kappa, 0.5, 3, step, 0.01);
        let p = sum3(&dp);
        assert!(p.iter().all(|x| x.abs() < 1e-14 * scale3(&dp) * 16.0));
        let de: f64 = (0..c.len()).map(|k| f.v[k][0] * dp[k][0] + f.v[k][1] * dp[k][1] + f.v[k][2] * dp[k][2] + f.thermo[k].temperature * ds[k]).sum();
        assert!(de.abs() < 1e-12 * scale1(&ds) * 16.0, "eq 87: {de}");
        (dp, ds)
    }, 0.5, 0.01);
    eprintln!("Voronoi DPD, eq 10 over {samples} realisations: largest deviation {worst:.2} standard errors");

    // Stepped with noise: mass and momentum exact.
    let model = FiniteVolume { energy: VDW, transport: CellTransport { kb: 1e-3, kappa, ..TR }, dissipation: CellDissipation::Dpd { gamma }, seed: 4 };
    let mut s = c.clone();
    let (m0, p0) = (c.m.iter().sum::<f64>(), sum3(&c.p));
    for step in 0..10 {
        let f0 = CellFrame::new(&s, &VDW, LO, LEN).unwrap();
        model.step(&mut s, &f0, LO, LEN, 0.01, step).unwrap();
    }
    let p = sum3(&s.p);
    let pscale: f64 = s.p.iter().flatten().map(|x| x.abs()).sum();
    assert!((s.m.iter().sum::<f64>() - m0).abs() < 1e-13 * m0 && (0..3).all(|x| (p[x] - p0[x]).abs() < 1e-14 * pscale));
}

/// Largest |z| over cells and components of sum_l <dP~_mu dS~_l>/(2 k_B dt) and
/// T_mu sum_l <dS~_mu dS~_l>/(2 k_B dt) against the drift (eq 10), over 4000 realisations
/// `noise(step)`; panics beyond 5 standard errors.
fn eq_10_deviation(f: &CellFrame, drift: &Rates, noise: impl Fn(u64) -> (Vec<[f64; 3]>, Vec<f64>), kb: f64, dt: f64) -> (f64, u64) {
    let samples = 4000;
    let n = f.v.len();
    let mut sum = vec![[0.0f64; 4]; n];
    let mut sum2 = vec![[0.0f64; 4]; n];
    for step in 0..samples {
        let (dp, ds) = noise(step);
        let total: f64 = ds.iter().sum();
        for k in 0..n {
            let x = [dp[k][0] * total, dp[k][1] * total, dp[k][2] * total, f.thermo[k].temperature * ds[k] * total];
            for a in 0..4 {
                let y = x[a] / (2.0 * kb * dt);
                sum[k][a] += y;
                sum2[k][a] += y * y;
            }
        }
    }
    let mut worst: f64 = 0.0;
    for k in 0..n {
        let expected = [drift.p[k][0], drift.p[k][1], drift.p[k][2], f.thermo[k].temperature * drift.s[k]];
        for a in 0..4 {
            let mean = sum[k][a] / samples as f64;
            let se = ((sum2[k][a] / samples as f64 - mean * mean) / samples as f64).sqrt();
            let z = (mean - expected[a]) / se;
            worst = worst.max(z.abs());
            assert!(z.abs() < 5.0, "cell {k} component {a}: covariance {mean:.5} +- {se:.5}, drift {:.5}", expected[a]);
        }
    }
    (worst, samples)
}
