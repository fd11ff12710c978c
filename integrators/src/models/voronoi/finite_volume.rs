//! The Voronoi Lagrangian finite-volume model (Serrano & Español, Secs V-VI.A): cells of
//! the tessellation carry position R, momentum P, mass M and entropy S; mass and entropy
//! flow through the faces.
//!
//! - reversible part: eq 75 (the finite-volume equations 46 plus eq 74's Gibbs-Duhem term);
//! - irreversible part: eq 82 with eq 60, 83 (sign corrected, docs/models/voronoi.md), 84;
//! - noise: eqs 76-80.
//!
//! Divergences are written in flux form, sum_nu Omega_mu_nu . (X_nu + X_mu), and gradients
//! in difference form, sum_nu Omega_mu_nu (phi_nu - phi_mu): both equal the printed sums by
//! the closure of every cell (eq 56) and make every face term antisymmetric, so mass and
//! momentum are conserved face by face and energy to round-off.

use super::tessellation::{Face, Tessellation, TessellationError};
use crate::rng;
use gendpde_potentials::{CellEnergy, CellState, CellStateError};
use std::fmt;

type V3 = [f64; 3];
type M3 = [[f64; 3]; 3];

/// The dynamic variables of every cell (tags key the noise).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cells {
    pub tag: Vec<u64>,
    pub r: Vec<V3>,
    pub p: Vec<V3>,
    pub m: Vec<f64>,
    pub s: Vec<f64>,
}

impl Cells {
    pub fn len(&self) -> usize {
        self.r.len()
    }

    pub fn is_empty(&self) -> bool {
        self.r.is_empty()
    }

    /// Whether `other` has the same tags and the same bits in every variable.
    pub fn same_bits(&self, other: &Cells) -> bool {
        self.tag == other.tag && same_bits(self.r.as_flattened(), other.r.as_flattened()) && same_bits(self.p.as_flattened(), other.p.as_flattened()) && same_bits(&self.m, &other.m) && same_bits(&self.s, &other.s)
    }
}

/// Whether two slices hold the same bits (unlike ==, -0.0 and 0.0 differ).
pub fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// CellTransport coefficients (eq 78) and the noise scale k_B (0: the deterministic
/// finite-volume scheme of eqs 61-63; 1: thermal noise in the reduced units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellTransport {
    pub eta: f64,
    pub zeta: f64,
    pub kappa: f64,
    pub kb: f64,
}

/// The irreversible part: the finite-volume hydrodynamics of eqs 76-84 (eta, zeta, kappa
/// of `CellTransport`) or the Voronoi DPD of eqs 85-90 (one friction gamma, kappa; eta and zeta
/// unused).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CellDissipation {
    Hydrodynamic,
    Dpd { gamma: f64 },
}

/// Time derivatives of the cell variables (dR/dt = v).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Rates {
    pub r: Vec<V3>,
    pub p: Vec<V3>,
    pub m: Vec<f64>,
    pub s: Vec<f64>,
}

impl Rates {
    fn zeroed(n: usize) -> Self {
        Self { r: vec![[0.0; 3]; n], p: vec![[0.0; 3]; n], m: vec![0.0; n], s: vec![0.0; n] }
    }
}

/// Why the model cannot advance.
#[derive(Clone, Debug, PartialEq)]
pub enum ModelError {
    Tessellation(TessellationError),
    State { tag: u64, err: CellStateError },
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Tessellation(e) => e.fmt(f),
            Self::State { tag, err } => write!(f, "Voronoi cell of particle {tag}: {err}"),
        }
    }
}

impl std::error::Error for ModelError {}

/// The geometry and thermodynamics of one configuration.
#[derive(Clone, Debug)]
pub struct CellFrame {
    pub tess: Tessellation,
    pub thermo: Vec<CellState>,
    pub v: Vec<V3>,
}

