//! Full Verlet neighbour lists, rebuilt when a particle has moved more than half the
//! skin (the decision is the integrator's).
//!
//! Every owned particle lists all its neighbours (owned or ghost) by stencil offset in a
//! fixed order, then by tag within each cell, so density and force sums run in an order
//! no decomposition can change.

use crate::cells::CellBins;
use crate::{dot, sub, Particles};

#[derive(Clone, Debug, Default)]
pub struct NeighborList {
    /// List radius: interaction cutoff plus skin.
    pub radius: f64,
    /// Neighbours of owned particle i: `neighbors[offsets[i]..offsets[i + 1]]`.
    pub offsets: Vec<u32>,
    pub neighbors: Vec<u32>,
}

impl NeighborList {
    /// Builds the lists of all owned particles from the cell bins.
    pub fn build(&mut self, store: &Particles, bins: &CellBins, radius: f64) {
        self.radius = radius;
        let r2max = radius * radius;
        self.offsets.clear();
        self.neighbors.clear();
        self.offsets.push(0);
        for i in 0..store.nlocal {
            let start = self.neighbors.len();
            let (ri, c) = (store.r[i], store.cell[i]);
            for dz in -1..=1 {
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        for &j in bins.cell([c[0] + dx, c[1] + dy, c[2] + dz]) {
                            let d = sub(ri, store.r[j as usize]);
                            if j as usize != i && dot(d, d) < r2max {
                                self.neighbors.push(j);
                            }
                        }
                    }
                }
            }
            debug_assert!(self.neighbors.len() >= start);
            self.offsets.push(self.neighbors.len() as u32);
        }
    }

    /// Neighbours of owned particle i.
    #[inline]
    pub fn of(&self, i: usize) -> &[u32] {
        &self.neighbors[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
}
