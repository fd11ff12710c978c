//! Text dumps in LAMMPS's formats: `dump ID all custom|atom|xyz N FILE ...` every N
//! steps, and `write_dump all custom FILE COLUMNS... [modify ...]` once.
//!
//! The per-particle keywords (LAMMPS's and gendpde's) are one table, [`KEYWORDS`]: a
//! keyword that is a field of the particle table reads it (`engine::FIELDS`), the others
//! are derived (v = p/m, unwrapped and scaled positions, uMech = u - uCond). H5MD dumps
//! select their elements from the same table.
//!
//! Rank 0 writes the rows in ID order, collected in blocks of 2^20 IDs (`gather`), so it
//! never holds more than one block. Unlike LAMMPS, dumps are always sorted by ID.

use crate::base::args::Args;
use crate::base::gather;
pub use crate::base::particle_keywords::{keyword_names, readers, Keyword, Reader};
use crate::model::per_atom;
use crate::model::sim::Sim;
use crate::output::thermo::{ThermoConfig, ThermoContext};
use crate::output::schedule::{Frame, RunOutput, Span};
use gendpde_integrators::System;
use gendpde_io::{format_printf, ScriptError, Variables};
use std::fs::File;
use std::io::{BufWriter, Write};

/// A column of a text dump: a per-particle keyword, or LAMMPS's `c_ID` or `c_ID[k]` (a
/// per-atom compute's vector or array column) or `v_name` (an atom-style variable, evaluated per particle
/// when the frame is written).
#[derive(Clone)]
enum Column {
    Keyword(Keyword),
    Compute(String),
    /// `f_ID` or `f_ID[k]` of a fix with per-atom values (fix ave/atom).
    Fix(String),
    Variable(String),
}

impl Column {
    fn name(&self) -> String {
        match self {
            Column::Keyword(k) => k.name.to_string(),
            Column::Compute(id) => format!("c_{id}"),
            Column::Fix(id) => format!("f_{id}"),
            Column::Variable(name) => format!("v_{name}"),
        }
    }

    fn integer(&self) -> bool {
        matches!(self, Column::Keyword(k) if k.integer())
    }
}

/// Where a column's values come from in one frame.
enum ColumnValues {
    Reader(Reader),
    /// Per owned particle slot.
    Values(Vec<f64>),
}

/// What the values of `c_ID` and `v_name` columns read besides the system.
pub struct PerAtomInputs<'a> {
    pub vars: &'a Variables,
    pub thermo: &'a ThermoConfig,
}

impl PerAtomInputs<'_> {
    /// The values of `column` in a frame of `sys`.
    fn values(&self, column: &Column, sim: &Sim, sys: &System) -> Result<ColumnValues, String> {
        let s = &sys.store;
        Ok(match column {
            Column::Keyword(k) => ColumnValues::Reader(k.reader(s)?),
            Column::Compute(_) | Column::Fix(_) | Column::Variable(_) => {
                let name = column.name();
                let context = ThermoContext::new(sim, sys, self.thermo, self.vars, 0, 0.0);
                let global = |n: &str| context.keyword(n);
                ColumnValues::Values(per_atom::input(sim, sys, self.vars, &global, &name).map_err(|e| format!("{name}: {e}"))?)
            }
        })
    }
}

/// How a column prints its values.
#[derive(Clone, Debug, PartialEq)]
enum Format {
    /// Shortest text that reads back to the same double (write_dump's default).
    RoundTrip,
    Printf(String),
}

/// The text dump styles.
#[derive(Clone, Copy, PartialEq)]
enum Style {
    Custom,
    Atom,
    Xyz,
}

/// What a text frame holds and how it prints: LAMMPS's layout of each style and the
/// `dump_modify` settings of the text.
struct TextFormat {
    style: Style,
    columns: Vec<Column>,
    /// The float format before any `dump_modify format`.
    float: Format,
    /// Default column formats (`format line`/`int`/`float` applied), then per column
    /// overrides (`format M`).
    formats: Vec<Format>,
    overrides: Vec<Option<String>>,
    units: bool,
    time: bool,
    /// `element`: the xyz name of each type (default: the type number).
    elements: Vec<String>,
}

