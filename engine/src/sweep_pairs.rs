//! The pairs of the Shardlow sweep, grouped by colour and block.
//!
//! Pairs of colour c live in blocks C + {0..k}^3 of cells C with colour c (k the
//! grid's reach); blocks of one colour are disjoint, so they commute. Within a block,
//! pairs run by pair of cells in a fixed order, then by the octants and tags of the two
//! particles (the bins hold each cell by octant and tag): an order no decomposition can
//! change. Built by [`crate::pair_search`].

use crate::{dot, sub, Particles};

#[derive(Clone, Debug, Default)]
pub struct SweepPairs {
    /// List radius: sweep cutoff plus skin.
    pub radius: f64,
    /// Pairs (i, j) with tag[i] < tag[j].
    pub pairs: Vec<[u32; 2]>,
    /// Pairs of colour c: `pairs[colour_start[c]..colour_start[c + 1]]`.
    pub colour_start: Vec<usize>,
    /// Ghosts written by the pairs of colour c (sorted, unique); one entry per colour.
    pub ghost_writes: Vec<Vec<u32>>,
    /// Whether each particle (owned or ghost) is in a pair of colour c; one entry per
    /// colour.
    pub members: Vec<Vec<bool>>,
    /// Scratch of [`SweepPairs::within_displaced`]: the selected pairs lead it (the rest
    /// is left from earlier colours, so the scratch is filled only as it grows).
    active: Vec<[u32; 2]>,
    /// Scratch of [`SweepPairs::within_displaced`]: r_i - r_j and |r_i - r_j|^2 of each
    /// selected pair.
    displacement: Vec<[f64; 4]>,
}

impl SweepPairs {
    /// The number of colours ((k + 1)^3 for a grid of reach k).
    pub fn colours(&self) -> usize {
        self.ghost_writes.len()
    }

    /// Pairs of one colour.
    pub fn colour(&self, c: usize) -> &[[u32; 2]] {
        &self.pairs[self.colour_start[c]..self.colour_start[c + 1]]
    }