impl CellFrame {
    /// Tessellates the periodic box [lo, lo + len) and evaluates every cell's state.
    pub fn new<E: CellEnergy>(cells: &Cells, energy: &E, lo: V3, len: V3) -> Result<Self, ModelError> {
        let tess = Tessellation::build(&cells.r, lo, len).map_err(ModelError::Tessellation)?;
        let mut thermo = Vec::with_capacity(cells.len());
        for k in 0..cells.len() {
            let st = energy.state(cells.m[k], cells.s[k], tess.volumes[k]).map_err(|err| ModelError::State { tag: cells.tag[k], err })?;
            thermo.push(st);
        }
        let v = (0..cells.len()).map(|k| scale(cells.p[k], 1.0 / cells.m[k])).collect();
        Ok(Self { tess, thermo, v })
    }

    /// Total energy, eq 64: sum P^2/2M + E(M, S, V).
    pub fn energy(&self, cells: &Cells) -> f64 {
        (0..cells.len()).map(|k| 0.5 * dot(cells.p[k], self.v[k]) + self.thermo[k].energy).sum()
    }

    /// dV_mu/dt = sum_nu dV_mu/dR_nu . dR_nu/dt (eq 129).
    pub fn volume_rates(&self, dr: &[V3]) -> Vec<f64> {
        let mut dv = vec![0.0; dr.len()];
        for f in &self.tess.faces {
            let (gij, gji) = Tessellation::volume_gradients(f);
            let vij = sub(dr[f.i], dr[f.j]);
            dv[f.i] -= dot(gij, vij);
            dv[f.j] += dot(gji, vij);
        }
        dv
    }

    /// Each cell's share of the diagonal virial, p_mu dV_mu/d epsilon_aa: the change of its
    /// volume under the uniform stretch R -> (1 + epsilon_aa) R of all generators and of
    /// the box (eq 129 summed against R_nu - R_mu over the faces; the trace is 3 p_mu V_mu,
    /// the pyramids of height R/2 on the faces). The pressure is -dH/dV_T at fixed M, S of
    /// every cell: (sum_mu 3 p_mu V_mu + sum P^2/M) / (3 V_T).
    pub fn virial(&self) -> Vec<V3> {
        let mut w = vec![[0.0; 3]; self.v.len()];
        for f in &self.tess.faces {
            let (gij, gji) = Tessellation::volume_gradients(f);
            let (pi, pj) = (self.thermo[f.i].pressure, self.thermo[f.j].pressure);
            for a in 0..3 {
                // R_j - R_i = R n seen from i, the opposite from j.
                let d = f.dist * f.normal[a];
                w[f.i][a] += pi * gij[a] * d;
                w[f.j][a] -= pj * gji[a] * d;
            }
        }
        w
    }

    /// dE/dt along `rates`: sum v.dP - (v^2/2) dM + mu dM + T dS - p dV (eqs 64, 66).
    pub fn energy_rate(&self, rates: &Rates) -> f64 {
        let dv = self.volume_rates(&rates.r);
        (0..self.v.len())
            .map(|k| {
                let st = &self.thermo[k];
                dot(self.v[k], rates.p[k]) + (st.chemical - 0.5 * dot(self.v[k], self.v[k])) * rates.m[k] + st.temperature * rates.s[k] - st.pressure * dv[k]
            })
            .sum()
    }

    /// The reversible rates, eq 75.
    pub fn reversible(&self, cells: &Cells) -> Rates {
        let mut out = Rates::zeroed(cells.len());
        for k in 0..cells.len() {
            out.r[k] = self.v[k];
        }
        for f in &self.tess.faces {
            let (i, j) = (f.i, f.j);
            let (ti, tj) = (&self.thermo[i], &self.thermo[j]);
            let (vi, vj) = (self.tess.volumes[i], self.tess.volumes[j]);
            let rho = 0.5 * (cells.m[i] / vi + cells.m[j] / vj);
            let sd = 0.5 * (cells.s[i] / vi + cells.s[j] / vj);
            let a = f.area / f.dist;
            let vij = sub(self.v[i], self.v[j]);
            let cv = dot(f.offset, vij);
            let vbar = scale(add(self.v[i], self.v[j]), 0.5);
            let e = scale(f.normal, -1.0);
            // Eq 74: P_i - P_j - <rho>(mu_i - mu_j) - <s>(T_i - T_j).
            let gd = ti.pressure - tj.pressure - rho * (ti.chemical - tj.chemical) - sd * (ti.temperature - tj.temperature);
            let pbar = 0.5 * (ti.pressure + tj.pressure);
            let mut dp = [0.0; 3];
            for x in 0..3 {
                dp[x] = f.area * e[x] * pbar + a * rho * vbar[x] * cv + a * f.offset[x] * gd;
            }
            add_to(&mut out.p[i], dp);
            add_to(&mut out.p[j], scale(dp, -1.0));
            out.m[i] += a * rho * cv;
            out.m[j] -= a * rho * cv;
            out.s[i] += a * sd * cv;
            out.s[j] -= a * sd * cv;
        }
        out
    }

