//! `compute ID GROUP gyration`: LAMMPS's radius of gyration of the group, Rg = sqrt(sum m
//! |x - x_cm|^2 / M) from unwrapped positions (the scalar), and its tensor sum m d_a d_b /
//! M (xx, yy, zz, xy, xz, yz; the vector), also the variable function gyration().

use super::com::centre_of_mass;
use super::{Compute, ComputeContext, Eval, Shape};
use crate::base::args::Args;
use gendpde_engine::exact_sums;
use gendpde_integrators::System;
use gendpde_io::ScriptError;

/// The gyration tensor of group bit `mask` (collective; 0 for an empty group).
pub fn gyration_tensor(sys: &System, mask: u32) -> [f64; 6] {
    let cm = centre_of_mass(sys, mask);
    let s = &sys.store;
    let rows = (0..s.nlocal).filter(|&i| s.in_group(i, mask)).map(|i| {
        let (x, m) = (sys.domain.unwrap(s.r[i], s.image[i]), s.mass[i]);
        let d = [x[0] - cm[0], x[1] - cm[1], x[2] - cm[2]];
        [m, m * d[0] * d[0], m * d[1] * d[1], m * d[2] * d[2], m * d[0] * d[1], m * d[0] * d[2], m * d[1] * d[2]]
    });
    let [m, xx, yy, zz, xy, xz, yz] = exact_sums(sys.comm.transport(), rows);
    if m > 0.0 { [xx, yy, zz, xy, xz, yz].map(|t| t / m) } else { [0.0; 6] }
}

#[derive(Debug)]
pub struct Gyration {
    id: String,
    mask: u32,
}

impl Gyration {
    pub fn parse(a: &mut Args, c: &ComputeContext) -> Result<Self, ScriptError> {
        a.done()?;
        Ok(Self { id: c.id.clone(), mask: c.mask(a)? })
    }
}

impl Compute for Gyration {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "gyration"
    }
    fn shape(&self) -> Shape {
        Shape { scalar: true, vector: 6, ..Shape::default() }
    }
    fn scalar(&self, e: &Eval) -> Result<f64, String> {
        let t = gyration_tensor(e.sys, self.mask);
        Ok((t[0] + t[1] + t[2]).sqrt())
    }
    fn vector(&self, e: &Eval) -> Result<Vec<f64>, String> {
        Ok(gyration_tensor(e.sys, self.mask).to_vec())
    }
}
