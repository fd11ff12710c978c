//! The commands that run other commands: `run` (with `every`), `if`, and `quit`. The
//! commands they hold are executed as if they were the next lines of the script, their
//! quoted text substituted when they execute (LAMMPS's Input::one). And `clear`, which
//! starts the script's model over.

use super::{resolve, run, Interpreter};
use crate::base::args::Args;
use crate::base::script::{AppError, Mode};
use crate::output::Outputs;
use gendpde_io::{Command, ScriptError};

impl Interpreter {
    /// `run`: one run, or with `every M` runs of M steps each followed by the commands.
    pub(super) fn run(&mut self, a: &mut Args) -> Result<(), AppError> {
        let cmd = a.command();
        let step = self.sim.system.as_ref().map_or(0, |s| s.clock.step);
        let args = run::RunArgs::parse(a, step)?;
        let Some((every, commands)) = &args.every else {
            return self.run_part(cmd, args.part(step, args.nsteps, true, true));
        };
        let mut left = args.nsteps;
        loop {
            let step = self.sim.system.as_ref().map_or(0, |s| s.clock.step);
            let n = left.min(*every);
            let part = args.part(step, n, left == args.nsteps, n == left);
            self.run_part(cmd, part)?;
            self.nested(cmd, "run every", commands)?;
            left -= n;
            // a check sets up and runs the commands once
            if left == 0 || self.mode == Mode::Check {
                return Ok(());
            }
        }
    }

    /// One run, marked as running for ramp() and its kin while it sets up and steps.
    fn run_part(&mut self, cmd: &Command, part: run::RunPart) -> Result<(), AppError> {
        self.outputs.thermo.default_columns(self.sim.pe_is_pair());
        self.sim.running = true;
        let done = run::run(&mut self.sim, &mut self.outputs, &mut self.out, &self.vars, self.mode, cmd, part);
        self.sim.running = false;
        done
    }

    /// `if BOOLEAN then t1 t2 ... [elif BOOLEAN f1 ...]... [else e1 ...]`: the commands
    /// of the first true condition (LAMMPS's Input::ifthenelse; the conditions are
    /// substituted when they are evaluated).
    pub(super) fn if_then(&mut self, a: &mut Args) -> Result<(), AppError> {
        let cmd = a.command();
        let mut branches: Vec<(Option<&str>, Vec<String>)> = Vec::new();
        let condition = a.word("a Boolean expression")?;
        if a.word("then")? != "then" {
            return Err(a.err("expected 'then' after the Boolean expression").into());
        }
        branches.push((Some(condition), Vec::new()));
        let mut seen_else = false;
        while let Some(w) = a.peek() {
            a.word("a command")?;
            match w {
                "elif" | "else" if seen_else => return Err(a.err(format!("{w} after else")).into()),
                "elif" => branches.push((Some(a.word("a Boolean expression after elif")?), Vec::new())),
                "else" => {
                    seen_else = true;
                    branches.push((None, Vec::new()));
                }
                _ => branches.last_mut().into_iter().for_each(|b| b.1.push(w.to_string())),
            }
        }
        if branches.iter().any(|b| b.1.is_empty() && b.0.is_some()) {
            return Err(a.err("then and elif need at least one command each").into());
        }
        for (condition, commands) in &branches {
            let truth = match condition {
                None => true,
                Some(text) => {
                    let (sim, thermo, vars) = (&self.sim, &self.outputs.thermo, &self.vars);
                    let text = gendpde_io::substitute(text, vars, &|name| resolve(sim, thermo, vars, name)).map_err(|e| a.err(e))?;
                    gendpde_io::evaluate_boolean(&text).map_err(|e| a.err(e))?
                }
            };
            if truth {
                return self.nested(cmd, "if", commands);
            }
        }
        Ok(())
    }

    /// Executes `commands` of `cmd` (named `what` in errors); a `jump` among them takes
    /// effect in the script file once `cmd` is done.
    fn nested(&mut self, cmd: &Command, what: &str, commands: &[String]) -> Result<(), AppError> {
        let name = format!("{}:{} ({what})", cmd.loc.file.display(), cmd.loc.line);
        self.nested += 1;
        let result = commands.iter().try_for_each(|c| self.execute_str(&name, c));
        self.nested -= 1;
        result
    }
}

impl Interpreter {
    /// `clear`: closes the dumps and deletes the box, the particles, the styles and every
    /// setting, back to the defaults; the variables, the log, echo and the loop state stay
    /// (LAMMPS's clear).
    pub(super) fn clear(&mut self, a: &mut Args) -> Result<(), ScriptError> {
        a.done()?;
        for mut dump in self.outputs.dumps.drain(..) {
            dump.close().map_err(|e| a.err(e))?;
        }
        self.outputs = Outputs::default();
        self.sim.clear().map_err(|e| a.err(e))
    }
}

/// `quit [status]`: ends the script with the exit status (default 0), as a finished one.
pub(super) fn quit(a: &mut Args) -> Result<AppError, AppError> {
    let status = if a.remaining() > 0 { a.u64("the exit status")? } else { 0 };
    a.done()?;
    let status = u8::try_from(status).map_err(|_| a.err(format!("the exit status {status} is not in 0..255")))?;
    Ok(AppError::Quit { status })
}
