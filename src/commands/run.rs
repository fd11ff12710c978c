//! The `run` command: set up the dynamics, step, write the outputs that are due and
//! print LAMMPS's summary.

use crate::base::args::Args;
use crate::base::memory;
use crate::base::signals;
use crate::base::script::{AppError, Mode};
use crate::base::units::Units;
use crate::model::sim::Sim;
use crate::output::console::Output;
use crate::output::restart;
use crate::output::schedule::{Frame, RunOutput, Span};
use crate::output::thermo::{self, header_line, Observables};
use crate::output::Outputs;
use crate::styles::pair::{build_physics, RunInputs};
use crate::styles::fix::FixStyle;
use gendpde_engine::CellGrid;
use gendpde_integrators::{Physics, RebuildPolicy, Snapshot, System};
use gendpde_io::{Command, ScriptError, Variables};
use indicatif::ProgressBar;
use std::time::Instant;

/// `run N [upto] [start N1] [stop N2] [pre yes|no] [post yes|no] [every M c1 c2 ...]`,
/// read as LAMMPS's run.cpp reads it.
#[derive(Clone, Debug, PartialEq)]
pub struct RunArgs {
    /// Steps of the whole run (`upto`: up to step N).
    pub nsteps: u64,
    /// `start N1`, `stop N2`: the steps that time-dependent settings (thermostat and
    /// barostat targets) ramp between, instead of the run's own first and last.
    ramp: [Option<u64>; 2],
    /// `pre no`: a run that follows another continues its lists and forces.
    pre: bool,
    /// `post no`: the summary prints only its Loop time line.
    post: bool,
    /// `every M c1 c2 ...`: runs of M steps with the commands executed after each.
    pub every: Option<(u64, Vec<String>)>,
}

impl RunArgs {
    /// Reads the arguments of a run that starts at `step`.
    pub fn parse(a: &mut Args, step: u64) -> Result<Self, ScriptError> {
        let n = a.u64("the number of steps")?;
        let mut run = Self { nsteps: n, ramp: [None, None], pre: true, post: true, every: None };
        let mut upto = false;
        while let Some(key) = a.peek() {
            a.word("a run keyword")?;
            match key {
                "upto" => upto = true,
                "start" => run.ramp[0] = Some(a.u64("the start step")?),
                "stop" => run.ramp[1] = Some(a.u64("the stop step")?),
                "pre" => run.pre = a.yes_no("pre")?,
                "post" => run.post = a.yes_no("post")?,
                "every" => {
                    let m = a.u64("the steps between the commands of every")?;
                    if m == 0 {
                        return Err(a.err("run every: the number of steps must be positive"));
                    }
                    let mut commands = Vec::new();
                    while a.peek().is_some() {
                        commands.push(a.word("a command")?.to_string());
                    }
                    if commands.is_empty() {
                        return Err(a.err("missing argument: expected the commands of run every (or NULL)"));
                    }
                    if commands == ["NULL"] {
                        commands.clear();
                    }
                    run.every = Some((m, commands));
                }
                other => return Err(a.err(format!("unknown run keyword '{other}' (expected upto, start, stop, pre, post or every)"))),
            }
        }
        if upto {
            run.nsteps = n.checked_sub(step).ok_or_else(|| a.err(format!("run {n} upto: the current step {step} is already past it")))?;
        }
        if let Some(start) = run.ramp[0].filter(|&s| s > step) {
            return Err(a.err(format!("run start {start} is after the start of the run (step {step})")));
        }
        if let Some(stop) = run.ramp[1].filter(|&s| s < step + run.nsteps) {
            return Err(a.err(format!("run stop {stop} is before the end of the run (step {})", step + run.nsteps)));
        }
        Ok(run)
    }

    /// The part of the run of `nsteps` steps starting at `step`, its ramp span; `first`
    /// and `last` say whether it starts the run (set up unless `pre no`) and ends it (the
    /// full summary unless `post no`).
    pub fn part(&self, step: u64, nsteps: u64, first: bool, last: bool) -> RunPart {
        let ramp = [self.ramp[0].unwrap_or(step), self.ramp[1].unwrap_or(step + nsteps)];
        // LAMMPS sets up every part of `every` but the later ones under `pre no`, and
        // ends its last part with the full summary even under `post no`
        let every = self.every.is_some();
        RunPart { nsteps, ramp, continues: !self.pre && !(first && every), summary: self.post || (last && every) }
    }
}

