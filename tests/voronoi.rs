//! The Voronoi finite-volume model as a run (pair voronoi/fv + fix nve/voronoi,
//! examples/voronoi-vdw at 4^3 cells): total mass and momentum exact with noise while the
//! cells' masses change (hydrodynamic and DPD dissipation), the energy error second order in dt without noise, the refusal
//! of a second rank, and errors for bad input. The model's own invariants are tested in
//! integrators/src/voronoi/.

mod common;

use gendpde::{Interpreter, Mode, Observables, Output};

fn scene(kb: &str, dt: &str, diss: &str) -> Interpreter {
    common::run_example("voronoi-vdw", &[("k", "4"), ("kB", kb), ("dt", dt), ("steps", "0"), ("diss", diss)])
}

#[test]
fn mass_and_momentum_are_exact_and_the_energy_error_is_second_order() {
    let e1 = common::worst_energy_error(&mut scene("0", "0.1", "hydrodynamic"), 10);
    let e2 = common::worst_energy_error(&mut scene("0", "0.05", "hydrodynamic"), 20);
    eprintln!("voronoi/fv max relative energy error over t = 1: dt 0.1 {e1:.3e}, 0.05 {e2:.3e}, ratio {:.2}", e1 / e2);
    assert!(e1 < 1e-4 && (3.0..=6.0).contains(&(e1 / e2)), "not second order: {e1:e} {e2:e}");

    for diss in ["hydrodynamic", "dpd"] {
        let mut it = scene("1", "0.05", diss);
        let physics = it.dynamics().unwrap();
        let sys = it.system().unwrap();
        let n = sys.store.nlocal;
        let m0: f64 = sys.store.mass[..n].iter().sum();
        let p0: [f64; 3] = std::array::from_fn(|k| sys.store.p[..n].iter().map(|p| p[k]).sum());
        let scale: f64 = sys.store.p[..n].iter().map(|p| p[0].abs()).sum();
        let e0 = Observables::measure(sys).energy();
        for _ in 0..20 {
            physics.step(sys).unwrap();
        }
        let s = &sys.store;
        let m: f64 = s.mass[..n].iter().sum();
        let p: [f64; 3] = std::array::from_fn(|k| s.p[..n].iter().map(|p| p[k]).sum());
        let spread = s.mass[..n].iter().map(|&x| (x - 20.0).abs()).fold(0.0, f64::max);
        let de = (Observables::measure(sys).energy() - e0) / e0;
        eprintln!("{diss}, kB 1, 20 steps: total mass change {:.2e}, momentum change {:.2e}, largest cell-mass change {spread:.3}, energy change {de:.2e}", (m - m0) / m0, (0..3).map(|k| (p[k] - p0[k]).abs()).fold(0.0, f64::max) / scale);
        assert!(((m - m0) / m0).abs() < 1e-13, "total mass changed: {m0} -> {m}");
        assert!((0..3).all(|k| (p[k] - p0[k]).abs() < 1e-13 * scale), "momentum changed: {p0:?} -> {p:?}");
        assert!(spread > 1e-2, "the cells' masses did not change");
    }
}

#[cfg(feature = "mpi")]
#[test]
fn a_second_rank_is_refused_with_a_clear_error() {
    let dir = common::tempdir("voronoi-ranks");
    std::fs::copy(common::example("voronoi-vdw"), dir.join("in.v")).unwrap();
    let out = common::mpirun(2, &dir, &["run", "in.v", "-var", "k", "4", "-var", "steps", "2"]);
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(!out.status.success());
    assert!(text.contains("in.v:42: run: pair voronoi/fv runs on one MPI rank only (this run has 2)"), "{text}");
}

#[test]
fn bad_input_names_the_line_and_what_was_expected() {
    let base = "units lj\natom_style gendpde\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 random 20 7 NULL\nmass 1 1.0\n\
                set group all theta 1.0\npair_style voronoi/fv 5\n";
    for (tail, expected) in [
        ("pair_coeff * * 1 1 1 gas 1\n", "test.in:9: pair_coeff: unknown cell relation 'gas'; known: vdw, ideal"),
        ("pair_coeff * * 1 1 1 vdw 0\n", "test.in:9: pair_coeff"),
        ("pair_coeff * * 1 1 1 ideal 1\nrun 1\n", "pair voronoi/fv needs fix nve/voronoi"),
        ("pair_coeff * * 1 1 1 ideal 1\nfix a all nve/voronoi\nfix b all nve\nrun 1\n", "fix b does not work with pair voronoi/fv"),
    ] {
        let mut it = Interpreter::new(Mode::Run, Output::new(false));
        let err = it.execute_str("test.in", &format!("{base}{tail}")).expect_err(tail).to_string();
        assert!(err.contains(expected), "{tail}: {err}");
    }
    let mut it = Interpreter::new(Mode::Run, Output::new(false));
    let err = it.execute_str("test.in", "units lj\npair_style voronoi/fv 0\n").expect_err("seed 0").to_string();
    assert!(err.contains("random seed must be positive"), "{err}");
}
