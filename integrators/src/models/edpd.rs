//! Energy-conserving DPD in temperature form (eDPD, Li et al., J. Comput. Phys. 265, 113
//! (2014)), as LAMMPS's DPD-MESO package runs it: `pair edpd`, `fix mvv/edpd`,
//! `fix edpd/source`. Each particle carries a temperature T, a heat capacity C_V and the
//! heat flux Q = C_V dT/dt of the last force pass.
//!
//! Pair terms (LAMMPS src/DPD-MESO/pair_edpd.cpp; eqs 11-16 and 24-27 of the paper), with
//! T_ij = (T_i + T_j)/2, w_c = 1 - r/r_c, w_r = w_c^(s(T_ij)/2), w_rT = (1 - r/r_cT)^(s_T/2):
//!
//! - F = a0 T_ij w_c - gamma w_r^2 (e.v) + sigma w_r xi / sqrt(dt),
//!   sigma^2 = 4 gamma k_B T_i T_j / (T_i + T_j);
//! - conduction q_c = k_ij w_rT^2 (1/T_i - 1/T_j), k_ij = C_Vi C_Vj kappa(T_ij) T_ij^2 / k_B;
//! - viscous heating q_d = [w_r^2 (gamma (e.v)^2 - sigma^2/m) - sigma w_r (e.v) xi] /
//!   (C_Vi + C_Vj), to both particles;
//! - random heat q_r = sqrt(2 k_B k_ij) w_rT xi_T / sqrt(dt), antisymmetric;
//! - the `power` and `kappa` keywords scale s and kappa by 1 + sum_k c_k (T_ij - 1)^k.
//!
//! Where gendpde follows LAMMPS's source against its documentation or the paper:
//! xi_T is xi clipped to [-5, 5] (the source draws a second number and discards it);
//! the sigma^2/m term takes the mass of the particle of lower tag (LAMMPS: of the
//! first particle of its neighbour pair), and q_r goes + to the particle of lower tag,
//! so that a pair is the same on every rank; the noise is Philox keyed by the pair's tags
//! (LAMMPS: a per-rank Marsaglia stream).

use crate::error::StepError;
use crate::passes::verlet;
use crate::physics::{Physics, SetupError};
use crate::rng::{normal_pair, stream};
use crate::settings::Settings;
use crate::system::System;
use crate::type_table::TypeTable;
use gendpde_engine::{dot, sub, Fields, Particles, Vec3};
use std::sync::Arc;

/// The coefficients of one type pair (`pair_coeff I J A0 GAMMA POWER CUT KAPPA POWER_T
/// CUT_T [power c1 c2 c3 c4] [kappa c1 c2 c3 c4]`).
#[derive(Clone, Debug, PartialEq)]
pub struct EdpdCoeff {
    pub a0: f64,
    pub gamma: f64,
    pub power: f64,
    pub rc: f64,
    pub kappa: f64,
    pub power_t: f64,
    pub rc_t: f64,
    /// Temperature coefficients of the power (`power` keyword).
    pub power_poly: Option<[f64; 4]>,
    /// Temperature coefficients of kappa (`kappa` keyword).
    pub kappa_poly: Option<[f64; 4]>,
}

impl EdpdCoeff {
    /// 1 + sum_k c_k (T_ij - 1)^k, k = 1..4.
    fn factor(poly: &Option<[f64; 4]>, t_ij: f64) -> f64 {
        let Some(c) = poly else { return 1.0 };
        let x = t_ij - 1.0;
        1.0 + x * (c[0] + x * (c[1] + x * (c[2] + x * c[3])))
    }
}

/// Where `fix edpd/source` adds heat.
#[derive(Clone)]
pub enum SourceShape {
    /// Inside `|r - centre|^2 < radius^3` (LAMMPS's source squares nothing: it compares
    /// with the cube of the radius).
    Sphere { centre: Vec3, radius: f64 },
    /// Within half of each edge length of the centre (edges included).
    Cuboid { centre: Vec3, edges: Vec3 },
    /// Inside a region.
    Region(Arc<dyn Fn(Vec3) -> bool + Send + Sync>),
}

