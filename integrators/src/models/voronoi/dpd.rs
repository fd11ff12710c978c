//! The Voronoi DPD model (Serrano & Español, Sec VI.B): the reversible part of eq 75 with
//! the pairwise irreversible part of eqs 89-90 and the pair noise of eqs 85-88, one
//! friction gamma and one conductivity kappa, Vbar = V_T/N.
//!
//! Eq 88's B is short of a factor sqrt 2: eq 10 applied to eqs 85-86 with the printed B
//! gives the friction gamma/(2 Vbar) and heating gamma/(4 Vbar), half of eq 89; with
//! B^2 = 4 k_B gamma T_mu T_nu/((T_mu + T_nu) Vbar) Omega Omega every term of eqs 89-90,
//! the k_B ones included, follows from eq 10 (derivation in docs/models/voronoi.md), and the
//! paper's m is 2/m = 1/M_mu + 1/M_nu.

use super::finite_volume::{CellFrame, Rates};
use super::tessellation::Face;
use crate::rng;
use super::finite_volume::Cells;

/// Omega_ij = A e_ij/2 (eq 54), e_ij = -normal.
fn omega(f: &Face) -> [f64; 3] {
    let s = -0.5 * f.area;
    [s * f.normal[0], s * f.normal[1], s * f.normal[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl CellFrame {
    /// The mean cell volume Vbar = V_T/N.
    fn mean_volume(&self) -> f64 {
        self.tess.volumes.iter().sum::<f64>() / self.tess.len() as f64
    }

    /// The deterministic irreversible rates of eqs 89-90 (dP and dS).
    pub fn irreversible_dpd(&self, cells: &Cells, gamma: f64, kappa: f64, kb: f64) -> Rates {
        let n = cells.len();
        let mut out = Rates { r: vec![[0.0; 3]; n], p: vec![[0.0; 3]; n], m: vec![0.0; n], s: vec![0.0; n] };
        let vbar = self.mean_volume();
        let mut heat = vec![0.0; n];
        for f in &self.tess.faces {
            let (i, j) = (f.i, f.j);
            let om = omega(f);
            let om2 = dot(om, om);
            let (ti, tj) = (self.thermo[i].temperature, self.thermo[j].temperature);
            let (ci, cj) = (self.thermo[i].heat_capacity, self.thermo[j].heat_capacity);
            let w = dot(om, [self.v[i][0] - self.v[j][0], self.v[i][1] - self.v[j][1], self.v[i][2] - self.v[j][2]]);
            let g = ti * tj / ((ti + tj) * (ti + tj));
            // Eq 90.
            let gij = gamma * (1.0 - g * (kb / ci + kb / cj));
            for x in 0..3 {
                out.p[i][x] -= gij / vbar * w * om[x];
                out.p[j][x] += gij / vbar * w * om[x];
            }
            let visc = gij / (2.0 * vbar) * w * w;
            let cond = kappa / vbar * om2 * (tj - ti);
            heat[i] += visc + cond;
            heat[j] += visc - cond;
            if kb != 0.0 {
                let (fi, fj) = (tj / (ti + tj), ti / (ti + tj));
                let inv_m = 1.0 / cells.m[i] + 1.0 / cells.m[j];
                heat[i] -= gamma / (2.0 * vbar) * fi * kb / ci * w * w + gamma * kb * ti / vbar * fi * om2 * inv_m + kb * kappa / (ci * vbar) * om2 * tj;
                heat[j] -= gamma / (2.0 * vbar) * fj * kb / cj * w * w + gamma * kb * tj / vbar * fj * om2 * inv_m + kb * kappa / (cj * vbar) * om2 * ti;
            }
        }
        for k in 0..n {
            out.s[k] = heat[k] / self.thermo[k].temperature;
        }
        out
    }

    /// The pair noise of eqs 85-88 over `dt` (B with the factor of eq 10): one dW and one
    /// dV per face, keyed by (seed, step, lower tag, higher tag) and the image of the
    /// higher-tag cell seen from the lower (a stream per image); dV_ij = -dV_ji.
    pub fn noise_dpd(&self, cells: &Cells, gamma: f64, kappa: f64, kb: f64, seed: u64, step: u64, dt: f64) -> (Vec<[f64; 3]>, Vec<f64>) {
        let n = cells.len();
        let vbar = self.mean_volume();
        let mut dp = vec![[0.0; 3]; n];
        let mut heat = vec![0.0; n]; // T dS~
        let h = dt.sqrt();
        for f in &self.tess.faces {
            let (i, j) = (f.i, f.j);
            let (a, b) = (cells.tag[i].min(cells.tag[j]), cells.tag[i].max(cells.tag[j]));
            let sign = if cells.tag[i] < cells.tag[j] { 1 } else { -1 };
            let image = f.image.iter().fold(0u32, |code, &x| 3 * code + (sign * x as i32 + 1) as u32);
            let (w, v) = rng::normal_pair(seed, step, a, b, rng::stream::VORONOI_PAIR + image);
            let (dw, dv) = (w * h, if cells.tag[i] < cells.tag[j] { v * h } else { -v * h });
            let om = omega(f);
            let (ti, tj) = (self.thermo[i].temperature, self.thermo[j].temperature);
            let bamp = (4.0 * kb * ti * tj / (ti + tj) * gamma / vbar).sqrt();
            let aamp = (2.0 * kb * ti * tj * kappa / vbar).sqrt() * dot(om, om).sqrt();
            let vij = [self.v[i][0] - self.v[j][0], self.v[i][1] - self.v[j][1], self.v[i][2] - self.v[j][2]];
            let bv = bamp * dot(om, vij);
            for x in 0..3 {
                dp[i][x] += bamp * om[x] * dw;
                dp[j][x] -= bamp * om[x] * dw;
            }
            // Eq 85: T_i dS~_i = -(1/2) B_ij . v_ij dW + A dV_ij; j: the same with B_ji . v_ji = B_ij . v_ij.
            heat[i] += -0.5 * bv * dw + aamp * dv;
            heat[j] += -0.5 * bv * dw - aamp * dv;
        }
        let ds = (0..n).map(|k| heat[k] / self.thermo[k].temperature).collect();
        (dp, ds)
    }
}
