//! Conservation in the whole program: with gamma = kappa = 0 only the reversible
//! velocity-Verlet step acts, and its energy error must fall as dt^2.

mod common;

use gendpde::Observables;

/// Largest |E(t) - E(0)| / |E(0)| over 2 time units of the vdW scene at timestep `dt`,
/// started from the same equilibrated state.
fn energy_error(dt: f64) -> f64 {
    let mut it = common::run_example("vdw-equilibrium", &[("n", "11"), ("rc", "3.0"), ("steps", "300")]);
    it.execute_str("nve.in", &format!("unfix ssa\ntimestep {dt}\n")).unwrap();
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let e0 = Observables::measure(sys).energy();
    let mut worst: f64 = 0.0;
    for _ in 0..(2.0 / dt).round() as u64 {
        physics.step(sys).unwrap();
        worst = worst.max(((Observables::measure(sys).energy() - e0) / e0).abs());
    }
    worst
}

#[test]
fn reversible_step_energy_error_is_second_order() {
    let (e1, e2, e4) = (energy_error(0.02), energy_error(0.01), energy_error(0.005));
    eprintln!("max relative energy error: dt 0.02 {e1:.3e}, dt 0.01 {e2:.3e}, dt 0.005 {e4:.3e}; ratios {:.3} {:.3}", e1 / e2, e2 / e4);
    assert!((3.0..=5.0).contains(&(e2 / e4)), "ratio {}", e2 / e4);
    assert!((3.0..=5.0).contains(&(e1 / e2)), "ratio {}", e1 / e2);
}
