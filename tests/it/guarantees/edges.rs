//! Behaviour at the edges is designed, not accidental: one test per edge.
#![allow(clippy::approx_constant)] // 1.4142 is the vdW b of the 2019 paper, not sqrt 2

use crate::common;

use gendpde::Observables;
use std::process::Command;

/// A vdW scene of `n`^3 particles on a simple cubic lattice at density `rho`.
fn vdw(n: usize, rho: f64, extra: &str) -> String {
    format!(
        "units lj
lattice sc {rho}
region box block 0 {n} 0 {n} 0 {n}
create_box 1 box
create_atoms 1 box
mass 1 1.0
velocity all create 1.5 77 dist gaussian
set group all theta 1.5
pair_style gendpde 3.0 99
pair_coeff * * 4.5 1.0
fix eos all eos/vdw 60.0 2.4682 1.4142
fix rev all nve/gendpde
{extra}
timestep 0.01
"
    )
}

#[test]
fn isolated_particles_feel_no_force_and_keep_finite_states() {
    // lattice spacing 10 > rc = 3 + skin: every particle is isolated
    let mut it = common::run_script(&(vdw(4, 0.001, "fix ssa all shardlow") + "run 0\n"));
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let e0 = Observables::measure(sys).energy();
    for _ in 0..50 {
        physics.advance(sys).unwrap();
    }
    let s = &sys.store;
    for i in 0..s.nlocal {
        assert_eq!(s.n[i], 0.0, "no neighbours");
        assert_eq!(s.pn2[i], 0.0, "isolated rule: pi = 0");
        assert_eq!(s.f[i], [0.0; 3], "no force");
        assert!(s.theta[i].is_finite() && s.theta[i] > 0.0);
    }
    assert!((Observables::measure(sys).energy() - e0).abs() <= 1e-12 * e0.abs());
}

#[test]
fn densities_beyond_the_vdw_cap_stay_finite_and_repulsive() {
    // mean density 0.69, just below 1/b = 0.707: local densities cross n_s = 0.95/b
    let mut it = common::run_script(&(vdw(12, 0.69, "fix ssa all shardlow") + "run 0\n"));
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let e0 = Observables::measure(sys).energy();
    let ns = 0.95 / 1.4142;
    let mut max_n: f64 = 0.0;
    for _ in 0..300 {
        physics.advance(sys).unwrap();
        let s = &sys.store;
        max_n = max_n.max(s.n[..s.nlocal].iter().cloned().fold(0.0, f64::max));
        assert!(s.pn2[..s.nlocal].iter().all(|p| p.is_finite()));
    }
    let drift = ((Observables::measure(sys).energy() - e0) / e0).abs();
    eprintln!("largest local density {max_n:.4} (cap starts at {ns:.4}, 1/b = {:.4}); energy change {drift:.2e}", 1.0 / 1.4142);
    assert!(max_n > ns, "the scene should reach the continuation above n_s");
    assert!(drift < 1e-4);
}

/// Heat-only particles with C_V = 1.5 (close to k_B): some particle temperatures
/// approach 0 and single pair updates would overshoot.
fn near_zero(keywords: &str) -> String {
    format!(
        "units lj
lattice sc 0.5
region box block 0 10 0 10 0 10
create_box 1 box
create_atoms 1 box
mass 1 1.0
set group all theta 1.5
pair_style gendpde 3.0 2021
pair_coeff * * 0.0 1.0 3.0 3.0
fix eos all eos/cv 1.5
fix ssa all shardlow heat fourier {keywords}
timestep 0.02
neighbor 0.0 bin
run 0
"
    )
}

