//! Per-atom computes that read one value per particle: LAMMPS's `compute ID GROUP
//! property/atom NAME ...` (a per-atom vector for one name, an array for several; the
//! names of the particle keyword table, `base::particle_keywords`, and `proc`),
//! `ke/atom` (m v^2 / 2), `pe/atom` (half the energy of each pair a particle is in for
//! pairwise styles, its internal energy u for GenDPDE, whose pe is the sum of u) and
//! DPD-MESO's `edpd/temp/atom` (the eDPD temperature). Values are 0 outside the group.

use super::{Compute, ComputeContext, Eval, Shape};
use crate::base::args::Args;
use crate::base::particle_keywords::{keyword_names, Keyword};
use gendpde_io::ScriptError;

#[derive(Clone, Copy, Debug)]
enum Attribute {
    Keyword(&'static str),
    Proc,
    Kinetic,
    Potential,
}

#[derive(Debug)]
pub struct PropertyAtom {
    id: String,
    style: &'static str,
    mask: u32,
    attributes: Vec<Attribute>,
}

impl PropertyAtom {
    /// `ke/atom`, `pe/atom` or `edpd/temp/atom`.
    pub fn single(a: &mut Args, c: &ComputeContext, style: &'static str) -> Result<Self, ScriptError> {
        let attribute = match style {
            "ke/atom" => Attribute::Kinetic,
            "pe/atom" => {
                // LAMMPS's keywords select energy terms; gendpde's pair (or internal) energy is all of pe
                while let Some(k) = a.peek() {
                    match k {
                        "pair" | "bond" | "angle" | "dihedral" | "improper" | "kspace" | "fix" => a.word("a keyword")?,
                        k => return Err(a.err(format!("unknown keyword '{k}'; known: pair, bond, angle, dihedral, improper, kspace, fix"))),
                    };
                }
                Attribute::Potential
            }
            _ => Attribute::Keyword("edpd_temp"),
        };
        a.done()?;
        Ok(Self { id: c.id.clone(), style, mask: c.mask(a)?, attributes: vec![attribute] })
    }

    /// The words after `compute ID GROUP property/atom`.
    pub fn parse(a: &mut Args, c: &ComputeContext) -> Result<Self, ScriptError> {
        let mut attributes = Vec::new();
        while a.remaining() > 0 {
            let name = a.word("an attribute")?;
            attributes.push(match name {
                "proc" => Attribute::Proc,
                _ => match Keyword::find(name) {
                    Some(k) => Attribute::Keyword(k.name),
                    None => return Err(a.err(format!("Invalid keyword {name} for compute property/atom command; known: {} proc", keyword_names()))),
                },
            });
        }
        if attributes.is_empty() {
            return Err(a.err("Illegal compute property/atom command: expected attributes"));
        }
        Ok(Self { id: c.id.clone(), style: "property/atom", mask: c.mask(a)?, attributes })
    }
}

impl Compute for PropertyAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        self.style
    }
    fn shape(&self) -> Shape {
        let n = self.attributes.len();
        Shape { per_atom: Some(if n == 1 { 0 } else { n }), ..Shape::default() }
    }
    fn per_atom(&self, e: &Eval, col: usize) -> Result<Vec<f64>, String> {
        let (sys, s) = (e.sys, &e.sys.store);
        let attribute = self.attributes[col.max(1) - 1];
        let rank = sys.comm.rank() as f64;
        let reader = match attribute {
            Attribute::Keyword(name) => Some(Keyword::find(name).expect("a keyword of the table").reader(s).map_err(|m| format!("compute {} {}: {m}", self.id, self.style))?),
            _ => None,
        };
        let value = |i: usize| match attribute {
            Attribute::Keyword(_) => reader.expect("read above").get(sys, i),
            Attribute::Proc => rank,
            Attribute::Kinetic => 0.5 * s.p[i].iter().map(|p| p * p).sum::<f64>() / s.mass[i],
            Attribute::Potential if e.pair_energy => s.epair.get(i).copied().unwrap_or(0.0),
            Attribute::Potential => s.u[i],
        };
        Ok((0..s.nlocal).map(|i| if s.in_group(i, self.mask) { value(i) } else { 0.0 }).collect())
    }
}
