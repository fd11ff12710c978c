//! `fix ID GROUP ave/atom Nevery Nrepeat Nfreq value ...`, as LAMMPS's: per-atom values
//! (`x y z vx vy vz fx fy fz`, `c_ID`, `c_ID[k]` of per-atom computes, `f_ID`, `f_ID[k]`
//! of per-atom fixes, `v_name` of atom-style variables) averaged over Nrepeat samples
//! Nevery steps apart, renewed every Nfreq steps and read as the per-atom `f_ID` (one
//! value) or `f_ID[k]` by dumps and other fix ave/atom (compute reduce, fix ave/chunk
//! and fix ave/histo do not take `f_` inputs yet); 0 outside the group and before the
//! first block.
//!
//! The sums are held by tag on every rank: each sample's values of the owned particles
//! are merged over the ranks (each tag has one owner) and added in sample order, so a
//! particle moving between ranks within a block keeps its sum and nothing depends on the
//! rank count. A sample costs one reduction of (largest tag) x (values) doubles.

use super::{OutputFix, OutputFixContext};
use crate::base::args::Args;
use crate::base::groups;
use crate::model::per_atom;
use crate::model::sim::FixValues;
use crate::output::schedule::{Frame, RunOutput, Sampling, Span};
use crate::output::thermo::ThermoContext;
use crate::styles::compute;
use gendpde_io::ScriptError;

pub struct AveAtom {
    id: String,
    mask: u32,
    sampling: Sampling,
    values: Vec<String>,
    /// Sum of the samples of the current block by tag - 1 and value.
    sums: Vec<f64>,
    published: FixValues,
}

impl AveAtom {
    pub fn parse(a: &mut Args, c: &OutputFixContext) -> Result<Self, ScriptError> {
        let mask = groups::mask(&c.sim.groups, c.group, a)?;
        let sampling = Sampling::parse(a, c.step)?;
        let mut values = Vec::new();
        while a.remaining() > 0 {
            let w = a.word("a value")?;
            let known = match w {
                "x" | "y" | "z" | "vx" | "vy" | "vz" | "fx" | "fy" | "fz" => true,
                _ if w.starts_with("c_") => {
                    compute::check_per_atom(&c.sim.computes, w, "Fix ave/atom").map_err(|m| a.err(m))?;
                    true
                }
                _ if w.starts_with("f_") => per_atom::fix_values(c.sim, w).is_some(),
                _ => w.strip_prefix("v_").is_some_and(|v| c.vars.style(v) == Some("atom")),
            };
            if !known {
                return Err(a.err(format!("Illegal fix ave/atom command: value {w} is not a per-atom keyword, per-atom compute or fix, or atom-style variable")));
            }
            values.push(w.to_string());
        }
        if values.is_empty() {
            return Err(a.err("Illegal fix ave/atom command: expected values"));
        }
        let ncol = values.len();
        let published = FixValues { per_atom: Some((ncol, vec![0.0; c.sim.max_tag as usize * ncol])), freq: sampling.nfreq, ..FixValues::default() };
        Ok(Self { id: c.id.clone(), mask, sampling, values, sums: Vec::new(), published })
    }
}

impl OutputFix for AveAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "ave/atom"
    }
    fn published(&self) -> Option<&FixValues> {
        Some(&self.published)
    }
}

impl RunOutput for AveAtom {
    fn next_step(&self, _step: u64, _run: Span) -> Option<u64> {
        Some(self.sampling.next)
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let (sim, sys) = (f.sim, f.sys);
        let s = &sys.store;
        let ncol = self.values.len();
        let len = sim.max_tag as usize * ncol;
        if self.sampling.samples == 0 || self.sums.len() != len {
            self.sums = vec![0.0; len];
        }
        let ctx = ThermoContext::new(sim, sys, f.thermo, f.vars, 0, 0.0);
        let mut sample = vec![f64::NEG_INFINITY; len];
        for (k, w) in self.values.iter().enumerate() {
            let values = per_atom::input(sim, sys, f.vars, &|n| ctx.keyword(n), w).map_err(|e| format!("fix {} ave/atom: {w}: {e}", self.id))?;
            for i in (0..s.nlocal).filter(|&i| s.in_group(i, self.mask)) {
                sample[(s.tag[i] as usize - 1) * ncol + k] = values[i];
            }
        }
        // one owner per tag: the maximum is its value
        sys.comm.transport().max(&mut sample);
        for (sum, x) in self.sums.iter_mut().zip(&sample) {
            if x.is_finite() {
                *sum += x;
            }
        }
        if !self.sampling.sample(sys.clock.step, &format!("{} ave/atom", self.id))? {
            return Ok(());
        }
        let repeat = self.sampling.nrepeat as f64;
        self.published.per_atom = Some((ncol, self.sums.iter().map(|x| x / repeat).collect()));
        Ok(())
    }
}
