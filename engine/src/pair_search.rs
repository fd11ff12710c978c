//! One half pass over the cell pairs that builds both the neighbour list and the
//! coloured Shardlow pairs.
//!
//! Every unordered pair of cells A, B at most k apart per dimension (the grid's reach)
//! lies in exactly one block C + {0..k}^3 with C = min(A, B) componentwise, as the pair
//! of offsets (a, b) with min(a_d, b_d) = 0 in every dimension. The pass walks the
//! blocks of C in [lo - k, hi) colour by colour, in lexicographic order within a colour,
//! then the cell pairs of a block (14 for k = 1, 63 for k = 2), then the particles of the
//! first cell by octant and tag (the bins hold each cell so), each against the second
//! cell's particles in the same order; where both cells hold at least `SPLIT_FROM` (16)
//! particles, only against the second cell's octants in range of its own octant (~40 %
//! of the candidates of cells of side cutoff + skin are skipped). Each particle pair is
//! tested once. A cell A lies in exactly one block per colour, so the order in which a
//! particle meets its neighbours depends only on the parity of its cell, the octants
//! (kept from the last rebuild, ghosts carrying their owner's) and the tags: no
//! decomposition can change it. Pairs of owned blocks (C in [lo, hi)) are the sweep's
//! (with, per colour, the particles they touch and the ghosts among them); every pair
//! with an owned particle enters the neighbour list, in pass order.

use crate::cells::CellBins;
use crate::{dot, sub, CellGrid, NeighborList, Particles, SweepPairs};

/// Cell offsets (a, b) in {0..k}^3 within a block whose componentwise min is the
/// block's own cell, a <= b by index a_x + (k+1) (a_y + (k+1) a_z): for k = 1 the
/// 3-bit masks a, b with a & b == 0 (14 pairs of cells).
fn cell_pairs(reach: usize) -> Vec<([i32; 3], [i32; 3])> {
    let m = reach + 1;
    let offset = |i: usize| [(i % m) as i32, ((i / m) % m) as i32, (i / (m * m)) as i32];
    let mut out = Vec::new();
    for a in 0..m * m * m {
        for b in a..m * m * m {
            let (oa, ob) = (offset(a), offset(b));
            if (0..3).all(|d| oa[d].min(ob[d]) == 0) {
                out.push((oa, ob));
            }
        }
    }
    out
}

/// For cells B = A + `o` and each octant qa of A, the octants qb of B that may hold a
/// particle closer than sqrt(`r2`) to one in qa (bit qb of entry qa): the gap between two
/// octants along d is (|2 o_d + qb_d - qa_d| - 1) octant sides where positive, shrunk
/// by 1e-10 relative so that positions on an octant's border (rounded) stay in range.
/// Within one cell (o = 0) only qb >= qa: the pairs of a cell are visited once.
fn octant_masks(o: [i32; 3], side: [f64; 3], r2: f64) -> [u8; 8] {
    let bit = |q: usize, d: usize| ((q >> d) & 1) as i32;
    std::array::from_fn(|qa| {
        let mut mask = 0u8;
        for qb in 0..8 {
            let gap2: f64 = (0..3)
                .map(|d| {
                    let gap = ((2 * o[d] + bit(qb, d) - bit(qa, d)).abs() - 1).max(0) as f64 * side[d] * (1.0 - 1e-10);
                    gap * gap
                })
                .sum();
            if gap2 < r2 && (o != [0; 3] || qb >= qa) {
                mask |= 1 << qb;
            }
        }
        mask
    })
}

/// Cells holding fewer particles than this are searched whole, not by octant (the
/// search of an octant pair costs more than the distance tests it saves).
const SPLIT_FROM: usize = 16;

