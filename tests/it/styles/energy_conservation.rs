//! Conservation in the whole program: with gamma = kappa = 0 only the reversible
//! velocity-Verlet step acts, and its energy error must fall as dt^2.

use crate::common;

use gendpde::Observables;

/// Largest |E(t) - E(0)| / |E(0)| over 2 time units of the vdW scene at timestep `dt`,
/// started from the same equilibrated state.
fn energy_error(dt: f64) -> f64 {
    let mut it = common::run_example("vdw-equilibrium", &[("n", "11"), ("rc", "3.0"), ("steps", "300")]);
    it.execute_str("nve.in", &format!("unfix ssa\ntimestep {dt}\n")).unwrap();
    common::worst_energy_error(&mut it, (2.0 / dt).round() as u64)
}

#[test]
fn reversible_step_energy_error_is_second_order() {
    let (e1, e2, e4) = (energy_error(0.02), energy_error(0.01), energy_error(0.005));
    eprintln!("max relative energy error: dt 0.02 {e1:.3e}, dt 0.01 {e2:.3e}, dt 0.005 {e4:.3e}; ratios {:.3} {:.3}", e1 / e2, e2 / e4);
    assert!((3.0..=5.0).contains(&(e2 / e4)), "ratio {}", e2 / e4);
    assert!((3.0..=5.0).contains(&(e1 / e2)), "ratio {}", e1 / e2);
}

/// The Shardlow sweep alone (particles held in place) conserves total momentum and
/// K + U to round-off: every ghost written in a colour must reach its owner.
#[test]
fn colour_sweep_through_ghosts_conserves_momentum_and_energy() {
    let mut it = common::run_example("vdw-equilibrium", &[("n", "11"), ("rc", "3.0"), ("steps", "20")]);
    it.execute_str("sweep.in", "unfix rev\nfix bump all shardlow heat fourier\nunfix ssa\n").unwrap();
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let total_p = |sys: &gendpde_integrators::System| {
        let s = &sys.store;
        (0..3).map(|k| s.p[..s.nlocal].iter().map(|p| p[k]).sum::<f64>()).collect::<Vec<_>>()
    };
    let (e0, p0) = (Observables::measure(sys).energy(), total_p(sys));
    let p_scale: f64 = sys.store.p[..sys.store.nlocal].iter().map(|p| p[0].abs()).sum();
    let (mut worst_e, mut worst_p): (f64, f64) = (0.0, 0.0);
    for _ in 0..100 {
        physics.advance(sys).unwrap();
        worst_e = worst_e.max(((Observables::measure(sys).energy() - e0) / e0).abs());
        let p = total_p(sys);
        worst_p = worst_p.max((0..3).map(|k| (p[k] - p0[k]).abs()).fold(0.0, f64::max) / p_scale);
    }
    eprintln!("sweep only, 100 steps: max relative energy change {worst_e:.2e}, momentum {worst_p:.2e}");
    assert!(worst_e < 1e-13, "energy changed by {worst_e:e}");
    assert!(worst_p < 1e-13, "momentum changed by {worst_p:e}");
}
