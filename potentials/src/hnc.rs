//! Pair structure and macroscopic thermodynamics of an LTh fluid (argon paper, Colella et
//! al., secs 3.2-3.3 and 4.2.2).
//!
//! [`solve`] is the Ornstein-Zernike equation h = c + rho c * h with the hypernetted-chain
//! closure c = h - ln g - beta u (eq 120 is the two together) for any pair potential u(r),
//! by Picard iteration on the indirect correlation gamma = h - c, accelerated by Anderson
//! mixing; the convolution is a product in Fourier space ([`RadialGrid`], a sine transform):
//!
//! c(r) = exp(-beta u + gamma) - 1 - gamma,  gamma^(k) = rho c^(k)^2 / (1 - rho c^(k)).
//!
//! [`LthFluid`] is the LTh model with the corrected volume: its pair potential 2 u_1 =
//! 2 \[W_n\] w(r) (eq 119; the factor 2 is explained in `hnc/lth.rs`) depends on the mean
//! primitive density n^b = c int w g (eq 78), which the paper makes self-consistent with
//! the HNC g ([`LthFluid::hnc`]), and its
//! macroscopic pressure and energy (eqs 85-91 and 99) follow from any g(r)
//! ([`LthFluid::macro_state`]): simulated (sampled with [`RadialGrid::sample`]) or HNC.

mod anderson;
mod lth;
mod transform;

#[cfg(test)]
mod tests;

pub use lth::{LthFluid, LthHnc, MacroState, MeanField};
pub use transform::RadialGrid;

use std::fmt;

/// Picard iteration settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HncOptions {
    /// Weight of the new residual G(x) - x in each Anderson step (0 < mixing <= 1).
    pub mixing: f64,
    /// Convergence when max |gamma_new - gamma| (and |dn^b| for [`LthFluid::hnc`]) < tol.
    pub tol: f64,
    pub max_iter: usize,
}

impl Default for HncOptions {
    fn default() -> Self {
        Self { mixing: 0.3, tol: 1e-10, max_iter: 20_000 }
    }
}

/// Why the iteration stopped without a solution.
#[derive(Clone, Debug, PartialEq)]
pub enum HncError {
    /// max_iter reached; the last residual.
    NotConverged { iterations: usize, residual: f64 },
    /// 1 - rho c^(k) <= 0 or a non-finite value even after the step was halved many
    /// times: no HNC solution along this path (e.g. inside a spinodal).
    Diverged { iteration: usize },
}

impl fmt::Display for HncError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotConverged { iterations, residual } => {
                write!(f, "HNC not converged after {iterations} iterations (residual {residual:e})")
            }
            Self::Diverged { iteration } => write!(f, "HNC iteration diverged at step {iteration}"),
        }
    }
}

impl std::error::Error for HncError {}

/// A converged HNC solution on the grid.
#[derive(Clone, Debug)]
pub struct Hnc {
    /// Pair distribution function g(r_i).
    pub g: Vec<f64>,
    /// Direct correlation function c(r_i).
    pub c: Vec<f64>,
    /// Indirect correlation gamma = h - c (a warm start for a nearby state).
    pub gamma: Vec<f64>,
    pub iterations: usize,
}

/// g and c of the closure at `gamma`, with the OZ update of gamma in `gamma` of the
/// result; None if 1 - rho c^ <= 0 or a value is not finite.
fn picard(grid: &RadialGrid, rho: f64, beta_u: &[f64], gamma: &[f64]) -> Option<Hnc> {
    let n = grid.points();
    let g: Vec<f64> = beta_u.iter().zip(gamma).map(|(&bu, &y)| (y - bu).exp()).collect();
    let c: Vec<f64> = g.iter().zip(gamma).map(|(&g, &y)| g - 1.0 - y).collect();
    let mut ck = vec![0.0; n];
    grid.forward(&c, &mut ck);
    let mut yk = vec![0.0; n];
    for (y, &c) in yk.iter_mut().zip(&ck) {
        let d = 1.0 - rho * c;
        if d.is_nan() || d <= 0.0 {
            return None;
        }
        *y = rho * c * c / d;
    }
    let mut next = vec![0.0; n];
    grid.inverse(&yk, &mut next);
    next.iter().all(|y| y.is_finite()).then_some(Hnc { g, c, gamma: next, iterations: 0 })
}

/// HNC for the pair potential beta u(r_i) (+inf allowed) at number density `rho`, from
/// gamma = `start` (zero if None). The returned g, c are the closure at the returned gamma,
/// whose OZ update differs from it by less than `tol`.
pub fn solve(
    grid: &RadialGrid,
    rho: f64,
    beta_u: &[f64],
    start: Option<&[f64]>,
    opts: &HncOptions,
) -> Result<Hnc, HncError> {
    assert_eq!(beta_u.len(), grid.points(), "beta u on the grid");
    let x0 = start.map_or_else(|| vec![0.0; grid.points()], <[f64]>::to_vec);
    let (gamma, iterations) =
        anderson::fixed_point(x0, opts, |y| picard(grid, rho, beta_u, y).map(|s| s.gamma))?;
    let s =
        picard(grid, rho, beta_u, &gamma).ok_or(HncError::Diverged { iteration: iterations })?;
    Ok(Hnc { gamma, iterations, ..s })
}