    /// The velocity gradients L_mu = sum_nu Omega_mu_nu (v_nu - v_mu)^T (eq 58-60).
    fn velocity_gradients(&self) -> Vec<M3> {
        let mut l = vec![[[0.0; 3]; 3]; self.v.len()];
        for f in &self.tess.faces {
            let om = omega(f);
            let vji = sub(self.v[f.j], self.v[f.i]);
            // Omega_ji (v_i - v_j) = Omega_ij (v_j - v_i): the same for both cells.
            for a in 0..3 {
                for b in 0..3 {
                    l[f.i][a][b] += om[a] * vji[b];
                    l[f.j][a][b] += om[a] * vji[b];
                }
            }
        }
        l
    }

    /// The deterministic irreversible rates, eq 82 with eqs 60, 83, 84 (dP and dS; the
    /// k_B terms are the Ito drift of the noise of eqs 76-80).
    pub fn irreversible(&self, cells: &Cells, tr: &CellTransport) -> Rates {
        let n = cells.len();
        let mut out = Rates::zeroed(n);
        let l = self.velocity_gradients();
        let mut sigma = vec![[[0.0; 3]; 3]; n];
        let mut heat = vec![0.0; n]; // T dS/dt
        for k in 0..n {
            let v = self.tess.volumes[k];
            let st = &self.thermo[k];
            let (gbar, d) = shear_and_divergence(&l[k]);
            let mut gg = 0.0;
            for a in 0..3 {
                for b in 0..3 {
                    sigma[k][a][b] = -2.0 * tr.eta / v * gbar[a][b] + if a == b { -tr.zeta / v * d } else { 0.0 };
                    gg += gbar[a][b] * gbar[a][b];
                }
            }
            heat[k] = (1.0 - tr.kb / st.heat_capacity) * (2.0 * tr.eta / v * gg + tr.zeta / v * d * d);
        }
        // Eq 83 (sign corrected): J_mu = -kappa T_mu^2 / V_mu sum_nu Omega_mu_nu (phi_nu - phi_mu),
        // phi = (1 - k_B/C)/T.
        let phi: Vec<f64> = self.thermo.iter().map(|st| (1.0 - tr.kb / st.heat_capacity) / st.temperature).collect();
        let mut flux = vec![[0.0; 3]; n];
        for f in &self.tess.faces {
            let om = omega(f);
            let dphi = phi[f.j] - phi[f.i];
            // Omega_ji (phi_i - phi_j) = Omega_ij (phi_j - phi_i).
            add_to(&mut flux[f.i], scale(om, dphi));
            add_to(&mut flux[f.j], scale(om, dphi));
        }
        for k in 0..n {
            let t = self.thermo[k].temperature;
            flux[k] = scale(flux[k], -tr.kappa * t * t / self.tess.volumes[k]);
        }
        let shear_bulk = (3.0 * 3.0 + 3.0 - 2.0) / (2.0 * 3.0) * 2.0 * tr.eta;
        for f in &self.tess.faces {
            let (i, j) = (f.i, f.j);
            let om = omega(f);
            let om2 = dot(om, om);
            // dP_i = sum Omega_ij . (sigma_i + sigma_j); dP_j the opposite.
            let dp = mat_vec_t(add_m(&sigma[i], &sigma[j]), om);
            add_to(&mut out.p[i], dp);
            add_to(&mut out.p[j], scale(dp, -1.0));
            let q = dot(om, add(flux[i], flux[j]));
            heat[i] += q;
            heat[j] -= q;
            if tr.kb != 0.0 {
                let (si, sj) = (&self.thermo[i], &self.thermo[j]);
                let (vi, vj) = (self.tess.volumes[i], self.tess.volumes[j]);
                let (ti, tj) = (si.temperature, sj.temperature);
                heat[i] -= tr.kb / (ti * si.heat_capacity) * om2 * tr.kappa / vj * tj * tj;
                heat[j] -= tr.kb / (tj * sj.heat_capacity) * om2 * tr.kappa / vi * ti * ti;
                heat[i] -= tr.kb * ti * (shear_bulk + tr.zeta) / vi * om2 / cells.m[j];
                heat[j] -= tr.kb * tj * (shear_bulk + tr.zeta) / vj * om2 / cells.m[i];
            }
        }
        for k in 0..n {
            out.s[k] = heat[k] / self.thermo[k].temperature;
        }
        out
    }

