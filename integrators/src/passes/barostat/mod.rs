//! `fix nph`: LAMMPS's Nose-Hoover barostat (fix_nh.cpp, fix_nph.cpp; Martyna, Tobias and
//! Klein 1994 with the MTK terms of Martyna, Tuckerman, Tobias and Klein, Mol Phys 87,
//! 1117 (1996), in Shinoda's time-reversible splitting) on an orthogonal box, without a
//! thermostat. Quantities and their order follow fix_nh.cpp:
//!
//! - barostat masses W_d = (N + 1) k_B T0 / Pfreq_d^2 (Pfreq = 1/Pdamp), T0 the temperature
//!   at the first set-up (or `ptemp`); chain masses Q_k = k_B T0 / Pfreq_max^2;
//! - omega_dot_d += dt/2 [(P_d - P_target) V / W_d + mtk1 / W_d], mtk1 = sum m v^2 / (pdim N)
//!   (`nh_omega_dot`), P_d the coupled pressure (`couple`), minus h sigma h^T / W (x/y/z
//!   styles, `compute_deviatoric`);
//! - v *= exp(-dt/2 (omega_dot_d + mtk2)), mtk2 = sum_d omega_dot_d / (pdim N) (`nh_v_press`,
//!   two quarter steps);
//! - box and dilated positions scaled by exp(dt/2 omega_dot_d) about the fixed point,
//!   before and after the drift (`remap`);
//! - the chain on omega_dot, half a step at each end of the step (`nhc_press_integrate`);
//! - the fix's energy (`compute_scalar`, thermo `ecouple`): sum_d [W_d omega_dot_d^2 / 2 +
//!   P_hydro (V - V0) / pdim] + L k_B T0 eta_1 + Q_1 eta_dot_1^2 / 2 + sum_{k>1} [k_B T0 eta_k +
//!   Q_k eta_dot_k^2 / 2] (+ the strain energy sigma:h h^T / 2 for x/y/z), L the number of
//!   barostatted dimensions (LAMMPS counts L = pdim here but drives eta_dot_1 with
//!   k_B T0 alone for iso; followed as is).
//!
//! Pressures are kept in the units' pressure (bar in metal), as LAMMPS does, and converted
//! by nktv2p where they meet energies.

pub mod state;

pub use self::state::NphState;
use crate::error::StepError;
use crate::system::System;
use gendpde_engine::exact_sums;

/// How the pressure components drive the box (LAMMPS's `couple`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Couple {
    None,
    Xyz,
    Xy,
    Yz,
    Xz,
}

/// The settings of a `fix nph` (after `fix_modify`).
#[derive(Clone, Debug, PartialEq)]
pub struct Nph {
    /// The fix ID (the key of its state, [`crate::FixState`]).
    pub id: String,
    pub p_start: [f64; 3],
    pub p_stop: [f64; 3],
    /// 1 / Pdamp of each barostatted dimension (0 elsewhere).
    pub p_freq: [f64; 3],
    pub p_flag: [bool; 3],
    pub couple: Couple,
    /// x, y or z given on their own: the target stress is not hydrostatic.
    pub deviatoric: bool,
    pub pchain: usize,
    pub mtk: bool,
    pub ploop: u32,
    pub nreset: u64,
    pub drag: f64,
    /// `ptemp`: T0 instead of the current temperature.
    pub ptemp: Option<f64>,
    /// Group bit of the particles whose positions are dilated (`u32::MAX`: all).
    pub dilate: u32,
    /// The temperature compute (`fix_modify temp`): its group bit and extra dof.
    pub temp_mask: u32,
    pub extra_dof: f64,
    pub kb: f64,
    pub nktv2p: f64,
}

impl Nph {
    fn pdim(&self) -> f64 {
        self.p_flag.iter().filter(|&&f| f).count() as f64
    }

    fn iso(&self) -> bool {
        self.couple == Couple::Xyz
    }

    fn p_freq_max(&self) -> f64 {
        self.p_freq.iter().copied().fold(0.0, f64::max)
    }

    fn pdrag_factor(&self, dt: f64) -> f64 {
        1.0 - dt * self.p_freq_max() * self.drag / self.ploop as f64
    }