/// The lists wanted from a pass, each with its radius (cutoff plus skin).
pub struct ListRequest<'a> {
    pub nlist: Option<(&'a mut NeighborList, f64)>,
    pub sweep: Option<(&'a mut SweepPairs, f64)>,
}

/// Builds the requested lists for the owned cells [lo, hi) from the bins (which hold
/// [lo - k, hi + k) with the ghosts, k their reach).
pub fn build_lists(store: &Particles, bins: &CellBins, lo: [i32; 3], hi: [i32; 3], req: ListRequest<'_>) {
    let ListRequest { mut nlist, mut sweep } = req;
    let rn2 = nlist.as_ref().map_or(-1.0, |(_, r)| r * r);
    let rs2 = sweep.as_ref().map_or(-1.0, |(_, r)| r * r);
    let r2max = rn2.max(rs2);
    let nlocal = store.nlocal as u32;
    let owned = |c: [i32; 3]| (0..3).all(|d| c[d] >= lo[d] && c[d] < hi[d]);
    let reach = bins.reach;
    let k = reach as i32;
    let offset = |c: [i32; 3], o: [i32; 3]| [c[0] + o[0], c[1] + o[1], c[2] + o[2]];
    let colours = (reach + 1).pow(3);
    let cell_pairs = cell_pairs(reach);
    let mut candidates: Vec<u32> = Vec::new();
    let octant_masks: Vec<[u8; 8]> = cell_pairs.iter().map(|&(a, b)| octant_masks([0, 1, 2].map(|d| b[d] - a[d]), bins.octant_side, r2max)).collect();
    // reuse the memory of the previous lists
    let mut half = match nlist.as_mut() {
        Some((nl, _)) => std::mem::take(&mut nl.pairs),
        None => Vec::new(),
    };
    half.clear();
    let (mut sweep_pairs, mut ghost_writes, mut members) = match sweep.as_mut() {
        Some((sp, _)) => (std::mem::take(&mut sp.pairs), std::mem::take(&mut sp.ghost_writes), std::mem::take(&mut sp.members)),
        None => Default::default(),
    };
    sweep_pairs.clear();
    ghost_writes.resize_with(colours, Vec::new);
    ghost_writes.iter_mut().for_each(Vec::clear);
    members.resize_with(colours, Vec::new);
    if rs2 > 0.0 {
        for m in &mut members {
            m.clear();
            m.resize(store.len(), false);
        }
    }
    let mut colour_start = vec![0usize; colours + 1];
    for colour in 0..colours {
        colour_start[colour] = sweep_pairs.len();
        // the blocks of this colour: every (k + 1)-th cell from the first of the colour
        let m = reach + 1;
        let first = |d: usize, r: usize| lo[d] - k + ((r as i32 - (lo[d] - k)).rem_euclid(m as i32));
        let (fx, fy, fz) = (first(0, colour % m), first(1, (colour / m) % m), first(2, colour / (m * m)));
        for z in (fz..hi[2]).step_by(m) {
            for y in (fy..hi[1]).step_by(m) {
                for x in (fx..hi[0]).step_by(m) {
                    let c = [x, y, z];
                    debug_assert_eq!(CellGrid::colour(c, reach), colour);
                    let block_owned = owned(c) && rs2 > 0.0;
                    let block_start = sweep_pairs.len();
                    for (&(a, b), masks) in cell_pairs.iter().zip(&octant_masks) {
                        let (cell_a, cell_b) = (offset(c, a), offset(c, b));
                        let listed = rn2 > 0.0 && (owned(cell_a) || owned(cell_b));
                        if !(block_owned || listed) {
                            continue;
                        }
                        let (ca, cb) = (bins.cell(cell_a), bins.cell(cell_b));
                        if ca.is_empty() || cb.is_empty() {
                            continue;
                        }
                        // the particles of `sa` against their partners in `group` (within
                        // one cell, `group` starts with `sa`: each pair is tested once)
                        let same = a == b;
                        let mut test = |sa: &[u32], group: &[u32]| {
                            for (t, &i) in sa.iter().enumerate() {
                                let ri = store.r[i as usize];
                                let partners = if same { &group[t + 1..] } else { group };
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
                        };
                        if ca.len() < SPLIT_FROM || cb.len() < SPLIT_FROM {
                            // few particles a cell: the cells whole, octant after octant
                            test(ca, cb);
                            continue;
                        }
                        let (oa, ob) = (bins.octants(cell_a), bins.octants(cell_b));
                        for (sa, &mask) in oa.iter().zip(masks) {
                            if sa.is_empty() {
                                continue;
                            }
                            // the candidates of octant qa, gathered once for its particles
                            // (within one cell, qa's own particles first)
                            candidates.clear();
                            let mut mask = mask;
                            while mask != 0 {
                                let qb = mask.trailing_zeros() as usize;
                                mask &= mask - 1;
                                candidates.extend_from_slice(ob[qb]);
                            }
                            test(sa, &candidates);
                        }
                    }
                    // the block's pairs are still in cache: mark their particles
                    for &k in sweep_pairs[block_start..].iter().flatten() {
                        members[colour][k as usize] = true;
                    }
                }
            }
        }
        if rs2 > 0.0 {
            let ghosts = members[colour].iter().enumerate().skip(store.nlocal).filter(|&(_, &m)| m);
            ghost_writes[colour].extend(ghosts.map(|(k, _)| k as u32));
        }
    }
    colour_start[colours] = sweep_pairs.len();
    if let Some((sp, radius)) = sweep {
        sp.radius = radius;
        sp.pairs = sweep_pairs;
        sp.colour_start = colour_start;
        sp.ghost_writes = ghost_writes;
        sp.members = members;
    }
    if let Some((nl, radius)) = nlist {
        nl.pairs = half;
        nl.radius = radius;
    }
}
