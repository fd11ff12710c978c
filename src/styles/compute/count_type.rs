//! `compute ID GROUP count/type atom`: LAMMPS's count of the group's particles of each
//! type (the vector, one element per type). The `bond`, `angle`, `dihedral` and
//! `improper` modes count bonded interactions, which gendpde's particles do not have.

use super::{Compute, ComputeContext, Eval, Shape};
use crate::base::args::Args;
use gendpde_engine::exact_column_sums;
use gendpde_io::ScriptError;

#[derive(Debug)]
pub struct CountType {
    id: String,
    mask: u32,
    ntypes: usize,
}

impl CountType {
    pub fn parse(a: &mut Args, c: &ComputeContext) -> Result<Self, ScriptError> {
        match a.word("a mode (atom)")? {
            "atom" => {}
            m @ ("bond" | "angle" | "dihedral" | "improper") => return Err(a.err(format!("compute count/type {m}: gendpde's particles have no {m}s; mode atom counts particles"))),
            m => return Err(a.err(format!("Invalid compute count/type keyword {m}: expected atom"))),
        }
        a.done()?;
        Ok(Self { id: c.id.clone(), mask: c.mask(a)?, ntypes: c.ntypes })
    }
}

impl Compute for CountType {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "count/type"
    }
    fn shape(&self) -> Shape {
        Shape { vector: self.ntypes, ..Shape::default() }
    }
    fn vector(&self, e: &Eval) -> Result<Vec<f64>, String> {
        let s = &e.sys.store;
        let terms = (0..s.nlocal).filter(|&i| s.in_group(i, self.mask)).map(|i| (s.kind[i] as usize - 1, 1.0));
        Ok(exact_column_sums(e.sys.comm.transport(), self.ntypes, terms))
    }
}
