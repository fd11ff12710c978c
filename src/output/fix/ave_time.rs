//! `fix ID GROUP ave/time Nevery Nrepeat Nfreq value ... [mode scalar|vector] [ave
//! one|running|window M] [start N] [off K] [file FILE] [format F] [title1|2|3 T]`, as
//! LAMMPS's: values averaged over Nrepeat samples Nevery steps apart, one block every
//! Nfreq steps, written to FILE and published as `f_ID` (one value) or `f_ID[k]`.
//!
//! Mode scalar (the default): `c_ID` (a global scalar), `c_ID[k]` (element k of a global
//! vector), `c_ID[*]` (every element), `f_ID`, `f_ID[k]` (a fix's published values),
//! `v_name` (an equal-style variable); one line per block. Mode vector: `c_ID` (a global
//! vector: one row per element) or `c_ID[k]`, `c_ID[*]` (columns of the array of a
//! compute rdf); a block of rows per block. The group is ignored (as in LAMMPS).
//! Rank 0 writes the file and flushes each block.

use super::blocks::Blocks;
use super::{OutputFix, OutputFixContext};
use crate::base::args::Args;
use crate::model::sim::FixValues;
use crate::output::schedule::{write_on_rank0, Frame, RunOutput, Sampling, Span};
use crate::output::thermo::ThermoContext;
use crate::styles::compute::rdf::COLUMNS;
use crate::styles::compute::{self, Shape};
use gendpde_io::ScriptError;
use std::fs::File;
use std::io::{BufWriter, Write};

/// One input of mode vector: the global vector of a compute, or column k (from 0) of the
/// array of a compute rdf.
#[derive(Clone, Debug)]
enum Rows {
    Vector(String),
    Rdf(String, usize),
}

pub struct AveTime {
    id: String,
    sampling: Sampling,
    /// The values as LAMMPS names them (wildcards expanded): the file's heading.
    names: Vec<String>,
    /// Mode vector: the inputs (None: mode scalar, whose values are `names`).
    rows: Option<Vec<Rows>>,
    /// Whether each value is extensive (published so to thermo's norm).
    extensive: Vec<bool>,
    blocks: Blocks,
    /// `off K`: value K (from 0) is not averaged but its last sample kept.
    off: Vec<usize>,
    file: Option<String>,
    /// printf format of one value (LAMMPS's default " %g").
    format: String,
    titles: [Option<String>; 3],
    /// The open file (rank 0).
    out: Option<BufWriter<File>>,
    /// Sum of the samples of the current block, row-major (rows x values).
    sums: Vec<f64>,
    /// The last combined block, published as `f_ID`.
    published: FixValues,
}

