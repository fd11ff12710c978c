//! `compute ID GROUP cluster/atom Rc`: LAMMPS's cluster ID of each particle of the group,
//! the smallest particle ID among the group's particles connected to it through pairs
//! closer than Rc (minimum image in periodic dimensions); 0 outside the group. LAMMPS
//! requires Rc within the pair cutoff ("Compute cluster/atom cutoff is longer than
//! pairwise cutoff"); so does gendpde.
//!
//! Every rank gathers the group's positions by tag and labels the clusters with a
//! union-find over a cell grid of side >= Rc, so the labels need no iteration between
//! ranks and do not depend on the rank count; the cost is the group's positions held on
//! every rank (4 values per particle) at each evaluation.

use super::{Compute, ComputeContext, Eval, Shape};
use crate::base::args::Args;
use gendpde_engine::Vec3;
use gendpde_io::ScriptError;

#[derive(Debug)]
pub struct ClusterAtom {
    id: String,
    mask: u32,
    cutoff: f64,
}

impl ClusterAtom {
    pub fn parse(a: &mut Args, c: &ComputeContext) -> Result<Self, ScriptError> {
        let cutoff = a.positive("the cutoff Rc")?;
        a.done()?;
        Ok(Self { id: c.id.clone(), mask: c.mask(a)?, cutoff })
    }
}

/// The root of `i` in the union-find `parent`, halving the path.
fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

impl Compute for ClusterAtom {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "cluster/atom"
    }
    fn shape(&self) -> Shape {
        Shape { per_atom: Some(0), ..Shape::default() }
    }
    fn per_atom(&self, e: &Eval, _col: usize) -> Result<Vec<f64>, String> {
        let (sys, s) = (e.sys, &e.sys.store);
        if self.cutoff > sys.lists.cutoff {
            return Err(format!("compute {} cluster/atom: Compute cluster/atom cutoff {} is longer than pairwise cutoff {}", self.id, self.cutoff, sys.lists.cutoff));
        }
        // tag and position of every member on every rank (bit patterns of the doubles)
        let local: Vec<u64> = (0..s.nlocal).filter(|&i| s.in_group(i, self.mask)).flat_map(|i| [s.tag[i], s.r[i][0].to_bits(), s.r[i][1].to_bits(), s.r[i][2].to_bits()]).collect();
        let all = crate::base::gather::all_ranks(sys, &local);
        let mut members: Vec<(u64, Vec3)> = all.chunks_exact(4).map(|c| (c[0], [f64::from_bits(c[1]), f64::from_bits(c[2]), f64::from_bits(c[3])])).collect();
        members.sort_by_key(|m| m.0);
        let d = &sys.domain;
        let len = d.len();
        let n: [usize; 3] = std::array::from_fn(|k| ((len[k] / self.cutoff).floor() as usize).clamp(1, 1024));
        // positions wrapped into the box (owned ones may lie a little outside between
        // migrations) pick the cells
        let cell_of = |x: Vec3| -> [usize; 3] {
            std::array::from_fn(|k| {
                let f = if d.periodic[k] { (x[k] - d.lo[k]).rem_euclid(len[k]) } else { x[k] - d.lo[k] };
                ((f / len[k] * n[k] as f64).floor().max(0.0) as usize).min(n[k] - 1)
            })
        };
        let index = |c: [usize; 3]| (c[0] * n[1] + c[1]) * n[2] + c[2];
        let mut cells: Vec<Vec<usize>> = vec![Vec::new(); n[0] * n[1] * n[2]];
        for (k, m) in members.iter().enumerate() {
            cells[index(cell_of(m.1))].push(k);
        }
        let rc2 = self.cutoff * self.cutoff;
        let close = |a: Vec3, b: Vec3| {
            let r2: f64 = (0..3)
                .map(|k| {
                    let mut x = a[k] - b[k];
                    if d.periodic[k] {
                        x -= len[k] * (x / len[k]).round();
                    }
                    x * x
                })
                .sum();
            r2 < rc2
        };
        // the neighbouring cells along each dimension, each once
        let around = |c: usize, k: usize| -> Vec<usize> {
            let mut v: Vec<usize> = [-1i64, 0, 1].iter().filter_map(|o| {
                let j = c as i64 + o;
                match (j >= 0 && j < n[k] as i64, d.periodic[k]) {
                    (true, _) => Some(j as usize),
                    (false, true) => Some(j.rem_euclid(n[k] as i64) as usize),
                    (false, false) => None,
                }
            }).collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        let mut parent: Vec<usize> = (0..members.len()).collect();
        for (k, m) in members.iter().enumerate() {
            let c = cell_of(m.1);
            for x in around(c[0], 0) {
                for y in around(c[1], 1) {
                    for z in around(c[2], 2) {
                        for &j in &cells[index([x, y, z])] {
                            if j > k && close(m.1, members[j].1) {
                                let (a, b) = (root(&mut parent, k), root(&mut parent, j));
                                // the root is the smaller index, so the smaller tag
                                parent[a.max(b)] = a.min(b);
                            }
                        }
                    }
                }
            }
        }
        let label: Vec<u64> = (0..members.len()).map(|k| members[root(&mut parent, k)].0).collect();
        Ok((0..s.nlocal)
            .map(|i| match s.in_group(i, self.mask) {
                true => members.binary_search_by_key(&s.tag[i], |m| m.0).map_or(0.0, |k| label[k] as f64),
                false => 0.0,
            })
            .collect())
    }
}
