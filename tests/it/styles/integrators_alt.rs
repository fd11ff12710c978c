//! The alternative integrators on the vdW scene of examples/vdw-equilibrium (N = 1331,
//! rc = 3, equilibrated by 300 eSSA steps first): `fix vv/euler` (argon paper sec 4.1)
//! and `fix nve/gendpde work isentropic` (SPEC section 6); and `fix eos/lth`.
#![allow(clippy::approx_constant)] // 1.4142 is the vdW b of the 2019 paper, not sqrt 2

use crate::common;

use common::stats::mean;
use gendpde::Observables;
use gendpde_potentials::{Eos, LinearTheta};

const T: f64 = 1.5;
const VV_EULER: &str = "unfix rev\nunfix ssa\nfix vv all vv/euler\n";

/// The equilibrated vdW scene, then `switch` (fix changes, timestep) executed.
fn scene(switch: &str) -> gendpde::Interpreter {
    let mut it = common::run_example("vdw-equilibrium", &[("n", "11"), ("rc", "3.0"), ("steps", "300")]);
    it.execute_str("switch.in", switch).unwrap();
    it
}

/// (t, (E(t) - E(0))/E(0)) over `duration` time units at timestep `dt`.
fn energy_series(switch: &str, dt: f64, duration: f64) -> Vec<(f64, f64)> {
    let mut it = scene(&format!("{switch}timestep {dt}\n"));
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let e0 = Observables::measure(sys).energy();
    let steps = (duration / dt).round() as u64;
    (1..=steps)
        .map(|k| {
            physics.advance(sys).unwrap();
            (k as f64 * dt, (Observables::measure(sys).energy() - e0) / e0)
        })
        .collect()
}

/// Least-squares slope of y against t.
fn slope(series: &[(f64, f64)]) -> f64 {
    let n = series.len() as f64;
    let (mt, my) = (series.iter().map(|p| p.0).sum::<f64>() / n, series.iter().map(|p| p.1).sum::<f64>() / n);
    let sxy: f64 = series.iter().map(|p| (p.0 - mt) * (p.1 - my)).sum();
    let sxx: f64 = series.iter().map(|p| (p.0 - mt) * (p.0 - mt)).sum();
    sxy / sxx
}

fn max_abs(series: &[(f64, f64)]) -> f64 {
    series.iter().map(|p| p.1.abs()).fold(0.0, f64::max)
}

#[test]
fn vv_euler_conserves_momentum_to_round_off() {
    for heat in ["original", "fourier"] {
        let mut it = scene(&VV_EULER.replace("vv/euler", &format!("vv/euler heat {heat}")));
        let physics = it.dynamics().unwrap();
        let sys = it.system().unwrap();
        let p0 = Observables::measure(sys).momentum;
        let scale: f64 = sys.store.p[..sys.store.nlocal].iter().map(|p| p.iter().map(|x| x.abs()).sum::<f64>()).sum();
        let mut worst: f64 = 0.0;
        for _ in 0..200 {
            physics.advance(sys).unwrap();
            let p = Observables::measure(sys).momentum;
            worst = worst.max((0..3).map(|c| (p[c] - p0[c]).abs()).fold(0.0, f64::max) / scale);
        }
        eprintln!("vv/euler heat {heat}: largest total-momentum change over 200 steps {worst:.2e} of sum |p|");
        assert!(worst < 1e-14, "momentum changed by {worst:e}");
    }
}

