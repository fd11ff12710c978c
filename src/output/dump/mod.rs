//! Dumps: `dump ID GROUP STYLE N FILE ...` every N steps and `write_dump GROUP STYLE FILE
//! ...` once: LAMMPS's text formats ([`text`]), H5MD ([`h5md`]), and the binary
//! trajectories of VMD and GROMACS ([`dcd`], [`xtc`]).
//!
//! The per-particle keywords (LAMMPS's and gendpde's) are one table, [`KEYWORDS`]: a
//! keyword that is a field of the particle table reads it (`engine::FIELDS`), the others
//! are derived (v = p/m, unwrapped and scaled positions, uMech = u - uCond). H5MD dumps
//! select their elements from the same table.
//!
//! Rank 0 writes the rows of the dump's group in ID order, collected in blocks of 2^20
//! IDs (`gather`), so it never holds more than one block (dcd and xtc hold the frame's
//! positions, as LAMMPS). Unlike LAMMPS, text dumps are always sorted by ID.

pub mod dcd;
pub mod h5md;
pub mod text;
mod xdr;
pub mod xtc;

use crate::base::args::Args;
use crate::base::{gather, groups};
use self::h5md::H5mdDump;
use crate::model::sim::Sim;
use crate::output::schedule::{Frame, RunOutput, Span};
use gendpde_engine::{FieldReader, Particles, Vec3};
use gendpde_integrators::System;
use gendpde_io::ScriptError;
use std::fs::File;
use std::io::{BufWriter, Write};

/// Where a keyword's value comes from.
#[derive(Clone, Copy)]
enum Source {
    /// Value k of a field of the particle table.
    Field(&'static str, usize),
    /// Computed from the system; reads the named fields.
    Derived(fn(&System, usize) -> f64, &'static [&'static str]),
}

/// A per-particle dump keyword.
#[derive(Clone, Copy)]
pub struct Keyword {
    pub name: &'static str,
    source: Source,
}

const fn field(name: &'static str, field: &'static str, k: usize) -> Keyword {
    Keyword { name, source: Source::Field(field, k) }
}

