//! `fix ID GROUP vector Nevery value [nmax N]`, as LAMMPS's for one value: the value (`c_ID`,
//! `c_ID[k]`, `f_ID`, `f_ID[k]`, `v_name` of an equal-style variable) every Nevery steps,
//! the set-up's step too and no step twice, appended to a global vector read as `f_ID[i]`
//! (i from 1, the first stored first). Several values (LAMMPS's global array `f_ID[i][j]`)
//! are refused.

use super::{OutputFix, OutputFixContext};
use crate::base::args::Args;
use crate::model::sim::FixValues;
use crate::output::schedule::{Frame, RunOutput, Span};
use crate::output::thermo::ThermoContext;
use gendpde_io::ScriptError;

pub struct Vector {
    id: String,
    every: u64,
    value: String,
    /// `nmax N`: the longest the vector grows (LAMMPS's default: no bound).
    nmax: Option<usize>,
    /// The last step stored.
    last: Option<u64>,
    published: FixValues,
}

impl Vector {
    pub fn parse(a: &mut Args, c: &OutputFixContext) -> Result<Self, ScriptError> {
        crate::base::groups::mask(&c.sim.groups, c.group, a)?;
        let every = match a.u64("Nevery")? {
            0 => return Err(a.err("Illegal fix vector command: Nevery must be positive")),
            n => n,
        };
        let value = a.word("a value")?.to_string();
        if !["c_", "f_", "v_"].iter().any(|p| value.starts_with(p)) {
            return Err(a.err(format!("Illegal fix vector command: value {value} (expected c_ID, c_ID[k], f_ID, f_ID[k] or v_name)")));
        }
        let mut nmax = None;
        while let Some(w) = a.peek() {
            a.word("a keyword")?;
            match w {
                "nmax" => nmax = Some(a.u64("nmax")? as usize),
                _ if ["c_", "f_", "v_"].iter().any(|p| w.starts_with(p)) => {
                    return Err(a.err("fix vector of several values (LAMMPS's global array f_ID[i][j]) is not supported: one fix vector per value"))
                }
                k => return Err(a.err(format!("Illegal fix vector command: unknown keyword {k}; known: nmax"))),
            }
        }
        let published = FixValues { freq: every, ..FixValues::default() };
        Ok(Self { id: c.id.clone(), every, value, nmax, last: None, published })
    }
}

impl OutputFix for Vector {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "vector"
    }
    fn published(&self) -> Option<&FixValues> {
        Some(&self.published)
    }
}

impl RunOutput for Vector {
    fn next_step(&self, step: u64, _run: Span) -> Option<u64> {
        let next = if self.last == Some(step) { step + 1 } else { step };
        Some(next.next_multiple_of(self.every))
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let mut thermo = f.thermo.clone();
        thermo.norm = false;
        let ctx = ThermoContext::new(f.sim, f.sys, &thermo, f.vars, 0, 0.0);
        let v = match ctx.keyword(&self.value) {
            Some(v) => v,
            None => gendpde_io::evaluate(&self.value, f.vars, &|n| ctx.keyword(n)).map_err(|e| format!("fix {} vector: {}: {e}", self.id, self.value))?,
        };
        if self.nmax.is_some_and(|n| self.published.vector.len() >= n) {
            return Err(format!("fix {} vector: Overflow of allocated fix vector storage (nmax {})", self.id, self.nmax.unwrap_or(0)));
        }
        self.published.vector.push((v, false));
        self.last = Some(f.sys.clock.step);
        Ok(())
    }
}
