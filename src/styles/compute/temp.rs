//! The temperature computes of LAMMPS: `compute ID GROUP temp`, `temp/partial xflag yflag
//! zflag`, `temp/com` and `temp/region RID`. Each gives the scalar T = sum m v^2 / (dof
//! k_B) and the vector sum m v_a v_b (xx, yy, zz, xy, xz, yz, extensive), with LAMMPS's
//! degrees of freedom (extra/dof 3 by default, `compute_modify ID extra/dof N`):
//! temp: dof = 3 N - extra; temp/partial: dof = n N - (n / 3) extra for n flagged
//! components, which alone are counted; temp/com: velocities relative to the group's
//! centre-of-mass velocity, dof = 3 N - extra; temp/region: the group's particles in the
//! region now, dof = 3 N_region - extra.

use super::{Compute, ComputeContext, Eval, Shape, Temperature};
use crate::base::args::Args;
use crate::base::region::Region;
use gendpde_engine::{exact_sums, Vec3};
use gendpde_integrators::System;
use gendpde_io::ScriptError;

#[derive(Debug)]
enum Kind {
    All,
    /// The counted components.
    Partial([bool; 3]),
    Com,
    Region(Region),
}

#[derive(Debug)]
pub struct Temp {
    id: String,
    style: &'static str,
    mask: u32,
    extra_dof: f64,
    kind: Kind,
}

impl Temp {
    /// The words after `compute ID GROUP STYLE` of temperature style `style`.
    pub fn parse(a: &mut Args, c: &ComputeContext, style: &'static str) -> Result<Self, ScriptError> {
        let kind = match style {
            "temp/partial" => {
                let mut flags = [false; 3];
                for f in &mut flags {
                    *f = match a.word("a flag 0 or 1 (xflag yflag zflag)")? {
                        "0" => false,
                        "1" => true,
                        w => return Err(a.err(format!("Illegal compute temp/partial command: xflag, yflag and zflag are 0 or 1, got '{w}'"))),
                    };
                }
                Kind::Partial(flags)
            }
            "temp/com" => Kind::Com,
            "temp/region" => Kind::Region(c.region(a, style)?),
            _ => Kind::All,
        };
        a.done()?;
        Ok(Self { id: c.id.clone(), style, mask: c.mask(a)?, extra_dof: 3.0, kind })
    }

    /// The group's centre-of-mass velocity (temp/com), else 0 (collective).
    fn drift(&self, sys: &System) -> Vec3 {
        if !matches!(self.kind, Kind::Com) {
            return [0.0; 3];
        }
        let s = &sys.store;
        let rows = (0..s.nlocal).filter(|&i| s.in_group(i, self.mask)).map(|i| [s.mass[i], s.p[i][0], s.p[i][1], s.p[i][2]]);
        let [m, px, py, pz] = exact_sums(sys.comm.transport(), rows);
        if m > 0.0 { [px / m, py / m, pz / m] } else { [0.0; 3] }
    }
}

/// The kinetic sums of group bit `mask` with 3N - `extra_dof` degrees of freedom, those of
/// a compute temp (collective; velocity scale and create read them).
pub fn group_temperature(sys: &System, mask: u32, extra_dof: f64) -> Temperature {
    Temp { id: String::new(), style: "temp", mask, extra_dof, kind: Kind::All }.measure(sys)
}

impl Temp {
    /// The kinetic sums of the counted particles (collective).
    fn measure(&self, sys: &System) -> Temperature {
        let s = &sys.store;
        let vcm = self.drift(sys);
        let flags = match self.kind {
            Kind::Partial(f) => f.map(|f| if f { 1.0 } else { 0.0 }),
            _ => [1.0; 3],
        };
        let counted = |i: usize| s.in_group(i, self.mask) && if let Kind::Region(r) = &self.kind { r.contains(s.r[i]) } else { true };
        let rows = (0..s.nlocal).filter(|&i| counted(i)).map(|i| {
            // momenta relative to the drift: p p / m as the integrators' kinetic energy
            let m = s.mass[i];
            let q: [f64; 3] = std::array::from_fn(|d| flags[d] * (s.p[i][d] - m * vcm[d]));
            [1.0, q[0] * q[0] / m, q[1] * q[1] / m, q[2] * q[2] / m, q[0] * q[1] / m, q[0] * q[2] / m, q[1] * q[2] / m]
        });
        let [n, xx, yy, zz, xy, xz, yz] = exact_sums(sys.comm.transport(), rows);
        let dof = match self.kind {
            Kind::Partial(_) => {
                let nper: f64 = flags.iter().sum();
                nper * n - nper / 3.0 * self.extra_dof
            }
            _ => 3.0 * n - self.extra_dof,
        };
        Temperature { dof, tensor: [xx, yy, zz, xy, xz, yz] }
    }
}

impl Compute for Temp {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        self.style
    }
    fn shape(&self) -> Shape {
        Shape { scalar: true, vector: 6, extensive_vector: true, ..Shape::default() }
    }
    fn scalar(&self, e: &Eval) -> Result<f64, String> {
        Ok(self.temperature(e).expect("a temperature compute").value(e.units.kb))
    }
    /// LAMMPS's vector is extensive while the scalar is not.
    fn vector(&self, e: &Eval) -> Result<Vec<f64>, String> {
        Ok(self.temperature(e).expect("a temperature compute").tensor.to_vec())
    }
    fn temperature(&self, e: &Eval) -> Option<Temperature> {
        Some(self.measure(e.sys))
    }
    fn temp_group(&self) -> Option<(u32, f64)> {
        matches!(self.kind, Kind::All).then_some((self.mask, self.extra_dof))
    }
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<bool, ScriptError> {
        match key {
            "extra/dof" | "extra" => self.extra_dof = a.f64("the extra degrees of freedom")?,
            _ => return Ok(false),
        }
        Ok(true)
    }
}