    /// The noise increments over `dt` (eqs 76-80): dP~ and dS~ of every cell, keyed by
    /// (seed, step, tag) so that neither the order nor the rank of a cell changes them.
    pub fn noise(&self, cells: &Cells, tr: &CellTransport, seed: u64, step: u64, dt: f64) -> (Vec<V3>, Vec<f64>) {
        let n = cells.len();
        let l = self.velocity_gradients();
        let mut dsig = vec![[[0.0; 3]; 3]; n];
        let mut dj = vec![[0.0; 3]; n];
        let mut heat = vec![0.0; n]; // T dS~
        let h = dt.sqrt();
        for k in 0..n {
            let mut g = [0.0; 12];
            for q in 0..6 {
                let (a, b) = rng::normal_pair(seed, step, cells.tag[k], q as u64, rng::stream::VORONOI);
                g[2 * q] = a * h;
                g[2 * q + 1] = b * h;
            }
            let w = [[g[0], g[1], g[2]], [g[3], g[4], g[5]], [g[6], g[7], g[8]]];
            let v = self.tess.volumes[k];
            let t = self.thermo[k].temperature;
            let amp_shear = (4.0 * tr.kb * t * tr.eta / v).sqrt();
            let amp_bulk = (2.0 * 3.0 * tr.kb * t * tr.zeta / v).sqrt();
            let amp_heat = t * (2.0 * tr.kb * tr.kappa / v).sqrt();
            let trw = (w[0][0] + w[1][1] + w[2][2]) / 3.0;
            for a in 0..3 {
                for b in 0..3 {
                    let sym = 0.5 * (w[a][b] + w[b][a]) - if a == b { trw } else { 0.0 };
                    dsig[k][a][b] = amp_shear * sym + if a == b { amp_bulk * trw } else { 0.0 };
                }
                dj[k][a] = amp_heat * g[9 + a];
            }
            heat[k] = ddot(&dsig[k], &l[k]);
        }
        let mut dp = vec![[0.0; 3]; n];
        for f in &self.tess.faces {
            let om = omega(f);
            let x = mat_vec_t(add_m(&dsig[f.i], &dsig[f.j]), om);
            add_to(&mut dp[f.i], x);
            add_to(&mut dp[f.j], scale(x, -1.0));
            let q = dot(om, add(dj[f.i], dj[f.j]));
            heat[f.i] += q;
            heat[f.j] -= q;
        }
        let ds = (0..n).map(|k| heat[k] / self.thermo[k].temperature).collect();
        (dp, ds)
    }
}

/// The finite-volume model with a cell relation E(M, S, V).
#[derive(Clone, Debug)]
pub struct FiniteVolume<E> {
    pub energy: E,
    pub transport: CellTransport,
    pub dissipation: CellDissipation,
    pub seed: u64,
}

impl<E: CellEnergy> FiniteVolume<E> {
    /// With thermal noise every cell needs C > k_B: the factors 1 - k_B/C of eqs 82-84 and
    /// 89-90 change sign below, and the heating they scale runs away (a cell of a few
    /// molecules; larger cells keep clear of it). Stops the step at the first such cell.
    fn check_capacities(&self, cells: &Cells, frame: &CellFrame) -> Result<(), ModelError> {
        let kb = self.transport.kb;
        match (0..cells.len()).find(|&k| kb > 0.0 && frame.thermo[k].heat_capacity <= kb) {
            None => Ok(()),
            Some(k) => Err(ModelError::State {
                tag: cells.tag[k],
                err: CellStateError { m: cells.m[k], s: cells.s[k], v: frame.tess.volumes[k], what: "heat capacity C <= k_B, where 1 - k_B/C of the irreversible part changes sign (cells too small: raise the mean cell volume)" },
            }),
        }
    }

