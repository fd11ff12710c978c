//! The Voronoi finite-volume model as a run (pair voronoi/fv + fix nve/voronoi,
//! examples/voronoi-vdw at 4^3 cells): total mass and momentum exact with noise while the
//! cells' masses change (hydrodynamic and DPD dissipation), the energy error second order
//! in dt without noise, no stale tessellation after a change between steps, thermo press
//! against the vdW EOS, the refusal of a second rank, and errors for bad input. The model's own invariants are tested in
//! integrators/src/models/voronoi/.

use crate::common;

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
            physics.advance(sys).unwrap();
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

/// A step starts from the previous step's end-of-step tessellation only while the cells
/// are unchanged: after a cell's momentum is changed between steps, the next step is the
/// same to the bit as one whose frame is recomputed by a new set-up (a stale frame would
/// move the cells with the old velocity).
#[test]
fn a_cell_changed_between_steps_is_tessellated_afresh() {
    let run = |setup_again: bool| {
        let mut it = scene("1", "0.05", "hydrodynamic");
        let physics = it.dynamics().unwrap();
        let sys = it.system().unwrap();
        physics.advance(sys).unwrap();
        let i = (0..sys.store.nlocal).find(|&i| sys.store.tag[i] == 7).unwrap();
        sys.store.p[i][0] += 0.5;
        if setup_again {
            physics.setup(sys).unwrap();
        }
        physics.advance(sys).unwrap();
        let s = &sys.store;
        let mut rows: Vec<(u64, [u64; 8])> = (0..s.nlocal)
            .map(|i| (s.tag[i], [s.r[i][0], s.r[i][1], s.r[i][2], s.p[i][0], s.p[i][1], s.p[i][2], s.mass[i], s.entropy[i]].map(f64::to_bits)))
            .collect();
        rows.sort();
        rows
    };
    assert!(run(false) == run(true), "the step after a change differs from one with a recomputed frame");
}

/// Thermo `press` of the Voronoi fluid, (sum_mu 3 p_mu V_mu + sum P^2/M) / (3 V_T): on a
/// simple-cubic lattice of equal vdW cells at rest it is the EOS pressure p = (3/8) P~(n~,
/// T~) in these units (eq 162, P~ = 8 T~ n~/(3 - n~) - 3 n~^2), in every diagonal
/// component; with velocities the kinetic part 2 K/(3 V_T) is added.
#[test]
fn press_is_the_cell_pressure_plus_the_kinetic_part() {
    let dir = common::tempdir("voronoi-press");
    let (n, t, v) = (0.7_f64, 0.9_f64, 20.0_f64);
    let eos = 3.0 / 8.0 * (8.0 * t * n / (3.0 - n) - 3.0 * n * n);
    for moving in [false, true] {
        let script = format!(
            "units lj\natom_style gendpde\nlattice sc {}\nregion box block 0 4 0 4 0 4\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 {}\n\
             {}set group all theta {t}\npair_style voronoi/fv 5 kB 0\npair_coeff * * 1 1 1 vdw 4.836e-5\nfix int all nve/voronoi\n\
             thermo_style custom step ke vol press pxx pyy pzz\nthermo_modify norm no format float %.17g\nrun 0\n",
            1.0 / v,
            n * v,
            if moving { "velocity all create 1.3 77 dist gaussian\n" } else { "" },
        );
        std::fs::write(dir.join("in.p"), script).unwrap();
        let out = common::gendpde(&dir, &["run", "in.p"]);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{text}{}", String::from_utf8_lossy(&out.stderr));
        let row = &common::lammps::parse_thermo(&text, "Step")[0];
        let (ke, vol, press) = (row[1], row[2], row[3]);
        let expected = eos + 2.0 * ke / (3.0 * vol);
        eprintln!("moving {moving}: press {press:.17} against {expected:.17} (EOS {eos:.17}), pxx pyy pzz {:?}", &row[4..7]);
        assert!((press - expected).abs() < 1e-14 * expected, "press {press} against {expected}");
        if !moving {
            assert!(row[4..7].iter().all(|&p| (p - eos).abs() < 1e-14 * eos), "{row:?}");
        }
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
