//! The global cell grid: cells of side >= cutoff + skin, an even count >= 2 per
//! dimension, so that the 8-colour block ownership of ARCHITECTURE.md is well defined.
//!
//! A pair of particles in cells A and B (adjacent or equal, periodic) is owned by the
//! cell C = componentwise min(A, B); C's pairs touch only the block C + {0,1}^3, and the
//! colour of C is the parity of its index, so blocks of one colour are disjoint (with
//! 2 cells along a dimension a colour has one block along it, which covers both cells
//! once). A box of length >= 2 (cutoff + skin) holds at most one periodic image of a
//! particle within the cutoff of another, so every (pair, image) lies in one block.

use crate::{Domain, Vec3};
use std::fmt;

/// Smallest number of cells per dimension the colouring accepts.
pub const MIN_CELLS: usize = 2;

/// Cells a grid may have however few particles it holds (16^3).
pub const FEW_CELLS: usize = 4096;

#[derive(Clone, Debug, PartialEq)]
pub struct CellGrid {
    /// Cells per dimension (even, >= 2).
    pub count: [usize; 3],
    /// Cell side per dimension.
    pub side: Vec3,
    lo: Vec3,
    len: Vec3,
}

/// The box cannot hold the colour grid.
#[derive(Clone, Debug, PartialEq)]
pub struct GridError {
    pub dim: usize,
    pub length: f64,
    pub cut: f64,
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let axis = ["x", "y", "z"][self.dim];
        write!(
            f,
            "box length {:.6} along {axis} holds fewer than {MIN_CELLS} cells of side cutoff + skin = {:.6} \
             (a periodic image of a particle would interact twice); the smallest valid length is {:.6} \
             (enlarge the box, or reduce the cutoff or the skin)",
            self.length,
            self.cut,
            MIN_CELLS as f64 * self.cut
        )
    }
}

impl std::error::Error for GridError {}

impl CellGrid {
    /// The finest grid with an even number (>= 2) of cells of side >= `cut`.
    pub fn new(domain: &Domain, cut: f64) -> Result<Self, GridError> {
        let len = domain.len();
        let mut count = [0; 3];
        let mut side = [0.0; 3];
        for d in 0..3 {
            let fit = if cut > 0.0 { (len[d] / cut).floor() as usize } else { usize::MAX };
            let n = fit.min(1 << 10) & !1;
            if n < MIN_CELLS {
                return Err(GridError { dim: d, length: len[d], cut });
            }
            count[d] = n;
            side[d] = len[d] / n as f64;
        }
        Ok(Self { count, side, lo: domain.lo, len })
    }

    /// The grid with at most max(`particles`, [`FEW_CELLS`]) cells, coarsened two cells
    /// at a time along the finest dimension (to no fewer than 4): a dilute box needs no
    /// more cells than particles (LAMMPS caps its bins too), and the bins of a finer grid
    /// could outgrow memory. Dense boxes keep their grid.
    pub fn at_most(mut self, particles: usize) -> Self {
        let limit = particles.max(FEW_CELLS);
        while self.len() > limit {
            let d = (0..3).rev().max_by_key(|&d| self.count[d]).unwrap_or(0);
            if self.count[d] <= 4 {
                break;
            }
            self.count[d] -= 2;
            self.side[d] = self.len[d] / self.count[d] as f64;
        }
        self
    }

    /// Cell coordinates of a position inside the box.
    #[inline]
    pub fn locate(&self, r: Vec3) -> [i32; 3] {
        let mut c = [0; 3];
        for d in 0..3 {
            let k = ((r[d] - self.lo[d]) / self.side[d]).floor() as i64;
            c[d] = k.clamp(0, self.count[d] as i64 - 1) as i32;
        }
        c
    }

