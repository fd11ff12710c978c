//! One half pass over the cell pairs that builds both the neighbour list and the
//! coloured Shardlow pairs.
//!
//! Every unordered pair of adjacent (or equal) cells A, B lies in exactly one block
//! C + {0,1}^3 with C = min(A, B) componentwise, as the pair of offsets (a, b) with
//! a & b == 0. The pass walks the blocks of C in [lo - 1, hi) colour by colour, in
//! lexicographic order within a colour, then the 14 cell pairs of a block, then the
//! particles by tag (the bins hold each cell in tag order), and tests each particle pair
//! once. A cell A lies in exactly one block per colour, so the order in which a particle
//! meets its neighbours depends only on the parity of its cell and the tags: no
//! decomposition can change it. Pairs of owned blocks (C in [lo, hi)) are the sweep's;
//! every pair with an owned particle enters the neighbour list, in pass order.

use crate::cells::CellBins;
use crate::{dot, sub, CellGrid, NeighborList, Particles, SweepPairs};

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

/// The lists wanted from a pass, each with its radius (cutoff plus skin).
pub struct ListRequest<'a> {
    pub nlist: Option<(&'a mut NeighborList, f64)>,
    pub sweep: Option<(&'a mut SweepPairs, f64)>,
}

/// Builds the requested lists for the owned cells [lo, hi) from the bins (which hold
/// [lo - 1, hi] with the ghosts).
pub fn build_lists(store: &Particles, bins: &CellBins, lo: [i32; 3], hi: [i32; 3], req: ListRequest<'_>) {
    let ListRequest { mut nlist, mut sweep } = req;
    let rn2 = nlist.as_ref().map_or(-1.0, |(_, r)| r * r);
    let rs2 = sweep.as_ref().map_or(-1.0, |(_, r)| r * r);
    let r2max = rn2.max(rs2);
    let nlocal = store.nlocal as u32;
    let owned = |c: [i32; 3]| (0..3).all(|d| c[d] >= lo[d] && c[d] < hi[d]);
    let offset = |c: [i32; 3], m: u8| [c[0] + (m & 1) as i32, c[1] + ((m >> 1) & 1) as i32, c[2] + ((m >> 2) & 1) as i32];
    // reuse the memory of the previous lists
    let mut half = match nlist.as_mut() {
        Some((nl, _)) => std::mem::take(&mut nl.pairs),
        None => Vec::new(),
    };
    half.clear();
    let (mut sweep_pairs, mut ghost_writes) = match sweep.as_mut() {
        Some((sp, _)) => (std::mem::take(&mut sp.pairs), std::mem::take(&mut sp.ghost_writes)),
        None => Default::default(),
    };
    sweep_pairs.clear();
    ghost_writes.iter_mut().for_each(Vec::clear);
    let mut colour_start = [0usize; 9];
    for colour in 0..8 {
        colour_start[colour] = sweep_pairs.len();
        for z in lo[2] - 1..hi[2] {
            for y in lo[1] - 1..hi[1] {
                for x in lo[0] - 1..hi[0] {
                    let c = [x, y, z];
                    if CellGrid::colour(c) != colour {
                        continue;
                    }
                    let block_owned = owned(c) && rs2 > 0.0;
                    let block_start = sweep_pairs.len();
                    for &(a, b) in &CELL_PAIRS {
                        let (cell_a, cell_b) = (offset(c, a), offset(c, b));
                        let listed = rn2 > 0.0 && (owned(cell_a) || owned(cell_b));
                        if !(block_owned || listed) {
                            continue;
                        }
                        let (ca, cb) = (bins.cell(cell_a), bins.cell(cell_b));
                        for (k, &i) in ca.iter().enumerate() {
                            let ri = store.r[i as usize];
                            let partners = if a == b { &ca[k + 1..] } else { cb };
                            for &j in partners {
                                let d = sub(ri, store.r[j as usize]);
                                let d2 = dot(d, d);
                                if d2 >= r2max {
                                    continue;
                                }
                                if block_owned && d2 < rs2 {
                                    let pair = if store.tag[i as usize] < store.tag[j as usize] { [i, j] } else { [j, i] };
                                    sweep_pairs.push(pair);
                                }
                                if listed && d2 < rn2 && (i < nlocal || j < nlocal) {
                                    half.push([i, j]);
                                }
                            }
                        }
                    }
                    let block = &sweep_pairs[block_start..];
                    ghost_writes[colour].extend(block.iter().flatten().copied().filter(|&k| k >= nlocal));
                }
            }
        }
        ghost_writes[colour].sort_unstable();
        ghost_writes[colour].dedup();
    }
    colour_start[8] = sweep_pairs.len();
    if let Some((sp, radius)) = sweep {
        sp.radius = radius;
        sp.pairs = sweep_pairs;
        sp.colour_start = colour_start;
        sp.ghost_writes = ghost_writes;
    }
    if let Some((nl, radius)) = nlist {
        nl.pairs = half;
        nl.radius = radius;
    }
}