impl AveTime {
    /// The words after `fix ID GROUP ave/time`.
    pub fn parse(a: &mut Args, c: &OutputFixContext) -> Result<Self, ScriptError> {
        crate::base::groups::mask(&c.sim.groups, c.group, a).map_err(|_| a.err(format!("Could not find fix group ID {}", c.group)))?;
        let sampling = Sampling::parse(a, c.step)?;
        let mut words = Vec::new();
        while let Some(w) = a.peek().filter(|w| ["c_", "f_", "v_"].iter().any(|p| w.starts_with(p))) {
            words.push(w.to_string());
            a.word("a value")?;
        }
        if words.is_empty() {
            return Err(a.err(format!("Illegal fix ave/time command: expected values c_ID, c_ID[k], f_ID, f_ID[k] or v_name, got {}", a.peek().map_or("nothing".into(), |w| format!("'{w}'")))));
        }
        let (mut vector, mut blocks, mut start, mut off, mut file) = (false, Blocks::default(), 0, Vec::new(), None);
        let (mut format, mut titles) = (" %g".to_string(), [None, None, None]);
        while a.remaining() > 0 {
            match a.word("a keyword")? {
                "file" => file = Some(a.word("a file name")?.to_string()),
                "mode" => {
                    vector = match a.word("scalar or vector")? {
                        "scalar" => false,
                        "vector" => true,
                        m => return Err(a.err(format!("Illegal fix ave/time command: mode {m} (expected scalar or vector)"))),
                    }
                }
                "ave" => blocks = Blocks::parse(a)?,
                "start" => start = a.u64("the start step")?,
                "off" => match a.u64("the value index to leave unaveraged")? {
                    0 => return Err(a.err("Illegal fix ave/time command: off 0 (values count from 1)")),
                    k => off.push(k as usize - 1),
                },
                "format" => {
                    format = a.word("a printf format such as ' %.10g'")?.to_string();
                    gendpde_io::format_printf(&format, 1.0).map_err(|e| a.err(format!("bad format: {e}")))?;
                }
                t @ ("title1" | "title2" | "title3") => titles[usize::from(t.as_bytes()[5] - b'1')] = Some(a.word("a title")?.to_string()),
                "overwrite" => return Err(a.err("fix ave/time: keyword overwrite is not supported (the file keeps every block)")),
                k => return Err(a.err(format!("Unknown fix ave/time keyword {k}; known: mode, ave, start, off, file, format, title1, title2, title3"))),
            }
        }
        let sim = c.sim;
        let (mut names, mut extensive, mut rows) = (Vec::new(), Vec::new(), Vec::new());
        for w in &words {
            let (kind, id, index) = compute::reference(w).ok_or_else(|| a.err(format!("value '{w}': expected c_ID, c_ID[k], f_ID, f_ID[k] or v_name")))?;
            // a wildcard needs a compute or fix to expand (LAMMPS's message otherwise)
            let known = compute::find(&sim.computes, id).is_some() || sim.rdfs.iter().any(|r| r.id == id) || sim.fix_values.contains_key(id);
            if index == Some(0) && !known {
                return Err(a.err(format!("Invalid fix ave/time argument: {w}")));
            }
            let shape = match kind {
                'c' => match (compute::find(&sim.computes, id), sim.rdfs.iter().any(|r| r.id == id)) {
                    (Some(c), _) => c.shape(),
                    // a compute rdf: a global array of COLUMNS columns
                    (None, true) => Shape::default(),
                    (None, false) => return Err(a.err(format!("Compute ID {id} for fix ave/time does not exist"))),
                },
                'f' => match (sim.fix_values.get(id), index) {
                    (Some(v), _) => Shape { scalar: v.scalar.is_some(), vector: v.vector.len(), ..Shape::default() },
                    (None, _) => return Err(a.err(format!("Fix ID {id} for fix ave/time does not exist or publishes no global values"))),
                },
                _ => match c.vars.style(id) {
                    Some("equal" | "internal") if index.is_none() => Shape { scalar: true, ..Shape::default() },
                    Some(style) => return Err(a.err(format!("Fix ave/time variable {id} is {style}-style; expected an equal-style variable"))),
                    None => return Err(a.err(format!("Variable name {id} for fix ave/time does not exist"))),
                },
            };
            let rdf = kind == 'c' && sim.rdfs.iter().any(|r| r.id == id);
            if vector {
                let ks: Vec<usize> = match (rdf, index) {
                    (true, Some(0)) => (1..=COLUMNS).collect(),
                    (true, Some(k)) if k <= COLUMNS => vec![k],
                    (true, Some(_)) => return Err(a.err(format!("Fix ave/time compute {id} array is accessed out-of-range"))),
                    (false, None) if shape.vector > 0 && kind == 'c' => vec![0],
                    _ => return Err(a.err(format!("value '{w}': mode vector takes c_ID of a compute with a global vector or c_ID[k] of a compute rdf"))),
                };
                for k in ks {
                    if k == 0 {
                        rows.push(Rows::Vector(id.to_string()));
                        names.push(w.clone());
                    } else {
                        rows.push(Rows::Rdf(id.to_string(), k - 1));
                        names.push(format!("c_{id}[{k}]"));
                    }
                    extensive.push(shape.extensive_vector);
                }
                continue;
            }
            let prefix = &w[..2];
            if rdf {
                return Err(a.err(format!("Invalid fix ave/time argument: {w} (a compute rdf is an array: mode vector)")));
            }
            match index {
                None if shape.scalar => names.push(w.clone()),
                Some(0) if shape.vector > 0 => names.extend((1..=shape.vector).map(|k| format!("{prefix}{id}[{k}]"))),
                Some(k) if k <= shape.vector => names.push(w.clone()),
                _ => return Err(a.err(format!("value '{w}': Fix ave/time {} does not calculate a {}", if kind == 'c' { "compute" } else { "fix" }, if index.is_some() { "vector (or not this element)" } else { "scalar" }))),
            }
            extensive.resize(names.len(), if index.is_none() { shape.extensive } else { shape.extensive_vector });
        }
        if let Some(&k) = off.iter().find(|&&k| k >= names.len()) {
            return Err(a.err(format!("Invalid fix ave/time off column {}", k + 1)));
        }
        let published = FixValues { freq: sampling.nfreq, ..FixValues::default() };
        let rows = vector.then_some(rows);
        let mut fix = Self { id: c.id.clone(), sampling, names, rows, extensive, blocks, off, file, format, titles, out: None, sums: Vec::new(), published };
        fix.sampling.start_at(c.step, start);
        fix.publish(&[], 1.0);
        Ok(fix)
    }