#[test]
fn theta_near_zero_is_split_or_rejected_or_stops_cleanly() {
    // substeps + reject: the run goes on, energy exact, every theta positive
    let mut it = common::run_script(&near_zero("substeps 4 reject yes"));
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let u0: f64 = sys.store.u[..sys.store.nlocal].iter().sum();
    for _ in 0..1000 {
        physics.advance(sys).unwrap();
    }
    let s = &sys.store;
    let u1: f64 = s.u[..s.nlocal].iter().sum();
    eprintln!("theta -> 0: {} split pair updates, {} left out, sum u change {:.1e}", sys.control.substeps, sys.control.rejected, (u1 - u0) / u0);
    assert!(sys.control.substeps > 0, "the scene must exercise the splits");
    assert!(s.theta[..s.nlocal].iter().all(|t| *t > 0.0));
    assert!(((u1 - u0) / u0).abs() < 1e-12);
    // without splits the first failing pair stops the run with a clear error
    let mut it = common::run_script(&near_zero("substeps 0"));
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let err = (0..1000).find_map(|_| physics.advance(sys).err()).expect("a pair update must fail without splits");
    assert!(err.to_string().contains("particle temperature is not positive"), "{err}");
}

#[test]
fn heat_capacity_at_k_b_is_refused_and_just_above_runs() {
    let dir = std::env::temp_dir().join(format!("gendpde-edges-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("in.cv"), near_zero("").replace("eos/cv 1.5", "eos/cv 1.0")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).args(["check", "in.cv"]).current_dir(&dir).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("in.cv:10: fix: C_V = 1.0 must exceed k_B = 1.0"), "{err}");
    let mut it = common::run_script(&near_zero("substeps 4 reject yes").replace("eos/cv 1.5", "eos/cv 1.05"));
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    for _ in 0..200 {
        physics.advance(sys).unwrap();
    }
    // shape C_V/k_B ~ 1: exponential-like theta, still positive, mean 1.5
    let s = &sys.store;
    let mean = s.theta[..s.nlocal].iter().sum::<f64>() / s.nlocal as f64;
    assert!((mean - 1.5).abs() < 1e-9, "sum u is conserved, so <theta> = {mean}");
}

#[test]
fn non_finite_input_and_non_finite_states_stop_with_the_particle_named() {
    let dir = std::env::temp_dir().join(format!("gendpde-nan-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = |script: &str| {
        std::fs::write(dir.join("in.nan"), script).unwrap();
        Command::new(env!("CARGO_BIN_EXE_gendpde")).args(["run", "in.nan", "-log", "none"]).current_dir(&dir).output().unwrap()
    };
    // NaN in the script is refused at its line
    let out = run(&(vdw(12, 0.5, "") + "set atom 5 u nan\nrun 1\n"));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("in.nan:15: set: expected the internal energy u (a number), got 'nan'"), "{err}");
    // an absurd state overflows during the step: the run stops naming it and keeps the
    // last good state
    let out = run(&(vdw(12, 0.5, "fix ssa all shardlow") + "set atom 5 u 1e308\nrun 10\n"));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("run stopped: particle ") && err.contains(" during step 1: particle "), "{err}");
    assert!(err.contains("the last good state (step 0) is in failed.restart.h5"), "{err}");
    assert!(!err.contains("internal error"), "{err}");
}

#[test]
fn a_system_too_large_for_memory_is_refused_before_allocating() {
    let dir = std::env::temp_dir().join(format!("gendpde-mem-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("in.big"), vdw(100_000, 0.5, "")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).args(["check", "in.big"]).current_dir(&dir).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("in.big:5: create_atoms: create_atoms of up to") && err.contains("GiB of memory"), "{err}");
}

/// A particle that leaves an EOS table (theta beyond its range) stops the run with the
/// particle, the step and the table's range named, not a bare NaN.
#[test]
fn a_particle_leaving_the_eos_table_stops_naming_the_table_range() {
    let dir = std::env::temp_dir().join(format!("gendpde-table-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let script = vdw(12, 0.5, "fix ssa all shardlow").replace(
        "eos/vdw 60.0 2.4682 1.4142",
        "eos/vdw 60.0 2.4682 1.4142 table 1.45 1.55 11 0.0 1.2 65",
    ) + "run 200\n";
    std::fs::write(dir.join("in.table"), script).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_gendpde")).args(["run", "in.table", "-log", "none"]).current_dir(&dir).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("run stopped: particle ") && err.contains("lies outside the EOS table"), "{err}");
    assert!(err.contains("failed.restart.h5") && !err.contains("internal error"), "{err}");
}