/// `fix ID GROUP edpd/source ...`: Q_i += value C_Vi for group members in the shape.
#[derive(Clone)]
pub struct HeatSource {
    pub mask: u32,
    pub shape: SourceShape,
    pub value: f64,
}

impl HeatSource {
    fn contains(&self, r: Vec3) -> bool {
        match &self.shape {
            SourceShape::Sphere { centre, radius } => {
                let d = sub(r, *centre);
                dot(d, d) < radius * radius * radius
            }
            SourceShape::Cuboid { centre, edges } => (0..3).all(|k| (r[k] - centre[k]).abs() <= 0.5 * edges[k]),
            SourceShape::Region(inside) => inside(r),
        }
    }
}

/// An eDPD scene: `pair edpd` integrated by `fix mvv/edpd`.
pub struct Edpd {
    /// Coefficients by type pair.
    pub coeff: TypeTable<EdpdCoeff>,
    pub seed: u64,
    pub kb: f64,
    /// `fix mvv/edpd LAMBDA`.
    pub lambda: f64,
    pub sources: Vec<HeatSource>,
    pub settings: Settings,
}

impl Edpd {
    fn radius(&self) -> f64 {
        self.cutoff() + self.settings.skin
    }

    /// Forces, pair energies, virials and the pair heat flux Q of the owned particles, at
    /// the current positions, velocities and temperatures; the noise of step `step`.
    /// One pass over the half list: a pair gives its exact mirror to j.
    fn forces(&self, sys: &mut System, step: u64) {
        let inv_sqrt_dt = 1.0 / self.settings.dt.sqrt();
        let key = sys.noise_step(step);
        let (kb, s, pairs) = (self.kb, &mut sys.store, &sys.nlist.pairs);
        let n = s.nlocal;
        s.f[..n].fill([0.0; 3]);
        s.epair[..n].fill(0.0);
        s.virial[..n].fill([0.0; 3]);
        s.edpd_flux[..n].fill(0.0);
        for &[i, j] in pairs {
            let (i, j) = (i as usize, j as usize);
            let c = self.coeff.get(s.kind[i], s.kind[j]);
            let d = sub(s.r[i], s.r[j]);
            let r2 = dot(d, d);
            if r2 >= c.rc * c.rc {
                continue;
            }
            let r = r2.sqrt();
            if r < 1e-10 {
                continue;
            }
            let inv_r = 1.0 / r;
            let (ti, tj) = (s.edpd_temp[i], s.edpd_temp[j]);
            let vij = dot(d, sub(velocity(s, i), velocity(s, j))) * inv_r;
            let xi = normal_pair(self.seed, key, s.tag[i].min(s.tag[j]), s.tag[i].max(s.tag[j]), stream::FORCE).0;
            let t_ij = 0.5 * (ti + tj);
            let power = (c.power * EdpdCoeff::factor(&c.power_poly, t_ij)).max(0.01);
            let wc = (1.0 - r / c.rc).clamp(0.0, 1.0);
            let wr = wc.powf(0.5 * power);
            let sigma = (4.0 * c.gamma * kb * ti * tj / (ti + tj)).sqrt();
            let fp = c.a0 * t_ij * wc - c.gamma * wr * wr * vij + sigma * wr * xi * inv_sqrt_dt;
            let (mut q_sym, mut q_anti) = (0.0, 0.0);
            if r < c.rc_t {
                let wrt = (1.0 - r / c.rc_t).clamp(0.0, 1.0).powf(0.5 * c.power_t);
                let kappa = c.kappa * EdpdCoeff::factor(&c.kappa_poly, t_ij);
                let k_ij = s.edpd_cv[i] * s.edpd_cv[j] * kappa * t_ij * t_ij;
                let alpha = (2.0 * kb * k_ij).sqrt();
                let lower = if s.tag[i] < s.tag[j] { i } else { j };
                let q_c = k_ij * wrt * wrt * (tj - ti) / (ti * tj);
                let q_d = (wr * wr * (c.gamma * vij * vij - sigma * sigma / s.mass[lower]) - sigma * wr * vij * xi) / (s.edpd_cv[i] + s.edpd_cv[j]);
                let q_r = alpha * wrt * inv_sqrt_dt * xi.clamp(-5.0, 5.0);
                q_sym = q_d;
                q_anti = q_c + if lower == i { q_r } else { -q_r };
            }
            let fpair = fp * inv_r;
            let df = [fpair * d[0], fpair * d[1], fpair * d[2]];
            let virial = [0.5 * df[0] * d[0], 0.5 * df[1] * d[1], 0.5 * df[2] * d[2]];
            let e = 0.25 * c.a0 * t_ij * c.rc * wc * wc;
            for (k, sign) in [(i, 1.0), (j, -1.0)] {
                if k < n {
                    for a in 0..3 {
                        s.f[k][a] += sign * df[a];
                        s.virial[k][a] += virial[a];
                    }
                    s.epair[k] += e;
                    s.edpd_flux[k] += q_sym + sign * q_anti;
                }
            }
        }
    }