    /// Total number of cells.
    pub fn len(&self) -> usize {
        self.count.iter().product()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Colour 0..8 of a cell: the parity of its coordinates.
    #[inline]
    pub fn colour(c: [i32; 3]) -> usize {
        ((c[0] & 1) | ((c[1] & 1) << 1) | ((c[2] & 1) << 2)) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_is_even_and_at_least_the_cut() {
        let d = Domain::new([0.0; 3], [18.9, 20.0, 40.0]);
        let g = CellGrid::new(&d, 4.4).unwrap();
        assert_eq!(g.count, [4, 4, 8]);
        assert!(g.side.iter().all(|&s| s >= 4.4));
        assert_eq!(g.locate([18.89, 0.0, 39.99]), [3, 0, 7]);
    }

    #[test]
    fn too_small_box_names_the_smallest_valid_length() {
        let d = Domain::new([0.0; 3], [8.0, 20.0, 20.0]);
        let e = CellGrid::new(&d, 4.4).unwrap_err();
        assert_eq!(e.dim, 0);
        assert!(e.to_string().contains("8.8"), "{e}");
    }

    #[test]
    fn a_box_between_two_and_four_cuts_gets_two_cells() {
        // LAMMPS's DPD-BASIC in.dpd: a 5.5 box, cutoff 1.22 + skin 0.3
        let d = Domain::new([0.0; 3], [5.5, 5.5, 40.0]);
        let g = CellGrid::new(&d, 1.52).unwrap();
        assert_eq!(g.count, [2, 2, 26]);
    }

    #[test]
    fn a_dilute_box_gets_no_more_cells_than_particles() {
        let d = Domain::new([0.0; 3], [1e9, 1e9, 2e9]);
        let g = CellGrid::new(&d, 4.4).unwrap();
        assert_eq!(g.count, [1024; 3]);
        let g = g.at_most(100_000);
        assert!(g.len() <= 100_000 && g.len() > 90_000, "{:?}", g.count);
        assert!(g.count.iter().all(|&n| n % 2 == 0) && g.side.iter().all(|&s| s >= 4.4));
        assert_eq!(CellGrid::new(&d, 4.4).unwrap().at_most(10).count, [16; 3]);
        // a dense box keeps its grid
        let dense = Domain::new([0.0; 3], [18.9, 20.0, 40.0]);
        assert_eq!(CellGrid::new(&dense, 4.4).unwrap().at_most(1000).count, [4, 4, 8]);
    }

    #[test]
    fn colours_alternate() {
        assert_eq!(CellGrid::colour([0, 0, 0]), 0);
        assert_eq!(CellGrid::colour([3, 2, 5]), 5);
        assert_eq!(CellGrid::colour([-1, 4, 4]), 1);
    }
}

/// Particles (owned and ghost) sorted by cell over the owned range plus one ghost
/// cell on every side, and by tag within each cell. Walking cells in a fixed stencil
/// order and particles in tag order gives every list an order that no decomposition can
/// change (the lists need no sorting of their own).
#[derive(Clone, Debug, Default)]
pub struct CellBins {
    lo: [i32; 3],
    dims: [usize; 3],
    start: Vec<u32>,
    items: Vec<u32>,
    fill: Vec<u32>,
}

impl CellBins {
    /// Bins particles by their `cell` for the owned range [lo, hi), ordered by `tag`
    /// within each cell.
    pub fn build(&mut self, cells: &[[i32; 3]], tags: &[u64], lo: [i32; 3], hi: [i32; 3]) {
        self.lo = [lo[0] - 1, lo[1] - 1, lo[2] - 1];
        self.dims = [0, 1, 2].map(|d| (hi[d] - lo[d] + 2) as usize);
        let ncell = self.dims.iter().product::<usize>();
        self.start.clear();
        self.start.resize(ncell + 1, 0);
        for c in cells {
            let k = self.index(*c);
            self.start[k + 1] += 1;
        }
        for k in 0..ncell {
            self.start[k + 1] += self.start[k];
        }
        self.fill.clear();
        self.fill.extend_from_slice(&self.start[..ncell]);
        self.items.clear();
        self.items.resize(cells.len(), 0);
        for (i, c) in cells.iter().enumerate() {
            let k = self.index(*c);
            self.items[self.fill[k] as usize] = i as u32;
            self.fill[k] += 1;
        }
        for k in 0..ncell {
            self.items[self.start[k] as usize..self.start[k + 1] as usize].sort_unstable_by_key(|&i| tags[i as usize]);
        }
    }

    #[inline]
    fn index(&self, c: [i32; 3]) -> usize {
        let x = (c[0] - self.lo[0]) as usize;
        let y = (c[1] - self.lo[1]) as usize;
        let z = (c[2] - self.lo[2]) as usize;
        debug_assert!(x < self.dims[0] && y < self.dims[1] && z < self.dims[2], "cell {c:?} outside bins");
        (z * self.dims[1] + y) * self.dims[0] + x
    }

    /// Particles in cell `c` (which must lie in the binned range).
    #[inline]
    pub fn cell(&self, c: [i32; 3]) -> &[u32] {
        let k = self.index(c);
        &self.items[self.start[k] as usize..self.start[k + 1] as usize]
    }
}
