//! `dump ID all h5md N FILE field... [append yes]`: H5MD snapshots every N steps,
//! written by rank 0 from particles gathered in tag order (`gather`).

use crate::base::args::Args;
use crate::base::gather::sorted_rows;
use crate::output::schedule::{Frame, RunOutput, Span};
use gendpde_io::{H5mdField, H5mdWriter, ScriptError};
use std::path::Path;

pub struct H5mdDump {
    pub id: String,
    pub every: u64,
    pub file: String,
    pub fields: Vec<H5mdField>,
    /// Continue an existing file (a run restarted from a checkpoint) instead of
    /// truncating it.
    pub append: bool,
    writer: Option<H5mdWriter>,
    last_step: Option<u64>,
}

const FIELDS: &str = "x|position, image, v|velocity, p|momentum, mass, id, type|species, u|internal_energy, theta|temperature, n|density";

impl H5mdDump {
    /// The words after `dump`.
    pub fn parse(a: &mut Args) -> Result<Self, ScriptError> {
        let id = a.word("a dump ID")?.to_string();
        let group = a.word("a group")?;
        if group != "all" {
            return Err(a.err(format!("group '{group}': only group all is defined")));
        }
        match a.word("a dump style (h5md)")? {
            "h5md" => {}
            s => return Err(a.err(format!("unknown dump style '{s}'; known: h5md (write_dump writes text snapshots)"))),
        }
        let every = a.u64("the output interval N")?;
        if every == 0 {
            return Err(a.err("the output interval must be positive"));
        }
        let file = a.word("a file name")?.to_string();
        let (mut fields, mut append) = (Vec::new(), false);
        while let Some(w) = a.peek() {
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
        Ok(Self { id, every, file, fields, append, writer: None, last_step: None })
    }

}

impl RunOutput for H5mdDump {
    /// Every N steps, once per step (a run's setup repeats the last step of the one before).
    fn next_step(&self, step: u64, _run: Span) -> Option<u64> {
        let next = step.next_multiple_of(self.every);
        Some(if self.last_step == Some(next) { next + self.every } else { next })
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        self.write_frame(f).map_err(|e| format!("dump {}: {e}", self.id))
    }
}

impl H5mdDump {
    /// Writes a frame of the current step.
    fn write_frame(&mut self, frame: &Frame) -> Result<(), String> {
        let (sys, natoms) = (frame.sys, frame.sys.comm.count(frame.sys.store.nlocal) as usize);
        self.last_step = Some(sys.step);
        if sys.comm.rank() == 0 && self.writer.is_none() {
            let path = Path::new(&self.file);
            let w = if self.append && path.exists() {
                H5mdWriter::append(path, natoms, &self.fields)
            } else {
                H5mdWriter::create(path, natoms, sys.domain.len(), &self.fields, "gendpde user", env!("CARGO_PKG_VERSION"))
            };
            self.writer = Some(w.map_err(|e| e.0)?);
        }
        let width = 1 + self.fields.iter().map(|f| f.width()).sum::<usize>();
        let fields = self.fields.clone();
        let s = &sys.store;
        let row = |i: usize, b: &mut Vec<f64>| {
            b.push(s.tag[i] as f64);
            for f in &fields {
                match f {
                    H5mdField::Position => b.extend_from_slice(&s.r[i]),
                    H5mdField::Image => b.extend(s.image[i].iter().map(|&x| x as f64)),
                    H5mdField::Velocity => b.extend(s.p[i].iter().map(|p| p / s.mass[i])),
                    H5mdField::Momentum => b.extend_from_slice(&s.p[i]),
                    H5mdField::Mass => b.push(s.mass[i]),
                    H5mdField::Id => b.push(s.tag[i] as f64),
                    H5mdField::Species => b.push(s.kind[i] as f64),
                    H5mdField::InternalEnergy => b.push(s.u[i]),
                    H5mdField::Temperature => b.push(s.theta[i]),
                    H5mdField::Density => b.push(s.n.get(i).copied().unwrap_or(0.0)),
                }
            }
        };
        if let Some(w) = self.writer.as_mut() {
            w.begin_frame(sys.step, sys.time).map_err(|e| e.0)?;
        }
        let mut first_row = 0;
        let mut column = Vec::new();
        let writer = &mut self.writer;
        let mut emit = |rows: &[f64]| -> Result<(), String> {
            let Some(w) = writer.as_mut() else { return Ok(()) };
            let n = rows.len() / width;
            let mut offset = 1;
            for f in &fields {
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
        sorted_rows(sys, frame.sim.max_tag, width, row, &mut emit)?;
        if let Some(w) = self.writer.as_mut() {
            w.end_frame().map_err(|e| e.0)?;
        }
        Ok(())
    }
}
