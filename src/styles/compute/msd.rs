//! Computes against a reference recorded by tag when they are defined: LAMMPS's `compute
//! ID GROUP msd [com yes|no]`, the mean squared displacement from the unwrapped
//! positions then (vector <dx^2>, <dy^2>, <dz^2>, <dr^2>; with `com yes` the group's
//! centre-of-mass displacement is taken out of every particle's), and `compute ID GROUP
//! vacf`, the velocity autocorrelation with the velocities then (vector <vx vx0>, <vy
//! vy0>, <vz vz0>, <v . v0>).
//!
//! The reference is held by tag on every rank (3 values per tag), so it follows no
//! particle between ranks; the sums are exact, so the values do not depend on the rank
//! count.

use super::com::centre_of_mass;
use super::{Compute, ComputeContext, Eval, Shape};
use crate::base::args::Args;
use gendpde_engine::{exact_sums, Vec3};
use gendpde_integrators::System;
use gendpde_io::ScriptError;

#[derive(Debug)]
pub struct Msd {
    id: String,
    style: &'static str,
    mask: u32,
    com: bool,
    /// The reference (msd: unwrapped position minus the group's centre of mass with `com
    /// yes`; vacf: velocity) by tag - 1; NaN for tags outside the group.
    origin: Vec<Vec3>,
}

impl Msd {
    /// The words after `compute ID GROUP msd|vacf` (`style`); the system's particles now
    /// are the reference.
    pub fn parse(a: &mut Args, c: &ComputeContext, style: &'static str) -> Result<Self, ScriptError> {
        let sys = c.system(a, style)?;
        let mut com = false;
        while a.remaining() > 0 {
            match a.word("a keyword")? {
                "com" if style == "msd" => com = a.yes_no("com")?,
                "average" if style == "msd" => return Err(a.err("keyword average: only the default, average no, is supported")),
                k if style == "msd" => return Err(a.err(format!("unknown keyword '{k}'; known: com"))),
                k => return Err(a.err(format!("Illegal compute {style} command: unexpected argument '{k}'"))),
            }
        }
        let mask = c.mask(a)?;
        let max_tag = c.max_tag;
        let mut msd = Self { id: c.id.clone(), style, mask, com, origin: Vec::new() };
        let len = usize::try_from(max_tag).ok().and_then(|n| n.checked_mul(3)).ok_or_else(|| a.err(format!("compute {style}: {max_tag} tags do not fit in memory")))?;
        crate::base::memory::check(len as f64 * 8.0, &format!("the reference of compute {style}")).map_err(|e| a.err(e))?;
        let cm = msd.centre(sys);
        let mut flat = vec![f64::NEG_INFINITY; len];
        let s = &sys.store;
        for i in (0..s.nlocal).filter(|&i| s.in_group(i, mask)) {
            let x = msd.quantity(sys, i);
            let k = 3 * (s.tag[i] as usize - 1);
            flat[k..k + 3].copy_from_slice(&[x[0] - cm[0], x[1] - cm[1], x[2] - cm[2]]);
        }
        sys.comm.transport().max(&mut flat);
        msd.origin = flat.chunks_exact(3).map(|c| if c[0] == f64::NEG_INFINITY { [f64::NAN; 3] } else { [c[0], c[1], c[2]] }).collect();
        Ok(msd)
    }

    /// The quantity compared with the reference: the unwrapped position (msd) or the
    /// velocity (vacf) of particle i.
    fn quantity(&self, sys: &System, i: usize) -> Vec3 {
        let s = &sys.store;
        match self.style {
            "vacf" => s.p[i].map(|p| p / s.mass[i]),
            _ => sys.domain.unwrap(s.r[i], s.image[i]),
        }
    }

    /// The group's centre of mass with `com yes`, else 0 (collective).
    fn centre(&self, sys: &System) -> Vec3 {
        if self.com { centre_of_mass(sys, self.mask) } else { [0.0; 3] }
    }
}

impl Compute for Msd {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        self.style
    }
    fn shape(&self) -> Shape {
        Shape { vector: 4, ..Shape::default() }
    }
    /// msd: <dx^2>, <dy^2>, <dz^2>, <dr^2>; vacf: <vx vx0>, <vy vy0>, <vz vz0>, <v . v0>
    /// over the group (collective).
    fn vector(&self, e: &Eval) -> Result<Vec<f64>, String> {
        let sys = e.sys;
        let cm = self.centre(sys);
        let s = &sys.store;
        let vacf = self.style == "vacf";
        let rows = (0..s.nlocal).filter(|&i| s.in_group(i, self.mask)).map(|i| {
            // particles created after the compute have no reference: NaN
            let o = self.origin.get(s.tag[i] as usize - 1).copied().unwrap_or([f64::NAN; 3]);
            let x = self.quantity(sys, i);
            let t = if vacf {
                [x[0] * o[0], x[1] * o[1], x[2] * o[2]]
            } else {
                let d = [x[0] - cm[0] - o[0], x[1] - cm[1] - o[1], x[2] - cm[2] - o[2]];
                [d[0] * d[0], d[1] * d[1], d[2] * d[2]]
            };
            [1.0, t[0], t[1], t[2], t[0] + t[1] + t[2]]
        });
        let [n, xx, yy, zz, rr] = exact_sums(sys.comm.transport(), rows);
        Ok(if n > 0.0 { vec![xx / n, yy / n, zz / n, rr / n] } else { vec![0.0; 4] })
    }
}
