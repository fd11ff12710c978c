//! `fix ID all ave/time Nevery Nrepeat Nfreq c_ID[k]|c_ID[*] ... file FILE mode vector
//! [ave one] [format F]`: the columns of compute rdf arrays averaged over Nrepeat samples
//! Nevery steps apart, one block every Nfreq steps, in LAMMPS's ave/time vector layout.
//! Rank 0 writes the file and flushes each block.

use crate::base::args::Args;
use crate::output::schedule::{Frame, RunOutput, Span};
use crate::styles::compute::rdf::{Rdf, COLUMNS};
use gendpde_io::ScriptError;
use std::fs::File;
use std::io::{BufWriter, Write};

pub struct AveTime {
    pub id: String,
    nevery: u64,
    nrepeat: u64,
    nfreq: u64,
    /// (compute ID, column from 0) of each value.
    columns: Vec<(String, usize)>,
    file: String,
    /// printf format of one value (LAMMPS's default " %g").
    format: String,
    /// The open file (rank 0, from the first block on).
    out: Option<BufWriter<File>>,
    /// Sum of the samples of the current block, row-major (rows x columns).
    sums: Vec<f64>,
    samples: u64,
    /// The next step to sample (LAMMPS's nvalid).
    next: u64,
}

impl AveTime {
    /// The words after `fix ID all ave/time`; `rdfs` are the computes defined so far and
    /// `step` the current step.
    pub fn parse(id: String, a: &mut Args, rdfs: &[Rdf], step: u64) -> Result<Self, ScriptError> {
        let nevery = a.u64("Nevery")?;
        let nrepeat = a.u64("Nrepeat")?;
        let nfreq = a.u64("Nfreq")?;
        if nevery == 0 || nrepeat == 0 || nfreq == 0 || nfreq % nevery != 0 || (nrepeat - 1).saturating_mul(nevery) >= nfreq {
            return Err(a.err(format!(
                "Nevery {nevery}, Nrepeat {nrepeat}, Nfreq {nfreq}: all must be positive, Nfreq a multiple of Nevery and (Nrepeat - 1) Nevery < Nfreq"
            )));
        }
        let (mut columns, mut nbin) = (Vec::new(), None);
        while let Some(v) = a.peek().filter(|w| w.starts_with("c_")) {
            a.word("a value")?;
            let (cid, k) = v[2..].strip_suffix(']').and_then(|r| r.split_once('[')).ok_or_else(|| a.err(format!("value '{v}': expected c_ID[k] or c_ID[*] of a compute rdf")))?;
            let rdf = rdfs.iter().find(|r| r.id == cid).ok_or_else(|| a.err(format!("value '{v}': no compute rdf with ID '{cid}'")))?;
            if *nbin.get_or_insert(rdf.nbin) != rdf.nbin {
                return Err(a.err(format!("value '{v}': the computes of one fix ave/time need the same number of bins")));
            }
            let ks: Vec<usize> = match k {
                "*" => (1..=COLUMNS).collect(),
                k => match k.parse::<usize>() {
                    Ok(k) if (1..=COLUMNS).contains(&k) => vec![k],
                    _ => return Err(a.err(format!("value '{v}': the column must be 1..{COLUMNS} or *"))),
                },
            };
            columns.extend(ks.into_iter().map(|k| (cid.to_string(), k - 1)));
        }
        if columns.is_empty() {
            return Err(a.err(format!("expected values c_ID[k] or c_ID[*] of a compute rdf, got {}", a.peek().map_or("nothing".into(), |w| format!("'{w}'")))));
        }
        let (mut file, mut vector, mut format) = (None, false, " %g".to_string());
        while a.remaining() > 0 {
            match a.word("a keyword")? {
                "file" => file = Some(a.word("a file name")?.to_string()),
                "mode" => match a.word("vector")? {
                    "vector" => vector = true,
                    m => return Err(a.err(format!("mode {m}: only mode vector is supported"))),
                },
                "ave" => match a.word("one")? {
                    "one" => {}
                    m => return Err(a.err(format!("ave {m}: only ave one is supported"))),
                },
                "format" => {
                    format = a.word("a printf format such as ' %.10g'")?.to_string();
                    gendpde_io::format_printf(&format, 1.0).map_err(|e| a.err(format!("bad format: {e}")))?;
                }
                k => return Err(a.err(format!("unknown keyword '{k}'; known: file, mode, ave, format"))),
            }
        }
        let file = file.ok_or_else(|| a.err("missing keyword: file FILE"))?;
        if !vector {
            return Err(a.err("missing keyword: mode vector (mode scalar is not supported)"));
        }
        let mut fix = Self { id, nevery, nrepeat, nfreq, columns, file, format, out: None, sums: Vec::new(), samples: 0, next: 0 };
        fix.next = fix.next_block(step);
        Ok(fix)
    }

