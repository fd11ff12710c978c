//! `fix ID GROUP ave/chunk Nevery Nrepeat Nfreq CHUNKID value ... [norm all|sample|none]
//! [ave one|running|window M] [adof A] [cdof C] [file FILE] [format F] [title1|2|3 T]`:
//! per-chunk averages of density/number, density/mass, temp, vx vy vz, fx fy fz and
//! per-atom computes c_ID over the bins of a compute chunk/atom, in LAMMPS's fix
//! ave/chunk file layout and arithmetic.
//!
//! Each sample sums the particles of each bin with exact sums (integer counts), so the
//! file does not depend on the number of ranks; rank 0 writes it and flushes each block.

use crate::base::args::Args;
use crate::base::groups;
use crate::base::units::Units;
use crate::model::per_atom;
use crate::output::thermo::ThermoContext;
use super::blocks::Blocks;
use super::{OutputFix, OutputFixContext};
use crate::output::schedule::{write_on_rank0, Frame, RunOutput, Sampling, Span};
use crate::styles::compute::chunk::ChunkAtom;
use crate::styles::compute;
use gendpde_engine::exact_column_sums;
use gendpde_integrators::System;
use gendpde_io::ScriptError;
use std::fs::File;
use std::io::{BufWriter, Write};

/// A per-particle quantity averaged per chunk.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Value {
    DensityNumber,
    DensityMass,
    Temp,
    Velocity(usize),
    Force(usize),
    /// `c_ID`, `c_ID[k]` of a per-atom compute or `v_name` of an atom-style variable: the
    /// input of this index among [`AveChunk::variables`].
    PerAtom(usize),
}

impl Value {
    /// Its term for particle `i` of `sys`: 1, m, m v^2, v_k, f_k or the per-atom input's
    /// value (`variables`: each input's values per owned particle).
    fn term(self, sys: &System, i: usize, variables: &[Vec<f64>]) -> f64 {
        let s = &sys.store;
        match self {
            Self::PerAtom(k) => variables[k][i],
            Self::DensityNumber => 1.0,
            Self::DensityMass => s.mass[i],
            Self::Temp => s.p[i].iter().map(|p| p * p).sum::<f64>() / s.mass[i],
            Self::Velocity(k) => s.p[i][k] / s.mass[i],
            Self::Force(k) => s.f[i][k],
        }
    }
}

/// How a block is normalised (LAMMPS's normflag; `none` is its SAMPLE with NOSCALE).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Norm {
    All,
    Sample,
    None,
}

/// A block's counts and values, one row per chunk (`1 + nvalues` columns: count first).
type Block = Vec<f64>;

pub struct AveChunk {
    id: String,
    group: String,
    mask: u32,
    chunk: String,
    sampling: Sampling,
    /// The value words as given (the file's third heading line).
    names: Vec<String>,
    values: Vec<Value>,
    /// The atom-style variables of `v_name` values.
    variables: Vec<String>,
    norm: Norm,
    blocks: Blocks,
    adof: f64,
    cdof: f64,
    file: Option<String>,
    format: String,
    titles: [Option<String>; 3],
    /// The open file (rank 0, from the first block on).
    out: Option<BufWriter<File>>,
    /// Chunks of the current block (fixed at its first sample, as LAMMPS locks them).
    nchunk: usize,
    /// Sums of the samples of the current block.
    many: Block,
}

