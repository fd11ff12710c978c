//! The rows of the particles of all ranks for output written by rank 0, which arrive in blocks of consecutive tags, sorted by tag, so rank 0
//! never holds more than one block (BLOCK rows).

use gendpde_integrators::System;

/// Tags per block gathered on rank 0.
pub const BLOCK: u64 = 1 << 20;

/// Calls `emit` on rank 0 with the rows of all particles in tag order, one block at a
/// time. `row(i, buf)` appends `width` values for owned particle i, the tag first.
/// Every rank must call this (it communicates); `emit` runs on rank 0 only.
pub fn sorted_rows<E>(
    sys: &System,
    max_tag: u64,
    width: usize,
    row: impl Fn(usize, &mut Vec<f64>),
    emit: &mut dyn FnMut(&[f64]) -> Result<(), E>,
) -> Result<(), E> {
    let mut first_err = None;
    let mut block = 0;
    while block * BLOCK < max_tag.max(1) {
        let (lo, hi) = (block * BLOCK + 1, (block + 1) * BLOCK);
        let mut local = Vec::new();
        for i in (0..sys.store.nlocal).filter(|&i| (lo..=hi).contains(&sys.store.tag[i])) {
            row(i, &mut local);
        }
        let mut rows: Vec<f64> = Vec::new();
        sys.comm.transport().gather_to_root(&local, &mut |buf| rows.extend_from_slice(buf));
        if sys.comm.rank() == 0 && first_err.is_none() {
            let mut order: Vec<usize> = (0..rows.len() / width).collect();
            order.sort_unstable_by(|&a, &b| rows[a * width].total_cmp(&rows[b * width]));
            let sorted: Vec<f64> = order.iter().flat_map(|&k| rows[k * width..(k + 1) * width].iter().copied()).collect();
            if let Err(e) = emit(&sorted) {
                first_err = Some(e);
            }
        }
        block += 1;
    }
    first_err.map_or(Ok(()), Err)
}

/// Every rank's `local` words on every rank, concatenated in rank order (the ranks may
/// hold different numbers of them). Collective.
pub fn all_ranks(sys: &System, local: &[u64]) -> Vec<u64> {
    let t = sys.comm.transport();
    let counts = t.all_gather(&[local.len() as u64]);
    let width = counts.iter().copied().max().unwrap_or(0) as usize;
    let mut padded = local.to_vec();
    padded.resize(width, 0);
    let all = t.all_gather(&padded);
    counts.iter().zip(all.chunks_exact(width.max(1))).flat_map(|(&n, rank)| rank[..n as usize].iter().copied()).collect()
}
