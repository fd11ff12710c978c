//! Isothermal SDPD of Tait water as LAMMPS's DPD-SMOOTH package runs it: `pair
//! sdpd/taitwater/isothermal T MU [SEED]` integrated by `fix sph` (atom_style sph). The
//! model is Espanol and Revenga's SDPD (Phys. Rev. E 67, 026705 (2003)) with the density
//! carried by the SPH continuity equation instead of the kernel sum.
//!
//! Pair terms (LAMMPS src/DPD-SMOOTH/pair_sdpd_taitwater_isothermal.cpp), with the 3D
//! Lucy kernel W of support h, F = W'(r)/r (< 0), v_ij = v_i - v_j, R_ij = r_i - r_j:
//!
//! - pressure force -m_i m_j (P_i/rho_i^2 + P_j/rho_j^2) F R_ij, P from Tait's EOS;
//! - viscous force f_v [v_ij + R_ij (R_ij . v_ij)/r^2], f_v = (5/3) mu m_i m_j F/(rho_i rho_j);
//! - random force sqrt(-4 k_B T f_v / dt)/r dW R_ij, dW a symmetric matrix of normals with
//!   unit diagonal and 1/2 off-diagonal variances;
//! - drho_i/dt = sum_j m_j F (R_ij . v_ij).
//!
//! The velocities the forces read are fix sph's estimates v + dt f/m. The virial is that
//! of the whole pair force, as LAMMPS's f.r sum gives it (the pair energy is zero).
//!
//! Where gendpde differs: the noise is Philox keyed by the pair's tags and the step, the
//! same on any rank count (LAMMPS: a Marsaglia stream per rank, seeded by SEED plus the
//! rank, the number of ranks and the number of owned atoms); 3D only.

use crate::error::StepError;
use crate::passes::verlet;
use crate::physics::{Physics, SetupError};
use crate::rng::Normals;
use crate::settings::Settings;
use crate::system::System;
use crate::type_table::TypeTable;
use gendpde_engine::{dot, sub, Fields};
use gendpde_potentials::{Lucy, Tait, Weight};

/// Philox streams of the three normal pairs of a pair's Wiener matrix.
const WIENER_STREAM: u32 = 8;

/// One pair style's settings and coefficients.
pub struct SdpdTaitwater {
    /// Tait water of each type (`pair_coeff I J RHO0 C0 H` sets it for the types I).
    pub eos: Vec<Tait>,
    /// The Lucy kernel of each type pair.
    pub kernel: TypeTable<Lucy>,
    /// k_B T of the noise.
    pub kbt: f64,
    /// Dynamic viscosity mu.
    pub viscosity: f64,
    pub seed: u64,
    /// LAMMPS's mvv2e: the formulas take LAMMPS's masses, M / mvv2e.
    pub mvv2e: f64,
    pub settings: Settings,
}

impl SdpdTaitwater {
    fn radius(&self) -> f64 {
        self.cutoff() + self.settings.skin
    }

