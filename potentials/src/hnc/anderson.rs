//! Fixed-point iteration x = G(x) with Anderson mixing (depth [`DEPTH`]): the next x
//! combines the last iterates so that the linearised residual G(x) - x is least squares
//! (Anderson 1965; Ng 1974 is the depth-2 case for the OZ equation). Where G is undefined
//! at an extrapolated x (the OZ denominator 1 - rho c^ changed sign), the history is
//! dropped and a plain mixing step, halved on each failure, restarts from the last x where
//! G was defined.

use super::{HncError, HncOptions};
use std::collections::VecDeque;

/// Iterates kept for the least-squares combination.
const DEPTH: usize = 6;
/// Consecutive halvings of the plain step before giving up.
const MAX_HALVINGS: u32 = 30;

/// Solves x = G(x) from x0; `g` returns None where G is undefined. Returns the last x with
/// max |G(x) - x| < tol, and the number of evaluations of G.
pub(super) fn fixed_point(
    x0: Vec<f64>,
    opts: &HncOptions,
    mut g: impl FnMut(&[f64]) -> Option<Vec<f64>>,
) -> Result<(Vec<f64>, usize), HncError> {
    let mut x = x0;
    let mut history: VecDeque<(Vec<f64>, Vec<f64>)> = VecDeque::new(); // (x, f = G(x) - x)
    let mut good: Option<(Vec<f64>, Vec<f64>)> = None;
    let (mut halvings, mut residual) = (0, f64::INFINITY);
    for it in 1..=opts.max_iter {
        let Some(gx) = g(&x) else {
            // back to the last good point with a smaller plain step
            let Some((xg, fg)) = good.as_ref().filter(|_| halvings < MAX_HALVINGS) else {
                return Err(HncError::Diverged { iteration: it });
            };
            halvings += 1;
            history.clear();
            let step = opts.mixing * 0.5f64.powi(halvings as i32);
            x = xg.iter().zip(fg).map(|(x, f)| x + step * f).collect();
            continue;
        };
        let f: Vec<f64> = gx.iter().zip(&x).map(|(g, x)| g - x).collect();
        residual = f.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        if !residual.is_finite() {
            return Err(HncError::Diverged { iteration: it });
        }
        if residual < opts.tol {
            return Ok((x, it));
        }
        halvings = 0;
        history.push_back((x.clone(), f.clone()));
        if history.len() > DEPTH + 1 {
            history.pop_front();
        }
        let next = anderson_step(&history, opts.mixing);
        good = Some((std::mem::replace(&mut x, next), f));
    }
    Err(HncError::NotConverged { iterations: opts.max_iter, residual })
}

/// x_k + beta f_k - sum_i c_i (dx_i + beta df_i), with c minimising |f_k - sum_i c_i df_i|
/// over the differences of consecutive iterates in `h` (last entry = current iterate).
fn anderson_step(h: &VecDeque<(Vec<f64>, Vec<f64>)>, beta: f64) -> Vec<f64> {
    let (xk, fk) = h.back().expect("the history holds the current iterate");
    let m = h.len() - 1;
    let diffs: Vec<(Vec<f64>, Vec<f64>)> = (0..m)
        .map(|i| {
            let ((x0, f0), (x1, f1)) = (&h[i], &h[i + 1]);
            (
                x1.iter().zip(x0).map(|(a, b)| a - b).collect(),
                f1.iter().zip(f0).map(|(a, b)| a - b).collect(),
            )
        })
        .collect();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| a * b).sum::<f64>();
    // normal equations, lightly regularised
    let mut a: Vec<Vec<f64>> =
        (0..m).map(|i| (0..m).map(|j| dot(&diffs[i].1, &diffs[j].1)).collect()).collect();
    let mut b: Vec<f64> = (0..m).map(|i| dot(&diffs[i].1, fk)).collect();
    let trace: f64 = (0..m).map(|i| a[i][i]).sum();
    for (i, row) in a.iter_mut().enumerate() {
        row[i] += 1e-12 * trace;
    }
    let c = gauss_solve(&mut a, &mut b);
    let mut next: Vec<f64> = xk.iter().zip(fk).map(|(x, f)| x + beta * f).collect();
    for (ci, (dx, df)) in c.iter().zip(&diffs) {
        for (n, (dx, df)) in next.iter_mut().zip(dx.iter().zip(df)) {
            *n -= ci * (dx + beta * df);
        }
    }
    next
}

/// Solves a x = b by Gaussian elimination with partial pivoting (a tiny system); a zero
/// pivot drops that unknown.
fn gauss_solve(a: &mut [Vec<f64>], b: &mut [f64]) -> Vec<f64> {
    let m = b.len();
    for col in 0..m {
        let p = (col..m).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs())).expect("col < m");
        a.swap(col, p);
        b.swap(col, p);
        if a[col][col] == 0.0 {
            continue;
        }
        for row in col + 1..m {
            let (head, tail) = a.split_at_mut(row);
            let (pivot, r) = (&head[col], &mut tail[0]);
            let f = r[col] / pivot[col];
            for (x, p) in r[col..].iter_mut().zip(&pivot[col..]) {
                *x -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = vec![0.0; m];
    for i in (0..m).rev() {
        let s: f64 = (i + 1..m).map(|k| a[i][k] * x[k]).sum();
        x[i] = if a[i][i] == 0.0 { 0.0 } else { (b[i] - s) / a[i][i] };
    }
    x
}
