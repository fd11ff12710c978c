//! `dump ID GROUP h5md N FILE field... [append yes]`: H5MD snapshots every N steps of
//! the group's particles, written by rank 0 from particles gathered in tag order
//! (`gather`); the values of each element are those of the dump keywords
//! (`dump::KEYWORDS`).

use crate::base::args::Args;
use crate::output::dump::head::{unknown_key, Dump, Head};
use crate::base::particle_keywords::{readers, Keyword};
use crate::output::schedule::{Frame, RunOutput, Span};
use crate::output::thermo;
use gendpde_io::{H5mdField, H5mdMeta, H5mdWriter, ScriptError};
use std::path::Path;

pub struct H5mdDump {
    head: Head,
    fields: Vec<H5mdField>,
    /// Continue an existing file (a run restarted from a checkpoint) instead of
    /// truncating it.
    append: bool,
    /// `dump_modify author NAME email ADDRESS` (default name: $USER).
    author: String,
    email: Option<String>,
    writer: Option<H5mdWriter>,
}

const FIELDS: &str = "x|position, image, v|velocity, p|momentum, mass, id, type|species, u|internal_energy, theta|temperature, n|density";

/// The dump keywords of an element's values.
fn keywords(f: H5mdField) -> &'static [&'static str] {
    match f {
        H5mdField::Position => &["x", "y", "z"],
        H5mdField::Image => &["ix", "iy", "iz"],
        H5mdField::Velocity => &["vx", "vy", "vz"],
        H5mdField::Momentum => &["px", "py", "pz"],
        H5mdField::Mass => &["mass"],
        H5mdField::Id => &["id"],
        H5mdField::Species => &["type"],
        H5mdField::InternalEnergy => &["u"],
        H5mdField::Temperature => &["theta"],
        H5mdField::Density => &["n"],
    }
}

impl H5mdDump {
    /// The words after `dump ID GROUP h5md N FILE`: `field... [append yes|no]`.
    pub fn parse(head: Head, a: &mut Args) -> Result<Self, ScriptError> {
        let (mut fields, mut append) = (Vec::new(), false);
        while let Some(w) = a.peek().filter(|_| !head.at_end(a)) {
            a.word("a field")?;
            if w == "append" {
                append = a.yes_no("append")?;
                continue;
            }
            let f = H5mdField::parse(w).ok_or_else(|| a.err(format!("unknown h5md field '{w}'; known: {FIELDS}")))?;
            if !fields.contains(&f) {
                fields.push(f);
            }
        }
        if fields.is_empty() {
            return Err(a.err(format!("missing argument: expected fields ({FIELDS})")));
        }
        let author = std::env::var("USER").unwrap_or_else(|_| "unknown".into());
        Ok(Self { head, fields, append, author, email: None, writer: None })
    }
}

impl RunOutput for H5mdDump {
    fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        self.head.every.next_step(step, run)
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        self.write_frame(f).map_err(|e| format!("dump {}: {e}", self.head.id))
    }
}

impl Dump for H5mdDump {
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<(), ScriptError> {
        if self.head.modify(key, a)? {
            return Ok(());
        }
        match key {
            "append" => self.append = a.yes_no("append")?,
            "author" => self.author = a.word("an author name (quoted if it has spaces)")?.to_string(),
            "email" => self.email = Some(a.word("an email address")?.to_string()),
            _ => return Err(unknown_key(&self.head, key, "append, author, email", a)),
        }
        Ok(())
    }

    fn close(&mut self) -> Result<(), String> {
        self.writer = None;
        self.append = true;
        Ok(())
    }

    fn head(&self) -> &Head {
        &self.head
    }

    fn head_mut(&mut self) -> &mut Head {
        &mut self.head
    }
}

impl H5mdDump {
    /// Writes a frame of the current step.
    fn write_frame(&mut self, frame: &Frame) -> Result<(), String> {
        let (sys, natoms) = (frame.sys, self.head.count(frame.sim, frame.sys)? as usize);
        self.head.every.wrote(sys.clock.step);
        // the thermo keywords at this step, the observables (every rank: collective)
        let values = thermo::values(frame.thermo, frame)?;
        let observables: Vec<(&str, f64)> = frame.thermo.keywords.iter().map(String::as_str).zip(values).filter(|(k, _)| *k != "step").collect();
        if sys.comm.rank() == 0 && self.writer.is_none() {
            let file = self.head.path(sys.clock.step);
            let path = Path::new(&file);
            let w = if self.append && path.exists() {
                H5mdWriter::append(path, natoms, &self.fields)
            } else {
                let meta = H5mdMeta {
                    author: self.author.clone(),
                    email: self.email.clone(),
                    creator_version: env!("CARGO_PKG_VERSION").into(),
                    units: Some(frame.sim.units.name.into()),
                    observables: observables.iter().map(|(n, _)| n.to_string()).collect(),
                };
                H5mdWriter::create(path, natoms, sys.domain.len(), &self.fields, &meta)
            };
            self.writer = Some(w.map_err(|e| e.0)?);
        }
        let columns: Vec<Keyword> = self.fields.iter().flat_map(|&f| keywords(f)).filter_map(|k| Keyword::find(k)).collect();
        let readers = readers(&columns, sys)?;
        let width = 1 + columns.len();
        let row = |i: usize, b: &mut Vec<f64>| {
            b.push(sys.store.tag[i] as f64);
            b.extend(readers.iter().map(|r| r.get(sys, i)));
        };
        if let Some(w) = self.writer.as_mut() {
            w.set_edges(sys.domain.len());
            w.begin_frame(sys.clock.step, sys.clock.time).map_err(|e| e.0)?;
            w.write_observables(&observables).map_err(|e| e.0)?;
        }
        let mut first_row = 0;
        let mut column = Vec::new();
        let (writer, fields, head) = (&mut self.writer, &self.fields, &self.head);
        let mut emit = |rows: &[f64]| -> Result<(), String> {
            let Some(w) = writer.as_mut() else { return Ok(()) };
            let n = rows.len() / width;
            let mut offset = 1;
            for f in fields {
                column.clear();
                for r in rows.chunks_exact(width) {
                    column.extend_from_slice(&r[offset..offset + f.width()]);
                }
                w.write_rows(*f, first_row, &column).map_err(|e| e.0)?;
                offset += f.width();
            }
            first_row += n;
            Ok(())
        };
        head.rows(frame.sim, sys, width, row, &mut emit)?;
        if let Some(w) = self.writer.as_mut() {
            w.end_frame().map_err(|e| e.0)?;
        }
        Ok(())
    }
}