    /// All deterministic rates at a frame.
    pub fn rates(&self, cells: &Cells, frame: &CellFrame) -> Rates {
        let mut r = frame.reversible(cells);
        let tr = &self.transport;
        let irr = match self.dissipation {
            CellDissipation::Hydrodynamic => frame.irreversible(cells, tr),
            CellDissipation::Dpd { gamma } => frame.irreversible_dpd(cells, gamma, tr.kappa, tr.kb),
        };
        for k in 0..cells.len() {
            add_to(&mut r.p[k], irr.p[k]);
            r.s[k] += irr.s[k];
        }
        r
    }

    /// One step of `dt` from step number `step`: Heun's predictor-corrector on the
    /// deterministic rates, plus the noise increments with coefficients at the start (Ito).
    /// `f0` is the frame of `cells` (a run reuses the previous step's end frame), so the
    /// step tessellates once, for the predictor.
    pub fn step(&self, cells: &mut Cells, f0: &CellFrame, lo: V3, len: V3, dt: f64, step: u64) -> Result<(), ModelError> {
        self.check_capacities(cells, f0)?;
        let k0 = self.rates(cells, f0);
        let tr = &self.transport;
        let noise = (tr.kb != 0.0).then(|| match self.dissipation {
            CellDissipation::Hydrodynamic => f0.noise(cells, tr, self.seed, step, dt),
            CellDissipation::Dpd { gamma } => f0.noise_dpd(cells, gamma, tr.kappa, tr.kb, self.seed, step, dt),
        });
        let mut pred = cells.clone();
        advance(&mut pred, &k0, dt, 1.0);
        let f1 = CellFrame::new(&pred, &self.energy, lo, len)?;
        self.check_capacities(&pred, &f1)?;
        let k1 = self.rates(&pred, &f1);
        advance(cells, &k0, dt, 0.5);
        advance(cells, &k1, dt, 0.5);
        if let Some((dp, ds)) = noise {
            for k in 0..cells.len() {
                add_to(&mut cells.p[k], dp[k]);
                cells.s[k] += ds[k];
            }
        }
        Ok(())
    }
}

/// x += w dt rates.
fn advance(c: &mut Cells, r: &Rates, dt: f64, w: f64) {
    let h = w * dt;
    for k in 0..c.len() {
        add_to(&mut c.r[k], scale(r.r[k], h));
        add_to(&mut c.p[k], scale(r.p[k], h));
        c.m[k] += h * r.m[k];
        c.s[k] += h * r.s[k];
    }
}

/// Omega_ij = A_ij e_ij / 2 (eq 54); the face normal points from i to j, so e_ij = -normal.
#[inline]
fn omega(f: &Face) -> V3 {
    scale(f.normal, -0.5 * f.area)
}

/// G-bar (traceless symmetric, eq 60) and D = -tr L from L = sum Omega (v_nu - v_mu)^T.
fn shear_and_divergence(l: &M3) -> (M3, f64) {
    let tr = l[0][0] + l[1][1] + l[2][2];
    let mut g = [[0.0; 3]; 3];
    for a in 0..3 {
        for b in 0..3 {
            g[a][b] = -(0.5 * (l[a][b] + l[b][a]) - if a == b { tr / 3.0 } else { 0.0 });
        }
    }
    (g, -tr)
}

#[inline]
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline]
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

#[inline]
fn add_to(a: &mut V3, b: V3) {
    for x in 0..3 {
        a[x] += b[x];
    }
}

fn add_m(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|x| add(a[x], b[x]))
}

/// (Omega . M)^b = sum_a Omega^a M^ab.
fn mat_vec_t(m: M3, om: V3) -> V3 {
    std::array::from_fn(|b| om[0] * m[0][b] + om[1] * m[1][b] + om[2] * m[2][b])
}

fn ddot(a: &M3, b: &M3) -> f64 {
    (0..3).map(|x| dot(a[x], b[x])).sum()
}
