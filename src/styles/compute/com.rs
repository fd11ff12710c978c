//! `compute ID GROUP com`: the group's centre of mass from unwrapped positions, as LAMMPS's
//! compute com (vector `c_ID[1..3]`); also the centre compute msd takes out with `com yes`,
//! compute gyration and the variable function xcm() measure from.

use super::{Compute, ComputeContext, Eval, Shape};
use crate::base::args::Args;
use gendpde_engine::{exact_sums, Vec3};
use gendpde_integrators::System;
use gendpde_io::ScriptError;

/// The centre of mass of the particles of group bit `mask` from unwrapped positions, 0
/// for an empty group (collective; exact sums, so the same on every rank count).
pub fn centre_of_mass(sys: &System, mask: u32) -> Vec3 {
    let s = &sys.store;
    let rows = (0..s.nlocal).filter(|&i| s.in_group(i, mask)).map(|i| {
        let (x, m) = (sys.domain.unwrap(s.r[i], s.image[i]), s.mass[i]);
        [m, m * x[0], m * x[1], m * x[2]]
    });
    let [m, mx, my, mz] = exact_sums(sys.comm.transport(), rows);
    if m > 0.0 { [mx / m, my / m, mz / m] } else { [0.0; 3] }
}

#[derive(Debug)]
pub struct Com {
    id: String,
    mask: u32,
}

impl Com {
    pub fn parse(a: &mut Args, c: &ComputeContext) -> Result<Self, ScriptError> {
        a.done()?;
        Ok(Self { id: c.id.clone(), mask: c.mask(a)? })
    }
}

impl Compute for Com {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "com"
    }
    fn shape(&self) -> Shape {
        Shape { vector: 3, ..Shape::default() }
    }
    fn vector(&self, e: &Eval) -> Result<Vec<f64>, String> {
        Ok(centre_of_mass(e.sys, self.mask).to_vec())
    }
}
