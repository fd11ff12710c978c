//! Sums over particles that do not depend on how particles are spread over ranks or
//! ordered within them: every term is rounded down to a grid 2^-96 below the largest
//! magnitude (found by a global max) and added as a 128-bit integer, which is exact and
//! so associative. Terms smaller than the grid lose at most one grid step each
//! (relative 1e-29 of the largest term), far below double precision of the total.

use super::Transport;

/// Bits of headroom below the largest term: 2^31 terms cannot overflow 127 bits.
const GRID_BITS: i32 = 96;

/// Column sums of `rows`, identical for every decomposition of the rows over ranks.
pub fn exact_sums<const K: usize>(t: &dyn Transport, rows: impl Iterator<Item = [f64; K]> + Clone) -> [f64; K] {
    let sums = exact_column_sums(t, K, rows.flat_map(|row| row.into_iter().enumerate()));
    std::array::from_fn(|k| sums[k])
}

/// Sums of `terms` (column, value) into `ncol` columns, identical for every decomposition
/// of the terms over ranks (each column has its own grid). Panics on a column >= `ncol`.
pub fn exact_column_sums(t: &dyn Transport, ncol: usize, terms: impl Iterator<Item = (usize, f64)> + Clone) -> Vec<f64> {
    let mut max = vec![0.0f64; ncol];
    for (k, v) in terms.clone() {
        max[k] = max[k].max(v.abs());
    }
    t.max(&mut max);
    let scale: Vec<f64> = max
        .iter()
        .map(|&m| if m > 0.0 && m.is_finite() { 2f64.powi(m.log2().ceil() as i32 - GRID_BITS) } else { 1.0 })
        .collect();
    let mut acc = vec![0i128; ncol];
    let mut nonfinite = vec![false; ncol];
    for (k, v) in terms {
        if v.is_finite() {
            acc[k] = acc[k].wrapping_add((v / scale[k]) as i128);
        } else {
            nonfinite[k] = true;
        }
    }
    let mut words = Vec::with_capacity(3 * ncol);
    for k in 0..ncol {
        words.push(acc[k] as u64);
        words.push((acc[k] >> 64) as u64);
        words.push(nonfinite[k] as u64);
    }
    let all = t.all_gather(&words);
    (0..ncol)
        .map(|k| {
            let (mut total, mut bad) = (0i128, false);
            for rank in all.chunks_exact(3 * ncol) {
                total = total.wrapping_add((rank[3 * k] as u128 | ((rank[3 * k + 1] as u128) << 64)) as i128);
                bad |= rank[3 * k + 2] != 0;
            }
            if bad { f64::NAN } else { total as f64 * scale[k] }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::comm::Local;

    #[test]
    fn sums_do_not_depend_on_order() {
        let mut x: u64 = 5;
        let values: Vec<f64> = (0..10_000)
            .map(|_| {
                x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                ((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 10f64.powi((x % 7) as i32)
            })
            .collect();
        let forward = exact_sums(&Local, values.iter().map(|&v| [v, v * v]));
        let backward = exact_sums(&Local, values.iter().rev().map(|&v| [v, v * v]));
        assert_eq!(forward, backward);
        let naive: f64 = values.iter().sum();
        assert!((forward[0] - naive).abs() < 1e-9 * values.iter().map(|v| v.abs()).sum::<f64>());
    }

    #[test]
    fn nan_and_empty_are_handled() {
        assert_eq!(exact_sums(&Local, std::iter::empty::<[f64; 1]>()), [0.0]);
        assert!(exact_sums(&Local, [[1.0], [f64::NAN]].into_iter())[0].is_nan());
        assert_eq!(exact_column_sums(&Local, 2, [(1, 2.0), (1, 0.5)].into_iter()), vec![0.0, 2.5]);
    }
}
