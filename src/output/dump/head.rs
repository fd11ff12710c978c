//! What every dump shares: the [`Dump`] trait, its [`Head`] (ID, group, schedule, file)
//! with the group's count, rows and positions, and the `dump_modify` keywords of all
//! styles.

use crate::base::args::Args;
use crate::base::gather;
use crate::model::sim::Sim;
use crate::output::schedule::{Frame, RunOutput, Span};
use gendpde_engine::Vec3;
use gendpde_integrators::System;
use gendpde_io::ScriptError;
use std::fs::File;
use std::io::{BufWriter, Write};

/// When a periodic dump writes: every N steps, at the setup of a run when the step is
/// a multiple of N (`first yes`: at the first setup after the dump command whatever the
/// step, as LAMMPS), once per step, none before the `delay` step.
#[derive(Clone, Debug)]
pub struct Every {
    pub every: u64,
    pub first: bool,
    /// `dump_modify delay D`: no frame before step D.
    pub delay: u64,
    last_step: Option<u64>,
}

impl Every {
    pub fn new(every: u64) -> Self {
        Self { every, first: false, delay: 0, last_step: None }
    }

    pub fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        let first = self.first && self.last_step.is_none() && step == run.first;
        let due = if first { step } else { step.next_multiple_of(self.every) };
        let due = if self.last_step == Some(due) { (due + 1).next_multiple_of(self.every) } else { due };
        Some(if due < self.delay { self.delay.next_multiple_of(self.every) } else { due })
    }

    /// Notes a frame written at `step`.
    pub fn wrote(&mut self, step: u64) {
        self.last_step = Some(step);
    }

    /// `dump_modify every N`, `first yes|no` and `delay D` (read already); false for
    /// other keys.
    pub fn modify(&mut self, key: &str, a: &mut Args) -> Result<bool, ScriptError> {
        match key {
            "every" => {
                self.every = a.u64("the output interval N")?;
                if self.every == 0 {
                    return Err(a.err("every: the output interval must be positive"));
                }
            }
            "first" => self.first = a.yes_no("first")?,
            "delay" => self.delay = a.u64("the first step a frame may be written at")?,
            _ => return Ok(false),
        }
        Ok(true)
    }
}

/// A dump: text, H5MD, dcd or xtc.
pub trait Dump: RunOutput {
    /// One `dump_modify` keyword (read already) and its values.
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<(), ScriptError>;
    /// Flushes and closes its file (it reopens, appending, when written again).
    fn close(&mut self) -> Result<(), String> {
        self.head_mut().close()
    }
    /// Its ID, group, schedule and file.
    fn head(&self) -> &Head;
    fn head_mut(&mut self) -> &mut Head;
}

impl dyn Dump {
    pub fn id(&self) -> &str {
        &self.head().id
    }
}

/// What every dump has: its ID, the bit mask of its group, its schedule and file.
pub struct Head {
    pub id: String,
    pub group: u32,
    pub every: Every,
    pub file: String,
    /// `dump_modify pad N`: the digits of the step in the file name's `*` (0: as many as
    /// it has).
    pub pad: usize,
    /// Written once by `write_dump` (LAMMPS's dump `WRITE_DUMP`), not every N steps.
    pub once: bool,
    /// `dump_modify region ID` (custom, image): only the particles in the region.
    pub region: Option<String>,
    /// The open file of the text, dcd and xtc styles (rank 0).
    pub out: Option<BufWriter<File>>,
}