/// Without friction and noise the error of K + sum u is bounded and first order: eq 21
/// takes the work with the velocities of the start of the step. With friction, noise and
/// heat flow the mean drift is second order (the Ito term of eq 21 removes the O(dt)
/// kinetic energy of the noise; see integrators/src/vv_euler.rs).
#[test]
fn vv_euler_energy_error_orders() {
    let conservative = VV_EULER.to_string() + "pair_coeff * * 0.0 0.0\n";
    let e: Vec<f64> = [0.02, 0.01, 0.005].iter().map(|&dt| max_abs(&energy_series(&conservative, dt, 2.0))).collect();
    eprintln!(
        "gamma = kappa = 0, max |dE/E| over 2 time units: dt 0.02 {:.3e}, 0.01 {:.3e}, 0.005 {:.3e}; ratios {:.2} {:.2}",
        e[0], e[1], e[2], e[0] / e[1], e[1] / e[2]
    );
    for r in [e[0] / e[1], e[1] / e[2]] {
        assert!((1.7..=2.4).contains(&r), "first order expected, ratio {r}");
    }
    let d: Vec<f64> = [0.02, 0.01, 0.005].iter().map(|&dt| slope(&energy_series(VV_EULER, dt, 4.0))).collect();
    eprintln!(
        "gamma 4.5, kappa 1, drift of dE/E per time unit: dt 0.02 {:.3e}, 0.01 {:.3e}, 0.005 {:.3e}; ratios {:.2} {:.2}",
        d[0], d[1], d[2], d[0] / d[1], d[1] / d[2]
    );
    for r in [d[0] / d[1], d[1] / d[2]] {
        assert!((3.0..=6.0).contains(&r), "second order expected, ratio {r}");
    }
}

/// Mean and batch-means standard error (10 batches).
fn mean_and_error(x: &[f64]) -> (f64, f64) {
    let batches: Vec<f64> = x.chunks(x.len() / 10).take(10).map(mean).collect();
    let m = mean(&batches);
    let var = batches.iter().map(|b| (b - m) * (b - m)).sum::<f64>() / 9.0;
    (mean(x), (var / 10.0).sqrt())
}

/// With a reservoir at T (kappa 50, relaxation time ~3) at dt = 0.005, where the energy
/// drift (-2.6e-4 of E per time unit) shifts <T_int> by ~0.001 against the reservoir.
#[test]
fn vv_euler_equilibrium_temperatures() {
    let mut it = scene(&format!("{VV_EULER}fix bath all heat/reservoir {T} 50.0 777\ntimestep 0.005\n"));
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let (mut tk, mut ti) = (vec![], vec![]);
    for k in 1..=4000 {
        physics.advance(sys).unwrap();
        if k > 1000 && k % 10 == 0 {
            let o = Observables::measure(sys);
            tk.push(o.temperature(1.0));
            ti.push(o.theta / o.atoms);
        }
    }
    let ((mk, ek), (mi, ei)) = (mean_and_error(&tk), mean_and_error(&ti));
    eprintln!("vv/euler + reservoir, dt 0.005: <T_kin> = {mk:.5} +- {ek:.5}, <T_int> = {mi:.5} +- {ei:.5} (T = {T})");
    assert!(ek < 0.003 * T && ei < 0.003 * T, "statistical errors {ek}, {ei} too large to test anything");
    assert!((mk - T).abs() < 3.0 * ek, "<T_kin> = {mk} +- {ek}");
    assert!((mi - T).abs() < 3.0 * ei, "<T_int> = {mi} +- {ei}");
}

#[test]
fn vv_euler_is_refused_with_nve_gendpde_or_shardlow() {
    let mut it = common::run_example("vdw-equilibrium", &[("n", "11"), ("rc", "3.0"), ("steps", "0")]);
    it.execute_str("a.in", "fix vv all vv/euler\n").unwrap();
    let e = it.execute_str("b.in", "run 1\n").unwrap_err().to_string();
    eprintln!("{e}");
    assert!(e.contains("b.in") && e.contains("both move the particles"), "{e}");
    it.execute_str("c.in", "unfix rev\n").unwrap();
    let e = it.execute_str("d.in", "run 1\n").unwrap_err().to_string();
    eprintln!("{e}");
    assert!(e.contains("d.in") && e.contains("unfix ssa"), "{e}");
}

