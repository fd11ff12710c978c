//! LAMMPS's text dumps: `dump ID GROUP custom|atom|xyz N FILE [COLUMNS...]` and their
//! `dump_modify` keywords (formats, headers, units, time, element names).

use crate::base::args::Args;
use crate::model::per_atom;
use crate::model::sim::Sim;
use crate::output::dump::head::{unknown_key, Dump, Head, LAMMPS_MODIFY_KEYS};
use crate::base::particle_keywords::{keyword_names, Keyword, Reader};
use crate::output::schedule::{Frame, RunOutput, Span};
use crate::output::thermo::{ThermoConfig, ThermoContext};
use gendpde_integrators::System;
use gendpde_io::{format_printf, ScriptError, Variables};
use std::fs::File;
use std::io::{BufWriter, Write};

/// A column of a text dump: a per-particle keyword, or LAMMPS's `c_ID` or `c_ID[k]` (a
/// per-atom compute's vector or array column), `f_ID` or `f_ID[k]`, or `v_name` (an atom-style variable, evaluated per particle
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

/// What the values of `c_ID`, `f_ID` and `v_name` columns read besides the system.
struct PerAtomInputs<'a> {
    vars: &'a Variables,
    thermo: &'a ThermoConfig,
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
    /// `colname`: the header names of columns (custom), None for the column's own.
    names: Vec<Option<String>>,
    units: bool,
    time: bool,
    /// `header`: write each frame's header (default yes).
    header: bool,
    /// `element`: the xyz name of each type (default: the type number).
    elements: Vec<String>,
}

fn check_format(a: &Args, f: &str) -> Result<String, ScriptError> {
    format_printf(f, 1.0).map_err(|e| a.err(format!("bad format '{f}': {e}")))?;
    Ok(f.to_string())
}

impl TextFormat {
    fn new(style: Style, columns: Vec<Column>, float: Format) -> Self {
        let mut f = Self { style, columns: Vec::new(), float, formats: Vec::new(), overrides: Vec::new(), names: Vec::new(), units: false, time: false, header: true, elements: Vec::new() };
        f.reset(columns);
        f
    }

    /// Sets the columns, with the default formats.
    fn reset(&mut self, columns: Vec<Column>) {
        self.formats = columns.iter().map(|c| if c.integer() { Format::Printf("%d".into()) } else { self.float.clone() }).collect();
        self.overrides = vec![None; columns.len()];
        self.names = vec![None; columns.len()];
        self.columns = columns;
    }