    /// The pairs of colour c closer than `rc` and farther than 1e-10, in order,
    /// selected without a branch per pair (about half the list lies in the skin, a test
    /// the processor could not predict), with each pair's r_i - r_j and |r_i - r_j|^2 as
    /// the selection computed them (`[x, y, z, r^2]`), for a sweep that would compute them
    /// again.
    pub fn within_displaced(&mut self, c: usize, store: &Particles, rc: f64) -> (&[[u32; 2]], &[[f64; 4]]) {
        let range = self.colour_start[c]..self.colour_start[c + 1];
        if self.active.len() < range.len() {
            self.active.resize(range.len(), [0; 2]);
        }
        if self.displacement.len() < range.len() {
            self.displacement.resize(range.len(), [0.0; 4]);
        }
        let mut m = 0;
        for &[i, j] in &self.pairs[range] {
            let d = sub(store.r[i as usize], store.r[j as usize]);
            let r2 = dot(d, d);
            self.active[m] = [i, j];
            self.displacement[m] = [d[0], d[1], d[2], r2];
            m += (r2 < rc * rc && r2 >= 1e-20) as usize;
        }
        (&self.active[..m], &self.displacement[..m])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cells::CellBins;
    use crate::pair_search::{build_lists, ListRequest};
    use crate::{CellGrid, Comm, Domain, NeighborList, Particles};
    use std::collections::{HashMap, HashSet};

    /// Boxes for a cut of 2.1: 4x4x6 cells (reach 1), 2x4x2 cells (reach 1, 2 cells
    /// across), 6x9x6 cells (reach 2), 2x2x4 cells (reach 1); the 700 particles fill the
    /// cells of the second and the fourth with ~40 each, which are searched by octant.
    const BOXES: [[f64; 3]; 4] = [[9.0, 9.5, 13.0], [4.5, 9.5, 5.0], [7.0, 9.5, 6.5], [5.0, 5.0, 9.0]];

    /// A random gas in a box of `lengths`, with its ghosts and bins.
    fn gas(lengths: [f64; 3]) -> (Particles, CellBins, CellGrid, Domain) {
        let domain = Domain::new([0.0; 3], lengths);
        let grid = CellGrid::new(&domain, 2.1).unwrap();
        let mut s = Particles::default();
        let mut x: u64 = 12345;
        let mut next = || {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let l = domain.len();
        for tag in 1..=700u64 {
            let r = [l[0] * next(), l[1] * next(), l[2] * next()];
            s.push(tag * 7 % 701, 1, 1.0, r);
        }
        let mut comm = Comm::serial();
        comm.exchange(&mut s, &domain, &grid, false);
        let mut bins = CellBins::default();
        let (lo, hi) = comm.owned_cells(&grid);
        bins.build(&s.cell, &s.octant, &s.tag, &grid, lo, hi);
        (s, bins, grid, domain)
    }

    #[test]
    fn every_pair_within_range_appears_once() {
        for thin in BOXES {
            every_pair_within_range_appears_once_in(thin);
        }
    }

    fn every_pair_within_range_appears_once_in(thin: [f64; 3]) {
        let (s, bins, grid, domain) = gas(thin);
        let (lo, hi) = ([0; 3], grid.count.map(|c| c as i32));
        let mut sp = SweepPairs::default();
        build_lists(&s, &bins, lo, hi, ListRequest { nlist: None, sweep: Some((&mut sp, 2.0)) });
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
        for thin in BOXES {
            within_a_colour_every_particle_has_one_writer_in(thin);
        }
    }

    fn within_a_colour_every_particle_has_one_writer_in(thin: [f64; 3]) {
        let (s, bins, grid, _) = gas(thin);
        let mut sp = SweepPairs::default();
        let hi = grid.count.map(|c| c as i32);
        build_lists(&s, &bins, [0; 3], hi, ListRequest { nlist: None, sweep: Some((&mut sp, 2.0)) });
        assert_eq!(sp.colours(), grid.colours());
        for c in 0..sp.colours() {
            // tag -> the local index (owned or ghost copy) written in this colour
            let mut writer: HashMap<u64, u32> = HashMap::new();
            for &[i, j] in sp.colour(c) {
                for k in [i, j] {
                    let prev = writer.insert(s.tag[k as usize], k);
                    assert!(prev.is_none() || prev == Some(k), "two copies of one particle in colour {c}");
                }
            }
            let mut ghosts: Vec<u32> = writer.values().copied().filter(|&k| k as usize >= s.nlocal).collect();
            ghosts.sort_unstable();
            assert_eq!(ghosts, sp.ghost_writes[c]);
            let members: Vec<u32> = (0..s.len() as u32).filter(|&k| sp.members[c][k as usize]).collect();
            let mut written: Vec<u32> = writer.values().copied().collect();
            written.sort_unstable();
            assert_eq!(members, written);
        }
    }

    /// Tags of the particles closer than `radius` to each owned particle, by brute force
    /// over the periodic images.
    fn brute_neighbours(s: &Particles, domain: &Domain, radius: f64) -> Vec<Vec<u64>> {
        let l = domain.len();
        (0..s.nlocal)
            .map(|i| {
                let mut tags: Vec<u64> = (0..s.nlocal)
                    .filter(|&j| {
                        let mut d2 = 0.0;
                        for k in 0..3 {
                            let mut d = s.r[i][k] - s.r[j][k];
                            d -= l[k] * (d / l[k]).round();
                            d2 += d * d;
                        }
                        j != i && d2 < radius * radius
                    })
                    .map(|j| s.tag[j])
                    .collect();
                tags.sort_unstable();
                tags
            })
            .collect()
    }

    #[test]
    fn neighbour_pairs_give_every_owned_particle_each_neighbour_once() {
        for thin in BOXES {
            neighbour_pairs_give_every_owned_particle_each_neighbour_once_in(thin);
        }
    }

    fn neighbour_pairs_give_every_owned_particle_each_neighbour_once_in(thin: [f64; 3]) {
        let (s, bins, grid, domain) = gas(thin);
        let (mut sp, mut nl) = (SweepPairs::default(), NeighborList::default());
        let hi = grid.count.map(|c| c as i32);
        // the sweep on a shorter radius than the lists: each filtered on its own
        let req = ListRequest { nlist: Some((&mut nl, 2.0)), sweep: Some((&mut sp, 1.5)) };
        build_lists(&s, &bins, [0; 3], hi, req);
        let expect = brute_neighbours(&s, &domain, 2.0);
        let mut got = vec![Vec::new(); s.nlocal];
        for &[i, j] in &nl.pairs {
            for (a, b) in [(i as usize, j as usize), (j as usize, i as usize)] {
                if a < s.nlocal {
                    got[a].push(s.tag[b]);
                }
            }
        }
        for i in 0..s.nlocal {
            got[i].sort_unstable();
            assert_eq!(got[i], expect[i], "neighbours of tag {}", s.tag[i]);
        }
        let closer: usize = brute_neighbours(&s, &domain, 1.5).iter().map(Vec::len).sum();
        assert_eq!(2 * sp.pairs.len(), closer);
    }
}