/// Entropy of every particle by tag, at its current density.
fn entropies(sys: &gendpde_integrators::System) -> Vec<(u64, f64)> {
    let eos = LinearTheta::vdw_excess(60.0, 2.4682, 1.4142);
    let s = &sys.store;
    let mut out: Vec<(u64, f64)> = (0..s.nlocal).map(|i| (s.tag[i], eos.entropy(s.u[i], s.n[i]).unwrap())).collect();
    out.sort_by_key(|x| x.0);
    out
}

/// With gamma = kappa = 0 nothing but the reversible step changes u: at fixed entropy
/// every particle keeps its s (to round-off), while the work split changes it by O(dt^3)
/// per step.
#[test]
fn isentropic_step_keeps_every_entropy() {
    let mut change = vec![];
    for work in ["isentropic", "split"] {
        let mut it = scene(&format!("unfix ssa\nfix rev all nve/gendpde work {work}\n"));
        let physics = it.dynamics().unwrap();
        let sys = it.system().unwrap();
        let before = entropies(sys);
        for _ in 0..200 {
            physics.advance(sys).unwrap();
        }
        let after = entropies(sys);
        let worst = before.iter().zip(&after).map(|(a, b)| (a.1 - b.1).abs()).fold(0.0, f64::max);
        eprintln!("work {work}: largest entropy change of a particle over 200 steps {worst:.2e} k_B");
        change.push(worst);
    }
    assert!(change[0] < 1e-11, "isentropic step changed an entropy by {:e}", change[0]);
    assert!(change[1] > 1e-6, "the split should change entropies measurably: {:e}", change[1]);
}

/// `count` initial states for the order test: the equilibrated scene, then every 0.5 time
/// units (50 eSSA steps) of its continuation; the interpreter is left without `fix ssa`.
fn equilibrated_states(count: usize) -> (gendpde::Interpreter, Vec<gendpde_integrators::Snapshot>) {
    let mut it = scene("");
    let mut states = vec![gendpde_integrators::Snapshot::default(); count];
    for (k, snap) in states.iter_mut().enumerate() {
        if k > 0 {
            it.execute_str("more.in", "run 50\n").unwrap();
        }
        it.system().unwrap().save(snap);
    }
    it.execute_str("switch.in", "unfix ssa\n").unwrap();
    (it, states)
}

/// RMS of (E(t) - E(0))/E(0) over `duration` time units at timestep `dt` from `state`,
/// with `fix rev all nve/gendpde work {work}`.
fn rms_energy_error(it: &mut gendpde::Interpreter, state: &gendpde_integrators::Snapshot, work: &str, dt: f64, duration: f64) -> f64 {
    it.execute_str("work.in", &format!("unfix rev\nfix rev all nve/gendpde work {work}\ntimestep {dt}\n")).unwrap();
    it.system().unwrap().restore(state);
    let physics = it.dynamics().unwrap();
    let sys = it.system().unwrap();
    let e0 = Observables::measure(sys).energy();
    let steps = (duration / dt).round() as u64;
    let sum2: f64 = (0..steps)
        .map(|_| {
            physics.advance(sys).unwrap();
            ((Observables::measure(sys).energy() - e0) / e0).powi(2)
        })
        .sum();
    (sum2 / steps as f64).sqrt()
}

