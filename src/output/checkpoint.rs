//! `checkpoint N FILE`: a restart file every N steps of a run (not at its setup); a `*`
//! in FILE becomes the step.

use crate::base::args::Args;
use crate::output::restart;
use crate::output::schedule::{Frame, RunOutput, Span};
use gendpde_io::ScriptError;

pub struct Checkpoint {
    every: u64,
    file: String,
}

impl Checkpoint {
    /// The words after `checkpoint`; None for N = 0 (off).
    pub fn parse(a: &mut Args) -> Result<Option<Self>, ScriptError> {
        let every = a.u64("the checkpoint interval N (0: off)")?;
        let file = a.word("a restart file")?.to_string();
        a.done()?;
        Ok((every > 0).then_some(Self { every, file }))
    }

    /// The file written at `step`.
    pub fn file_at(&self, step: u64) -> String {
        self.file.replace('*', &step.to_string())
    }
}

impl RunOutput for Checkpoint {
    fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        let next = step.next_multiple_of(self.every);
        Some(if next == run.first { next + self.every } else { next })
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        restart::write(f.sim, &self.file_at(f.sys.clock.step)).map_err(|e| format!("checkpoint: {e}"))
    }
}