    /// `FixNH::init` and `setup`: V0 and h0^-1 at the first run, T0 from the current
    /// temperature (an error below 1e-6, as LAMMPS), the masses, P and the chain forces.
    /// `span` is the run's first and last step.
    pub fn setup(&self, sys: &System, st: &mut NphState, span: (u64, u64)) -> Result<(), String> {
        st.span = span;
        let l = sys.domain.len();
        if st.vol0 == 0.0 {
            st.vol0 = l[0] * l[1] * l[2];
            st.h0_inv = l.map(|x| 1.0 / x);
        }
        self.measure(sys, st, true);
        if st.t0 == 0.0 {
            st.t0 = match self.ptemp {
                Some(t) => t,
                None if st.t_current < 1e-6 => {
                    return Err(format!("fix {}: current temperature too close to zero, consider using ptemp keyword", self.id));
                }
                None => st.t_current,
            };
        }
        self.press_target(sys.clock.step, sys.domain.len(), st);
        let kt = self.kb * st.t0;
        let nkt = (st.natoms + 1.0) * kt;
        for d in 0..3 {
            if self.p_flag[d] {
                st.omega_mass[d] = nkt / (self.p_freq[d] * self.p_freq[d]);
            }
        }
        let m = st.etap.len();
        let f = self.p_freq_max();
        st.etap_mass = vec![kt / (f * f); m];
        for k in 1..m {
            st.etap_dotdot[k] = (st.etap_mass[k - 1] * st.etap_dot[k - 1] * st.etap_dot[k - 1] - kt) / st.etap_mass[k];
        }
        Ok(())
    }

    /// The temperature and coupled pressure at the current velocities, virials and
    /// volume; `temperature` also stores T as the MTK term's (LAMMPS's `t_current`, set
    /// at the set-up and the end of a step only).
    fn measure(&self, sys: &System, st: &mut NphState, temperature: bool) {
        let s = &sys.store;
        let mask = self.temp_mask;
        let rows = (0..s.nlocal).map(|i| {
            let (p, m, w) = (s.p[i], s.mass[i], s.virial.get(i).copied().unwrap_or_default());
            let g = if s.in_group(i, mask) { 1.0 } else { 0.0 };
            [1.0, g, g * p[0] * p[0] / m, g * p[1] * p[1] / m, g * p[2] * p[2] / m, w[0], w[1], w[2]]
        });
        let [natoms, count, kx, ky, kz, wx, wy, wz] = exact_sums(sys.comm.transport(), rows);
        let dof = 3.0 * count - self.extra_dof;
        let t = if dof > 0.0 { (kx + ky + kz) / (dof * self.kb) } else { 0.0 };
        st.natoms = natoms;
        if temperature {
            (st.t_current, st.tdof) = (t, dof);
        }
        let inv_volume = 1.0 / sys.domain.volume();
        let tensor = [(kx + wx) * inv_volume * self.nktv2p, (ky + wy) * inv_volume * self.nktv2p, (kz + wz) * inv_volume * self.nktv2p];
        let ave = |a: usize, b: usize| 0.5 * (tensor[a] + tensor[b]);
        st.p_current = match self.couple {
            Couple::Xyz => {
                // compute pressure's scalar: (dof k_B T + W) / 3V
                let scalar = (dof.max(0.0) * self.kb * t + wx + wy + wz) / 3.0 * inv_volume * self.nktv2p;
                [scalar; 3]
            }
            Couple::Xy => [ave(0, 1), ave(0, 1), tensor[2]],
            Couple::Yz => [tensor[0], ave(1, 2), ave(1, 2)],
            Couple::Xz => [ave(0, 2), tensor[1], ave(0, 2)],
            Couple::None => tensor,
        };
        // the MTK term of aniso reads the kinetic tensor (LAMMPS's mvv_current)
        st.mvv = [kx, ky, kz].iter().zip(self.p_flag).filter(|(_, f)| *f).map(|(k, _)| k).sum();
    }

    /// `compute_press_target`: P ramps from Pstart to Pstop over the run.
    fn press_target(&self, step: u64, len: [f64; 3], st: &mut NphState) {
        let (begin, end) = st.span;
        let delta = if end > begin { (step.saturating_sub(begin)) as f64 / (end - begin) as f64 } else { 0.0 };
        st.p_hydro = 0.0;
        for d in 0..3 {
            if self.p_flag[d] {
                st.p_target[d] = self.p_start[d] + delta * (self.p_stop[d] - self.p_start[d]);
                st.p_hydro += st.p_target[d];
            }
        }
        st.p_hydro /= self.pdim();
        if self.deviatoric {
            self.sigma(step, len, st);
        }
    }

    /// `compute_sigma` on an orthogonal box: sigma_d = V0 h0inv_d^2 (P_target_d - P_hydro),
    /// with V0 and h0^-1 reset every `nreset` steps of the run.
    fn sigma(&self, step: u64, l: [f64; 3], st: &mut NphState) {
        if self.nreset > 0 && step.saturating_sub(st.span.0) % self.nreset == 0 {
            st.vol0 = l[0] * l[1] * l[2];
            st.h0_inv = l.map(|x| 1.0 / x);
        }
        for d in 0..3 {
            st.sigma[d] = st.vol0 * (st.h0_inv[d] * ((st.p_target[d] - st.p_hydro) * st.h0_inv[d]));
        }
    }