    /// One `dump_modify` keyword of text dumps (read already) and its values; false when
    /// `key` is none of them.
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<bool, ScriptError> {
        match key {
            // `off`: LAMMPS's rows come in no set order; ID order is one
            "sort" => match a.word("off or id")? {
                "id" | "off" => {}
                v => return Err(a.err(format!("sort {v}: text dumps are sorted by id (sort id or off)"))),
            },
            "header" => self.header = a.yes_no("header")?,
            "colname" if self.style == Style::Custom => {
                let which = a.word("a column number, a column keyword or default")?;
                if which == "default" {
                    self.names.fill(None);
                    return Ok(true);
                }
                let n = self.columns.len() as i64;
                let col = match which.parse::<i64>() {
                    Ok(k) if (1..=n).contains(&k) => Some(k - 1),
                    Ok(k) if (-n..=-1).contains(&k) => Some(n + k),
                    Ok(_) => None,
                    Err(_) => self.columns.iter().position(|c| c.name() == which).map(|k| k as i64),
                };
                let name = a.word("a column name")?;
                let col = col.ok_or_else(|| a.err(format!("Incorrect dump_modify arguments: colname {which} {name}")))?;
                self.names[col as usize] = Some(name.to_string());
            }
            // LAMMPS's buffering of the ranks' rows: the text is the same either way
            "buffer" => _ = a.yes_no("buffer")?,
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
        let names: Vec<String> = self.columns.iter().zip(&self.names).map(|(c, n)| n.clone().unwrap_or_else(|| c.name())).collect();
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
    fn frame(&self, o: &mut Option<impl Write>, head: &Head, sim: &Sim, sys: &System, inputs: &PerAtomInputs, first: bool) -> Result<(), String> {
        let mut columns = self.columns.clone();
        if self.style == Style::Xyz {
            columns.insert(0, Column::Keyword(Keyword::find("type").expect("type is a keyword")));
        }
        let values: Vec<ColumnValues> = columns.iter().map(|c| inputs.values(c, sim, sys)).collect::<Result<_, _>>()?;
        let natoms = head.count(sim, sys)?;
        if let Some(o) = o.as_mut().filter(|_| self.header) {
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
        head.rows(sim, sys, width, row, &mut emit)
    }
}

/// Whether `w` is a `dump_modify` keyword (ends a list of element names).
fn is_modify_key(w: &str) -> bool {
    LAMMPS_MODIFY_KEYS.contains(&w)
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

/// `dump ID GROUP custom|atom|xyz N FILE [COLUMNS...]`.
pub struct TextDump {
    head: Head,
    format: TextFormat,
    append: bool,
    /// `dump atom`: `scale` and `image` of dump_modify.
    scale: bool,
    image: bool,
    /// `flush`: flush the file after every frame (LAMMPS's default).
    flush: bool,
    /// A frame was written (with the units, when asked for).
    wrote_units: bool,
}

impl TextDump {
    /// The words after `dump ID GROUP STYLE N FILE` of a text style: the columns of
    /// `custom`. A `write_dump` prints floats in the shortest form that reads back.
    /// A `c_ID` or `f_ID` column names a compute or fix with per-atom values defined so
    /// far (in `sim`).
    pub fn parse(head: Head, style: &str, sim: &Sim, a: &mut Args) -> Result<Self, ScriptError> {
        let (style, columns) = match style {
            "custom" => (Style::Custom, parse_columns(a)?),
            "atom" => (Style::Atom, keyword_columns(&["id", "type", "xs", "ys", "zs"])),
            _ => (Style::Xyz, keyword_columns(&["x", "y", "z"])),
        };
        for c in &columns {
            if let Column::Compute(id) = c {
                crate::styles::compute::check_per_atom(&sim.computes, &format!("c_{id}"), "Dump custom").map_err(|m| a.err(m))?;
            }
            if let Column::Fix(id) = c {
                if per_atom::fix_values(sim, &format!("f_{id}")).is_none() {
                    return Err(a.err(format!("Could not find dump custom fix ID: {id} (or it has no per-atom values of that column)")));
                }
            }
        }
        head.done(a)?;
        let float = if head.once { Format::RoundTrip } else { Format::Printf("%g".into()) };
        let format = TextFormat::new(style, columns, float);
        Ok(Self { head, format, append: false, scale: true, image: false, flush: true, wrote_units: false })
    }

    /// `dump atom`'s columns after `scale` or `image` changed.
    fn atom_columns(&mut self) {
        let pos = if self.scale { ["id", "type", "xs", "ys", "zs"] } else { ["id", "type", "x", "y", "z"] };
        let image: &[&str] = if self.image { &["ix", "iy", "iz"] } else { &[] };
        self.format.reset(keyword_columns(&[&pos[..], image].concat()));
    }

    fn open(&mut self, step: u64) -> Result<(), String> {
        if self.head.out.is_some() {
            return Ok(());
        }
        let per_frame = self.head.file.contains('*');
        let path = self.head.path(step);
        let append = self.append && !per_frame;
        let f = File::options().create(true).write(true).append(append).truncate(!append).open(&path);
        self.head.out = Some(BufWriter::new(f.map_err(|e| format!("cannot open '{path}': {e}"))?));
        // later frames of the same file append, as LAMMPS keeps it open
        self.append = self.append || !per_frame;
        Ok(())
    }
}

/// The columns of keywords `names`.
fn keyword_columns(names: &[&str]) -> Vec<Column> {
    names.iter().filter_map(|k| Keyword::find(k)).map(Column::Keyword).collect()
}

impl RunOutput for TextDump {
    fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        self.head.every.next_step(step, run)
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let step = f.sys.clock.step;
        self.head.every.wrote(step);
        let result = (|| {
            if f.sys.comm.rank() == 0 {
                self.open(step)?;
            }
            let mut out = self.head.out.take();
            let wrote = self.format.frame(&mut out, &self.head, f.sim, f.sys, &PerAtomInputs { vars: f.vars, thermo: f.thermo }, !self.wrote_units);
            self.head.out = out;
            wrote?;
            self.wrote_units = true;
            if self.head.file.contains('*') {
                self.head.close()?;
            } else if let Some(o) = self.head.out.as_mut().filter(|_| self.flush) {
                o.flush().map_err(|e| e.to_string())?;
            }
            Ok(())
        })();
        result.map_err(|e: String| format!("dump {}: {e}", self.head.id))
    }
}

impl Dump for TextDump {
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<(), ScriptError> {
        if self.head.modify(key, a)? || self.format.modify(key, a)? {
            return Ok(());
        }
        match key {
            "append" => self.append = a.yes_no("append")?,
            "flush" => self.flush = a.yes_no("flush")?,
            "region" if self.format.style == Style::Custom => self.head.set_region(a)?,
            "scale" | "image" if self.format.style == Style::Atom => {
                *(if key == "scale" { &mut self.scale } else { &mut self.image }) = a.yes_no(key)?;
                self.atom_columns();
            }
            _ => return Err(unknown_key(&self.head, key, "append, flush, sort, format, header, units, time, buffer, element (region, colname: dump custom; scale, image: dump atom)", a)),
        }
        Ok(())
    }

    fn head(&self) -> &Head {
        &self.head
    }

    fn head_mut(&mut self) -> &mut Head {
        &mut self.head
    }
}
