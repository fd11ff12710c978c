//! `fix ID GROUP ave/histo Nevery Nrepeat Nfreq lo hi Nbin value ... [mode scalar|vector]
//! [ave one|running|window M] [start N] [beyond ignore|end|extra] [file F] [title1|2|3
//! T]`, as LAMMPS's: histograms of values over Nbin bins between lo and hi, the counts of
//! Nrepeat samples Nevery steps apart summed into one block every Nfreq steps.
//!
//! Mode scalar: global scalars (`c_ID`, `c_ID[k]`, `f_ID`, `f_ID[k]`, `v_name`). Mode
//! vector: global vectors (`c_ID` of a compute with one) and per-atom values of the
//! group's particles (`x y z vx vy vz fx fy fz`, `c_ID`, `c_ID[k]` of per-atom
//! computes, `v_name` of atom-style variables). Values beyond lo..hi are missing (beyond
//! ignore), counted in the end bins (end) or in two extra bins (extra). Publishes the
//! vector (total count, missing count, min, max) as `f_ID[1..4]`; the file holds a line
//! per bin: bin, coordinate, count, count / total. Counts are integers and extremes
//! exact, so nothing depends on the rank count.

use super::blocks::Blocks;
use super::{OutputFix, OutputFixContext};
use crate::base::args::Args;
use crate::base::groups;
use crate::model::per_atom;
use crate::model::sim::FixValues;
use crate::output::schedule::{write_on_rank0, Frame, RunOutput, Sampling, Span};
use crate::output::thermo::ThermoContext;
use crate::styles::compute::{self, Shape};
use gendpde_engine::exact_column_sums;
use gendpde_io::{format_shortest, ScriptError};
use std::collections::VecDeque;
use std::fs::File;
use std::io::{BufWriter, Write};

/// LAMMPS's extremes of no values.
const BIG: f64 = 1.0e20;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Beyond {
    Ignore,
    End,
    Extra,
}

/// The kind of the inputs (LAMMPS: all values of one fix are of one kind).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Global,
    PerAtom,
}

pub struct AveHisto {
    id: String,
    mask: u32,
    sampling: Sampling,
    values: Vec<String>,
    kind: Kind,
    /// Mode vector (global values: the elements of vectors).
    vector: bool,
    lo: f64,
    hi: f64,
    /// Bins, the two extra ones included.
    nbins: usize,
    beyond: Beyond,
    blocks: Blocks,
    /// How many blocks the extremes combine (1, the window, or all).
    span: usize,
    file: Option<String>,
    titles: [Option<String>; 3],
    out: Option<BufWriter<File>>,
    /// This block so far: total, missing, then the bins; and min, max.
    counts: Vec<f64>,
    extremes: [f64; 2],
    /// The extremes of the blocks the combination holds.
    history: VecDeque<[f64; 2]>,
    published: FixValues,
}

impl AveHisto {
    pub fn parse(a: &mut Args, c: &OutputFixContext) -> Result<Self, ScriptError> {
        let mask = groups::mask(&c.sim.groups, c.group, a)?;
        let sampling = Sampling::parse(a, c.step)?;
        let lo = a.f64("lo")?;
        let hi = a.f64("hi")?;
        let nbin = a.u64("Nbin")?;
        if nbin == 0 || lo >= hi {
            return Err(a.err("Illegal fix ave/histo command: Nbin must be positive and lo < hi"));
        }
        let mut values = Vec::new();
        while let Some(w) = a.peek().filter(|w| is_per_atom_keyword(w) || ["c_", "f_", "v_"].iter().any(|p| w.starts_with(p))) {
            values.push(w.to_string());
            a.word("a value")?;
        }
        if values.is_empty() {
            return Err(a.err("Illegal fix ave/histo command: expected values"));
        }
        let (mut vector, mut blocks, mut start, mut beyond, mut file, mut titles) = (false, Blocks::default(), 0, Beyond::Ignore, None, [None, None, None]);
        while a.remaining() > 0 {
            match a.word("a keyword")? {
                "mode" => {
                    vector = match a.word("scalar or vector")? {
                        "scalar" => false,
                        "vector" => true,
                        m => return Err(a.err(format!("Illegal fix ave/histo command: mode {m} (expected scalar or vector)"))),
                    }
                }
                "ave" => blocks = Blocks::parse(a)?,
                "start" => start = a.u64("the start step")?,
                "beyond" => {
                    beyond = match a.word("ignore, end or extra")? {
                        "ignore" => Beyond::Ignore,
                        "end" => Beyond::End,
                        "extra" => Beyond::Extra,
                        b => return Err(a.err(format!("Illegal fix ave/histo command: beyond {b} (expected ignore, end or extra)"))),
                    }
                }
                "file" => file = Some(a.word("a file name")?.to_string()),
                t @ ("title1" | "title2" | "title3") => titles[usize::from(t.as_bytes()[5] - b'1')] = Some(a.word("a title")?.to_string()),
                k @ ("overwrite" | "kind") => return Err(a.err(format!("fix ave/histo: keyword {k} is not supported"))),
                k => return Err(a.err(format!("Unknown fix ave/histo keyword {k}; known: mode, ave, start, beyond, file, title1, title2, title3"))),
            }
        }
        let mut kinds = Vec::new();
        for w in &values {
            kinds.push(value_kind(w, vector, c).map_err(|m| a.err(m))?);
        }
        let kind = kinds[0];
        if kinds.iter().any(|&k| k != kind) {
            return Err(a.err("Fix ave/histo input kind is invalid: the values must be all global or all per-atom"));
        }
        let nbins = nbin as usize + if beyond == Beyond::Extra { 2 } else { 0 };
        let span = blocks.span();
        let published = FixValues { vector: vec![(0.0, false); 4], freq: sampling.nfreq, ..FixValues::default() };
        let mut fix = Self {
            id: c.id.clone(),
            mask,
            sampling,
            values,
            kind,
            vector,
            lo,
            hi,
            nbins,
            beyond,
            blocks,
            span,
            file,
            titles,
            out: None,
            counts: Vec::new(),
            extremes: [BIG, -BIG],
            history: VecDeque::new(),
            published,
        };
        fix.sampling.start_at(c.step, start);
        Ok(fix)
    }

