//! What every layer says about a script: whether `run` advances time, the failure that
//! stops the script, and the echo of a command.

use gendpde_integrators::StepError;
use gendpde_io::{Command, ScriptError};
use std::fmt;

/// Whether `run` advances time or only validates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Run,
    Check,
}

/// A failure that stops the script.
#[derive(Debug)]
pub enum AppError {
    Script(ScriptError),
    Step { cmd: Command, err: StepError },
    /// A signal stopped a run (`base::signals`); `what` says what was saved.
    Interrupted { cmd: Command, signal: usize, step: u64, what: String },
    /// `quit`: the script ends here with this exit status (not an error).
    Quit { status: u8 },
}

impl fmt::Display for AppError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Script(e) => e.fmt(f),
            Self::Step { cmd, err } => write!(f, "{}: run stopped: {err}", cmd.loc),
            Self::Interrupted { cmd, signal, step, what } => {
                write!(f, "{}: run stopped by {} after step {step}: {what}", cmd.loc, crate::base::signals::name(*signal))
            }
            Self::Quit { status } => write!(f, "quit with status {status}"),
        }
    }
}

impl From<ScriptError> for AppError {
    fn from(e: ScriptError) -> Self {
        Self::Script(e)
    }
}

/// The command as LAMMPS echoes it to the log.
pub fn echo(cmd: &Command) -> String {
    std::iter::once(cmd.name.as_str()).chain(cmd.args.iter().map(String::as_str)).collect::<Vec<_>>().join(" ")
}