const fn derived(name: &'static str, f: fn(&System, usize) -> f64, reads: &'static [&'static str]) -> Keyword {
    Keyword { name, source: Source::Derived(f, reads) }
}

fn velocity(s: &System, i: usize, k: usize) -> f64 {
    s.store.p[i][k] / s.store.mass[i]
}

fn unwrapped(s: &System, i: usize, k: usize) -> f64 {
    s.domain.unwrap(s.store.r[i], s.store.image[i])[k]
}

fn scaled(s: &System, i: usize, k: usize) -> f64 {
    (s.store.r[i][k] - s.domain.lo[k]) / s.domain.len()[k]
}

/// LAMMPS's dump keywords and gendpde's (p, u, theta, n, eDPD's T, C_V and Q, SPH's drho and
/// the Voronoi cell volume).
pub const KEYWORDS: &[Keyword] = &[
    field("id", "id", 0),
    field("type", "type", 0),
    field("mass", "mass", 0),
    field("x", "x", 0),
    field("y", "x", 1),
    field("z", "x", 2),
    derived("xs", |s, i| scaled(s, i, 0), &[]),
    derived("ys", |s, i| scaled(s, i, 1), &[]),
    derived("zs", |s, i| scaled(s, i, 2), &[]),
    derived("xu", |s, i| unwrapped(s, i, 0), &[]),
    derived("yu", |s, i| unwrapped(s, i, 1), &[]),
    derived("zu", |s, i| unwrapped(s, i, 2), &[]),
    field("ix", "image", 0),
    field("iy", "image", 1),
    field("iz", "image", 2),
    derived("vx", |s, i| velocity(s, i, 0), &[]),
    derived("vy", |s, i| velocity(s, i, 1), &[]),
    derived("vz", |s, i| velocity(s, i, 2), &[]),
    field("px", "p", 0),
    field("py", "p", 1),
    field("pz", "p", 2),
    field("fx", "f", 0),
    field("fy", "f", 1),
    field("fz", "f", 2),
    field("u", "u", 0),
    field("theta", "theta", 0),
    field("dpdTheta", "theta", 0),
    field("uCond", "uCond", 0),
    derived("uMech", |s, i| s.store.u[i] - s.store.u_cond[i], &["uCond"]),
    field("n", "n", 0),
    field("rho", "rho", 0),
    field("edpd_temp", "edpd_temp", 0),
    field("edpd_cv", "edpd_cv", 0),
    field("edpd_flux", "edpd_flux", 0),
    field("drho", "drho", 0),
    field("vol", "vol", 0),
];

/// The keyword names, for error messages.
pub fn keyword_names() -> String {
    KEYWORDS.iter().map(|k| k.name).collect::<Vec<_>>().join(" ")
}

impl Keyword {
    pub fn find(name: &str) -> Option<Keyword> {
        KEYWORDS.iter().find(|k| k.name == name).copied()
    }

    /// Whether its values are integers (printed with `%d`).
    pub fn integer(&self) -> bool {
        match self.source {
            Source::Field(f, _) => gendpde_engine::FIELDS.iter().any(|i| i.name == f && i.integer),
            Source::Derived(..) => false,
        }
    }

    /// Its value reader on `store`, or why the scene has none.
    pub fn reader(&self, store: &Particles) -> Result<Reader, String> {
        let missing = |f: &str| format!("keyword {}: this scene has no per-particle '{f}' (its styles do not compute it)", self.name);
        match self.source {
            Source::Field(f, k) => store.reader(f).map(|r| Reader::Field(r, k)).ok_or_else(|| missing(f)),
            Source::Derived(g, reads) => match reads.iter().find(|f| store.reader(f).is_none()) {
                Some(f) => Err(missing(f)),
                None => Ok(Reader::Derived(g)),
            },
        }
    }
}

/// Reads one keyword's value of owned particle i.
#[derive(Clone, Copy)]
pub enum Reader {
    Field(FieldReader, usize),
    Derived(fn(&System, usize) -> f64),
}

impl Reader {
    pub fn get(&self, sys: &System, i: usize) -> f64 {
        match *self {
            Reader::Field(f, k) => f(&sys.store, i, k),
            Reader::Derived(g) => g(sys, i),
        }
    }
}

/// The readers of `keywords` on the system's store.
pub fn readers(keywords: &[Keyword], sys: &System) -> Result<Vec<Reader>, String> {
    keywords.iter().map(|k| k.reader(&sys.store)).collect()
}

/// When a periodic dump writes: every N steps, at the setup of a run when the step is
/// a multiple of N (`first yes`: at the first setup after the dump command whatever the
/// step, as LAMMPS), once per step.
#[derive(Clone, Debug)]
pub struct Every {
    pub every: u64,
    pub first: bool,
    last_step: Option<u64>,
}

impl Every {
    pub fn new(every: u64) -> Self {
        Self { every, first: false, last_step: None }
    }

    pub fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        let first = self.first && self.last_step.is_none() && step == run.first;
        let due = if first { step } else { step.next_multiple_of(self.every) };
        Some(if self.last_step == Some(due) { (due + 1).next_multiple_of(self.every) } else { due })
    }

    /// Notes a frame written at `step`.
    pub fn wrote(&mut self, step: u64) {
        self.last_step = Some(step);
    }

    /// `dump_modify every N` and `first yes|no` (read already); false for other keys.
    pub fn modify(&mut self, key: &str, a: &mut Args) -> Result<bool, ScriptError> {
        match key {
            "every" => {
                self.every = a.u64("the output interval N")?;
                if self.every == 0 {
                    return Err(a.err("every: the output interval must be positive"));
                }
            }
            "first" => self.first = a.yes_no("first")?,
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
    fn close(&mut self) -> Result<(), String>;
    /// Its ID, group, schedule and file.
    fn head(&self) -> &Head;
    fn head_mut(&mut self) -> &mut Head;
}

impl dyn Dump {
    pub fn id(&self) -> &str {
        &self.head().id
    }

    fn file(&self) -> &str {
        &self.head().file
    }

    fn set_file(&mut self, file: String) {
        self.head_mut().file = file;
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
}

impl Head {
    /// The number of the group's particles on all ranks (every rank calls).
    pub fn count(&self, sys: &System) -> u64 {
        let s = &sys.store;
        sys.comm.count((0..s.nlocal).filter(|&i| s.in_group(i, self.group)).count())
    }

    /// The file of a frame at `step`: the step in place of a `*`.
    pub fn path(&self, step: u64) -> String {
        self.file.replace('*', &format!("{step:0pad$}", pad = self.pad))
    }

    /// `dump_modify every N`, `first yes|no` and `pad N` (read already); false for other
    /// keys.
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

    /// Flushes and closes the dump's file `out`, if open.
    pub fn close(&self, out: &mut Option<BufWriter<File>>) -> Result<(), String> {
        match out.take() {
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
        self.rows(sys, f.sim.max_tag, 4, row, &mut |rows: &[f64]| -> Result<(), String> {
            out.extend(rows.chunks_exact(4).map(|r| [r[1], r[2], r[3]]));
            Ok(())
        })?;
        Ok(out)
    }

    /// Calls `emit` on rank 0 with the rows of the group's particles in ID order, as
    /// `gather::sorted_rows` (every rank calls).
    pub fn rows<E>(&self, sys: &System, max_tag: u64, width: usize, row: impl Fn(usize, &mut Vec<f64>), emit: &mut dyn FnMut(&[f64]) -> Result<(), E>) -> Result<(), E> {
        let group = self.group;
        gather::sorted_rows(sys, max_tag, width, |i, b| if sys.store.in_group(i, group) { row(i, b) }, emit)
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
/// besides every and first.
pub fn unknown_key(head: &Head, key: &str, known: &str, a: &Args) -> ScriptError {
    let what = if LAMMPS_MODIFY_KEYS.contains(&key) { "is not supported for this dump style" } else { "is unknown" };
    a.err(format!("dump {}: dump_modify keyword '{key}' {what}; supported: every, first, {known}", head.id))
}

/// The dump styles, for messages.
const STYLES: &str = "custom, atom, xyz, h5md, dcd, xtc";

/// The words after `dump ID` (`GROUP STYLE N FILE ...`) or, for `write_dump` (`once`),
/// after the command (`GROUP STYLE FILE ...`).
pub fn parse(id: &str, sim: &Sim, a: &mut Args, once: bool) -> Result<Box<dyn Dump>, ScriptError> {
    let group = groups::mask(&sim.groups, a.word("a group ID")?, a)?;
    let style = a.word(&format!("a dump style ({STYLES})"))?.to_string();
    let every = if once { 1 } else { a.u64("the output interval N")? };
    if every == 0 {
        return Err(a.err("the output interval must be positive"));
    }
    let file = a.word("a file name")?.to_string();
    if file.contains('%') || file.ends_with(".gz") || file.ends_with(".bin") {
        return Err(a.err(format!("file '{file}': per-rank (%), compressed and binary dumps are not supported")));
    }
    if matches!(style.as_str(), "dcd" | "xtc") && file.contains('*') {
        return Err(a.err(format!("Invalid dump {style} filename '{file}': one file holds every frame")));
    }
    let head = Head { id: id.to_string(), group, every: Every::new(every), file, pad: 0, once };
    Ok(match style.as_str() {
        "custom" | "atom" | "xyz" => Box::new(text::TextDump::parse(head, &style, a)?),
        "h5md" => Box::new(H5mdDump::parse(head, a)?),
        "dcd" => Box::new(dcd::DcdDump::parse(head, a)?),
        "xtc" => {
            let root = sim.system.as_ref().is_none_or(|s| s.comm.rank() == 0);
            Box::new(xtc::XtcDump::parse(head, &sim.units, root, a)?)
        }
        _ => return Err(a.err(format!("unknown dump style '{style}'; known: {STYLES}"))),
    })
}

/// A `write_dump` snapshot: a dump of any style writing one frame to a temporary file,
/// renamed to the file once complete (never a partial file).
pub struct WriteDump {
    dump: Box<dyn Dump>,
    file: String,
}

impl WriteDump {
    /// The words after `write_dump`: `GROUP STYLE FILE ARGS... [modify KEY VALUES...]`.
    pub fn parse(sim: &Sim, a: &mut Args) -> Result<Self, ScriptError> {
        let mut dump = parse("WRITE_DUMP", sim, a, true)?;
        let file = dump.file().to_string();
        dump.set_file(format!("{file}.tmp"));
        if a.peek() == Some("modify") {
            a.word("modify")?;
            while a.remaining() > 0 {
                let key = a.word("a dump_modify keyword")?;
                dump.modify(key, a)?;
            }
        }
        Ok(Self { dump, file })
    }

    /// Writes the snapshot (every rank calls).
    pub fn write(mut self, frame: &mut Frame) -> Result<(), String> {
        self.dump.write(frame)?;
        self.dump.close()?;
        let step = frame.sys.clock.step;
        let tmp = self.dump.head().path(step);
        self.dump.set_file(std::mem::take(&mut self.file));
        let file = self.dump.head().path(step);
        match frame.sys.comm.rank() {
            0 => std::fs::rename(&tmp, &file).map_err(|e| format!("renaming '{tmp}' to '{file}': {e}")),
            _ => Ok(()),
        }
    }
}


#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn field_keywords_name_fields_of_the_particle_table() {
        let width = |f: &str| gendpde_engine::FIELDS.iter().find(|x| x.name == f).map(|x| x.width);
        for k in KEYWORDS {
            match k.source {
                Source::Field(f, i) => assert!(width(f).is_some_and(|w| i < w), "{}: value {i} of field '{f}'", k.name),
                Source::Derived(_, reads) => assert!(reads.iter().all(|f| width(f).is_some()), "{}: reads {reads:?}", k.name),
            }
        }
    }
}
