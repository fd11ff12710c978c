//! The script interpreter: reads commands one at a time, handles the loop commands
//! (label, next, jump) and hands every other command to the body of its family.

mod change_box;
mod control;
mod delete_atoms;
mod group;
mod output;
mod particles;
mod run;
mod session;
mod set;
mod setup;
mod styles;
mod velocity;
mod write_coeff;

use crate::base::args::Args;
use crate::base::script::{echo, AppError, Mode};
use crate::model::sim::Sim;
use crate::output::checkpoint::Checkpoint;
use crate::output::console::Output;
use crate::output::thermo::{ThermoConfig, ThermoContext};
use crate::output::Outputs;
use gendpde_engine::{Local, Transport};
use gendpde_integrators::{Physics, System};
use gendpde_io::{Command, Location, ScriptError, ScriptReader, Variables};
use std::path::Path;

pub struct Interpreter {
    pub sim: Sim,
    pub outputs: Outputs,
    pub vars: Variables,
    pub out: Output,
    pub mode: Mode,
    /// Commands are echoed to the screen too (`echo screen|both`, `-echo`); always to the log.
    pub echo_screen: bool,
    /// A `next` exhausted its variables: the next `jump` falls through.
    skip_jump: bool,
    /// Jumps since the last `run` or `next` (see [`MAX_IDLE_JUMPS`]).
    idle_jumps: u64,
    /// Depth of the commands of `if` and `run every` being executed: a `jump` among them
    /// moves the script file they stand in, once they are done (`pending_jump`).
    nested: usize,
    pending_jump: Option<Command>,
}

/// Jumps a loop may make without a `run` or a `next` in between before it is taken for
/// an endless loop (LAMMPS would spin silently).
pub const MAX_IDLE_JUMPS: u64 = 1_000_000;

impl Interpreter {
    /// A single-rank interpreter.
    pub fn new(mode: Mode, out: Output) -> Self {
        Self::with_transport(mode, out, Box::new(Local))
    }

    /// An interpreter whose box is split over the ranks of `transport`.
    pub fn with_transport(mode: Mode, out: Output, transport: Box<dyn Transport>) -> Self {
        Self { sim: Sim::new(transport), outputs: Outputs::default(), vars: Variables::new(), out, mode, echo_screen: false, skip_jump: false, idle_jumps: 0, nested: 0, pending_jump: None }
    }

    /// Executes a script file to its end.
    pub fn execute_file(&mut self, path: &Path) -> Result<(), AppError> {
        self.execute_reader(ScriptReader::open(path)?)
    }

    /// Executes a script held in memory; `name` stands for its file name in errors.
    pub fn execute_str(&mut self, name: &str, text: &str) -> Result<(), AppError> {
        self.execute_reader(ScriptReader::from_string(name, text))
    }

    /// The dynamics of the styles defined so far, set up on the current system, for
    /// programs that step it themselves (tests, benchmarks), as for `run 0` (a ramped
    /// thermostat holds its TSTART).
    pub fn dynamics(&mut self) -> Result<Box<dyn Physics>, AppError> {
        let cmd = Command { name: "run".into(), args: vec![], loc: Location { file: "<api>".into(), line: 0 } };
        let step = self.sim.system.as_ref().map_or(0, |s| s.clock.step);
        run::prepare(&mut self.sim, &self.outputs.rdfs(), &cmd, run::RunPart { nsteps: 0, ramp: [step, step], continues: false, summary: true })
    }

    /// The system built by the script.
    pub fn system(&mut self) -> Option<&mut System> {
        self.sim.system.as_mut()
    }

    fn execute_reader(&mut self, mut reader: ScriptReader) -> Result<(), AppError> {
        loop {
            let next = {
                let (sim, vars, thermo) = (&self.sim, &self.vars, &self.outputs.thermo);
                reader.next_command(vars, &|name| resolve(sim, thermo, vars, name))?
            };
            let Some(cmd) = next else { return Ok(()) };
            if self.echo_screen {
                self.out.line(&echo(&cmd));
            } else {
                self.out.log_line(&echo(&cmd));
            }
            if let Some(e) = self.out.take_error() {
                return Err(ScriptError::at(&cmd, e).into());
            }
            match cmd.name.as_str() {
                // LAMMPS loops: `label L`, `next V ...`, `jump SELF L`; a `next` that
                // exhausts its variables makes the following `jump` fall through
                "label" => {}
                "next" => {
                    if cmd.args.is_empty() {
                        return Err(ScriptError::at(&cmd, "missing argument: expected variable names").into());
                    }
                    let (exhausted, universe) = self.vars.next(&cmd.args).map_err(|mut e| {
                        e.loc = Some(cmd.loc.clone());
                        e
                    })?;
                    self.skip_jump = exhausted;
                    if let Some(n) = universe {
                        self.out.line(&format!("Increment via next: value {n} on partition 0"));
                    }
                    self.idle_jumps = 0;
                }
                "jump" => {
                    if !std::mem::take(&mut self.skip_jump) {
                        self.idle_jumps += 1;
                        if self.idle_jumps > MAX_IDLE_JUMPS {
                            let what = format!("{MAX_IDLE_JUMPS} jumps without a run or a next in between: the loop never ends");
                            return Err(ScriptError::at(&cmd, what).into());
                        }
                        if self.nested > 0 {
                            self.pending_jump = Some(cmd);
                        } else {
                            reader.jump(&cmd)?;
                        }
                    }
                }
                _ => {
                    if cmd.name == "run" {
                        self.idle_jumps = 0;
                    }
                    self.execute(&cmd)?;
                    if self.nested == 0 {
                        if let Some(jump) = self.pending_jump.take() {
                            reader.jump(&jump)?;
                        }
                    }
                }
            }
        }
    }