    /// The samples of this step, row-major (rows x values); collective.
    fn sample(&self, f: &Frame) -> Result<(Vec<f64>, usize), String> {
        let (sim, sys) = (f.sim, f.sys);
        let mut thermo = f.thermo.clone();
        thermo.norm = false;
        let ctx = ThermoContext::new(sim, sys, &thermo, f.vars, 0, 0.0);
        let Some(rows) = &self.rows else {
            let resolve = |name: &str| ctx.keyword(name);
            let values = self.names.iter().map(|n| match ctx.keyword(n) {
                Some(v) => Ok(v),
                None => gendpde_io::evaluate(n, f.vars, &resolve).map_err(|e| format!("fix {} ave/time: {n}: {e}", self.id)),
            });
            return Ok((values.collect::<Result<_, _>>()?, 1));
        };
        let mut columns = Vec::with_capacity(rows.len());
        // each compute rdf once per sample
        let mut tables: Vec<(&str, Vec<[f64; COLUMNS]>)> = Vec::new();
        for r in rows {
            columns.push(match r {
                Rows::Vector(id) => {
                    let c = compute::find(&sim.computes, id).ok_or_else(|| format!("fix {} ave/time: compute '{id}' no longer exists", self.id))?;
                    crate::model::per_atom::evaluate(sim, sys, f.vars, &|n| ctx.keyword(n), |e| c.vector(e))?
                }
                Rows::Rdf(id, k) => {
                    if tables.iter().all(|t| t.0 != id) {
                        let rdf = sim.rdfs.iter().find(|r| &r.id == id).ok_or_else(|| format!("fix {} ave/time: compute rdf '{id}' no longer exists", self.id))?;
                        let rc = rdf.cutoff_for(sys.lists.cutoff);
                        tables.push((id, rdf.rows(sys, rc, rc + sim.skin)?));
                    }
                    tables.iter().find(|t| t.0 == id).expect("computed above").1.iter().map(|row| row[*k]).collect()
                }
            });
        }
        let nrow = columns[0].len();
        if columns.iter().any(|c| c.len() != nrow) {
            return Err(format!("fix {} ave/time: the values of mode vector need the same number of rows", self.id));
        }
        Ok(((0..nrow).flat_map(|r| columns.iter().map(move |c| c[r])).collect(), nrow))
    }