impl Head {
    /// Which owned particles a frame writes: those of the group (and of the `dump_modify
    /// region`, if any, at their current positions).
    fn selected<'a>(&'a self, sim: &'a Sim, sys: &'a System) -> Result<impl Fn(usize) -> bool + 'a, String> {
        let region = match &self.region {
            Some(id) => Some(sim.regions.get(id).ok_or_else(|| format!("Dump_modify region ID {id} does not exist"))?),
            None => None,
        };
        Ok(move |i: usize| sys.store.in_group(i, self.group) && region.is_none_or(|r| r.contains(sys.store.r[i])))
    }

    /// The number of particles a frame writes, on all ranks (every rank calls).
    pub fn count(&self, sim: &Sim, sys: &System) -> Result<u64, String> {
        let selected = self.selected(sim, sys)?;
        Ok(sys.comm.count((0..sys.store.nlocal).filter(|&i| selected(i)).count()))
    }

    /// The file of a frame at `step`: the step in place of a `*`.
    pub fn path(&self, step: u64) -> String {
        self.file.replace('*', &format!("{step:0pad$}", pad = self.pad))
    }

    /// `dump_modify region ID|none` (read already) of the styles that take it (custom,
    /// image).
    pub fn set_region(&mut self, a: &mut Args) -> Result<(), ScriptError> {
        self.region = Some(a.word("a region ID or none")?).filter(|&r| r != "none").map(String::from);
        Ok(())
    }

    /// `dump_modify every N`, `first yes|no`, `delay D` and `pad N` (read already); false
    /// for other keys.
    pub fn modify(&mut self, key: &str, a: &mut Args) -> Result<bool, ScriptError> {
        match key {
            "pad" => self.pad = a.u64("the number of digits of the step")? as usize,
            _ => return self.every.modify(key, a),
        }
        Ok(true)
    }

    /// Whether the style's words end here: at the end of the command, or of the words
    /// before `modify` of a `write_dump`.
    pub fn at_end(&self, a: &Args) -> bool {
        a.peek().is_none() || (self.once && a.peek() == Some("modify"))
    }

    /// Fails unless the style's words end here ([`Head::at_end`]).
    pub fn done(&self, a: &Args) -> Result<(), ScriptError> {
        if self.at_end(a) { Ok(()) } else { a.done() }
    }

    /// Flushes and closes the dump's file, if open.
    pub fn close(&mut self) -> Result<(), String> {
        match self.out.take() {
            Some(mut o) => o.flush().map_err(|e| format!("dump {}: closing '{}': {e}", self.id, self.file)),
            None => Ok(()),
        }
    }

    /// The positions of the group's particles in ID order on rank 0 (unwrapped: through
    /// their images; empty on other ranks, every rank calls).
    pub fn positions(&self, f: &Frame, unwrap: bool) -> Result<Vec<Vec3>, String> {
        let sys = f.sys;
        let row = |i: usize, b: &mut Vec<f64>| {
            let r = if unwrap { sys.domain.unwrap(sys.store.r[i], sys.store.image[i]) } else { sys.store.r[i] };
            b.extend([sys.store.tag[i] as f64, r[0], r[1], r[2]]);
        };
        let mut out = Vec::new();
        self.rows(f.sim, sys, 4, row, &mut |rows: &[f64]| -> Result<(), String> {
            out.extend(rows.chunks_exact(4).map(|r| [r[1], r[2], r[3]]));
            Ok(())
        })?;
        Ok(out)
    }

    /// Calls `emit` on rank 0 with the rows of the group's particles in ID order, as
    /// `gather::sorted_rows` (every rank calls).
    pub fn rows(&self, sim: &Sim, sys: &System, width: usize, row: impl Fn(usize, &mut Vec<f64>), emit: &mut dyn FnMut(&[f64]) -> Result<(), String>) -> Result<(), String> {
        let selected = self.selected(sim, sys)?;
        gather::sorted_rows(sys, sim.max_tag, width, |i, b| if selected(i) { row(i, b) }, emit)
    }
}

/// LAMMPS's `dump_modify` keywords.
pub const LAMMPS_MODIFY_KEYS: &[&str] = &[
    "append", "author", "buffer", "colname", "delay", "element", "email", "every", "every/time", "fileper", "first", "flush", "format", "header",
    "image", "maxfiles", "nfile", "pad", "pbc", "precision", "refresh", "region", "scale", "sfactor", "skip", "sort", "tfactor",
    "thresh", "time", "triclinic/general", "units", "unwrap",
];

/// The error for `dump_modify` keyword `key` that dump `head` does not take: one of
/// LAMMPS's it does not implement, or an unknown one; `known` lists those it takes
/// besides every, first, delay and pad.
pub fn unknown_key(head: &Head, key: &str, known: &str, a: &Args) -> ScriptError {
    let what = if LAMMPS_MODIFY_KEYS.contains(&key) { "is not supported for this dump style" } else { "is unknown" };
    a.err(format!("dump {}: dump_modify keyword '{key}' {what}; supported: every, first, delay, pad, {known}", head.id))
}