impl AveChunk {
    /// The words after `fix ID GROUP ave/chunk` (the chunk/atom and per-atom computes
    /// defined so far are the context's).
    pub fn parse(a: &mut Args, c: &OutputFixContext) -> Result<Self, ScriptError> {
        let (id, group, chunks, computes) = (c.id.clone(), c.group, &c.sim.chunks, &c.sim.computes);
        let mask = groups::mask(&c.sim.groups, group, a)?;
        let sampling = Sampling::parse(a, c.step)?;
        let chunk = a.word("a compute chunk/atom ID")?.to_string();
        if !chunks.iter().any(|c| c.id == chunk) {
            return Err(a.err(format!("no compute chunk/atom with ID '{chunk}'")));
        }
        let (mut names, mut values, mut variables) = (Vec::new(), Vec::new(), Vec::new());
        while let Some(w) = a.peek() {
            let v = match w {
                "density/number" => Value::DensityNumber,
                "density/mass" => Value::DensityMass,
                "temp" => Value::Temp,
                "vx" | "vy" | "vz" => Value::Velocity(usize::from(w.as_bytes()[1] - b'x')),
                "fx" | "fy" | "fz" => Value::Force(usize::from(w.as_bytes()[1] - b'x')),
                _ if (w.starts_with("c_") && compute::check_per_atom(computes, w, "Fix ave/chunk").is_ok()) || (w.len() > 2 && w.starts_with("v_")) => {
                    variables.push(w.to_string());
                    Value::PerAtom(variables.len() - 1)
                }
                _ if w.starts_with("c_") || w.starts_with("f_") => {
                    return Err(a.err(format!("value '{w}': not a per-atom compute (per-atom fixes are not supported); values: density/number, density/mass, temp, vx, vy, vz, fx, fy, fz, c_ID, v_name")));
                }
                _ => break,
            };
            a.word("a value")?;
            names.push(w.to_string());
            values.push(v);
        }
        if values.is_empty() {
            return Err(a.err(format!("expected values (density/number, density/mass, temp, vx, vy, vz, fx, fy, fz), got {}", a.peek().map_or("nothing".into(), |w| format!("'{w}'")))));
        }
        let (mut norm, mut ave, mut adof, mut cdof) = (Norm::All, Blocks::default(), 3.0, 0.0);
        let (mut file, mut format, mut titles) = (None, " %g".to_string(), [None, None, None]);
        while a.remaining() > 0 {
            match a.word("a keyword")? {
                "norm" => {
                    norm = match a.word("all, sample or none")? {
                        "all" => Norm::All,
                        "sample" => Norm::Sample,
                        "none" => Norm::None,
                        n => return Err(a.err(format!("expected norm all, sample or none, got '{n}'"))),
                    }
                }
                "ave" => ave = Blocks::parse(a)?,
                "adof" => adof = a.f64("the degrees of freedom per particle")?,
                "cdof" => cdof = a.f64("the degrees of freedom per chunk")?,
                "file" => file = Some(a.word("a file name")?.to_string()),
                "format" => {
                    format = a.word("a printf format such as %.10g")?.to_string();
                    gendpde_io::format_printf(&format, 1.0).map_err(|e| a.err(format!("bad format: {e}")))?;
                }
                t @ ("title1" | "title2" | "title3") => titles[usize::from(t.as_bytes()[5] - b'1')] = Some(a.word("a title")?.to_string()),
                k => return Err(a.err(format!("unknown keyword '{k}'; known: norm, ave, adof, cdof, file, format, title1, title2, title3"))),
            }
        }
        Ok(Self { id, group: group.to_string(), mask, chunk, sampling, names, values, variables, norm, blocks: ave, adof, cdof, file, format, titles, out: None, nchunk: 0, many: Vec::new() })
    }

    /// The sums of one sample: count and values per chunk (exact over the ranks).
    fn sample(&self, chunk: &ChunkAtom, sys: &System, variables: &[Vec<f64>]) -> Result<Block, String> {
        let (d, s) = (&sys.domain, &sys.store);
        let bins = chunk.bins(d)?;
        if bins.nchunk() != self.nchunk {
            return Err(format!("fix {} ave/chunk: the box changed the number of chunks within a block ({} to {})", self.id, self.nchunk, bins.nchunk()));
        }
        let ncol = 1 + self.values.len();
        let members = (0..s.nlocal).filter(|&i| s.in_group(i, self.mask) && s.in_group(i, chunk.mask));
        let terms = members.flat_map(|i| {
            let row = chunk.chunk(&bins, d, s.r[i]) * ncol;
            std::iter::once((row, 1.0)).chain(self.values.iter().enumerate().map(move |(j, v)| (row + 1 + j, v.term(sys, i, variables))))
        });
        Ok(exact_column_sums(sys.comm.transport(), self.nchunk * ncol, terms))
    }

    /// Adds one sample to the block (LAMMPS's per-sample normalisation of norm sample and
    /// none). `volume` is the bin volume.
    fn add(&mut self, one: &[f64], units: &Units, volume: f64) {
        let ncol = 1 + self.values.len();
        for (sum, row) in self.many.chunks_exact_mut(ncol).zip(one.chunks_exact(ncol)) {
            let count = row[0];
            if self.norm == Norm::All {
                sum.iter_mut().zip(row).for_each(|(s, x)| *s += x);
                continue;
            }
            if count > 0.0 {
                for (j, v) in self.values.iter().enumerate() {
                    let x = row[1 + j];
                    sum[1 + j] += match v {
                        Value::Temp => units.mvv2e * x / ((self.cdof + self.adof * count) * units.kb),
                        Value::DensityNumber => x / volume,
                        Value::DensityMass => units.mv2d * (x / volume),
                        _ if self.norm == Norm::None => x,
                        _ => x / count,
                    };
                }
            }
            sum[0] += count;
        }
    }

