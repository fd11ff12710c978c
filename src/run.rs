//! The `run` command: set up the dynamics, step, and print thermo as LAMMPS does.

use crate::commands::{AppError, Interpreter, Mode};
use crate::styles;
use crate::thermo::{header_line, value_line, Observables, ThermoContext};
use gendpde_integrators::{Physics, SetupError};
use gendpde_io::{Command, ScriptError};
use std::time::Instant;

/// Builds the dynamics of the current styles and sets the system up for it (lists,
/// densities, forces); errors name `cmd`.
pub fn prepare(it: &mut Interpreter, cmd: &Command) -> Result<Box<dyn Physics>, AppError> {
    let err = |m: String| AppError::Script(ScriptError::at(cmd, m));
    let sim = &mut it.sim;
    let physics = styles::build_physics(cmd, sim.pair.as_ref(), &sim.fixes, sim.dt, sim.skin, sim.rebuild.clone(), sim.units.kb)?;
    let sys = sim.system.as_mut().ok_or_else(|| err("run before create_box".into()))?;
    if sys.store.nlocal == 0 {
        return Err(err("the box holds no particles (create_atoms)".into()));
    }
    // the cells must reach the pairs that the computes read by fix ave/time count
    sys.min_cell = 0.0;
    for rdf in sim.rdfs.iter().filter(|r| sim.averages.iter().any(|f| f.computes().any(|c| c == r.id))) {
        let rc = rdf.cutoff_for(sim.pair.as_ref()).unwrap_or(0.0);
        rdf.check_reach(sys, rc + sim.skin).map_err(err)?;
        sys.min_cell = sys.min_cell.max(rc + sim.skin);
    }
    if let Some(i) = (0..sys.store.nlocal).find(|&i| !sys.store.mass[i].is_finite()) {
        return Err(err(format!("the mass of type {} is not set", sys.store.kind[i])));
    }
    // neighbour and sweep lists, estimated from the mean density before they are built
    let (n, volume) = (sys.store.nlocal as f64, sys.domain.volume() / sys.comm.size() as f64);
    let reach = physics.list_radius();
    let neighbours = n / volume * 4.0 / 3.0 * std::f64::consts::PI * reach.powi(3);
    let bytes = n * neighbours * (crate::memory::NEIGHBOUR_ENTRY_BYTES + 0.5 * crate::memory::SWEEP_PAIR_BYTES);
    crate::memory::check(bytes, &format!("the neighbour lists ({neighbours:.0} neighbours per particle)")).map_err(err)?;
    // a continuation keeps the forces of the step its restart was written at: they
    // depend on that step's velocities and noise, which the set-up cannot redo
    let resume = sys.restored.then(|| sys.store.save_by_tag(gendpde_engine::stage::RESUME));
    physics.setup(sys).map_err(|e| match e {
        SetupError::Grid(g) | SetupError::Types(g) => err(g),
        SetupError::State(s) => AppError::Step { cmd: cmd.clone(), err: s },
    })?;
    if let Some(saved) = resume.filter(|_| sys.restored_grid == sys.grid.as_ref().map(|g| g.count)) {
        let exchanged = sys.store.restore_by_tag(&saved);
        sys.comm.forward(&mut sys.store, exchanged);
    }
    if let Some(grid) = &sys.grid {
        log::info!(
            "cell grid {:?} of side {:?}; {} ghosts; {} neighbour pairs; {} sweep pairs",
            grid.count,
            grid.side,
            sys.store.nghost(),
            sys.nlist.pairs.len(),
            sys.sweep.pairs.len()
        );
    }
    Ok(physics)
}

