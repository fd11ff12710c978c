//! What the script reader produces: a command with its location, and the error a
//! script can stop with.

use std::fmt;
use std::path::PathBuf;

/// A position in an input script.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The script file, as named when it was opened.
    pub file: PathBuf,
    /// 1-based line on which the command starts.
    pub line: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "{}:{}", self.file.display(), self.line)
    }
}

/// One command: its name, its argument words and where it starts.
#[derive(Clone, Debug)]
pub struct Command {
    /// The first word, e.g. `pair_coeff`.
    pub name: String,
    /// The remaining words, unquoted and with variables substituted.
    pub args: Vec<String>,
    /// Where the command starts.
    pub loc: Location,
}

/// An error in an input script, displayed as `file:line: command: message`
/// with absent parts left out.
#[derive(Clone, Debug)]
pub struct ScriptError {
    /// Where the error occurred, if known.
    pub loc: Option<Location>,
    /// The command being processed, if any.
    pub command: Option<String>,
    /// What went wrong.
    pub message: String,
}

impl ScriptError {
    /// An error in command `cmd`.
    pub fn at(cmd: &Command, msg: impl Into<String>) -> Self {
        ScriptError {
            loc: Some(cmd.loc.clone()),
            command: Some(cmd.name.clone()),
            message: msg.into(),
        }
    }

    /// An error tied to no particular command.
    pub fn new(msg: impl Into<String>) -> Self {
        ScriptError {
            loc: None,
            command: None,
            message: msg.into(),
        }
    }

    /// An error at `loc` before a command could be formed.
    pub(crate) fn located(loc: Location, msg: impl Into<String>) -> Self {
        ScriptError {
            loc: Some(loc),
            command: None,
            message: msg.into(),
        }
    }
}

impl fmt::Display for ScriptError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        if let Some(loc) = &self.loc {
            write!(f, "{loc}: ")?;
        }
        if let Some(command) = &self.command {
            write!(f, "{command}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for ScriptError {}
