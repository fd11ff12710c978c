//! `compute ID GROUP reduce MODE input ...` and `compute ID GROUP reduce/region RID MODE
//! input ...`: one global value per input, reduced over the group's particles (in the
//! region now, for reduce/region), as LAMMPS's compute reduce. Inputs: `x y z vx vy vz fx
//! fy fz`, `c_ID` of a per-atom compute, `c_ID[k]` of a per-atom array, `v_name` of an
//! atom-style variable. Modes: sum, sumsq, sumabs, min, max, ave, avesq, aveabs. One
//! input gives `c_ID`, several `c_ID[1]` ... (LAMMPS's scalar and vector; the sums are
//! extensive). Sums are exact and min/max are exact, so the values do not depend on the
//! rank count.

use super::{check_per_atom, Compute, ComputeContext, Eval, Shape};
use crate::base::args::Args;
use crate::base::region::Region;
use gendpde_engine::exact_column_sums;
use gendpde_io::ScriptError;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    Sum,
    SumSq,
    SumAbs,
    Min,
    Max,
    Ave,
    AveSq,
    AveAbs,
}

#[derive(Clone, Debug, PartialEq)]
enum Input {
    X(usize),
    V(usize),
    F(usize),
    /// `c_ID` or `c_ID[k]` of a per-atom compute, or `v_name` of an atom-style variable
    /// (checked when evaluated, as LAMMPS at init).
    PerAtom(String),
}

/// LAMMPS's value of min and max over no particles.
const BIG: f64 = 1.0e20;

#[derive(Debug)]
pub struct Reduce {
    id: String,
    mask: u32,
    /// reduce/region: only the particles in it.
    region: Option<Region>,
    mode: Mode,
    inputs: Vec<Input>,
}

impl Reduce {
    /// The words after `compute ID GROUP reduce` (`region`: reduce/region, whose region
    /// ID comes first).
    pub fn parse(a: &mut Args, c: &ComputeContext, region: bool) -> Result<Self, ScriptError> {
        let region = if region { Some(c.region(a, "reduce/region")?) } else { None };
        let mode = match a.word("a mode (sum, sumsq, sumabs, min, max, ave, avesq, aveabs)")? {
            "sum" => Mode::Sum,
            "sumsq" => Mode::SumSq,
            "sumabs" => Mode::SumAbs,
            "min" => Mode::Min,
            "max" => Mode::Max,
            "ave" => Mode::Ave,
            "avesq" => Mode::AveSq,
            "aveabs" => Mode::AveAbs,
            m => return Err(a.err(format!("mode '{m}': expected sum, sumsq, sumabs, min, max, ave, avesq or aveabs"))),
        };
        let mut inputs = Vec::new();
        while a.remaining() > 0 {
            let w = a.word("an input")?;
            let axis = |c: u8| usize::from(c - b'x');
            let input = match w.as_bytes() {
                [c @ b'x'..=b'z'] => Input::X(axis(*c)),
                [b'v', c @ b'x'..=b'z'] => Input::V(axis(*c)),
                [b'f', c @ b'x'..=b'z'] => Input::F(axis(*c)),
                _ if w == "replace" => return Err(a.err("keyword replace is not supported")),
                _ if w.len() > 2 && w.starts_with("v_") => Input::PerAtom(w.to_string()),
                _ if w.starts_with("c_") => {
                    check_per_atom(c.computes, w, "Compute reduce").map_err(|m| a.err(m))?;
                    Input::PerAtom(w.to_string())
                }
                _ => return Err(a.err(format!("input '{w}': expected x, y, z, vx, vy, vz, fx, fy, fz, c_ID of a per-atom compute or v_name of an atom-style variable"))),
            };
            inputs.push(input);
        }
        if inputs.is_empty() {
            return Err(a.err("missing argument: expected inputs (x, y, z, vx, vy, vz, fx, fy, fz, c_ID, v_name)"));
        }
        Ok(Self { id: c.id.clone(), mask: c.mask(a)?, region, mode, inputs })
    }

    /// The reduced value of input `k` (collective).
    fn reduce(&self, k: usize, e: &Eval) -> Result<f64, String> {
        let (sys, s) = (e.sys, &e.sys.store);
        let values = match &self.inputs[k] {
            Input::PerAtom(name) => Some((e.input)(name).map_err(|m| format!("compute {} reduce: {m}", self.id))?),
            _ => None,
        };
        let term = |i: usize| match &self.inputs[k] {
            Input::X(d) => s.r[i][*d],
            Input::V(d) => s.p[i][*d] / s.mass[i],
            Input::F(d) => s.f[i][*d],
            Input::PerAtom(_) => values.as_ref().expect("evaluated above")[i],
        };
        let members = (0..s.nlocal).filter(|&i| s.in_group(i, self.mask) && !matches!(&self.region, Some(r) if !r.contains(s.r[i])));
        let t = sys.comm.transport();
        if let Mode::Min | Mode::Max = self.mode {
            let sign = if self.mode == Mode::Max { 1.0 } else { -1.0 };
            let mut m = [members.map(|i| sign * term(i)).fold(-BIG, f64::max)];
            t.max(&mut m);
            return Ok(sign * m[0]);
        }
        let x = |i: usize| match self.mode {
            Mode::SumSq | Mode::AveSq => term(i) * term(i),
            Mode::SumAbs | Mode::AveAbs => term(i).abs(),
            _ => term(i),
        };
        let sums = exact_column_sums(t, 2, members.flat_map(|i| [(0, 1.0), (1, x(i))]));
        let (n, total) = (sums[0], sums[1]);
        Ok(match self.mode {
            Mode::Ave | Mode::AveSq | Mode::AveAbs if n > 0.0 => total / n,
            _ => total,
        })
    }
}

impl Compute for Reduce {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        if self.region.is_some() { "reduce/region" } else { "reduce" }
    }
    fn shape(&self) -> Shape {
        let n = self.inputs.len();
        let extensive = matches!(self.mode, Mode::Sum | Mode::SumSq | Mode::SumAbs);
        Shape { scalar: n == 1, vector: if n > 1 { n } else { 0 }, per_atom: None, extensive, extensive_vector: extensive }
    }
    fn scalar(&self, e: &Eval) -> Result<f64, String> {
        self.reduce(0, e)
    }
    fn vector(&self, e: &Eval) -> Result<Vec<f64>, String> {
        (0..self.inputs.len()).map(|k| self.reduce(k, e)).collect()
    }
}