/// One run of the dynamics: its steps, the span its ramps follow, whether it continues
/// the previous run's lists and forces (`pre no`),
/// and whether its summary is the full one or only the Loop time line.
#[derive(Clone, Copy, Debug)]
pub struct RunPart {
    pub nsteps: u64,
    pub ramp: [u64; 2],
    pub continues: bool,
    pub summary: bool,
}

/// Builds the dynamics of the current styles and sets the system up for it (lists,
/// densities, forces) for a run of `part.nsteps`; errors name `cmd`.
pub fn prepare(sim: &mut Sim, rdfs: &[String], cmd: &Command, part: RunPart) -> Result<Box<dyn Physics>, AppError> {
    let err = |m: String| AppError::Script(ScriptError::at(cmd, m));
    let mut inputs = RunInputs { fixes: &sim.fixes, dt: sim.dt, skin: sim.skin, rebuild: sim.rebuild.clone(), kb: sim.units.kb, mvv2e: sim.units.mvv2e, ntypes: sim.ntypes };
    let mut physics = build_physics(cmd, sim.pair.as_deref(), &inputs)?;
    let sys = sim.system.as_mut().ok_or_else(|| err("run before create_box".into()))?;
    // a rank may own none (all ranks must agree: a count over them)
    if sys.comm.count(sys.store.nlocal) == 0 {
        return Err(err("the box holds no particles (create_atoms)".into()));
    }
    sys.clock.run = part.ramp;
    sys.lists.min_cell = 0.0;
    let skin = list_skin(sys, physics.as_ref(), sim.skin, inputs.has(|f| matches!(f, FixStyle::Shardlow { .. }))).map_err(err)?;
    if skin < sim.skin {
        if sys.comm.rank() == 0 {
            log::warn!(
                "neighbor skin {} does not fit the box (cells of side cutoff + skin, two per box length): lists use skin \
                 {skin} and are rebuilt whenever a particle has moved half of it (the dynamics do not depend on the skin)",
                sim.skin
            );
        }
        // every, delay and check no would let particles outrun the shorter skin
        (inputs.skin, inputs.rebuild) = (skin, RebuildPolicy { every: 1, delay: 0, check: true });
        physics = build_physics(cmd, sim.pair.as_deref(), &inputs)?;
    }
    // the cells must reach the pairs that the computes read by fix ave/time count
    sys.lists.cutoff = physics.cutoff();
    for rdf in sim.rdfs.iter().filter(|r| rdfs.contains(&r.id)) {
        let rc = rdf.cutoff_for(sys.lists.cutoff);
        rdf.check_reach(sys, rc + skin).map_err(err)?;
        sys.lists.min_cell = sys.lists.min_cell.max(rc + skin);
    }
    // the largest type without a mass on any rank (every rank stops alike)
    let unset = (0..sys.store.nlocal).filter(|&i| !sys.store.mass[i].is_finite()).map(|i| sys.store.kind[i] as f64).fold(0.0, f64::max);
    let unset = sys.comm.max(unset);
    if unset > 0.0 {
        return Err(err(format!("the mass of type {unset} is not set")));
    }
    // neighbour and sweep lists, estimated from the mean density before they are built
    let (n, volume) = (sys.store.nlocal as f64, sys.domain.volume() / sys.comm.size() as f64);
    let reach = physics.list_radius();
    let neighbours = n / volume * 4.0 / 3.0 * std::f64::consts::PI * reach.powi(3);
    let bytes = n * neighbours * (memory::NEIGHBOUR_ENTRY_BYTES + 0.5 * memory::SWEEP_PAIR_BYTES);
    memory::check(bytes, &format!("the neighbour lists ({neighbours:.0} neighbours per particle)")).map_err(err)?;
    // a run that continues another (`pre no`, as LAMMPS's, once a run has been made and
    // while no particle has moved half the skin since the lists were built) keeps its
    // cells, lists and forces, as a restart's continuation does
    if part.continues && sim.energy0.is_some() && sys.grid.is_some() && sys.comm.max(sys.displacement_since_build()) <= 0.5 * skin {
        sys.control.restored = true;
        sys.control.restored_grid = sys.grid.as_ref().map(|g| g.count);
    }
    // a continuation keeps the forces of the step its restart was written at: they
    // depend on that step's velocities and noise, which the set-up cannot redo
    let resume = sys.control.restored.then(|| sys.store.save_by_tag(gendpde_engine::stage::RESUME));
    // energies and virials stored without having been computed at their step (a restart
    // written on a signal or a failure after a step without output) give way to the
    // set-up's
    let stale = !sys.control.tallied;
    sys.control.tally = true;
    physics.setup(sys).map_err(|e| err(e.to_string()))?;
    if let Some(saved) = resume.filter(|_| sys.control.restored_grid == sys.grid.as_ref().map(|g| g.count)) {
        let fresh = stale.then(|| (sys.store.virial.clone(), sys.store.epair.clone()));
        let exchanged = sys.store.restore_by_tag(&saved);
        if let Some((virial, epair)) = fresh {
            (sys.store.virial, sys.store.epair) = (virial, epair);
        }
        sys.comm.forward(&mut sys.store, exchanged);
    }
    sys.control.tallied = true;
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

/// The skin the lists use: the script's `skin`, or, when the box is too short for cells of
/// side cutoff + skin (two per box length), the skin of cells of a third of the shortest
/// box length (k = 2, room for 3 ranks per dimension), else of half of it. The choice
/// depends on the box only, so that every rank count lists alike. LAMMPS runs such boxes
/// (its ghost atoms reach any distance); its fix shardlow does not, and with it LAMMPS's
/// message is given. A box shorter than two cutoffs cannot be run.
fn list_skin(sys: &System, physics: &dyn Physics, skin: f64, shardlow: bool) -> Result<f64, String> {
    let reach = physics.list_radius();
    if CellGrid::new(&sys.domain, reach).is_ok() {
        return Ok(skin);
    }
    let len = sys.domain.len();
    if shardlow {
        let procs = sys.comm.grid.dims;
        return Err(format!(
            "Shardlow algorithm requires sub-domain length > 2*(rcut+skin). Either reduce the number of processors \
             requested, or change the cutoff/skin: rcut= {} bbx= {} bby= {} bbz= {}",
            2.0 * reach,
            len[0] / procs[0] as f64,
            len[1] / procs[1] as f64,
            len[2] / procs[2] as f64
        ));
    }
    let cutoff = (reach - skin).max(0.0);
    let shortest = len.iter().copied().fold(f64::INFINITY, f64::min);
    // just below the radius, so that rounding keeps the count of cells
    let fitting = [3.0, 2.0].map(|n| shortest / n * (1.0 - 1e-12) - cutoff);
    fitting.into_iter().find(|&s| s >= 0.0 && CellGrid::new(&sys.domain, cutoff + s).is_ok()).ok_or_else(|| {
        format!(
            "box length {shortest} is shorter than 2 x cutoff = {}: LAMMPS runs such a box, a particle then interacting \
             with several periodic images of another (or twice with one), but gendpde's cell grid holds one image of \
             each pair; enlarge the box to more than {} or shorten the cutoff",
            2.0 * cutoff,
            2.0 * cutoff
        )
    })
}

/// One run of `part.nsteps` steps of `run` command `cmd`: sets up, then advances,
/// writing the outputs that are due at the setup and after every step (a check only
/// sets up).
pub fn run(sim: &mut Sim, outputs: &mut Outputs, out: &mut Output, vars: &Variables, mode: Mode, cmd: &Command, part: RunPart) -> Result<(), AppError> {
    let nsteps = part.nsteps;
    let err = |m: String| AppError::Script(ScriptError::at(cmd, m));
    let physics = prepare(sim, &outputs.rdfs(), cmd, part)?;
    let sys = sim.system.as_mut().expect("prepared system");
    sys.control.interrupt = signals::received();
    sim.energy0.get_or_insert_with(|| Observables::measure(sys).energy());
    let run = Span { first: sys.clock.step, last: sys.clock.step + nsteps };
    if mode == Mode::Check {
        // the set-up's thermo line, evaluated as the run evaluates it, printing nothing
        let frame = Frame { sim, sys: sys_of(sim), vars, thermo: &outputs.thermo, out, run, cpu: 0.0 };
        return thermo::values(&outputs.thermo, &frame).map(|_| ()).map_err(err);
    }
    let sys = sim.system.as_mut().expect("prepared system");
    let comm_before = sys.comm.time().as_secs_f64();
    let traffic_before = sys.comm.traffic();
    let clock = Instant::now();
    let natoms = sys.comm.count(sys.store.nlocal);
    out.line(&format!("Setting up GenDPDE run: {natoms} particles, timestep {} ...", sim.dt));
    // LAMMPS's log readers (lammps-logfile) start a thermo block at this line
    let [min, avg, max] = memory_per_rank(sys).map(|b| gendpde_io::format_g(b / 1048576.0, 4));
    out.line(&format!("Per MPI rank memory allocation (min/avg/max) = {min} | {avg} | {max} Mbytes"));
    out.line(&header_line(&outputs.thermo.keywords));
    let progress = progress_bar(sys.comm.rank() == 0, nsteps);
    write_due(sim, outputs, out, vars, run, clock, &progress).map_err(err)?;
    let mut last_good = Snapshot::default();
    for k in 1..=nsteps {
        if k % 16 == 0 {
            progress.set_position(k);
        }
        // energies and virials only for a step after which something is written, as
        // LAMMPS's eflag/vflag (the same on every rank: a restart written on a signal
        // after another step says its tallies are stale)
        let next = sim.system.as_ref().map_or(0, |s| s.clock.step + 1);
        let wanted = next >= run.last || outputs.all().any(|o| o.next_step(next, run).is_some_and(|at| at <= next));
        let sys = sim.system.as_mut().expect("system exists during a run");
        sys.control.tally = wanted;
        sys.save(&mut last_good);
        if let Err(mut e) = physics.advance(sys) {
            progress.finish_and_clear();
            sys.restore(&last_good);
            let file = state_file(outputs, e.step, "failed");
            e.what = match restart::write(sim, &file) {
                Ok(()) => format!("{}; the last good state (step {}) is in {file}", e.what, e.step),
                Err(w) => format!("{}; writing the last good state to {file} failed: {w}", e.what),
            };
            out.flush();
            return Err(AppError::Step { cmd: cmd.clone(), err: e });
        }
        write_due(sim, outputs, out, vars, run, clock, &progress).map_err(err)?;
        let signal = sys_of(sim).control.interrupted.get();
        if signal != 0 {
            progress.finish_and_clear();
            return Err(interrupted(sim, outputs, signal, cmd));
        }
    }
    progress.finish_and_clear();
    let secs = clock.elapsed().as_secs_f64();
    let sys = sim.system.as_ref().expect("system exists during a run");
    let n = sys.comm.count(sys.store.nlocal);
    out.line(&format!("Loop time of {} on {} procs for {nsteps} steps with {n} atoms", gendpde_io::format_g(secs, 6), sys.comm.size()));
    out.line("");
    if !part.summary {
        out.flush();
        return Ok(());
    }
    if secs > 0.0 && nsteps > 0 {
        out.line(&performance(sim.units, sim.dt, nsteps as f64 / secs, n as f64));
    }
    let comm = sys.comm.time().as_secs_f64() - comm_before;
    if secs > 0.0 {
        out.line(&format!("Comm time (rank 0) = {comm:.6} s ({:.1} % of the loop)", 100.0 * comm / secs));
    }
    let (messages, bytes, rounds) = sys.comm.traffic();
    if sys.comm.size() > 1 && nsteps > 0 {
        let per_step = |now: u64, before: u64| (now - before) as f64 / nsteps as f64;
        out.line(&format!(
            "Comm messages per step (rank 0, point to point) = {:.1}, {:.1} kB per step, in {:.1} rounds",
            per_step(messages, traffic_before.0),
            per_step(bytes, traffic_before.1) / 1e3,
            per_step(rounds, traffic_before.2)
        ));
    }
    out.line(&format!("Neighbor list builds = {}", sys.lists.count));
    if sys.control.substeps > 0 || sys.control.rejected > 0 {
        out.line(&format!(
            "Shardlow pair updates split into half steps (theta -> 0 guard) = {}, left out = {}",
            sys.control.substeps, sys.control.rejected
        ));
    }
    out.flush();
    Ok(())
}

/// LAMMPS's Performance line: simulated time per day (tau/day in lj units, ns/day and
/// hours/ns in real and metal), steps and atom-steps per second.
fn performance(units: Units, dt: f64, steps_per_s: f64, atoms: f64) -> String {
    let day = 86400.0 * steps_per_s * dt / units.femtosecond;
    let simulated = if units.name == "lj" {
        format!("{day:.3} tau/day")
    } else {
        format!("{:.3} ns/day, {:.3} hours/ns", day / 1e6, 24.0 / (day / 1e6))
    };
    let rate = steps_per_s * atoms;
    let (scaled, prefix) = match rate {
        r if r < 1e6 => (r / 1e3, "k"),
        r if r < 1e9 => (r / 1e6, "M"),
        r => (r / 1e9, "G"),
    };
    format!("Performance: {simulated}, {steps_per_s:.3} timesteps/s, {scaled:.3} {prefix}atom-step/s")
}

/// Bytes held per rank (min, mean, max over the ranks): particles with their ghosts,
/// neighbour and sweep lists, the sweep's members (a byte per particle and colour)
/// (collective).
fn memory_per_rank(sys: &gendpde_integrators::System) -> [f64; 3] {
    let local = sys.store.nlocal as f64 * memory::STORE_BYTES_PER_PARTICLE
        + sys.nlist.pairs.len() as f64 * memory::NEIGHBOUR_ENTRY_BYTES
        + sys.sweep.pairs.len() as f64 * memory::SWEEP_PAIR_BYTES
        + sys.sweep.members.iter().map(Vec::len).sum::<usize>() as f64;
    let all = sys.comm.transport().all_gather(&[local as u64]);
    let min = all.iter().copied().min().unwrap_or(0) as f64;
    let max = all.iter().copied().max().unwrap_or(0) as f64;
    [min, all.iter().sum::<u64>() as f64 / all.len().max(1) as f64, max]
}

fn sys_of(sim: &Sim) -> &gendpde_integrators::System {
    sim.system.as_ref().expect("system exists during a run")
}

/// Where a run that cannot go on saves its state: the checkpoint's file of the step when
/// one is configured, else `<why>.restart.h5`.
fn state_file(outputs: &Outputs, step: u64, why: &str) -> String {
    outputs.checkpoint.as_ref().map_or_else(|| format!("{why}.restart.h5"), |c| c.file_at(step))
}

/// Stops a run at a signal all ranks agreed on, after a completed step: saves the state
/// (as a failed step does) and closes every dump.
fn interrupted(sim: &Sim, outputs: &mut Outputs, signal: usize, cmd: &Command) -> AppError {
    let step = sys_of(sim).clock.step;
    let file = state_file(outputs, step, "interrupted");
    let mut what = match restart::write(sim, &file) {
        Ok(()) => format!("the state is in {file} (read_restart {file} to continue)"),
        Err(e) => format!("writing the state to {file} failed: {e}"),
    };
    let closed: Vec<String> = outputs.dumps.iter_mut().map(|d| d.close().map_or_else(|e| e, |()| d.id().to_string())).collect();
    if !closed.is_empty() {
        what += &format!("; dumps closed: {}", closed.join(", "));
    }
    // no rank exits (and has mpirun end the others) before rank 0 has closed its files
    sys_of(sim).comm.max(0.0);
    AppError::Interrupted { cmd: cmd.clone(), signal, step, what }
}

/// Writes the outputs due at the current step, in the order of [`Outputs::all`], with
/// the progress bar hidden; what the output fixes publish is in `sim` before thermo and
/// the dumps read it.
fn write_due(sim: &mut Sim, outputs: &mut Outputs, out: &mut Output, vars: &Variables, run: Span, clock: Instant, progress: &ProgressBar) -> Result<(), String> {
    let step = sys_of(sim).clock.step;
    let due = |o: &dyn RunOutput| o.next_step(step, run).is_some_and(|next| next <= step);
    if !outputs.all().any(|o| due(o)) {
        return Ok(());
    }
    let thermo = outputs.thermo.clone();
    let cpu = clock.elapsed().as_secs_f64();
    for f in outputs.fixes.iter_mut().filter(|f| due(&***f)) {
        let mut frame = Frame { sim, sys: sys_of(sim), vars, thermo: &thermo, out, run, cpu };
        progress.suspend(|| f.write(&mut frame))?;
        if let Some(values) = f.published() {
            sim.fix_values.insert(f.id().to_string(), values.clone());
        }
    }
    let mut frame = Frame { sim, sys: sys_of(sim), vars, thermo: &thermo, out, run, cpu };
    let fixes = outputs.fixes.len();
    for o in outputs.all().skip(fixes).filter(|o| due(&**o)) {
        progress.suspend(|| o.write(&mut frame))?;
    }
    frame.out.take_error().map_or(Ok(()), Err)
}

/// A progress bar with rate and ETA on stderr, shown only when stderr is a terminal.
fn progress_bar(root: bool, nsteps: u64) -> ProgressBar {
    use std::io::IsTerminal;
    if !root || !std::io::stderr().is_terminal() || nsteps < 2 {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(nsteps);
    let style = indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} steps  {per_sec}  ETA {eta}")
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    bar.set_style(style);
    bar
}