    /// Runs one command by its family's body.
    fn execute(&mut self, cmd: &Command) -> Result<(), AppError> {
        let a = &mut Args::new(cmd);
        let (sim, outputs) = (&mut self.sim, &mut self.outputs);
        match cmd.name.as_str() {
            "units" => setup::units(sim, &mut outputs.thermo, a)?,
            "dimension" => setup::dimension(a)?,
            "boundary" => setup::boundary(a)?,
            "atom_style" => setup::atom_style(sim, a)?,
            "lattice" => setup::lattice(sim, a)?,
            "region" => setup::region(sim, a)?,
            "processors" => setup::processors(sim, a)?,
            "create_box" => setup::create_box(sim, a)?,
            "change_box" => change_box::change_box(sim, a)?,
            "create_atoms" => setup::create_atoms(sim, a)?,
            "mass" => setup::mass(sim, a)?,
            "set" => set::set(sim, &self.vars, &outputs.thermo, a)?,
            "timestep" => setup::timestep(sim, a)?,
            "neighbor" => setup::neighbor(sim, a)?,
            "neigh_modify" => setup::neigh_modify(sim, a)?,
            "reset_timestep" => setup::reset_timestep(sim, a)?,
            "run_style" => setup::run_style(a)?,
            "atom_modify" => setup::atom_modify(a)?,
            "comm_modify" => setup::comm_modify(a)?,
            "newton" => setup::newton(a)?,
            "group" => group::group(sim, &self.vars, &outputs.thermo, &mut self.out, a)?,
            "delete_atoms" => delete_atoms::delete_atoms(sim, &mut self.out, a)?,
            "velocity" => velocity::velocity(sim, &self.vars, &outputs.thermo, a)?,
            "read_data" => particles::read_data(sim, a)?,
            "write_data" => particles::write_data(sim, a)?,
            "write_restart" => particles::write_restart(sim, a)?,
            "read_restart" => {
                let (system, name, [before_box, after]) = particles::read_restart(sim, a)?;
                self.execute_str(&name, &before_box)?;
                self.sim.system = Some(system);
                self.execute_str(&name, &after)?;
                self.sim.restore_fix_state();
            }
            "pair_style" => styles::pair_style(sim, a)?,
            "pair_coeff" => styles::pair_coeff(sim, a)?,
            "fix" => styles::fix(sim, outputs, &self.vars, a)?,
            "unfix" => styles::unfix(sim, outputs, a)?,
            "fix_modify" => styles::fix_modify(sim, a)?,
            "compute" => styles::compute(sim, a)?,
            "compute_modify" => crate::styles::compute::modify(&mut sim.computes, a)?,
            "thermo" => output::thermo(&mut outputs.thermo, a)?,
            "thermo_style" => output::thermo_style(&mut outputs.thermo, &self.vars, sim.units.default_norm, a)?,
            "thermo_modify" => output::thermo_modify(&mut outputs.thermo, &sim.computes, a)?,
            "dump" => output::dump(&mut outputs.dumps, sim, a)?,
            "dump_modify" => output::dump_modify(&mut outputs.dumps, a)?,
            "undump" => output::undump(&mut outputs.dumps, a)?,
            "write_dump" => output::write_dump(sim, &self.vars, &outputs.thermo, &mut self.out, a)?,
            "checkpoint" => outputs.checkpoint = Checkpoint::parse(a)?,
            "print" => {
                let (sim, thermo, vars) = (&*sim, &outputs.thermo, &self.vars);
                output::print(&mut self.out, a, &|text| gendpde_io::substitute(text, vars, &|name| resolve(sim, thermo, vars, name)))?
            }
            "log" => output::log(&mut self.out, self.mode, a)?,
            "echo" => self.echo_screen = output::echo(a)?,
            "variable" => {
                // a string value is substituted as it is defined, its quotes having kept
                // it from the line's substitution (LAMMPS's variable.cpp)
                let mut cmd = cmd.clone();
                if let [_, style, value] = cmd.args.as_mut_slice() {
                    if style == "string" {
                        let (sim, thermo, vars) = (&*sim, &outputs.thermo, &self.vars);
                        *value = gendpde_io::substitute(value, vars, &|name| resolve(sim, thermo, vars, name)).map_err(|e| a.err(e))?;
                    }
                }
                self.vars.define(&cmd)?
            }
            "run" => self.run(a)?,
            "if" => self.if_then(a)?,
            "quit" => return Err(control::quit(a)?),
            "clear" => self.clear(a)?,
            "shell" => self.shell(a)?,
            "timer" => self.timer(a)?,
            "info" => self.info(a)?,
            "partition" => session::partition(a)?,
            "write_coeff" => write_coeff::write_coeff(sim, a)?,
            other => return Err(a.err(format!("unknown command '{other}' (see docs/commands/ for the commands gendpde knows)")).into()),
        }
        Ok(())
    }
}

/// Values of thermo keywords inside variables and `$(...)`, with the thermo settings.
pub(crate) fn resolve(sim: &Sim, thermo: &ThermoConfig, vars: &Variables, name: &str) -> Option<f64> {
    let sys = sim.system.as_ref()?;
    ThermoContext::new(sim, sys, thermo, vars, 0, 0.0).keyword(name)
}