/// The isentropic step is velocity Verlet on the potential sum_i u(s_i, n_i(r)): energy
/// error O(dt^2), like the split's. Measured from 8 equilibrated states 0.5 time units
/// apart: from each, the RMS of dE/E over 0.5 time units at dt 0.01, 0.005, 0.0025 and
/// its ratio for each halving; the geometric mean of a ratio over the states (2^order
/// averaged in the order) must lie within 3-5 (a first-order step gives ~2). One
/// trajectory is a poor measure of the order: its error is a fluctuating sum over the
/// particles, with rare large terms (close pairs, pairs crossing rc where the quadratic
/// weight's w'' jumps) that fall differently at each dt, so from one state the ratio
/// spans 2.7-8 and moves with any change of the equilibration (the list order of issue
/// 21 part 4 took the ratio of the largest |dE/E| of one run over 2 time units from 3.80
/// to 2.85). The mean over states is one over the equilibrium ensemble, where the
/// error's dt^2 scaling holds; the per-state ratios and the standard error of the mean
/// are printed. The split's error, mostly its systematic entropy change, gives 4.00-4.05
/// from every state: it is measured from 2.
#[test]
fn isentropic_energy_error_is_second_order() {
    let (mut it, states) = equilibrated_states(8);
    for (work, count) in [("split", 2), ("isentropic", 8)] {
        let e: Vec<Vec<f64>> = [0.01, 0.005, 0.0025].iter().map(|&dt| states[..count].iter().map(|s| rms_energy_error(&mut it, s, work, dt, 0.5)).collect()).collect();
        for a in 0..2 {
            let ratios: Vec<f64> = e[a].iter().zip(&e[a + 1]).map(|(x, y)| x / y).collect();
            let logs: Vec<f64> = ratios.iter().map(|r| r.ln()).collect();
            let m = mean(&logs);
            let se = (logs.iter().map(|l| (l - m) * (l - m)).sum::<f64>() / (count * (count - 1)) as f64).sqrt();
            let (ratio, dt) = (m.exp(), [0.01, 0.005][a]);
            let listed: Vec<String> = ratios.iter().map(|r| format!("{r:.2}")).collect();
            eprintln!(
                "work {work}, RMS dE/E over 0.5 time units, dt {dt} -> {}: {:.3e} -> {:.3e} (mean of {count} states); ratio {ratio:.2} \
                 (geometric mean, standard error x/ {:.2}; per state {})",
                dt / 2.0,
                mean(&e[a]),
                mean(&e[a + 1]),
                se.exp(),
                listed.join(" ")
            );
            assert!((3.0..=5.0).contains(&ratio), "work {work}: second order expected, ratio {ratio} at dt {dt}");
        }
    }
}