    /// IDs of the computes the fix reads.
    pub fn computes(&self) -> impl Iterator<Item = &str> {
        self.columns.iter().map(|c| c.0.as_str())
    }

    /// The first sample of the next block at or after `step` (LAMMPS's nextvalid).
    fn next_block(&self, step: u64) -> u64 {
        let end = (step / self.nfreq) * self.nfreq + self.nfreq;
        let mut first = if end - self.nfreq == step && self.nrepeat == 1 { step } else { end - (self.nrepeat - 1) * self.nevery };
        if first < step {
            first += self.nfreq;
        }
        first
    }

    /// Opens the file (with LAMMPS's three heading lines) at the first block, then
    /// appends `step nrow` and the averaged rows, and flushes.
    fn write_block(&mut self, step: u64, nrow: usize) -> std::io::Result<()> {
        let ncol = self.columns.len();
        let mut text = String::new();
        if self.out.is_none() {
            self.out = Some(BufWriter::new(File::create(&self.file)?));
            let names: Vec<String> = self.columns.iter().map(|(id, k)| format!("c_{id}[{}]", k + 1)).collect();
            text += &format!("# Time-averaged data for fix {}\n# TimeStep Number-of-rows\n# Row {}\n", self.id, names.join(" "));
        }
        text += &format!("{step} {nrow}\n");
        for r in 0..nrow {
            text += &(r + 1).to_string();
            for c in 0..ncol {
                let v = self.sums[r * ncol + c] / self.nrepeat as f64;
                text += &gendpde_io::format_printf(&self.format, v).map_err(std::io::Error::other)?;
            }
            text.push('\n');
        }
        let out = self.out.as_mut().expect("opened above");
        out.write_all(text.as_bytes())?;
        out.flush()
    }
}

impl RunOutput for AveTime {
    /// The next sample (LAMMPS's nvalid).
    fn next_step(&self, _step: u64, _run: Span) -> Option<u64> {
        Some(self.next)
    }

    /// Adds a sample and writes a block when it is complete. A failure on rank 0 stops
    /// all ranks.
    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let (sys, rdfs, pair, skin) = (f.sys, &f.sim.rdfs, f.sim.pair.as_ref(), f.sim.skin);
        if sys.step > self.next {
            return Err(format!("fix {} ave/time: step {} lies past the next sample {} (reset_timestep?)", self.id, sys.step, self.next));
        }
        // each compute once per sample
        let mut tables: Vec<(&str, Vec<[f64; COLUMNS]>)> = Vec::new();
        for id in self.computes() {
            let rdf = rdfs.iter().find(|r| r.id == id).ok_or_else(|| format!("fix {} ave/time: compute rdf '{id}' no longer exists", self.id))?;
            if tables.iter().all(|t| t.0 != rdf.id) {
                let rc = rdf.cutoff_for(pair).ok_or_else(|| format!("compute {id} rdf needs a pair style or the cutoff keyword"))?;
                tables.push((&rdf.id, rdf.rows(sys, rc, rc + skin)?));
            }
        }
        let ncol = self.columns.len();
        let nrow = tables[0].1.len();
        if self.samples == 0 {
            self.sums = vec![0.0; nrow * ncol];
        }
        for (c, (id, k)) in self.columns.iter().enumerate() {
            let rows = &tables.iter().find(|t| t.0 == id).expect("table computed above").1;
            for (r, row) in rows.iter().enumerate() {
                self.sums[r * ncol + c] += row[*k];
            }
        }
        self.samples += 1;
        if self.samples < self.nrepeat {
            self.next += self.nevery;
            return Ok(());
        }
        let written = if sys.comm.rank() == 0 { self.write_block(sys.step, nrow).map_err(|e| format!("fix {} ave/time: writing {}: {e}", self.id, self.file)) } else { Ok(()) };
        self.samples = 0;
        self.next = sys.step + self.nfreq - (self.nrepeat - 1) * self.nevery;
        match (sys.comm.any(written.is_err()), written) {
            (true, Ok(())) => Err(format!("fix {} ave/time: writing {} failed on rank 0", self.id, self.file)),
            (_, result) => result,
        }
    }
}