    /// The bin centres (the extra bins at lo and hi).
    fn coords(&self) -> Vec<f64> {
        let n = self.nbins - if self.beyond == Beyond::Extra { 2 } else { 0 };
        let size = (self.hi - self.lo) / n as f64;
        let centres = (0..n).map(|i| self.lo + size * (i as f64 + 0.5));
        match self.beyond {
            Beyond::Extra => std::iter::once(self.lo).chain(centres).chain(std::iter::once(self.hi)).collect(),
            _ => centres.collect(),
        }
    }

    /// The counts column (0 total, 1 missing, 2.. the bins) of `value`, or None; LAMMPS's
    /// bin_one.
    fn bin(&self, value: f64) -> Option<usize> {
        let inner = self.nbins - if self.beyond == Beyond::Extra { 2 } else { 0 };
        let bin = if value < self.lo {
            match self.beyond {
                Beyond::Ignore => return None,
                _ => 0,
            }
        } else if value > self.hi {
            match self.beyond {
                Beyond::Ignore => return None,
                _ => self.nbins - 1,
            }
        } else {
            let k = (((value - self.lo) * inner as f64 / (self.hi - self.lo)) as usize).min(inner - 1);
            k + usize::from(self.beyond == Beyond::Extra)
        };
        Some(2 + bin)
    }

    /// The values of one sample on this rank (per-atom: the group's owned particles);
    /// collective.
    fn sample(&self, f: &Frame) -> Result<Vec<f64>, String> {
        let (sim, sys) = (f.sim, f.sys);
        let mut thermo = f.thermo.clone();
        thermo.norm = false;
        let ctx = ThermoContext::new(sim, sys, &thermo, f.vars, 0, 0.0);
        let global = |n: &str| ctx.keyword(n);
        let mut all = Vec::new();
        for w in &self.values {
            let what = |e: String| format!("fix {} ave/histo: {w}: {e}", self.id);
            match self.kind {
                Kind::PerAtom => {
                    let values = per_atom::input(sim, sys, f.vars, &global, w).map_err(what)?;
                    let s = &sys.store;
                    all.extend(values.into_iter().enumerate().filter(|&(i, _)| s.in_group(i, self.mask)).map(|(_, v)| v));
                }
                Kind::Global if self.vector => {
                    let (_, id, _) = compute::reference(w).expect("checked at parse");
                    let c = compute::find(&sim.computes, id).ok_or_else(|| what("the compute no longer exists".into()))?;
                    all.extend(per_atom::evaluate(sim, sys, f.vars, &global, |e| c.vector(e)).map_err(what)?);
                }
                Kind::Global => all.push(match ctx.keyword(w) {
                    Some(v) => v,
                    None => gendpde_io::evaluate(w, f.vars, &global).map_err(what)?,
                }),
            }
        }
        Ok(all)
    }

    fn write_block(&mut self, step: u64, counts: &[f64], extremes: [f64; 2]) -> std::io::Result<()> {
        let Some(file) = &self.file else { return Ok(()) };
        let mut text = String::new();
        if self.out.is_none() {
            self.out = Some(BufWriter::new(File::create(file)?));
            let defaults = [
                format!("# Histogrammed data for fix {}", self.id),
                "# TimeStep Number-of-bins Total-counts Missing-counts Min-value Max-value".to_string(),
                "# Bin Coord Count Count/Total".to_string(),
            ];
            for (title, default) in self.titles.iter().zip(defaults) {
                text += title.as_ref().unwrap_or(&default);
                text.push('\n');
            }
        }
        let [total, missing] = [counts[0], counts[1]];
        let shown = [total, missing, extremes[0], extremes[1]].map(format_shortest);
        text += &format!("{step} {} {}\n", self.nbins, shown.join(" "));
        let g = |x: f64| gendpde_io::format_g(x, 6);
        for (i, x) in self.coords().into_iter().enumerate() {
            let count = counts[2 + i];
            let fraction = if total != 0.0 { count / total } else { 0.0 };
            text += &format!("{} {} {} {}\n", i + 1, g(x), g(count), g(fraction));
        }
        let out = self.out.as_mut().expect("opened above");
        out.write_all(text.as_bytes())?;
        out.flush()
    }
}

