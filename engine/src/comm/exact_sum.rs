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
    let mut max = [0.0f64; K];
    for row in rows.clone() {
        for k in 0..K {
            max[k] = max[k].max(row[k].abs());
        }
    }
    t.max(&mut max);
    let scale: [f64; K] = std::array::from_fn(|k| {
        if max[k] > 0.0 && max[k].is_finite() {
            2f64.powi(max[k].log2().ceil() as i32 - GRID_BITS)
        } else {
            1.0
        }
    });
    let mut acc = [0i128; K];
    let mut nonfinite = [false; K];
    for row in rows {
        for k in 0..K {
            if row[k].is_finite() {
                acc[k] = acc[k].wrapping_add((row[k] / scale[k]) as i128);
            } else {
                nonfinite[k] = true;
            }
        }
    }
    let mut words = Vec::with_capacity(3 * K);
    for k in 0..K {
        words.push(acc[k] as u64);
        words.push((acc[k] >> 64) as u64);
        words.push(nonfinite[k] as u64);
    }
    let all = t.all_gather(&words);
    let mut out = [0.0; K];
    for k in 0..K {
        let (mut total, mut bad) = (0i128, false);
        for rank in all.chunks_exact(3 * K) {
            total = total.wrapping_add((rank[3 * k] as u128 | ((rank[3 * k + 1] as u128) << 64)) as i128);
            bad |= rank[3 * k + 2] != 0;
        }
        out[k] = if bad { f64::NAN } else { total as f64 * scale[k] };
    }
    out
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
    }
}