    /// Publishes `block` (rows x values, `norm` blocks summed) as `f_ID`.
    fn publish(&mut self, block: &[f64], norm: f64) {
        let n = self.names.len();
        let value = |k: usize| block.get(k).map_or(0.0, |v| v / norm);
        let p = &mut self.published;
        (p.scalar, p.vector) = match &self.rows {
            None if n == 1 => (Some((value(0), self.extensive[0])), Vec::new()),
            None => (None, (0..n).map(|k| (value(k), self.extensive[k])).collect()),
            Some(_) if n == 1 => (None, (0..block.len().max(1)).map(|r| (value(r), self.extensive[0])).collect()),
            Some(_) => (None, Vec::new()),
        };
    }

    /// Opens the file with LAMMPS's heading lines at the first block, then appends the
    /// block and flushes.
    fn write_block(&mut self, step: u64, nrow: usize, block: &[f64], norm: f64) -> std::io::Result<()> {
        let Some(file) = &self.file else { return Ok(()) };
        let mut text = String::new();
        if self.out.is_none() {
            self.out = Some(BufWriter::new(File::create(file)?));
            let names = self.names.join(" ");
            let mut defaults = vec![format!("# Time-averaged data for fix {}", self.id)];
            match self.rows {
                None => defaults.push(format!("# TimeStep {names}")),
                Some(_) => defaults.extend(["# TimeStep Number-of-rows".to_string(), format!("# Row {names}")]),
            }
            for (title, default) in self.titles.iter().zip(defaults) {
                text += title.as_ref().unwrap_or(&default);
                text.push('\n');
            }
        }
        let n = self.names.len();
        let value = |k: usize| gendpde_io::format_printf(&self.format, block[k] / norm).map_err(std::io::Error::other);
        match self.rows {
            None => {
                text += &step.to_string();
                for k in 0..n {
                    text += &value(k)?;
                }
                text.push('\n');
            }
            Some(_) => {
                text += &format!("{step} {nrow}\n");
                for r in 0..nrow {
                    text += &(r + 1).to_string();
                    for k in 0..n {
                        text += &value(r * n + k)?;
                    }
                    text.push('\n');
                }
            }
        }
        let out = self.out.as_mut().expect("opened above");
        out.write_all(text.as_bytes())?;
        out.flush()
    }
}

impl OutputFix for AveTime {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "ave/time"
    }
    fn published(&self) -> Option<&FixValues> {
        Some(&self.published)
    }
    fn rdfs(&self) -> Vec<&str> {
        self.rows.iter().flatten().filter_map(|r| if let Rows::Rdf(id, _) = r { Some(id.as_str()) } else { None }).collect()
    }
}

impl RunOutput for AveTime {
    /// The next sample (LAMMPS's nvalid).
    fn next_step(&self, _step: u64, _run: Span) -> Option<u64> {
        Some(self.sampling.next)
    }

    /// Adds a sample and writes and publishes a block when it is complete. A failure on
    /// rank 0 stops all ranks.
    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let (one, nrow) = self.sample(f)?;
        if self.sampling.samples == 0 || self.sums.len() != one.len() {
            self.sums = vec![0.0; one.len()];
        }
        let n = self.names.len();
        for (k, (s, x)) in self.sums.iter_mut().zip(&one).enumerate() {
            // an `off` value keeps its last sample (times Nrepeat: the block divides)
            *s = if self.off.contains(&(k % n)) { x * self.sampling.nrepeat as f64 } else { *s + x };
        }
        let step = f.sys.clock.step;
        if !self.sampling.sample(step, &format!("{} ave/time", self.id))? {
            return Ok(());
        }
        let repeat = self.sampling.nrepeat as f64;
        let block: Vec<f64> = self.sums.iter().map(|s| s / repeat).collect();
        let (total, norm) = self.blocks.combine(block);
        self.publish(&total, norm);
        let what = format!("fix {} ave/time: writing {}", self.id, self.file.as_deref().unwrap_or(""));
        write_on_rank0(f.sys, &what, || self.write_block(step, nrow, &total, norm))
    }
}
