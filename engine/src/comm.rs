//! Communication between the owners of particles and their ghost copies.
//!
//! Every pass reads ghosts; a single rank gets them as periodic images from
//! [`SerialComm`], so the serial path runs the same ghost machinery as MPI.

use crate::{CellGrid, Domain, Fields, Particles, Vec3};

/// Owner/ghost exchange and global reductions, one implementation per transport.
pub trait Comm {
    fn rank(&self) -> usize;
    fn size(&self) -> usize;
    /// Range [lo, hi) of the global cells this rank owns.
    fn owned_cells(&self, grid: &CellGrid) -> ([i32; 3], [i32; 3]);
    /// Wraps owned particles into the box, hands them to their owner ranks, assigns
    /// cells, and rebuilds the ghost layer: one cell on every side of the sub-domain.
    fn exchange(&mut self, store: &mut Particles, domain: &Domain, grid: &CellGrid);
    /// Copies `fields` from the owners to all their ghosts.
    fn forward(&mut self, store: &mut Particles, fields: Fields);
    /// Copies `fields` of the listed ghosts to their owners: values, not deltas.
    fn reverse(&mut self, store: &mut Particles, ghosts: &[u32], fields: Fields);
    /// Element-wise sum over ranks, in a fixed rank order.
    fn sum(&self, values: &mut [f64]);
    /// Maximum over ranks.
    fn max(&self, x: f64) -> f64;
}

/// One rank: ghosts are periodic images of owned particles.
#[derive(Default, Debug)]
pub struct SerialComm {
    /// Owner index of each ghost (ghost k is particle nlocal + k).
    src: Vec<u32>,
    /// Image shift of each ghost.
    shift: Vec<Vec3>,
}

impl SerialComm {
    pub fn new() -> Self {
        Self::default()
    }
}

impl Comm for SerialComm {
    fn rank(&self) -> usize {
        0
    }

    fn size(&self) -> usize {
        1
    }

    fn owned_cells(&self, grid: &CellGrid) -> ([i32; 3], [i32; 3]) {
        ([0; 3], grid.count.map(|c| c as i32))
    }

    fn exchange(&mut self, store: &mut Particles, domain: &Domain, grid: &CellGrid) {
        store.truncate_ghosts();
        self.src.clear();
        self.shift.clear();
        for i in 0..store.nlocal {
            domain.wrap(&mut store.r[i], &mut store.image[i]);
            store.cell[i] = grid.locate(store.r[i]);
        }
        let len = domain.len();
        for d in 0..3 {
            let n = grid.count[d] as i32;
            for k in 0..store.len() {
                let c = store.cell[k];
                for (edge, to, sign) in [(0, n, 1.0), (n - 1, -1, -1.0)] {
                    if c[d] != edge {
                        continue;
                    }
                    let (owner, mut shift) = if k < store.nlocal {
                        (k, [0.0; 3])
                    } else {
                        (self.src[k - store.nlocal] as usize, self.shift[k - store.nlocal])
                    };
                    shift[d] += sign * len[d];
                    let mut cell = c;
                    cell[d] = to;
                    store.push_ghost(owner, shift, cell);
                    self.src.push(owner as u32);
                    self.shift.push(shift);
                }
            }
        }
    }

    fn forward(&mut self, store: &mut Particles, fields: Fields) {
        let nlocal = store.nlocal;
        for (k, (&s, sh)) in self.src.iter().zip(&self.shift).enumerate() {
            let (g, s) = (nlocal + k, s as usize);
            copy_fields(store, s, g, fields);
            if fields.contains(Fields::POSITION) {
                let r = store.r[s];
                store.r[g] = [r[0] + sh[0], r[1] + sh[1], r[2] + sh[2]];
            }
        }
    }

    fn reverse(&mut self, store: &mut Particles, ghosts: &[u32], fields: Fields) {
        for &g in ghosts {
            let g = g as usize;
            let owner = self.src[g - store.nlocal] as usize;
            copy_fields(store, g, owner, fields);
        }
    }

    fn sum(&self, _values: &mut [f64]) {}

    fn max(&self, x: f64) -> f64 {
        x
    }
}

/// Copies the non-positional `fields` of particle `from` to particle `to`.
#[inline]
fn copy_fields(store: &mut Particles, from: usize, to: usize, fields: Fields) {
    if fields.contains(Fields::MOMENTUM) {
        store.p[to] = store.p[from];
    }
    if fields.contains(Fields::ENERGY) {
        store.u[to] = store.u[from];
    }
    if fields.contains(Fields::THETA) {
        store.theta[to] = store.theta[from];
    }
    for (flag, v) in [
        (Fields::DENSITY, &mut store.n),
        (Fields::PRESSURE, &mut store.pn2),
        (Fields::INV_TAU, &mut store.inv_tau),
    ] {
        if fields.contains(flag) && !v.is_empty() {
            v[to] = v[from];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn store_on_grid(l: f64, m: usize) -> (Particles, Domain, CellGrid) {
        let domain = Domain::new([0.0; 3], [l; 3]);
        let grid = CellGrid::new(&domain, l / 4.0).unwrap();
        let mut s = Particles::default();
        let h = l / m as f64;
        let mut tag = 1;
        for i in 0..m {
            for j in 0..m {
                for k in 0..m {
                    s.push(tag, 1, 1.0, [(i as f64 + 0.5) * h, (j as f64 + 0.5) * h, (k as f64 + 0.5) * h]);
                    tag += 1;
                }
            }
        }
        (s, domain, grid)
    }

    #[test]
    fn ghost_layer_is_one_cell_on_every_side() {
        let (mut s, d, g) = store_on_grid(8.0, 8);
        let mut c = SerialComm::new();
        c.exchange(&mut s, &d, &g);
        // 4^3 cells of 8 particles; ghosts fill one cell layer on every side: 6^3 - 4^3 cells
        assert_eq!(s.nlocal, 512);
        assert_eq!(s.nghost(), (216 - 64) * 8);
        for k in s.nlocal..s.len() {
            let src = c.src[k - s.nlocal] as usize;
            assert_eq!(s.tag[k], s.tag[src]);
            for dim in 0..3 {
                let expect = ((s.r[k][dim] / 2.0).floor()) as i32;
                assert_eq!(s.cell[k][dim], expect, "ghost cell follows its shifted position");
            }
        }
    }

    #[test]
    fn forward_and_reverse_copy_values() {
        let (mut s, d, g) = store_on_grid(8.0, 4);
        let mut c = SerialComm::new();
        c.exchange(&mut s, &d, &g);
        s.u[0] = 3.5;
        s.r[0][0] += 0.25;
        c.forward(&mut s, Fields::ENERGY | Fields::POSITION);
        let ghosts: Vec<u32> = (s.nlocal..s.len()).filter(|&k| c.src[k - s.nlocal] == 0).map(|k| k as u32).collect();
        assert!(!ghosts.is_empty());
        for &k in &ghosts {
            assert_eq!(s.u[k as usize], 3.5);
            let sh = c.shift[k as usize - s.nlocal];
            assert_eq!(s.r[k as usize][0], s.r[0][0] + sh[0]);
        }
        s.p[ghosts[0] as usize] = [1.0, 2.0, 3.0];
        c.reverse(&mut s, &ghosts[..1], Fields::MOMENTUM);
        assert_eq!(s.p[0], [1.0, 2.0, 3.0]);
    }
}