    /// The averages of the completed block.
    fn finish(&self, units: &Units, volume: f64) -> Block {
        let (ncol, repeat) = (1 + self.values.len(), self.sampling.nrepeat as f64);
        let mut block = self.many.clone();
        for row in block.chunks_exact_mut(ncol) {
            let count = row[0];
            if self.norm != Norm::All {
                row.iter_mut().for_each(|x| *x /= repeat);
                continue;
            }
            if count > 0.0 {
                for (j, v) in self.values.iter().enumerate() {
                    let x = &mut row[1 + j];
                    match v {
                        Value::Temp => *x *= units.mvv2e / ((repeat * self.cdof + self.adof * count) * units.kb),
                        Value::DensityNumber => *x = *x / volume / repeat,
                        Value::DensityMass => *x = *x / volume * (units.mv2d / repeat),
                        _ => *x /= count,
                    }
                }
            }
            row[0] /= repeat;
        }
        block
    }

    /// Opens the file (with LAMMPS's three heading lines) at the first block, then
    /// appends `step nchunk total-count` and a row per chunk, and flushes.
    fn write_block(&mut self, step: u64, coords: &[Vec<f64>], total: &[f64], norm: f64) -> std::io::Result<()> {
        let Some(file) = &self.file else { return Ok(()) };
        let mut text = String::new();
        if self.out.is_none() {
            self.out = Some(BufWriter::new(File::create(file)?));
            let ncoord = coords.first().map_or(0, Vec::len);
            let coord_names: String = (1..=ncoord).map(|k| format!(" Coord{k}")).collect();
            let defaults = [
                format!("# Chunk-averaged data for fix {} and group {}", self.id, self.group),
                "# Timestep Number-of-chunks Total-count".to_string(),
                format!("# Chunk{coord_names} Ncount {}", self.names.join(" ")),
            ];
            for (title, default) in self.titles.iter().zip(defaults) {
                text += title.as_ref().unwrap_or(&default);
                text.push('\n');
            }
        }
        let ncol = 1 + self.values.len();
        let count: f64 = total.chunks_exact(ncol).map(|r| r[0]).sum();
        text += &format!("{step} {} {count}\n", coords.len());
        let g = |x: f64| gendpde_io::format_printf("%g", x).map_err(std::io::Error::other);
        for (m, (c, row)) in coords.iter().zip(total.chunks_exact(ncol)).enumerate() {
            text += &format!("  {}", m + 1);
            for x in c {
                text += &format!(" {}", g(*x)?);
            }
            text += &format!(" {}", g(row[0] / norm)?);
            for x in &row[1..] {
                text += &gendpde_io::format_printf(&self.format, x / norm).map_err(std::io::Error::other)?;
            }
            text.push('\n');
        }
        let out = self.out.as_mut().expect("opened above");
        out.write_all(text.as_bytes())?;
        out.flush()
    }
}

impl OutputFix for AveChunk {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "ave/chunk"
    }
}

impl RunOutput for AveChunk {
    /// The next sample (LAMMPS's nvalid).
    fn next_step(&self, _step: u64, _run: Span) -> Option<u64> {
        Some(self.sampling.next)
    }

    /// Adds a sample and writes a block when it is complete. A failure on rank 0 stops
    /// all ranks.
    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let (sys, units) = (f.sys, &f.sim.units);
        let chunk = f.sim.chunks.iter().find(|c| c.id == self.chunk).ok_or_else(|| format!("fix {} ave/chunk: compute chunk/atom '{}' no longer exists", self.id, self.chunk))?;
        let bins = chunk.bins(&sys.domain)?;
        if self.sampling.samples == 0 {
            self.nchunk = bins.nchunk();
            self.many = vec![0.0; self.nchunk * (1 + self.values.len())];
        }
        let context = ThermoContext::new(f.sim, sys, f.thermo, f.vars, 0, 0.0);
        let variables: Vec<Vec<f64>> = self
            .variables
            .iter()
            .map(|v| per_atom::input(f.sim, sys, f.vars, &|n| context.keyword(n), v).map_err(|e| format!("fix {} ave/chunk: {v}: {e}", self.id)))
            .collect::<Result<_, _>>()?;
        let one = self.sample(chunk, sys, &variables)?;
        self.add(&one, units, bins.volume);
        if !self.sampling.sample(sys.clock.step, &format!("{} ave/chunk", self.id))? {
            return Ok(());
        }
        let block = self.finish(units, bins.volume);
        let (total, norm) = self.blocks.combine(block);
        let what = format!("fix {} ave/chunk: writing {}", self.id, self.file.as_deref().unwrap_or(""));
        write_on_rank0(sys, &what, || self.write_block(sys.clock.step, &bins.coords, &total, norm))
    }
}