    /// `fix edpd/source`: Q_i += value C_Vi (LAMMPS's post_force, after the pair forces).
    fn add_sources(&self, sys: &mut System) {
        let s = &mut sys.store;
        for src in &self.sources {
            for i in 0..s.nlocal {
                if s.in_group(i, src.mask) && src.contains(s.r[i]) {
                    s.edpd_flux[i] += src.value * s.edpd_cv[i];
                }
            }
        }
    }

    /// The owned particle of lowest tag whose temperature is not finite and positive.
    fn check_temperatures(sys: &System) -> Result<(), StepError> {
        sys.check_positive(&sys.store.edpd_temp, |t| format!("eDPD temperature {t} is not positive"))
    }
}

impl Physics for Edpd {
    fn settings(&self) -> &Settings {
        &self.settings
    }

    fn cutoff(&self) -> f64 {
        self.coeff.max_of(|c| c.rc.max(c.rc_t))
    }

    /// As LAMMPS's set-up: forces and the pair flux, without the sources (fix
    /// edpd/source acts in post_force only).
    fn setup(&self, sys: &mut System) -> Result<(), SetupError> {
        sys.lay_grid(self.radius()).map_err(SetupError::Grid)?;
        sys.store.enable(Fields::EDPD | Fields::PAIR_ENERGY);
        self.rebuild(sys, sys.clock.step);
        let state = Self::check_temperatures(sys);
        self.forces(sys, sys.clock.step);
        sys.settle(state).map_err(SetupError::State)
    }

    /// LAMMPS's fix mvv/edpd: vest = v + dt/2 f/m, T_est = T + dt/2 Q/C_V; r += dt vest;
    /// v += lambda dt f/m, T += lambda dt Q/C_V (what the forces read); forces, flux and
    /// sources; then v = vest + dt/2 f/m, T = T_est + dt/2 Q/C_V.
    fn step(&self, sys: &mut System) -> Result<(), StepError> {
        let (dt, lambda) = (self.settings.dt, self.lambda);
        let drifted = verlet::mvv_first_half(sys, dt, lambda, |s, i| {
            let dt_t = 0.5 * dt / s.edpd_cv[i];
            s.vest_temp[i] = s.edpd_temp[i] + dt_t * s.edpd_flux[i];
            s.edpd_temp[i] += 2.0 * lambda * dt_t * s.edpd_flux[i];
        });
        self.relist(sys, drifted)?;
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM | Fields::EDPD);
        self.forces(sys, sys.clock.step + 1);
        self.add_sources(sys);
        verlet::mvv_second_half(sys, dt, |s, i| s.edpd_temp[i] = s.vest_temp[i] + 0.5 * dt / s.edpd_cv[i] * s.edpd_flux[i]);
        let state = Self::check_temperatures(sys);
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM | Fields::EDPD);
        sys.settle(state)
    }
}

#[inline(always)]
fn velocity(s: &Particles, i: usize) -> Vec3 {
    let k = 1.0 / s.mass[i];
    [s.p[i][0] * k, s.p[i][1] * k, s.p[i][2] * k]
}
