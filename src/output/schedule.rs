//! When a run writes its outputs: each says at which step it is next due, and the run
//! writes the due ones at its setup and after every step, in the order of `Outputs::all`.

use crate::model::sim::Sim;
use crate::output::console::Output;
use crate::output::thermo_settings::ThermoConfig;
use gendpde_integrators::System;
use gendpde_io::Variables;

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

    /// Writes at step `frame.sys.step`. Every rank calls it.
    fn write(&mut self, frame: &mut Frame) -> Result<(), String>;
}
