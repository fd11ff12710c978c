//! The global cell grid: cells of side >= (cutoff + skin) / k, so that a pair spans at
//! most k cells per dimension (the grid's `reach`), with a count per dimension that is a
//! multiple of k + 1, so that the block-colour ownership of docs/models/sweep.md (8 colours
//! for k = 1) is well defined.
//!
//! A pair of particles in cells A and B (at most k apart per dimension, periodic) is
//! owned by the cell C = componentwise min(A, B); C's pairs touch only the block
//! C + {0..k}^3, and the colour of C is its index modulo k + 1, so blocks of one colour
//! are disjoint (with k + 1 cells along a dimension a colour has one block along it,
//! which covers each cell once). A box of length >= 2 (cutoff + skin) holds at most one
//! periodic image of a particle within the cutoff of another, so every (pair, image)
//! lies in one block.
//!
//! The grid depends on the box and the cutoff only (never on the ranks): k = 1 with an
//! even count >= 4 per dimension where the box allows it (every box of at least
//! 4 (cutoff + skin)); else k = 2 with >= 6 cells of side >= (cutoff + skin) / 2 (boxes
//! from 3 (cutoff + skin), LAMMPS's in.dpd), which leaves cells for up to 3 ranks per
//! dimension; else k = 1 with 2 cells (boxes from 2 (cutoff + skin), one rank across).

use crate::{Domain, Vec3};
use std::fmt;

/// Smallest number of cells of side cutoff + skin per dimension a box must hold.
pub const MIN_CELLS: usize = 2;

/// Cells a grid may have however few particles it holds (16^3).
pub const FEW_CELLS: usize = 4096;

#[derive(Clone, Debug, PartialEq)]
pub struct CellGrid {
    /// Cells per dimension (a multiple of `reach` + 1).
    pub count: [usize; 3],
    /// Cell side per dimension.
    pub side: Vec3,
    /// Cells a pair may span per dimension (k): blocks of (k + 1)^3 cells, (k + 1)^3
    /// colours, ghost layers k cells deep.
    pub reach: usize,
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
    /// The grid for pairs up to `cut` apart (see the module's rule for the reach k): the
    /// finest with a multiple of k + 1 cells of side >= `cut` / k per dimension.
    pub fn new(domain: &Domain, cut: f64) -> Result<Self, GridError> {
        let len = domain.len();
        // cells of side >= cut / k along each dimension, a multiple of k + 1 of them
        let counts = |k: usize| {
            [0, 1, 2].map(|d| {
                let fit = if cut > 0.0 { (len[d] * k as f64 / cut).floor() as usize } else { usize::MAX };
                let n = fit.min(1 << 10);
                n - n % (k + 1)
            })
        };
        let (reach, count) = match (counts(1), counts(2)) {
            (c, _) if c.iter().all(|&n| n >= 4) => (1, c),
            (_, c) if c.iter().all(|&n| n >= 6) => (2, c),
            (c, _) => (1, c),
        };
        if let Some(d) = (0..3).find(|&d| count[d] < MIN_CELLS) {
            return Err(GridError { dim: d, length: len[d], cut });
        }
        let side = [0, 1, 2].map(|d| len[d] / count[d] as f64);
        Ok(Self { count, side, reach, lo: domain.lo, len })
    }