pub fn run(it: &mut Interpreter, cmd: &Command, nsteps: u64) -> Result<(), AppError> {
    let err = |m: String| AppError::Script(ScriptError::at(cmd, m));
    let physics = prepare(it, cmd)?;
    if it.mode == Mode::Check {
        return Ok(());
    }
    let sim = &mut it.sim;
    let sys = sim.system.as_mut().expect("prepared system");
    let energy0 = *sim.energy0.get_or_insert_with(|| Observables::measure(sys).energy());
    let keys = sim.thermo.keywords.clone();
    let start_step = sys.step;
    let comm_before = sys.comm.time().as_secs_f64();
    let clock = Instant::now();
    let natoms = Observables::measure(sys).atoms;
    it.out.line(&format!("Setting up GenDPDE run: {natoms} particles, timestep {} ...", sim.dt));
    it.out.line(&header_line(&keys));
    let thermo = |it: &mut Interpreter| -> Result<(), AppError> {
        let sim = &it.sim;
        let sys = sim.system.as_ref().expect("system exists during a run");
        let ctx = ThermoContext {
            sys,
            obs: Observables::measure(sys),
            norm: sim.thermo.norm,
            dt: sim.dt,
            energy0: Some(energy0),
            elapsed: sys.step - start_step,
            cpu: clock.elapsed().as_secs_f64(),
            units: sim.units,
            pe_is_pair: sim.pe_is_pair(),
            computes: &sim.computes,
        };
        let resolve = |name: &str| ctx.keyword(name);
        let mut values = Vec::with_capacity(keys.len());
        for k in &keys {
            let v = match ctx.keyword(k) {
                Some(v) => v,
                None => gendpde_io::evaluate(k, &it.vars, &resolve).map_err(|e| err(format!("thermo keyword {k}: {e}")))?,
            };
            values.push(v);
        }
        let line = value_line(&keys, &values, sim.thermo.float_format.as_deref());
        it.out.line(&line);
        Ok(())
    };
    thermo(it)?;
    outputs(it, cmd, false)?;
    let mut last_good = gendpde_integrators::Snapshot::default();
    let every = it.sim.thermo.every;
    let progress = progress_bar(it.sim.system.as_ref().map_or(1, |s| s.comm.rank()) == 0, nsteps);
    for k in 1..=nsteps {
        if k % 16 == 0 {
            progress.set_position(k);
        }
        let sys = it.sim.system.as_mut().expect("system exists during a run");
        sys.save(&mut last_good);
        if let Err(mut e) = physics.step(sys) {
            progress.finish_and_clear();
            sys.restore(&last_good);
            let file = it.sim.checkpoint.as_ref().map_or_else(|| "failed.restart.h5".to_string(), |c| c.1.replace('*', &e.step.to_string()));
            e.what = match crate::restart::write(&it.sim, &file) {
                Ok(()) => format!("{}; the last good state (step {}) is in {file}", e.what, e.step),
                Err(w) => format!("{}; writing the last good state to {file} failed: {w}", e.what),
            };
            it.out.flush();
            return Err(AppError::Step { cmd: cmd.clone(), err: e });
        }
        if k == nsteps || (every > 0 && sys.step % every == 0) {
            progress.suspend(|| thermo(it))?;
        }
        outputs(it, cmd, true)?;
    }
    progress.finish_and_clear();
    let secs = clock.elapsed().as_secs_f64();
    let sys = it.sim.system.as_ref().expect("system exists during a run");
    let n = Observables::measure(sys).atoms as u64;
    it.out.line(&format!("Loop time of {secs:.6} on {} procs for {nsteps} steps with {n} atoms", sys.comm.size()));
    it.out.line("");
    if secs > 0.0 && nsteps > 0 {
        let rate = nsteps as f64 / secs;
        it.out.line(&format!(
            "Performance: {:.3} tau/day, {:.3} timesteps/s, {:.3} katom-step/s",
            rate * it.sim.dt * 86400.0,
            rate,
            rate * n as f64 / 1e3
        ));
    }
    let comm = sys.comm.time().as_secs_f64() - comm_before;
    if secs > 0.0 {
        it.out.line(&format!("Comm time (rank 0) = {comm:.6} s ({:.1} % of the loop)", 100.0 * comm / secs));
    }
    it.out.line(&format!("Neighbor list builds = {}", sys.builds));
    if sys.substeps > 0 || sys.rejected > 0 {
        it.out.line(&format!(
            "Shardlow pair updates split into half steps (theta -> 0 guard) = {}, left out = {}",
            sys.substeps, sys.rejected
        ));
    }
    it.out.flush();
    Ok(())
}

/// A progress bar with rate and ETA on stderr, shown only when stderr is a terminal.
fn progress_bar(root: bool, nsteps: u64) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !root || !std::io::stderr().is_terminal() || nsteps < 2 {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(nsteps);
    let style = indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} steps  {per_sec}  ETA {eta}")
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    bar.set_style(style);
    bar
}

/// H5MD frames due at this step, and the periodic checkpoint (`checkpoint`) when
/// `checkpoints` is set.
fn outputs(it: &mut Interpreter, cmd: &Command, checkpoints: bool) -> Result<(), AppError> {
    let err = |m: String| AppError::Script(ScriptError::at(cmd, m));
    let sim = &mut it.sim;
    let sys = sim.system.as_ref().expect("system exists during a run");
    if !sim.dumps.is_empty() {
        let natoms = Observables::measure(sys).atoms as usize;
        for d in &mut sim.dumps {
            d.maybe_write(sys, natoms, sim.max_tag).map_err(|e| err(format!("dump {}: {e}", d.id)))?;
        }
    }
    for f in &mut sim.averages {
        f.sample(sys, &sim.rdfs, sim.pair.as_ref(), sim.skin).map_err(err)?;
    }
    if let Some((every, file)) = &sim.checkpoint {
        if checkpoints && sys.step % every == 0 {
            let file = file.replace('*', &sys.step.to_string());
            crate::restart::write(sim, &file).map_err(|e| err(format!("checkpoint: {e}")))?;
        }
    }
    Ok(())
}
