//! `compute ID GROUP reduce MODE input ...`: one global value per input, reduced over the
//! group's particles, as LAMMPS's compute reduce. Inputs: `x y z vx vy vz fx fy fz` and
//! `c_ID` of a per-atom compute (ke/atom, pe/atom), `v_name` of an atom-style variable. Modes: sum, sumsq, sumabs, min, max,
//! ave, avesq, aveabs. One input gives thermo `c_ID`, several `c_ID[1]` ... (as LAMMPS's
//! scalar and vector). Sums are exact and min/max are exact, so the values do not depend
//! on the rank count.

use crate::base::args::Args;
use gendpde_engine::exact_column_sums;
use gendpde_integrators::System;
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
    /// A per-atom compute by ID.
    Compute(String),
    /// An atom-style variable by name (checked when evaluated, as LAMMPS at init).
    Variable(String),
}

/// LAMMPS's value of min and max over no particles.
const BIG: f64 = 1.0e20;

#[derive(Clone, Debug, PartialEq)]
pub struct Reduce {
    pub id: String,
    mask: u32,
    mode: Mode,
    inputs: Vec<Input>,
}

impl Reduce {
    /// The words after `compute ID GROUP reduce`; `per_atom(ID)` tells whether compute ID
    /// has per-atom values (None: no such compute).
    pub fn parse(id: String, mask: u32, a: &mut Args, per_atom: impl Fn(&str) -> Option<bool>) -> Result<Self, ScriptError> {
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
                _ if w.len() > 2 && w.starts_with("v_") => Input::Variable(w[2..].to_string()),
                _ => {
                    let cid = w.strip_prefix("c_").ok_or_else(|| a.err(format!("input '{w}': expected x, y, z, vx, vy, vz, fx, fy, fz, c_ID of a per-atom compute or v_name of an atom-style variable")))?;
                    match per_atom(cid) {
                        Some(true) => Input::Compute(cid.to_string()),
                        Some(false) => return Err(a.err(format!("input '{w}': compute {cid} has no per-atom values (ke/atom, pe/atom)"))),
                        None => return Err(a.err(format!("input '{w}': no per-atom compute with ID '{cid}' (ke/atom, pe/atom)"))),
                    }
                }
            };
            inputs.push(input);
        }
        if inputs.is_empty() {
            return Err(a.err("missing argument: expected inputs (x, y, z, vx, vy, vz, fx, fy, fz, c_ID, v_name)"));
        }
        Ok(Self { id, mask, mode, inputs })
    }

    /// Whether thermo divides the values by the particle count with `thermo_modify norm
    /// yes` (the sums; LAMMPS's extensive computes).
    pub fn extensive(&self) -> bool {
        matches!(self.mode, Mode::Sum | Mode::SumSq | Mode::SumAbs)
    }

    /// Thermo's `c_ID` (one input) or `c_ID[k]` (several); None if `name` is neither.
    pub fn index(&self, name: &str) -> Option<usize> {
        let rest = name.strip_prefix("c_")?;
        if rest == self.id {
            return (self.inputs.len() == 1).then_some(0);
        }
        let (id, k) = rest.strip_suffix(']')?.split_once('[')?;
        let k = k.parse::<usize>().ok()?;
        (id == self.id && self.inputs.len() > 1 && (1..=self.inputs.len()).contains(&k)).then(|| k - 1)
    }

    /// The ID of the per-atom compute input `k` reads, if it reads one.
    pub fn compute_input(&self, k: usize) -> Option<&str> {
        match &self.inputs[k] {
            Input::Compute(cid) => Some(cid),
            _ => None,
        }
    }

    /// The atom-style variable input `k` reads, if it reads one.
    pub fn variable_input(&self, k: usize) -> Option<&str> {
        match &self.inputs[k] {
            Input::Variable(name) => Some(name),
            _ => None,
        }
    }

    /// The reduced value of input `k` (collective); `per_atom(i)` is the value of particle
    /// i of its per-atom compute or atom-style variable.
    pub fn value(&self, k: usize, sys: &System, per_atom: impl Fn(usize) -> f64) -> f64 {
        let s = &sys.store;
        let term = |i: usize| match &self.inputs[k] {
            Input::X(d) => s.r[i][*d],
            Input::V(d) => s.p[i][*d] / s.mass[i],
            Input::F(d) => s.f[i][*d],
            Input::Compute(_) | Input::Variable(_) => per_atom(i),
        };
        let members = (0..s.nlocal).filter(|&i| s.in_group(i, self.mask));
        let t = sys.comm.transport();
        if let Mode::Min | Mode::Max = self.mode {
            let sign = if self.mode == Mode::Max { 1.0 } else { -1.0 };
            let mut m = [members.map(|i| sign * term(i)).fold(-BIG, f64::max)];
            t.max(&mut m);
            return sign * m[0];
        }
        let x = |i: usize| match self.mode {
            Mode::SumSq | Mode::AveSq => term(i) * term(i),
            Mode::SumAbs | Mode::AveAbs => term(i).abs(),
            _ => term(i),
        };
        let sums = exact_column_sums(t, 2, members.flat_map(|i| [(0, 1.0), (1, x(i))]));
        let (n, total) = (sums[0], sums[1]);
        match self.mode {
            Mode::Ave | Mode::AveSq | Mode::AveAbs if n > 0.0 => total / n,
            _ => total,
        }
    }
}