    /// `nh_omega_dot`: half a step of the barostat velocities.
    fn omega_dot(&self, sys: &System, st: &mut NphState, dt: f64) {
        let l = sys.domain.len();
        let volume = l[0] * l[1] * l[2];
        let pdim = self.pdim();
        let mtk_term1 = if !self.mtk {
            0.0
        } else if self.iso() {
            st.tdof * self.kb * st.t_current / (pdim * st.natoms)
        } else {
            st.mvv / (pdim * st.natoms)
        };
        let pdrag = self.pdrag_factor(dt);
        for d in 0..3 {
            if self.p_flag[d] {
                let w = st.omega_mass[d];
                let mut f_omega = (st.p_current[d] - st.p_hydro) * volume / (w * self.nktv2p) + mtk_term1 / w;
                if self.deviatoric {
                    // fdev = h sigma h^T
                    f_omega -= l[d] * (st.sigma[d] * l[d]) / (w * self.nktv2p);
                }
                st.omega_dot[d] += f_omega * (0.5 * dt);
                st.omega_dot[d] *= pdrag;
            }
        }
        st.mtk_term2 = 0.0;
        if self.mtk {
            for d in 0..3 {
                if self.p_flag[d] {
                    st.mtk_term2 += st.omega_dot[d];
                }
            }
            st.mtk_term2 /= pdim * st.natoms;
        }
    }

    /// `nh_v_press`: p_d *= exp(-dt/4 (omega_dot_d + mtk2)), twice.
    fn scale_momenta(&self, sys: &mut System, st: &NphState, dt: f64) {
        let factor = [0, 1, 2].map(|d| (-(0.25 * dt) * (st.omega_dot[d] + st.mtk_term2)).exp());
        let s = &mut sys.store;
        for p in &mut s.p[..s.nlocal] {
            for d in 0..3 {
                p[d] *= factor[d];
                p[d] *= factor[d];
            }
        }
    }

    /// `remap`: omega += dt/2 omega_dot; the box scaled by exp(dt/2 omega_dot) about the
    /// fixed point, dilated positions with it (through fractional coordinates, all
    /// three dimensions, as LAMMPS's x2lamda/lamda2x).
    fn remap(&self, sys: &mut System, st: &mut NphState, dt: f64) {
        let dto = 0.5 * dt;
        for d in 0..3 {
            st.omega[d] += dto * st.omega_dot[d];
        }
        let old = sys.domain.clone();
        let inv = old.len().map(|x| 1.0 / x);
        for d in 0..3 {
            if self.p_flag[d] {
                let e = (dto * st.omega_dot[d]).exp();
                let fp = st.fixedpoint[d];
                sys.domain.lo[d] = (old.lo[d] - fp) * e + fp;
                sys.domain.hi[d] = (old.hi[d] - fp) * e + fp;
            }
        }
        let (lo, len) = (sys.domain.lo, sys.domain.len());
        let s = &mut sys.store;
        for i in 0..s.nlocal {
            if s.in_group(i, self.dilate) {
                for d in 0..3 {
                    let lamda = inv[d] * (s.r[i][d] - old.lo[d]);
                    s.r[i][d] = len[d] * lamda + lo[d];
                }
            }
        }
    }

