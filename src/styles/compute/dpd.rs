//! The internal-energy computes: LAMMPS DPD-REACT's `compute ID all dpd` (vector: sum
//! uCond, sum uMech, sum uChem = 0, N / sum(1/theta), N) and `compute ID GROUP dpd/atom`
//! (per-atom uCond, uMech, uChem = 0, theta), and gendpde's `compute ID GROUP tint`
//! (vector: mean theta, mean u, count of the group; its scalar is the mean theta).

use super::{Compute, ComputeContext, Eval, Shape};
use crate::base::args::Args;
use gendpde_engine::exact_sums;
use gendpde_io::ScriptError;

/// `compute ID all dpd`.
#[derive(Debug)]
pub struct Dpd {
    id: String,
}

impl Dpd {
    pub fn parse(a: &mut Args, c: &ComputeContext) -> Result<Self, ScriptError> {
        if c.group != "all" {
            return Err(a.err(format!("compute dpd on group '{}': only group all is supported", c.group)));
        }
        a.done()?;
        Ok(Self { id: c.id.clone() })
    }
}

impl Compute for Dpd {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "dpd"
    }
    fn shape(&self) -> Shape {
        Shape { vector: 5, ..Shape::default() }
    }
    fn vector(&self, e: &Eval) -> Result<Vec<f64>, String> {
        let s = &e.sys.store;
        let opt = |v: &Vec<f64>, i: usize| v.get(i).copied().unwrap_or(0.0);
        let rows = (0..s.nlocal).map(|i| [1.0, s.u[i], opt(&s.u_cond, i), 1.0 / s.theta[i]]);
        let [n, u, u_cond, inv_theta] = exact_sums(e.sys.comm.transport(), rows);
        Ok(vec![u_cond, u - u_cond, 0.0, n / inv_theta, n])
    }
}

/// `compute ID GROUP dpd/atom`.
#[derive(Debug)]
pub struct DpdAtom {
    id: String,
    mask: u32,
}

impl DpdAtom {
    pub fn parse(a: &mut Args, c: &ComputeContext) -> Result<Self, ScriptError> {
        a.done()?;
        Ok(Self { id: c.id.clone(), mask: c.mask(a)? })
    }
}

impl Compute for DpdAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "dpd/atom"
    }
    fn shape(&self) -> Shape {
        Shape { per_atom: Some(4), ..Shape::default() }
    }
    fn per_atom(&self, e: &Eval, col: usize) -> Result<Vec<f64>, String> {
        let s = &e.sys.store;
        let opt = |v: &Vec<f64>, i: usize| v.get(i).copied().unwrap_or(0.0);
        let value = |i: usize| match col {
            1 => opt(&s.u_cond, i),
            2 => s.u[i] - opt(&s.u_cond, i),
            3 => 0.0,
            _ => s.theta[i],
        };
        Ok((0..s.nlocal).map(|i| if s.in_group(i, self.mask) { value(i) } else { 0.0 }).collect())
    }
}

/// `compute ID GROUP tint`.
#[derive(Debug)]
pub struct Tint {
    id: String,
    mask: u32,
}

impl Tint {
    pub fn parse(a: &mut Args, c: &ComputeContext) -> Result<Self, ScriptError> {
        a.done()?;
        Ok(Self { id: c.id.clone(), mask: c.mask(a)? })
    }
}

impl Compute for Tint {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "tint"
    }
    fn shape(&self) -> Shape {
        Shape { scalar: true, vector: 3, ..Shape::default() }
    }
    fn scalar(&self, e: &Eval) -> Result<f64, String> {
        Ok(self.vector(e)?[0])
    }
    fn vector(&self, e: &Eval) -> Result<Vec<f64>, String> {
        let s = &e.sys.store;
        let rows = (0..s.nlocal).filter(|&i| s.in_group(i, self.mask)).map(|i| [1.0, s.theta[i], s.u[i]]);
        let [count, theta, u] = exact_sums(e.sys.comm.transport(), rows);
        let mean = |x: f64| if count > 0.0 { x / count } else { 0.0 };
        Ok(vec![mean(theta), mean(u), count])
    }
}
