//! When a run writes its outputs: each says at which step it is next due, and the run
//! writes the due ones at its setup and after every step, in the order of `Outputs::all`.

use crate::base::args::Args;
use crate::model::sim::Sim;
use crate::output::console::Output;
use crate::output::thermo_settings::ThermoConfig;
use gendpde_integrators::System;
use gendpde_io::{ScriptError, Variables};

/// The steps of one `run`: its setup at `first`, then the steps up to `last`.
#[derive(Clone, Copy, Debug)]
pub struct Span {
    pub first: u64,
    pub last: u64,
}

/// What an output reads when it writes: the model and its system, the variables (thermo
/// `v_NAME`), the thermo keywords of the run and their `norm` (H5MD observables), the
/// screen and log, the run and its CPU time so far.
pub struct Frame<'a> {
    pub sim: &'a Sim,
    pub sys: &'a System,
    pub vars: &'a Variables,
    /// The thermo settings (observables of dumps use its keywords).
    pub thermo: &'a ThermoConfig,
    pub out: &'a mut Output,
    pub run: Span,
    pub cpu: f64,
}

/// An output of runs: thermo, the dumps, fix ave/time, the checkpoint.
pub trait RunOutput {
    /// The step, at or after `step` of `run`, at which it writes next (None: not in this
    /// run). A step before `step` is one it missed; `write` reports it.
    fn next_step(&self, step: u64, run: Span) -> Option<u64>;

    /// Writes at step `frame.sys.clock.step`. Every rank calls it.
    fn write(&mut self, frame: &mut Frame) -> Result<(), String>;
}

/// The sampling of fix ave/time and fix ave/chunk: blocks of Nrepeat samples Nevery steps
/// apart, each ending on a multiple of Nfreq (LAMMPS's nvalid and nextvalid).
pub struct Sampling {
    pub nevery: u64,
    pub nrepeat: u64,
    pub nfreq: u64,
    /// Samples of the current block so far.
    pub samples: u64,
    /// The next step to sample.
    pub next: u64,
}

impl Sampling {
    /// `Nevery Nrepeat Nfreq` of a fix defined at `step`.
    pub fn parse(a: &mut Args, step: u64) -> Result<Self, ScriptError> {
        let nevery = a.u64("Nevery")?;
        let nrepeat = a.u64("Nrepeat")?;
        let nfreq = a.u64("Nfreq")?;
        if nevery == 0 || nrepeat == 0 || nfreq == 0 || nfreq % nevery != 0 || (nrepeat - 1).saturating_mul(nevery) >= nfreq {
            return Err(a.err(format!(
                "Nevery {nevery}, Nrepeat {nrepeat}, Nfreq {nfreq}: all must be positive, Nfreq a multiple of Nevery and (Nrepeat - 1) Nevery < Nfreq"
            )));
        }
        let mut sampling = Self { nevery, nrepeat, nfreq, samples: 0, next: 0 };
        sampling.start_at(step, 0);
        Ok(sampling)
    }

    /// Schedules the first sample after `step` for a first block ending at or after
    /// `start` (LAMMPS's nextvalid with its `start` keyword).
    pub fn start_at(&mut self, step: u64, start: u64) {
        let (nevery, nrepeat, nfreq) = (self.nevery, self.nrepeat, self.nfreq);
        let mut end = (step / nfreq) * nfreq + nfreq;
        while end < start {
            end += nfreq;
        }
        self.next = if end - nfreq == step && nrepeat == 1 { step } else { end - (nrepeat - 1) * nevery };
        if self.next < step {
            self.next += nfreq;
        }
    }

    /// Counts the sample taken at `step` (the due one, else an error naming `fix`) and
    /// schedules the next; true when it completes a block.
    pub fn sample(&mut self, step: u64, fix: &str) -> Result<bool, String> {
        if step > self.next {
            return Err(format!("fix {fix}: step {step} lies past the next sample {} (reset_timestep?)", self.next));
        }
        self.samples += 1;
        if self.samples < self.nrepeat {
            self.next += self.nevery;
            return Ok(false);
        }
        self.samples = 0;
        self.next = step + self.nfreq - (self.nrepeat - 1) * self.nevery;
        Ok(true)
    }
}

/// Runs `write` on rank 0 (the file of an averaging fix) and stops every rank if it failed
/// there; `what` ("fix ID STYLE: writing FILE") heads the message.
pub fn write_on_rank0(sys: &System, what: &str, write: impl FnOnce() -> std::io::Result<()>) -> Result<(), String> {
    let written = if sys.comm.rank() == 0 { write().map_err(|e| format!("{what}: {e}")) } else { Ok(()) };
    match (sys.comm.any(written.is_err()), written) {
        (true, Ok(())) => Err(format!("{what} failed on rank 0")),
        (_, result) => result,
    }
}
