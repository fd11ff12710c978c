//! `fix ID all ave/time Nevery Nrepeat Nfreq c_ID[k]|c_ID[*] ... file FILE mode vector
//! [ave one] [format F]`: the columns of compute rdf arrays averaged over Nrepeat samples
//! Nevery steps apart, one block every Nfreq steps, in LAMMPS's ave/time vector layout.
//! Rank 0 writes the file and flushes each block.

use crate::base::args::Args;
use crate::output::schedule::{write_on_rank0, Frame, RunOutput, Sampling, Span};
use crate::styles::compute::rdf::{Rdf, COLUMNS};
use gendpde_io::ScriptError;
use std::fs::File;
use std::io::{BufWriter, Write};

pub struct AveTime {
    pub id: String,
    sampling: Sampling,
    /// (compute ID, column from 0) of each value.
    columns: Vec<(String, usize)>,
    file: String,
    /// printf format of one value (LAMMPS's default " %g").
    format: String,
    /// The open file (rank 0, from the first block on).
    out: Option<BufWriter<File>>,
    /// Sum of the samples of the current block, row-major (rows x columns).
    sums: Vec<f64>,
}

impl AveTime {
    /// The words after `fix ID all ave/time`; `rdfs` are the computes defined so far and
    /// `step` the current step.
    pub fn parse(id: String, a: &mut Args, rdfs: &[Rdf], step: u64) -> Result<Self, ScriptError> {
        let sampling = Sampling::parse(a, step)?;
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
        Ok(Self { id, sampling, columns, file, format, out: None, sums: Vec::new() })
    }

    /// IDs of the computes the fix reads.
    pub fn computes(&self) -> impl Iterator<Item = &str> {
        self.columns.iter().map(|c| c.0.as_str())
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
                let v = self.sums[r * ncol + c] / self.sampling.nrepeat as f64;
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
        Some(self.sampling.next)
    }

    /// Adds a sample and writes a block when it is complete. A failure on rank 0 stops
    /// all ranks.
    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let (sys, rdfs, skin) = (f.sys, &f.sim.rdfs, f.sim.skin);
        // each compute once per sample
        let mut tables: Vec<(&str, Vec<[f64; COLUMNS]>)> = Vec::new();
        for id in self.computes() {
            let rdf = rdfs.iter().find(|r| r.id == id).ok_or_else(|| format!("fix {} ave/time: compute rdf '{id}' no longer exists", self.id))?;
            if tables.iter().all(|t| t.0 != rdf.id) {
                let rc = rdf.cutoff_for(sys.lists.cutoff);
                tables.push((&rdf.id, rdf.rows(sys, rc, rc + skin)?));
            }
        }
        let ncol = self.columns.len();
        let nrow = tables[0].1.len();
        if self.sampling.samples == 0 {
            self.sums = vec![0.0; nrow * ncol];
        }
        for (c, (id, k)) in self.columns.iter().enumerate() {
            let rows = &tables.iter().find(|t| t.0 == id).expect("table computed above").1;
            for (r, row) in rows.iter().enumerate() {
                self.sums[r * ncol + c] += row[*k];
            }
        }
        if !self.sampling.sample(sys.clock.step, &format!("{} ave/time", self.id))? {
            return Ok(());
        }
        let what = format!("fix {} ave/time: writing {}", self.id, self.file);
        write_on_rank0(sys, &what, || self.write_block(sys.clock.step, nrow))
    }
}