    /// The grid with at most max(`particles`, [`FEW_CELLS`]) cells, coarsened k + 1 cells
    /// at a time along the finest dimension (to no fewer than 2 (k + 1)): a dilute box
    /// needs no more cells than particles (LAMMPS caps its bins too), and the bins of a
    /// finer grid could outgrow memory. Dense boxes keep their grid.
    pub fn at_most(mut self, particles: usize) -> Self {
        let limit = particles.max(FEW_CELLS);
        let step = self.reach + 1;
        while self.len() > limit {
            let d = (0..3).rev().max_by_key(|&d| self.count[d]).unwrap_or(0);
            if self.count[d] <= 2 * step {
                break;
            }
            self.count[d] -= step;
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

    /// The octant of position `r` within cell `c`: bit d set where r_d lies in the upper
    /// half of the cell along d. Taken for owned particles with their cell at a rebuild;
    /// ghosts carry their owner's (the `octant` field), so it is the same on every rank
    /// count.
    #[inline]
    pub fn octant(&self, c: [i32; 3], r: Vec3) -> usize {
        let mut q = 0;
        for d in 0..3 {
            let mid = self.lo[d] + (c[d] as f64 + 0.5) * self.side[d];
            q |= ((r[d] >= mid) as usize) << d;
        }
        q
    }

    /// Total number of cells.
    pub fn len(&self) -> usize {
        self.count.iter().product()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The number of colours, (k + 1)^3.
    pub fn colours(&self) -> usize {
        (self.reach + 1).pow(3)
    }

    /// Colour of a cell on a grid of reach k: its coordinates modulo k + 1, x fastest
    /// (for k = 1 the parity of its coordinates, 0..8).
    #[inline]
    pub fn colour(c: [i32; 3], reach: usize) -> usize {
        let m = reach as i32 + 1;
        (c[0].rem_euclid(m) + m * (c[1].rem_euclid(m) + m * c[2].rem_euclid(m))) as usize
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
    fn a_box_under_four_cuts_gets_finer_cells() {
        // LAMMPS's DPD-BASIC in.dpd: a 5.5 box, cutoff 1.22 + skin 0.3: cells of half the
        // cut, a multiple of 3 per dimension
        let d = Domain::new([0.0; 3], [5.5, 5.5, 40.0]);
        let g = CellGrid::new(&d, 1.52).unwrap();
        assert_eq!((g.reach, g.count, g.colours()), (2, [6, 6, 51], 27));
        assert!(g.side.iter().all(|&s| s >= 0.76));
        // under 3 cuts: 2 cells of the cut
        let g = CellGrid::new(&Domain::new([0.0; 3], [4.0, 5.5, 40.0]), 1.52).unwrap();
        assert_eq!((g.reach, g.count), (1, [2, 2, 26]));
    }

    #[test]
    fn a_dilute_box_gets_no_more_cells_than_particles() {
        let d = Domain::new([0.0; 3], [1e9, 1e9, 2e9]);
        let g = CellGrid::new(&d, 4.4).unwrap();
        assert_eq!(g.count, [1024; 3]);
        let g = g.at_most(100_000);
        assert!(g.len() <= 100_000 && g.len() > 90_000, "{:?}", g.count);
        assert!(g.reach == 1 && g.count.iter().all(|&n| n % 2 == 0) && g.side.iter().all(|&s| s >= 4.4));
        assert_eq!(CellGrid::new(&d, 4.4).unwrap().at_most(10).count, [16; 3]);
        // a dense box keeps its grid
        let dense = Domain::new([0.0; 3], [18.9, 20.0, 40.0]);
        assert_eq!(CellGrid::new(&dense, 4.4).unwrap().at_most(1000).count, [4, 4, 8]);
    }

    #[test]
    fn colours_alternate() {
        assert_eq!(CellGrid::colour([0, 0, 0], 1), 0);
        assert_eq!(CellGrid::colour([3, 2, 5], 1), 5);
        assert_eq!(CellGrid::colour([-1, 4, 4], 1), 1);
        assert_eq!(CellGrid::colour([-1, 4, 5], 2), 2 + 3 * (1 + 3 * 2));
    }
}

/// Particles (owned and ghost) sorted by cell over the owned range plus the ghost
/// cells (k on every side), by octant within each cell ([`CellGrid::octant`] at the
/// last rebuild), and by tag within each octant. Walking cells in a fixed stencil order,
/// octants in a fixed order and particles in tag order gives every list an order that
/// no decomposition can change (the lists need no sorting of their own); the octants let
/// the pair search skip the parts of a cell pair out of range.
#[derive(Clone, Debug, Default)]
pub struct CellBins {
    /// The grid's reach k: the bins hold k ghost cells on every side.
    pub reach: usize,
    /// Side of an octant (half the cell side) per dimension.
    pub octant_side: Vec3,
    lo: [i32; 3],
    dims: [usize; 3],
    /// Start of octant q of cell k in `items` at `start[8 k + q]`.
    start: Vec<u32>,
    items: Vec<u32>,
    fill: Vec<u32>,
    /// Scratch: the bin (8 cell + octant) of each particle.
    bin_of: Vec<u32>,
}

impl CellBins {
    /// Bins particles by their `cell` for the owned range [lo, hi) and the grid's reach
    /// of ghost cells on every side, by `octant` within a cell (kept from the last
    /// rebuild, like the cell, so that a restart continues with the same order), ordered
    /// by `tag` within an octant.
    pub fn build(&mut self, cells: &[[i32; 3]], octants: &[u32], tags: &[u64], grid: &CellGrid, lo: [i32; 3], hi: [i32; 3]) {
        let reach = grid.reach;
        let k = reach as i32;
        self.reach = reach;
        self.octant_side = grid.side.map(|s| 0.5 * s);
        self.lo = [lo[0] - k, lo[1] - k, lo[2] - k];
        self.dims = [0, 1, 2].map(|d| (hi[d] - lo[d] + 2 * k) as usize);
        let nbin = 8 * self.dims.iter().product::<usize>();
        self.start.clear();
        self.start.resize(nbin + 1, 0);
        let mut bin_of = std::mem::take(&mut self.bin_of);
        bin_of.clear();
        bin_of.extend(cells.iter().zip(octants).map(|(&c, &q)| 8 * self.index(c) as u32 + q));
        for &b in &bin_of {
            self.start[b as usize + 1] += 1;
        }
        for b in 0..nbin {
            self.start[b + 1] += self.start[b];
        }
        self.fill.clear();
        self.fill.extend_from_slice(&self.start[..nbin]);
        self.items.clear();
        self.items.resize(cells.len(), 0);
        for (i, &b) in bin_of.iter().enumerate() {
            self.items[self.fill[b as usize] as usize] = i as u32;
            self.fill[b as usize] += 1;
        }
        self.bin_of = bin_of;
        for b in 0..nbin {
            self.items[self.start[b] as usize..self.start[b + 1] as usize].sort_unstable_by_key(|&i| tags[i as usize]);
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

    /// Particles in cell `c` (which must lie in the binned range), by octant then tag.
    #[inline]
    pub fn cell(&self, c: [i32; 3]) -> &[u32] {
        let k = 8 * self.index(c);
        &self.items[self.start[k] as usize..self.start[k + 8] as usize]
    }

    /// The eight octants of cell `c`, each in tag order.
    #[inline]
    pub fn octants(&self, c: [i32; 3]) -> [&[u32]; 8] {
        let k = 8 * self.index(c);
        std::array::from_fn(|q| &self.items[self.start[k + q] as usize..self.start[k + q + 1] as usize])
    }
}
