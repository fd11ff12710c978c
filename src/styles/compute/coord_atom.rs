//! `compute ID GROUP coord/atom cutoff Rc [group G2] [T1 T2 ...]` (and the older `coord/atom
//! Rc`): LAMMPS's coordination number, the number of neighbours of each particle of the
//! group within Rc (of group G2, all by default), a per-atom vector; with type ranges
//! (`1 2*4`) a per-atom array of one column per range.
//!
//! Read from the run's neighbour list (every pair with an owned particle, owned-ghost
//! pairs on both ranks), which holds every pair closer than the pair cutoff: Rc may not
//! exceed it (LAMMPS: "Compute coord/atom cutoff is longer than pairwise cutoff").

use super::{Compute, ComputeContext, Eval, Shape};
use crate::base::args::Args;
use gendpde_io::ScriptError;
use std::ops::RangeInclusive;

#[derive(Debug)]
pub struct CoordAtom {
    id: String,
    mask: u32,
    /// Group bit mask of the counted neighbours.
    neighbours: u32,
    cutoff: f64,
    /// The type ranges of the columns.
    types: Vec<RangeInclusive<usize>>,
}

impl CoordAtom {
    pub fn parse(a: &mut Args, c: &ComputeContext) -> Result<Self, ScriptError> {
        if a.peek() == Some("cutoff") {
            a.word("cutoff")?;
        } else if a.peek() == Some("orientorder") {
            return Err(a.err("compute coord/atom orientorder: gendpde has no compute orientorder/atom; cstyle cutoff is supported"));
        }
        let cutoff = a.positive("the cutoff Rc")?;
        let (mut neighbours, mut types) = (u32::MAX, Vec::new());
        while let Some(w) = a.peek() {
            if w == "group" {
                a.word("group")?;
                let g = a.word("a group ID")?;
                neighbours = crate::base::groups::mask(c.groups, g, a).map_err(|_| a.err(format!("Group ID {g} requested by compute coord/atom does not exist")))?;
            } else {
                types.push(a.types(c.ntypes)?);
            }
        }
        if types.is_empty() {
            types.push(1..=c.ntypes.max(1));
        }
        Ok(Self { id: c.id.clone(), mask: c.mask(a)?, neighbours, cutoff, types })
    }
}

impl Compute for CoordAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "coord/atom"
    }
    fn shape(&self) -> Shape {
        let n = self.types.len();
        Shape { per_atom: Some(if n == 1 { 0 } else { n }), ..Shape::default() }
    }
    fn per_atom(&self, e: &Eval, col: usize) -> Result<Vec<f64>, String> {
        let (sys, s) = (e.sys, &e.sys.store);
        if self.cutoff > sys.lists.cutoff {
            return Err(format!("compute {} coord/atom: Compute coord/atom cutoff {} is longer than pairwise cutoff {}", self.id, self.cutoff, sys.lists.cutoff));
        }
        let types = &self.types[col.max(1) - 1];
        let counts = |j: usize| s.in_group(j, self.neighbours) && types.contains(&(s.kind[j] as usize));
        let mut n = vec![0.0; s.nlocal];
        let rc2 = self.cutoff * self.cutoff;
        for &[i, j] in &sys.nlist.pairs {
            let (i, j) = (i as usize, j as usize);
            let d: [f64; 3] = std::array::from_fn(|k| s.r[i][k] - s.r[j][k]);
            if d.iter().map(|x| x * x).sum::<f64>() >= rc2 {
                continue;
            }
            if i < s.nlocal && counts(j) {
                n[i] += 1.0;
            }
            if j < s.nlocal && counts(i) {
                n[j] += 1.0;
            }
        }
        Ok(n.into_iter().enumerate().map(|(i, c)| if s.in_group(i, self.mask) { c } else { 0.0 }).collect())
    }
}
