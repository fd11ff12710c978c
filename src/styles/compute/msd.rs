//! `compute ID GROUP msd [com yes|no]`: the mean squared displacement of the group's
//! particles from their unwrapped positions when the compute was defined, as LAMMPS's
//! compute msd: thermo `c_ID[1..4]` = <dx^2>, <dy^2>, <dz^2>, <dr^2>. With `com yes` the
//! group's centre-of-mass displacement is taken out of every particle's.
//!
//! The reference positions are held by tag on every rank (3 values per tag), so they
//! follow no particle between ranks; the sums are exact, so the values do not depend on
//! the rank count.

use super::com::centre_of_mass;
use crate::base::args::Args;
use gendpde_engine::{exact_sums, Vec3};
use gendpde_integrators::System;
use gendpde_io::ScriptError;

#[derive(Clone, Debug, PartialEq)]
pub struct Msd {
    pub id: String,
    mask: u32,
    com: bool,
    /// Unwrapped position at definition (minus the group's centre of mass with `com
    /// yes`) by tag - 1; NaN for tags outside the group.
    origin: Vec<Vec3>,
}

impl Msd {
    /// The words after `compute ID GROUP msd`; `sys` is the system whose positions are the
    /// origin, `max_tag` its largest tag.
    pub fn parse(id: String, mask: u32, a: &mut Args, sys: &System, max_tag: u64) -> Result<Self, ScriptError> {
        let mut com = false;
        while a.remaining() > 0 {
            match a.word("a keyword")? {
                "com" => com = a.yes_no("com")?,
                "average" => return Err(a.err("keyword average: only the default, average no, is supported")),
                k => return Err(a.err(format!("unknown keyword '{k}'; known: com"))),
            }
        }
        let mut msd = Self { id, mask, com, origin: Vec::new() };
        let len = usize::try_from(max_tag).ok().and_then(|n| n.checked_mul(3)).ok_or_else(|| a.err(format!("compute msd: {max_tag} tags do not fit in memory")))?;
        crate::base::memory::check(len as f64 * 8.0, "the reference positions of compute msd").map_err(|e| a.err(e))?;
        let cm = msd.centre(sys);
        let mut flat = vec![f64::NEG_INFINITY; len];
        let s = &sys.store;
        for i in (0..s.nlocal).filter(|&i| s.in_group(i, mask)) {
            let x = sys.domain.unwrap(s.r[i], s.image[i]);
            let k = 3 * (s.tag[i] as usize - 1);
            flat[k..k + 3].copy_from_slice(&[x[0] - cm[0], x[1] - cm[1], x[2] - cm[2]]);
        }
        sys.comm.transport().max(&mut flat);
        msd.origin = flat.chunks_exact(3).map(|c| if c[0] == f64::NEG_INFINITY { [f64::NAN; 3] } else { [c[0], c[1], c[2]] }).collect();
        Ok(msd)
    }

    /// The group's centre of mass with `com yes`, else 0 (collective).
    fn centre(&self, sys: &System) -> Vec3 {
        if self.com { centre_of_mass(sys, self.mask) } else { [0.0; 3] }
    }

    /// <dx^2>, <dy^2>, <dz^2>, <dr^2> over the group (collective).
    pub fn vector(&self, sys: &System) -> [f64; 4] {
        let cm = self.centre(sys);
        let s = &sys.store;
        let rows = (0..s.nlocal).filter(|&i| s.in_group(i, self.mask)).map(|i| {
            // particles created after the compute have no origin: NaN
            let o = self.origin.get(s.tag[i] as usize - 1).copied().unwrap_or([f64::NAN; 3]);
            let x = sys.domain.unwrap(s.r[i], s.image[i]);
            let d = [x[0] - cm[0] - o[0], x[1] - cm[1] - o[1], x[2] - cm[2] - o[2]];
            let d2 = [d[0] * d[0], d[1] * d[1], d[2] * d[2]];
            [1.0, d2[0], d2[1], d2[2], d2[0] + d2[1] + d2[2]]
        });
        let [n, xx, yy, zz, rr] = exact_sums(sys.comm.transport(), rows);
        if n > 0.0 { [xx / n, yy / n, zz / n, rr / n] } else { [0.0; 4] }
    }
}
