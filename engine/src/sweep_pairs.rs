//! The pairs of the Shardlow sweep, grouped by colour and block.
//!
//! Pairs of colour c live in blocks C + {0,1}^3 of cells C with colour c; blocks of
//! one colour are disjoint, so they commute. Within a block, pairs run by pair of cells
//! in a fixed order, then by the tags of the two particles (the bins hold each cell in
//! tag order): an order no decomposition can change.

use crate::cells::CellBins;
use crate::{dot, sub, CellGrid, Particles};

#[derive(Clone, Debug, Default)]
pub struct SweepPairs {
    /// List radius: sweep cutoff plus skin.
    pub radius: f64,
    /// Pairs (i, j) with tag[i] < tag[j].
    pub pairs: Vec<[u32; 2]>,
    /// Pairs of colour c: `pairs[colour_start[c]..colour_start[c + 1]]`.
    pub colour_start: [usize; 9],
    /// Ghosts written by the pairs of colour c (sorted, unique).
    pub ghost_writes: [Vec<u32>; 8],
}

/// Cell offsets (a, b) within a block whose componentwise min is the block's own cell:
/// the 3-bit masks a, b with a & b == 0 and a <= b (14 pairs of cells).
const CELL_PAIRS: [(u8, u8); 14] = {
    let mut out = [(0u8, 0u8); 14];
    let mut k = 0;
    let mut a = 0u8;
    while a < 8 {
        let mut b = a;
        while b < 8 {
            if a & b == 0 {
                out[k] = (a, b);
                k += 1;
            }
            b += 1;
        }
        a += 1;
    }
    out
};

impl SweepPairs {
    /// Collects, colour by colour, the pairs closer than `radius` owned by the cells
    /// in [lo, hi).
    pub fn build(&mut self, store: &Particles, bins: &CellBins, lo: [i32; 3], hi: [i32; 3], radius: f64) {
        self.radius = radius;
        let r2max = radius * radius;
        self.pairs.clear();
        let offset = |c: [i32; 3], m: u8| [c[0] + (m & 1) as i32, c[1] + ((m >> 1) & 1) as i32, c[2] + ((m >> 2) & 1) as i32];
        for colour in 0..8 {
            self.colour_start[colour] = self.pairs.len();
            let mut writes = Vec::new();
            for z in lo[2]..hi[2] {
                for y in lo[1]..hi[1] {
                    for x in lo[0]..hi[0] {
                        let c = [x, y, z];
                        if CellGrid::colour(c) != colour {
                            continue;
                        }
                        let block_start = self.pairs.len();
                        for &(a, b) in &CELL_PAIRS {
                            let (ca, cb) = (bins.cell(offset(c, a)), bins.cell(offset(c, b)));
                            for (k, &i) in ca.iter().enumerate() {
                                let partners = if a == b { &ca[k + 1..] } else { cb };
                                for &j in partners {
                                    let d = sub(store.r[i as usize], store.r[j as usize]);
                                    if dot(d, d) < r2max {
                                        let pair = if store.tag[i as usize] < store.tag[j as usize] { [i, j] } else { [j, i] };
                                        self.pairs.push(pair);
                                    }
                                }
                            }
                        }
                        let block = &self.pairs[block_start..];
                        writes.extend(block.iter().flatten().copied().filter(|&k| k as usize >= store.nlocal));
                    }
                }
            }
            writes.sort_unstable();
            writes.dedup();
            self.ghost_writes[colour] = writes;
        }
        self.colour_start[8] = self.pairs.len();
    }

    /// Pairs of one colour.
    pub fn colour(&self, c: usize) -> &[[u32; 2]] {
        &self.pairs[self.colour_start[c]..self.colour_start[c + 1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Comm, Domain};
    use std::collections::{HashMap, HashSet};

    /// A random gas in a 4x4x6 cell box, with its ghosts and bins.
    fn gas() -> (Particles, CellBins, CellGrid, Domain) {
        let domain = Domain::new([0.0; 3], [9.0, 9.5, 13.0]);
        let grid = CellGrid::new(&domain, 2.1).unwrap();
        let mut s = Particles::default();
        let mut x: u64 = 12345;
        let mut next = || {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for tag in 1..=700u64 {
            let r = [9.0 * next(), 9.5 * next(), 13.0 * next()];
            s.push(tag * 7 % 701, 1, 1.0, r);
        }
        let mut comm = Comm::serial();
        comm.exchange(&mut s, &domain, &grid, false);
        let mut bins = CellBins::default();
        let (lo, hi) = comm.owned_cells(&grid);
        bins.build(&s.cell, &s.tag, lo, hi);
        (s, bins, grid, domain)
    }

    #[test]
    fn every_pair_within_range_appears_once() {
        let (s, bins, grid, domain) = gas();
        let (lo, hi) = ([0; 3], grid.count.map(|c| c as i32));
        let mut sp = SweepPairs::default();
        sp.build(&s, &bins, lo, hi, 2.0);
        let l = domain.len();
        let mut expect = HashSet::new();
        for i in 0..s.nlocal {
            for j in i + 1..s.nlocal {
                let mut d2 = 0.0;
                for k in 0..3 {
                    let mut d = s.r[i][k] - s.r[j][k];
                    d -= l[k] * (d / l[k]).round();
                    d2 += d * d;
                }
                if d2 < 4.0 {
                    expect.insert((s.tag[i].min(s.tag[j]), s.tag[i].max(s.tag[j])));
                }
            }
        }
        let got: Vec<_> = sp.pairs.iter().map(|&[i, j]| (s.tag[i as usize], s.tag[j as usize])).collect();
        assert!(got.iter().all(|&(a, b)| a < b));
        let got_set: HashSet<_> = got.iter().copied().collect();
        assert_eq!(got.len(), got_set.len(), "a pair appears twice");
        assert_eq!(got_set, expect);
    }

    #[test]
    fn within_a_colour_every_particle_has_one_writer() {
        let (s, bins, grid, _) = gas();
        let mut sp = SweepPairs::default();
        sp.build(&s, &bins, [0; 3], grid.count.map(|c| c as i32), 2.0);
        for c in 0..8 {
            // tag -> the local index (owned or ghost copy) written in this colour
            let mut writer: HashMap<u64, u32> = HashMap::new();
            for &[i, j] in sp.colour(c) {
                for k in [i, j] {
                    let prev = writer.insert(s.tag[k as usize], k);
                    assert!(prev.is_none() || prev == Some(k), "two copies of one particle in colour {c}");
                }
            }
            let ghosts: Vec<u32> = writer.values().copied().filter(|&k| k as usize >= s.nlocal).collect();
            assert_eq!(ghosts.len(), sp.ghost_writes[c].len());
        }
    }
}