/// Runs `script` (thermo every 20 steps, 200 steps) on 1 and 2 ranks (mpirun, as
/// tests/it/guarantees/mpi.rs) and compares the thermo lines and the final particles.
#[cfg(feature = "mpi")]
fn same_on_1_and_2_ranks(name: &str, script: &str) {
    use std::process::Command;
    let dir = std::env::temp_dir().join(format!("gendpde-alt-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("in.test"), format!("{script}write_dump all custom final.dump id x y z px py pz u theta\n")).unwrap();
    let mut runs = vec![];
    for np in [1, 2] {
        let out = Command::new("mpirun")
            .args(["--oversubscribe", "-np", &np.to_string(), env!("CARGO_BIN_EXE_gendpde")])
            .args(["run", "in.test", "-log", "none"])
            .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
            .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
            .current_dir(&dir)
            .output()
            .expect("mpirun runs (scripts/test.sh installs OpenMPI)");
        assert!(out.status.success(), "{name} on {np} ranks failed:\n{}", String::from_utf8_lossy(&out.stderr));
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        let rows: Vec<String> = stdout.lines().filter(|l| l.trim_start().starts_with(|c: char| c.is_ascii_digit())).map(String::from).collect();
        assert_eq!(rows.len(), 11, "{name}: thermo every 20 steps");
        runs.push((rows, std::fs::read_to_string(dir.join("final.dump")).unwrap()));
    }
    assert_eq!(runs[0].0, runs[1].0, "{name}: thermo on 2 ranks differs from 1 rank");
    assert!(runs[0].1 == runs[1].1, "{name}: final particles on 2 ranks differ from 1 rank");
    eprintln!("{name}: 2 ranks identical to 1 rank, last thermo line {}", runs[0].0[10]);
}

/// The vdW example (N = 1331, rc = 3) with `fixes` replacing its two integration fixes.
#[cfg(feature = "mpi")]
fn vdw_script(fixes: &str) -> String {
    std::fs::read_to_string(common::example("vdw-equilibrium"))
        .unwrap()
        .replace("fix          rev all nve/gendpde\n", fixes)
        .replace("fix          ssa all shardlow heat original\n", "")
        .replace("thermo       100", "thermo       20")
        .replace("index 15 ", "index 11 ")
        .replace("index 500", "index 200")
        .replace("index 4.0 ", "index 3.0 ")
}

#[cfg(feature = "mpi")]
#[test]
fn vv_euler_is_identical_on_1_and_2_ranks() {
    same_on_1_and_2_ranks("vv-euler", &vdw_script("fix          vv all vv/euler heat fourier\n"));
}

/// The entropies ride in theta through the migration of the list rebuilds.
#[cfg(feature = "mpi")]
#[test]
fn isentropic_step_is_identical_on_1_and_2_ranks() {
    same_on_1_and_2_ranks("isentropic", &vdw_script("fix          rev all nve/gendpde work isentropic\nfix          ssa all shardlow\n"));
}

/// The LTh liquid with the corrected volume, the isentropic step and the sweep (argon
/// paper Tables 1-4).
#[cfg(feature = "mpi")]
#[test]
fn corrected_volume_is_identical_on_1_and_2_ranks() {
    let script = lth_script("volume corrected 1.33", "", 0.002)
        .replace("pair_coeff * * 0.0 0.0", "pair_coeff * * 2.14 0.00072")
        .replace("run 0", "fix ssa all shardlow\nthermo 20\nrun 200");
    same_on_1_and_2_ranks("corrected-volume", &script);
}

/// An LTh liquid (argon paper Table 1 with C_V of eq 108, reduced units, R* = 2.1564) of
/// 1000 particles at c* = 1, gamma = kappa = 0, moved by the isentropic reversible step:
/// its energy is conserved to O(dt^2) only if the forces are minus the gradient of
/// sum_i u(s_i, n_i(r)), which tests the EOS (pi = n^2 du/dn at fixed s) and the density.
fn lth_scene(pair_extra: &str, eos_extra: &str, dt: f64) -> gendpde::Interpreter {
    common::run_script(&lth_script(pair_extra, eos_extra, dt))
}

fn lth_script(pair_extra: &str, eos_extra: &str, dt: f64) -> String {
    format!(
        "units lj\nlattice sc 1.0\nregion box block 0 10 0 10 0 10\ncreate_box 1 box\ncreate_atoms 1 box\nmass 1 1.0\n\
         velocity all create 0.0111 4928459 dist gaussian\nset group all theta 0.0111\n\
         pair_style gendpde 2.1564 4928459 {pair_extra}\npair_coeff * * 0.0 0.0\n\
         fix eos all eos/lth 11.008 29.345 1.0112 0.11606 0.011054 1.0 {eos_extra}\nfix rev all nve/gendpde work isentropic\n\
         timestep {dt}\nneighbor 0.3 bin\nrun 0\n"
    )
}

/// Largest |E(t) - E(0)|/E(0) over 2 time units of [`lth_scene`], mean theta and n at the end.
fn lth_energy_error(pair_extra: &str, eos_extra: &str, dt: f64) -> (f64, f64, f64) {
    let mut it = lth_scene(pair_extra, eos_extra, dt);
    let worst = common::worst_energy_error(&mut it, (2.0 / dt).round() as u64);
    let sys = it.system().unwrap();
    let s = &sys.store;
    (worst, Observables::measure(sys).theta / 1000.0, mean(&s.n[..s.nlocal]))
}

#[test]
fn lth_eos_fix_conserves_energy_and_tabulates() {
    use gendpde_potentials::eos::Lth;
    let cmd = |args: &str| gendpde_io::Command {
        name: "fix".into(),
        args: args.split_whitespace().map(String::from).collect(),
        loc: gendpde_io::Location { file: "lth.in".into(), line: 7 },
    };
    let lth = Lth::new(11.008, 29.345, 1.0112, 0.11606, 0.011054, 1.0);
    let analytic = gendpde::styles::fix::parse_fix(&cmd("eos all eos/lth 11.008 29.345 1.0112 0.11606 0.011054 1.0"), 1.0, &[]).unwrap();
    let table = gendpde::styles::fix::parse_fix(&cmd("eos all eos/lth 11.008 29.345 1.0112 0.11606 0.011054 1.0 table 0.005 0.03 61 0.5 1.5 65"), 1.0, &[]).unwrap();
    // the table within the largest errors it measured against the model over its grid
    for fix in [analytic, table] {
        let gendpde::styles::fix::FixStyle::Eos(model) = fix.style else { panic!("an EOS fix") };
        let d: std::collections::HashMap<_, _> = model.describe(Some(0.0121), None, 0.93).unwrap().into_iter().collect();
        let (u, pi) = (lth.u(0.0121, 0.93), lth.pressure(0.0121, 0.93));
        let (tol_u, tol_pi) = (d.get("table_error_u").copied().unwrap_or(1e-15), d.get("table_error_pn2").copied().unwrap_or(1e-15));
        eprintln!("eos/lth at theta 0.0121, n 0.93: u {} (eq 52: {u}), pi {} (eq 41: {pi}); table errors {tol_u:.1e} {tol_pi:.1e}", d["u"], d["pi"]);
        assert!(tol_u < 1e-3 && tol_pi < 1e-3, "table errors {tol_u} {tol_pi}");
        assert!((d["u"] - u).abs() <= tol_u * u.abs() && (d["pi"] - pi).abs() <= tol_pi * pi.abs(), "{d:?}");
    }
    let e = gendpde::styles::fix::parse_fix(&cmd("eos all eos/lth 11.008 29.345 0.0 0.11606 0.011054 1.0"), 1.0, &[]).unwrap_err().to_string();
    assert!(e.contains("lth.in:7") && e.contains("kappa_T"), "{e}");

    let ((e1, _, _), (e2, t2, _)) = (lth_energy_error("", "", 0.004), lth_energy_error("", "", 0.002));
    let (e3, t3, _) = lth_energy_error("", "table 0.005 0.03 61 0.5 1.5 65", 0.002);
    eprintln!("eos/lth, isentropic, max |dE/E| over 2 time units: dt 0.004 {e1:.3e}, 0.002 {e2:.3e} (ratio {:.2}); table at 0.002 {e3:.3e}", e1 / e2);
    eprintln!("<theta> after 2 time units at dt 0.002: model {t2:.9}, table {t3:.9}");
    assert!((3.0..=5.0).contains(&(e1 / e2)), "ratio {}", e1 / e2);
    // the table's entropy is the model's: its error enters the energy at its own size
    assert!(e3 < 1e-6, "table: energy error {e3:e}");
    assert!((t3 - t2).abs() < 1e-5 * t2, "table and model part: {t3} vs {t2}");
}

/// The corrected particle volume (argon paper eqs 2-3, f_cut of Table 4): the force of
/// eq 27 with zeta = dn/dn^b keeps the isentropic step's energy error O(dt^2). (Without
/// zeta the error was 4.5e-5 at dt 0.004 and 3.5e-5 at 0.002.)
#[test]
fn corrected_volume_forces_conserve_energy() {
    let (e1, _, n1) = lth_energy_error("volume corrected 1.33", "", 0.004);
    let (e2, _, n2) = lth_energy_error("volume corrected 1.33", "", 0.002);
    let (_, _, nb) = lth_energy_error("", "", 0.004);
    eprintln!("corrected volume, max |dE/E| over 2 time units: dt 0.004 {e1:.3e}, 0.002 {e2:.3e} (ratio {:.2}); <n> {n1:.4} {n2:.4}, plain <n^b> {nb:.4}", e1 / e2);
    assert!((3.0..=5.0).contains(&(e1 / e2)), "ratio {}", e1 / e2);
    assert!(e1 < 1e-7, "energy error {e1:e}");
}

