//! Dumps: `dump ID GROUP STYLE N FILE ...` every N steps and `write_dump GROUP STYLE FILE
//! ...` once: LAMMPS's text formats ([`text`]), H5MD ([`h5md`]), and the binary
//! trajectories of VMD and GROMACS ([`dcd`], [`xtc`]), PNG pictures ([`image`]).
//!
//! The per-particle keywords are one table (`base::particle_keywords`); what every dump
//! shares is in [`head`].
//!
//! Rank 0 writes the rows of the dump's group in ID order, collected in blocks of 2^20
//! IDs (`gather`), so it never holds more than one block (dcd and xtc hold the frame's
//! positions, as LAMMPS). Unlike LAMMPS, text dumps are always sorted by ID.

pub mod dcd;
pub mod h5md;
pub mod head;
pub mod image;
pub mod text;
mod xdr;
pub mod xtc;

pub use self::head::Dump;
use self::head::{Every, Head};
use crate::base::args::Args;
use crate::base::groups;
use crate::model::sim::Sim;
use crate::output::schedule::Frame;
use gendpde_io::ScriptError;

/// The dump styles, for messages.
const STYLES: &str = "custom, atom, xyz, h5md, dcd, xtc, image";

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
    let head = Head { id: id.to_string(), group, every: Every::new(every), file, pad: 0, once, region: None, out: None };
    Ok(match style.as_str() {
        "custom" | "atom" | "xyz" => Box::new(text::TextDump::parse(head, &style, sim, a)?),
        "h5md" => Box::new(h5md::H5mdDump::parse(head, a)?),
        "dcd" => Box::new(dcd::DcdDump::parse(head, a)?),
        "image" => Box::new(image::ImageDump::parse(head, a)?),
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
        let file = dump.head().file.clone();
        dump.head_mut().file = format!("{file}.tmp");
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
        self.dump.head_mut().file = std::mem::take(&mut self.file);
        let file = self.dump.head().path(step);
        match frame.sys.comm.rank() {
            0 => std::fs::rename(&tmp, &file).map_err(|e| format!("renaming '{tmp}' to '{file}': {e}")),
            _ => Ok(()),
        }
    }
}