/// Whether `w` is a per-atom keyword fix ave/histo takes.
fn is_per_atom_keyword(w: &str) -> bool {
    matches!(w, "x" | "y" | "z" | "vx" | "vy" | "vz" | "fx" | "fy" | "fz")
}

/// Whether value `w` is global or per-atom (LAMMPS's messages when it is neither).
fn value_kind(w: &str, vector: bool, c: &OutputFixContext) -> Result<Kind, String> {
    if is_per_atom_keyword(w) {
        return if vector { Ok(Kind::PerAtom) } else { Err("fix ave/histo cannot process per-atom values in scalar mode".into()) };
    }
    let (kind, id, index) = compute::reference(w).ok_or_else(|| format!("Invalid fix ave/histo argument: {w}"))?;
    let sim = c.sim;
    let shape = match kind {
        'c' => compute::find(&sim.computes, id).ok_or_else(|| format!("Compute ID {id} for fix ave/histo does not exist"))?.shape(),
        'f' => {
            let v = sim.fix_values.get(id).ok_or_else(|| format!("Fix ID {id} for fix ave/histo does not exist or publishes no global values"))?;
            Shape { scalar: v.scalar.is_some(), vector: v.vector.len(), ..Shape::default() }
        }
        _ => match c.vars.style(id) {
            Some("equal" | "internal") => Shape { scalar: true, ..Shape::default() },
            Some("atom") => Shape { per_atom: Some(0), ..Shape::default() },
            Some(style) => return Err(format!("Fix ave/histo variable {id} is {style}-style")),
            None => return Err(format!("Variable name {id} for fix ave/histo does not exist")),
        },
    };
    match (vector, index) {
        (false, None) if shape.scalar => Ok(Kind::Global),
        (false, Some(k)) if k >= 1 && k <= shape.vector => Ok(Kind::Global),
        (false, _) if shape.per_atom.is_some() => Err("fix ave/histo cannot process per-atom values in scalar mode".into()),
        (true, None) if shape.per_atom == Some(0) => Ok(Kind::PerAtom),
        (true, Some(k)) if shape.per_atom.is_some_and(|n| k >= 1 && k <= n) => Ok(Kind::PerAtom),
        (true, None) if shape.vector > 0 && kind == 'c' => Ok(Kind::Global),
        _ => Err(format!("Fix ave/histo value {w} does not calculate what mode {} takes", if vector { "vector" } else { "scalar" })),
    }
}

impl OutputFix for AveHisto {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "ave/histo"
    }
    fn published(&self) -> Option<&FixValues> {
        Some(&self.published)
    }
}

impl RunOutput for AveHisto {
    fn next_step(&self, _step: u64, _run: Span) -> Option<u64> {
        Some(self.sampling.next)
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        if self.sampling.samples == 0 {
            self.counts = vec![0.0; 2 + self.nbins];
            self.extremes = [BIG, -BIG];
        }
        for v in self.sample(f)? {
            self.extremes = [self.extremes[0].min(v), self.extremes[1].max(v)];
            match self.bin(v) {
                Some(k) => {
                    self.counts[k] += 1.0;
                    self.counts[0] += 1.0;
                }
                None => self.counts[1] += 1.0,
            }
        }
        let step = f.sys.clock.step;
        if !self.sampling.sample(step, &format!("{} ave/histo", self.id))? {
            return Ok(());
        }
        let t = f.sys.comm.transport();
        let (counts, extremes) = match self.kind {
            // integer counts: exact sums; extremes: exact
            Kind::PerAtom => {
                let counts = exact_column_sums(t, self.counts.len(), self.counts.iter().copied().enumerate());
                let mut m = [-self.extremes[0], self.extremes[1]];
                t.max(&mut m);
                (counts, [-m[0], m[1]])
            }
            Kind::Global => (self.counts.clone(), self.extremes),
        };
        let (total, _) = self.blocks.combine(counts);
        self.history.push_back(extremes);
        if self.history.len() > self.span {
            self.history.pop_front();
        }
        // LAMMPS's running extremes start from 0 (its stats_total)
        let start = if self.span == usize::MAX { [0.0, 0.0] } else { [BIG, -BIG] };
        let extremes = self.history.iter().fold(start, |m, e| [m[0].min(e[0]), m[1].max(e[1])]);
        if self.span == usize::MAX {
            self.history = VecDeque::from([extremes]);
        }
        self.published.vector = vec![(total[0], false), (total[1], false), (extremes[0], false), (extremes[1], false)];
        let what = format!("fix {} ave/histo: writing {}", self.id, self.file.as_deref().unwrap_or(""));
        write_on_rank0(f.sys, &what, || self.write_block(step, &total, extremes))
    }
}
