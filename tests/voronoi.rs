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

/// The dump keyword `vol` is each cell's own volume after the cells have moved: in every
/// row, mass, vol and theta give the dumped cell energy u = (3/2) M T - (9/8) M^2 / V (eq 161,
/// so a stale or misplaced volume fails), and the volumes sum to the box.
#[test]
fn the_vol_dump_column_is_each_cells_volume() {
    let dir = common::tempdir("voronoi-vol");
    let script = std::fs::read_to_string(common::example("voronoi-coexistence")).unwrap();
    std::fs::write(dir.join("in.c"), format!("{script}write_dump all custom final.dump id mass vol theta u\n")).unwrap();
    let out = common::gendpde(&dir, &["-in", "in.c", "-var", "k", "4", "-var", "V", "40", "-var", "steps", "20", "-var", "dump", "10", "-log", "none"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stdout));
    let text = std::fs::read_to_string(dir.join("final.dump")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let len: f64 = 4.0 * 40f64.cbrt();
    let rows: Vec<Vec<f64>> = lines[9..].iter().map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 64);
    let total: f64 = rows.iter().map(|r| r[2]).sum();
    assert!((total - len.powi(3)).abs() < 1e-12 * total, "sum of vol {total} against the box {}", len.powi(3));
    let spread = rows.iter().map(|r| (r[2] - 40.0).abs()).fold(0.0, f64::max);
    assert!(spread > 1e-3, "the cells did not move (volumes still 40, largest change {spread})");
    for r in &rows {
        let (m, v, t, u) = (r[1], r[2], r[3], r[4]);
        let e = 1.5 * m * t - 1.125 * m * m / v;
        assert!((e - u).abs() < 1e-9 * (1.5 * m * t), "cell {}: u {u} against E(M, T, vol) {e}", r[0]);
    }
}