fn check_format(a: &Args, f: &str) -> Result<String, ScriptError> {
    format_printf(f, 1.0).map_err(|e| a.err(format!("bad format '{f}': {e}")))?;
    Ok(f.to_string())
}

impl TextFormat {
    fn new(style: Style, columns: Vec<Column>, float: Format) -> Self {
        let mut f = Self { style, columns: Vec::new(), float, formats: Vec::new(), overrides: Vec::new(), units: false, time: false, elements: Vec::new() };
        f.reset(columns);
        f
    }

    /// Sets the columns, with the default formats.
    fn reset(&mut self, columns: Vec<Column>) {
        self.formats = columns.iter().map(|c| if c.integer() { Format::Printf("%d".into()) } else { self.float.clone() }).collect();
        self.overrides = vec![None; columns.len()];
        self.columns = columns;
    }

    /// One `dump_modify` keyword of text dumps (read already) and its values; false when
    /// `key` is none of them.
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<bool, ScriptError> {
        match key {
            "sort" => match a.word("id")? {
                "id" => {}
                v => return Err(a.err(format!("sort {v}: dumps are always sorted by id"))),
            },
            "format" => match a.word("line, int, float, none or a column number M")? {
                "none" => {
                    let columns = std::mem::take(&mut self.columns);
                    self.reset(columns);
                }
                "line" => {
                    let line = a.word("a quoted line of formats, one per column")?;
                    let words: Vec<&str> = line.split_whitespace().collect();
                    let want = self.columns.len() + usize::from(self.style == Style::Xyz);
                    if words.len() != want {
                        return Err(a.err(format!("format line '{line}' has {} formats for {want} columns", words.len())));
                    }
                    let skip = usize::from(self.style == Style::Xyz);
                    for (f, w) in self.formats.iter_mut().zip(&words[skip..]) {
                        *f = Format::Printf(check_format(a, w)?);
                    }
                }
                kind @ ("int" | "float") => {
                    let f = check_format(a, a.peek().unwrap_or(""))?;
                    a.word("a format")?;
                    for (c, fmt) in self.columns.iter().zip(&mut self.formats) {
                        if c.integer() == (kind == "int") {
                            *fmt = Format::Printf(f.clone());
                        }
                    }
                }
                m => {
                    let col: usize = m.parse().ok().filter(|&m| m >= 1 && m <= self.columns.len()).ok_or_else(|| {
                        a.err(format!("format {m}: expected line, int, float, none or a column number 1..{}", self.columns.len()))
                    })?;
                    let f = check_format(a, a.peek().unwrap_or(""))?;
                    a.word("a format")?;
                    self.overrides[col - 1] = Some(f);
                }
            },
            "units" => self.units = a.yes_no("units")?,
            "time" => self.time = a.yes_no("time")?,
            "element" => {
                self.elements.clear();
                while let Some(w) = a.peek().filter(|w| !is_modify_key(w)) {
                    self.elements.push(w.to_string());
                    a.word("an element name")?;
                }
                if self.elements.is_empty() {
                    return Err(a.err("element: expected one name per atom type"));
                }
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// The header of a frame (`units`: the first frame of a dump with `units yes`).
    fn header(&self, o: &mut impl Write, sim: &Sim, sys: &System, natoms: u64, units: bool) -> std::io::Result<()> {
        if self.style == Style::Xyz {
            write!(o, "{natoms}\n Atoms. Timestep: {}", sys.clock.step)?;
            if self.time {
                write!(o, " Time: {:.6}", sys.clock.time)?;
            }
            return writeln!(o);
        }
        if units {
            write!(o, "ITEM: UNITS\n{}\n", sim.units.name)?;
        }
        if self.time {
            write!(o, "ITEM: TIME\n{}\n", gendpde_io::format_g(sys.clock.time, 16))?;
        }
        write!(o, "ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{natoms}\nITEM: BOX BOUNDS pp pp pp\n", sys.clock.step)?;
        let d = &sys.domain;
        for k in 0..3 {
            let e = |x: f64| format_printf("%1.16e", x).unwrap_or_else(|_| format!("{x:e}"));
            writeln!(o, "{} {}", e(d.lo[k]), e(d.hi[k]))?;
        }
        let names: Vec<String> = self.columns.iter().map(Column::name).collect();
        writeln!(o, "ITEM: ATOMS {}", names.join(" "))
    }

    /// One row: `values` in column order.
    fn row(&self, o: &mut impl Write, values: &[f64]) -> Result<(), String> {
        let mut line = String::new();
        for (k, v) in values.iter().enumerate() {
            if k > 0 {
                line.push(' ');
            }
            if self.style == Style::Xyz && k == 0 {
                let t = *v as usize;
                line.push_str(self.elements.get(t.wrapping_sub(1)).map_or(&t.to_string(), |e| e));
                continue;
            }
            let (c, fmt) = (k - usize::from(self.style == Style::Xyz), &self.formats);
            match (&self.overrides[c], &fmt[c]) {
                (Some(f), _) | (None, Format::Printf(f)) => line.push_str(&format_printf(f, *v).map_err(|e| format!("column {}: {e}", self.columns[c].name()))?),
                (None, Format::RoundTrip) if self.columns[c].integer() => line.push_str(&(*v as i64).to_string()),
                (None, Format::RoundTrip) => line.push_str(&format!("{v:?}")),
            }
        }
        writeln!(o, "{line}").map_err(|e| e.to_string())
    }

    /// Writes a frame of `sys` to `o` on rank 0 (every rank must call: it gathers);
    /// `first`: the first frame of the dump (LAMMPS writes the units once).
    fn frame(&self, o: &mut Option<impl Write>, sim: &Sim, sys: &System, inputs: &PerAtomInputs, first: bool) -> Result<(), String> {
        let mut columns = self.columns.clone();
        if self.style == Style::Xyz {
            columns.insert(0, Column::Keyword(Keyword::find("type").expect("type is a keyword")));
        }
        let values: Vec<ColumnValues> = columns.iter().map(|c| inputs.values(c, sim, sys)).collect::<Result<_, _>>()?;
        let natoms = sys.comm.count(sys.store.nlocal);
        if let Some(o) = o.as_mut() {
            self.header(o, sim, sys, natoms, self.units && first).map_err(|e| e.to_string())?;
        }
        let width = columns.len() + 1;
        let row = |i: usize, buf: &mut Vec<f64>| {
            buf.push(sys.store.tag[i] as f64);
            buf.extend(values.iter().map(|v| match v {
                ColumnValues::Reader(r) => r.get(sys, i),
                ColumnValues::Values(x) => x[i],
            }));
        };
        let mut emit = |rows: &[f64]| -> Result<(), String> {
            let Some(o) = o.as_mut() else { return Ok(()) };
            rows.chunks_exact(width).try_for_each(|r| self.row(o, &r[1..]))
        };
        gather::sorted_rows(sys, sim.max_tag, width, row, &mut emit)?;
        if let Some(o) = o.as_mut() {
            o.flush().map_err(|e| e.to_string())?;
        }
        Ok(())
    }
}

/// Whether `w` is a `dump_modify` keyword (ends a list of element names).
fn is_modify_key(w: &str) -> bool {
    matches!(w, "sort" | "format" | "units" | "time" | "element" | "every" | "first" | "append" | "author" | "email" | "scale" | "image")
}

/// The columns of a `dump custom` or `write_dump custom`.
fn parse_columns(a: &mut Args) -> Result<Vec<Column>, ScriptError> {
    let mut cols = Vec::new();
    while let Some(w) = a.peek().filter(|&w| w != "modify") {
        let c = match (w.strip_prefix("c_"), w.strip_prefix("v_")) {
            (Some(id), _) if !id.is_empty() => Column::Compute(id.to_string()),
            (_, Some(name)) if !name.is_empty() => Column::Variable(name.to_string()),
            _ if w.len() > 2 && w.starts_with("f_") => Column::Fix(w[2..].to_string()),
            _ => Column::Keyword(Keyword::find(w).ok_or_else(|| a.err(format!("unknown keyword '{w}'; known: {}, c_ID, v_name", keyword_names())))?),
        };
        a.word("a keyword")?;
        cols.push(c);
    }
    if cols.is_empty() {
        return Err(a.err(format!("missing argument: expected per-particle keywords ({}, c_ID, v_name)", keyword_names())));
    }
    Ok(cols)
}

/// The group word of a dump command (only `all`).
pub fn group_all(a: &mut Args) -> Result<(), ScriptError> {
    match a.word("a group")? {
        "all" => Ok(()),
        g => Err(a.err(format!("group '{g}': only group all is defined"))),
    }
}

/// A `write_dump` snapshot: its file and format.
pub struct WriteDump {
    file: String,
    format: TextFormat,
}

impl WriteDump {
    /// The words after `write_dump`: `all custom FILE COLUMNS... [modify KEY VALUES...]`.
    /// Floats print in the shortest form that reads back to the same double unless a
    /// format is given.
    pub fn parse(a: &mut Args) -> Result<Self, ScriptError> {
        group_all(a)?;
        match a.word("a dump style (custom)")? {
            "custom" => {}
            s => return Err(a.err(format!("unknown write_dump style '{s}'; known: custom"))),
        }
        let file = a.word("a file name")?.to_string();
        let mut format = TextFormat::new(Style::Custom, parse_columns(a)?, Format::RoundTrip);
        if a.peek() == Some("modify") {
            a.word("modify")?;
            while a.remaining() > 0 {
                let key = a.word("a dump_modify keyword")?;
                if !format.modify(key, a)? {
                    return Err(a.err(format!("write_dump modify {key}: known are sort, format, units, time")));
                }
            }
        }
        Ok(Self { file, format })
    }

    /// Writes the snapshot (rank 0 writes, through a temporary file; every rank calls).
    pub fn write(&self, sim: &Sim, sys: &System, inputs: &PerAtomInputs) -> Result<(), String> {
        let (file, tmp) = (&self.file, format!("{}.tmp", self.file));
        let mut out = match sys.comm.rank() {
            0 => Some(BufWriter::new(File::create(&tmp).map_err(|e| format!("cannot create '{tmp}': {e}"))?)),
            _ => None,
        };
        self.format.frame(&mut out, sim, sys, inputs, true).map_err(|e| format!("writing '{file}': {e}"))?;
        if out.is_some() {
            drop(out);
            std::fs::rename(&tmp, file).map_err(|e| format!("renaming '{tmp}' to '{file}': {e}"))?;
        }
        Ok(())
    }
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

/// A periodic dump: text or H5MD.
pub trait Dump: RunOutput {
    fn id(&self) -> &str;
    /// One `dump_modify` keyword (read already) and its values.
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<(), ScriptError>;
    /// Flushes and closes its file (it reopens, appending, when written again).
    fn close(&mut self) -> Result<(), String>;
}

/// `dump ID all custom|atom|xyz N FILE [COLUMNS...]`.
pub struct TextDump {
    id: String,
    every: Every,
    file: String,
    format: TextFormat,
    append: bool,
    /// `dump atom`: `scale` and `image` of dump_modify.
    scale: bool,
    image: bool,
    out: Option<BufWriter<File>>,
    /// A frame was written (with the units, when asked for).
    wrote_units: bool,
}

impl TextDump {
    /// The words after `dump ID` when the style is a text one (None otherwise).
    pub fn parse(id: &str, style: &str, a: &mut Args) -> Result<Option<Self>, ScriptError> {
        let style = match style {
            "custom" => Style::Custom,
            "atom" => Style::Atom,
            "xyz" => Style::Xyz,
            _ => return Ok(None),
        };
        let every = a.u64("the output interval N")?;
        if every == 0 {
            return Err(a.err("the output interval must be positive"));
        }
        let file = a.word("a file name")?.to_string();
        if file.contains('%') || file.ends_with(".gz") || file.ends_with(".bin") {
            return Err(a.err(format!("file '{file}': per-rank (%), compressed and binary dumps are not supported")));
        }
        let columns = match style {
            Style::Custom => parse_columns(a)?,
            Style::Atom => ["id", "type", "xs", "ys", "zs"].iter().filter_map(|k| Keyword::find(k)).map(Column::Keyword).collect(),
            Style::Xyz => ["x", "y", "z"].iter().filter_map(|k| Keyword::find(k)).map(Column::Keyword).collect(),
        };
        a.done()?;
        let format = TextFormat::new(style, columns, Format::Printf("%g".into()));
        Ok(Some(Self { id: id.to_string(), every: Every::new(every), file, format, append: false, scale: true, image: false, out: None, wrote_units: false }))
    }

    /// `dump atom`'s columns after `scale` or `image` changed.
    fn atom_columns(&mut self) {
        let pos = if self.scale { ["id", "type", "xs", "ys", "zs"] } else { ["id", "type", "x", "y", "z"] };
        let image: &[&str] = if self.image { &["ix", "iy", "iz"] } else { &[] };
        self.format.reset(pos.iter().chain(image).filter_map(|k| Keyword::find(k)).map(Column::Keyword).collect());
    }

    fn open(&mut self, step: u64) -> Result<(), String> {
        if self.out.is_some() {
            return Ok(());
        }
        let per_frame = self.file.contains('*');
        let path = self.file.replace('*', &step.to_string());
        let append = self.append && !per_frame;
        let f = File::options().create(true).write(true).append(append).truncate(!append).open(&path);
        self.out = Some(BufWriter::new(f.map_err(|e| format!("cannot open '{path}': {e}"))?));
        // later frames of the same file append, as LAMMPS keeps it open
        self.append = self.append || !per_frame;
        Ok(())
    }
}

impl RunOutput for TextDump {
    fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        self.every.next_step(step, run)
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let step = f.sys.clock.step;
        self.every.wrote(step);
        let result = (|| {
            if f.sys.comm.rank() == 0 {
                self.open(step)?;
            }
            self.format.frame(&mut self.out, f.sim, f.sys, &PerAtomInputs { vars: f.vars, thermo: f.thermo }, !self.wrote_units)?;
            self.wrote_units = true;
            if self.file.contains('*') {
                self.out = None;
            }
            Ok(())
        })();
        result.map_err(|e: String| format!("dump {}: {e}", self.id))
    }
}

impl Dump for TextDump {
    fn id(&self) -> &str {
        &self.id
    }

    fn modify(&mut self, key: &str, a: &mut Args) -> Result<(), ScriptError> {
        if self.every.modify(key, a)? || self.format.modify(key, a)? {
            return Ok(());
        }
        match key {
            "append" => self.append = a.yes_no("append")?,
            "scale" | "image" if self.format.style == Style::Atom => {
                *(if key == "scale" { &mut self.scale } else { &mut self.image }) = a.yes_no(key)?;
                self.atom_columns();
            }
            _ => {
                return Err(a.err(format!(
                    "dump {}: unknown dump_modify keyword '{key}'; known: every, first, append, sort, format, units, time, element (scale, image: dump atom)",
                    self.id
                )))
            }
        }
        Ok(())
    }

    fn close(&mut self) -> Result<(), String> {
        match self.out.take() {
            Some(mut o) => o.flush().map_err(|e| format!("dump {}: closing '{}': {e}", self.id, self.file)),
            None => Ok(()),
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