    /// `nhc_press_integrate`: half a step of the chain acting on omega_dot.
    fn chain(&self, st: &mut NphState, dt: f64) {
        let m = st.etap.len();
        if m == 0 {
            return;
        }
        let kt = self.kb * st.t0;
        let (dt8, dt4, dthalf) = (0.125 * dt, 0.25 * dt, 0.5 * dt);
        let pdrag = self.pdrag_factor(dt);
        let ke = |st: &NphState| (0..3).filter(|&d| self.p_flag[d]).map(|d| st.omega_mass[d] * st.omega_dot[d] * st.omega_dot[d]).sum::<f64>();
        let lkt_press = if self.iso() { kt } else { self.pdim() * kt };
        st.etap_dotdot[0] = (ke(st) - lkt_press) / st.etap_mass[0];
        let ncfac = 1.0 / self.ploop as f64;
        for _ in 0..self.ploop {
            for k in (1..m).rev() {
                let e = (-ncfac * dt8 * st.etap_dot[k + 1]).exp();
                st.etap_dot[k] *= e;
                st.etap_dot[k] += st.etap_dotdot[k] * ncfac * dt4;
                st.etap_dot[k] *= pdrag;
                st.etap_dot[k] *= e;
            }
            let e = (-ncfac * dt8 * st.etap_dot[1]).exp();
            st.etap_dot[0] *= e;
            st.etap_dot[0] += st.etap_dotdot[0] * ncfac * dt4;
            st.etap_dot[0] *= pdrag;
            st.etap_dot[0] *= e;
            for k in 0..m {
                st.etap[k] += ncfac * dthalf * st.etap_dot[k];
            }
            let factor = (-ncfac * dthalf * st.etap_dot[0]).exp();
            for d in 0..3 {
                if self.p_flag[d] {
                    st.omega_dot[d] *= factor;
                }
            }
            st.etap_dotdot[0] = (ke(st) - lkt_press) / st.etap_mass[0];
            st.etap_dot[0] *= e;
            st.etap_dot[0] += st.etap_dotdot[0] * ncfac * dt4;
            st.etap_dot[0] *= e;
            for k in 1..m {
                let e = (-ncfac * dt8 * st.etap_dot[k + 1]).exp();
                st.etap_dot[k] *= e;
                st.etap_dotdot[k] = (st.etap_mass[k - 1] * st.etap_dot[k - 1] * st.etap_dot[k - 1] - kt) / st.etap_mass[k];
                st.etap_dot[k] += st.etap_dotdot[k] * ncfac * dt4;
                st.etap_dot[k] *= e;
            }
        }
    }

    /// `FixNH::initial_integrate` (after fix shardlow's sweep): the chain, P at the swept
    /// velocities and the last forces, omega_dot, the momentum scaling, the half kick,
    /// then remap, drift, remap. Every rank computes the same box (the sums are exact).
    pub fn initial(&self, sys: &mut System, st: &mut NphState, dt: f64) -> Result<(), StepError> {
        self.chain(st, dt);
        self.measure(sys, st, false);
        check_pressure(sys, st)?;
        self.press_target(sys.clock.step + 1, sys.domain.len(), st);
        self.omega_dot(sys, st, dt);
        self.scale_momenta(sys, st, dt);
        crate::passes::verlet::kick(sys, 0.5 * dt);
        self.remap(sys, st, dt);
        let drifted = crate::passes::verlet::drift(sys, dt);
        self.remap(sys, st, dt);
        drifted
    }

    /// `FixNH::final_integrate` (after the forces): the half kick, the momentum scaling,
    /// T and P at the new state, omega_dot, the chain.
    pub fn last(&self, sys: &mut System, st: &mut NphState, dt: f64) -> Result<(), StepError> {
        crate::passes::verlet::kick(sys, 0.5 * dt);
        self.scale_momenta(sys, st, dt);
        self.measure(sys, st, true);
        check_pressure(sys, st)?;
        self.omega_dot(sys, st, dt);
        self.chain(st, dt);
        Ok(())
    }

    /// The fix's energy (`FixNH::compute_scalar`, thermo `ecouple` and `f_ID`).
    pub fn energy(&self, sys: &System, st: &NphState) -> f64 {
        let l = sys.domain.len();
        let volume = l[0] * l[1] * l[2];
        let kt = self.kb * st.t0;
        let mut energy = 0.0;
        let mut lkt_press = 0.0;
        for d in 0..3 {
            if self.p_flag[d] {
                energy += 0.5 * st.omega_dot[d] * st.omega_dot[d] * st.omega_mass[d] + st.p_hydro * (volume - st.vol0) / (self.pdim() * self.nktv2p);
                lkt_press += kt;
            }
        }
        let m = st.etap.len();
        if m > 0 {
            energy += lkt_press * st.etap[0] + 0.5 * st.etap_mass[0] * st.etap_dot[0] * st.etap_dot[0];
            for k in 1..m {
                energy += kt * st.etap[k] + 0.5 * st.etap_mass[k] * st.etap_dot[k] * st.etap_dot[k];
            }
        }
        if self.deviatoric {
            // compute_strain_energy: Tr(sigma h h^T) / 2
            energy += 0.5 * (0..3).map(|d| st.sigma[d] * (l[d] * l[d])).sum::<f64>() / self.nktv2p;
        }
        energy
    }
}

/// LAMMPS's "Non-numeric pressure - simulation unstable", as a step error on every rank.
fn check_pressure(sys: &System, st: &NphState) -> Result<(), StepError> {
    if st.p_current.iter().all(|p| p.is_finite()) {
        return Ok(());
    }
    Err(StepError::global(sys.clock.step, "fix nph: non-numeric pressure (simulation unstable)"))
}