    /// Forces, virials and drho/dt of the owned particles at the current
    /// positions, densities and (estimated) velocities; the noise of step `step`.
    fn forces(&self, sys: &mut System, step: u64) {
        let (normals, key) = (Normals::get(), sys.noise_step(step));
        let inv_m = 1.0 / self.mvv2e;
        let noise = 4.0 * self.kbt / self.settings.dt;
        let (s, pairs) = (&mut sys.store, &sys.nlist.pairs);
        let n = s.nlocal;
        s.f[..n].fill([0.0; 3]);
        s.virial[..n].fill([0.0; 3]);
        s.epair[..n].fill(0.0);
        s.drho[..n].fill(0.0);
        for &[i, j] in pairs {
            let (i, j) = (i as usize, j as usize);
            let (ti, tj) = (s.kind[i] as usize - 1, s.kind[j] as usize - 1);
            let kernel = self.kernel.get(s.kind[i], s.kind[j]);
            let d = sub(s.r[i], s.r[j]);
            let r2 = dot(d, d);
            let h = kernel.cutoff();
            if r2 >= h * h {
                continue;
            }
            let r = r2.sqrt();
            let wfd = kernel.eval(r).1 / r;
            let (mi, mj) = (s.mass[i] * inv_m, s.mass[j] * inv_m);
            let (rho_i, rho_j) = (s.rho[i], s.rho[j]);
            let (pi, pj) = (self.eos[ti].p_over_rho2(rho_i), self.eos[tj].p_over_rho2(rho_j));
            let (vi, vj) = (s.p[i], s.p[j]);
            let vel = [vi[0] / s.mass[i] - vj[0] / s.mass[j], vi[1] / s.mass[i] - vj[1] / s.mass[j], vi[2] / s.mass[i] - vj[2] / s.mass[j]];
            let dv = dot(d, vel);
            let fvisc = (5.0 / 3.0) * self.viscosity * mi * mj * wfd / (rho_i * rho_j);
            let fpair = -mi * mj * (pi + pj) * wfd;
            let (a, b) = if s.tag[i] < s.tag[j] { (s.tag[i], s.tag[j]) } else { (s.tag[j], s.tag[i]) };
            let (w00, w11) = normals.pair(self.seed, key, a, b, WIENER_STREAM);
            let (w22, w01) = normals.pair(self.seed, key, a, b, WIENER_STREAM + 1);
            let (w02, w12) = normals.pair(self.seed, key, a, b, WIENER_STREAM + 2);
            let half = std::f64::consts::FRAC_1_SQRT_2;
            let (w01, w02, w12) = (half * w01, half * w02, half * w12);
            let prefactor = (-noise * fvisc).sqrt() / r;
            let random = [
                prefactor * (w00 * d[0] + w01 * d[1] + w02 * d[2]),
                prefactor * (w01 * d[0] + w11 * d[1] + w12 * d[2]),
                prefactor * (w02 * d[0] + w12 * d[1] + w22 * d[2]),
            ];
            let along = dv / r2;
            let df: [f64; 3] = std::array::from_fn(|k| d[k] * fpair + (vel[k] + d[k] * along) * fvisc + random[k]);
            let virial = [0.5 * df[0] * d[0], 0.5 * df[1] * d[1], 0.5 * df[2] * d[2]];
            for (k, sign, m_other) in [(i, 1.0, mj), (j, -1.0, mi)] {
                if k < n {
                    for c in 0..3 {
                        s.f[k][c] += sign * df[c];
                        s.virial[k][c] += virial[c];
                    }
                    s.drho[k] += m_other * dv * wfd;
                }
            }
        }
    }

    /// The owned particle of lowest tag whose density is not finite and positive.
    fn check_densities(sys: &System) -> Result<(), StepError> {
        sys.check_positive(&sys.store.rho, |rho| format!("SPH density {rho} is not positive (set sph/rho)"))
    }
}

impl Physics for SdpdTaitwater {
    fn settings(&self) -> &Settings {
        &self.settings
    }

    fn cutoff(&self) -> f64 {
        self.kernel.max_of(Lucy::cutoff)
    }

    /// As LAMMPS's set-up: the forces and drho/dt with the estimates equal to v.
    fn setup(&self, sys: &mut System) -> Result<(), SetupError> {
        sys.lay_grid(self.radius()).map_err(SetupError::Grid)?;
        sys.store.enable(Fields::RHO | Fields::SPH | Fields::PAIR_ENERGY);
        self.rebuild(sys, sys.clock.step);
        let state = Self::check_densities(sys);
        sys.settle(state).map_err(SetupError::State)?;
        self.forces(sys, sys.clock.step);
        Ok(())
    }

    /// LAMMPS's fix sph: rho += dt/2 drho; v += dt/2 f/m, with the estimate v + dt f/m
    /// what the forces read; r += dt v; forces and drho; v += dt/2 f/m, rho += dt/2 drho.
    /// The half-step momentum waits in `vest` while `p` holds the estimate.
    fn step(&self, sys: &mut System) -> Result<(), StepError> {
        let dt = self.settings.dt;
        // lambda = 1: 1.0 * dt is dt, so p += dt f as fix sph writes it
        let drifted = verlet::mvv_first_half(sys, dt, 1.0, |s, i| s.rho[i] += 0.5 * dt * s.drho[i]);
        self.relist(sys, drifted)?;
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM | Fields::RHO);
        self.forces(sys, sys.clock.step + 1);
        verlet::mvv_second_half(sys, dt, |s, i| s.rho[i] += 0.5 * dt * s.drho[i]);
        let state = Self::check_densities(sys);
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM | Fields::RHO);
        sys.settle(state)
    }
}
