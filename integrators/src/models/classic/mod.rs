//! LAMMPS's pairwise DPD styles, with LAMMPS's semantics, for users who compare with it:
//! `pair dpd` (isothermal DPD, friction and noise in the force), `pair dpd/fdt` and
//! `dpd/fdt/energy` (with `fix shardlow`: conservative force only; friction, noise and heat
//! in the sweep, theta from `fix eos/cv`; without it, velocity Verlet with every force in
//! the pair pass and, for `dpd/fdt/energy`, the rates duCond and duMech that `fix
//! dpd/energy` integrates by half steps), and many-body DPD (`pair mdpd/rhosum` + `mdpd`,
//! integrated by `fix mvv/dpd`), and DPD-REACT's many-body `pair multi/lucy` (fix nve).
//! As in LAMMPS the sweep runs at the start of the step and
//! theta is not refreshed between pairs (it follows the sweep through eos/cv).
//!
//! Formulas (LAMMPS documentation and sources): w = 1 - r/rc;
//! dpd: F = [a0 w - gamma w^2 (e.v) + sigma w xi / sqrt(dt)] e, sigma = sqrt(2 k_B T gamma);
//! mdpd: F = [A w_c + B (rho_i + rho_j) w_d - gamma w_c^2 (e.v) + sigma w_c xi / sqrt(dt)] e
//! with rho_i = sum_j m_j W_Lucy(r_ij; h); pair energy a0 rc w^2 / 2 (dpd);
//! dpd/ext (and the thermostats dpd/tstat, dpd/ext/tstat without a0): with P = I - e e,
//! F = [a0 w - gamma_par w^(2 s_par) (e.v) + sigma_par w^s_par xi / sqrt(dt)] e -
//! gamma_perp w^(2 s_perp) P v + sigma_perp w^s_perp P xi_vec / sqrt(dt),
//! sigma = sqrt(2 k_B T gamma) each, T ramped linearly over the run for the thermostats.
//! multi/lucy (pair_multi_lucy.cpp; Moore et al., J. Chem. Phys. 144, 104501 (2016)):
//! rho_i = sum_{j != i} 84/(5 pi rc^3) (1 + 3r/2rc)(1 - r/rc)^4, F = (A(rho_i) + A(rho_j))/2
//! (1 + 3r/rc)(1 - r/rc)^3 with A the table's f column at rho (read in rho^2), and the
//! energy of particle i e(rho_i) pi rc_ii^4 / 84 from the table's e column.
//! Shardlow DPDE pair update: gamma = sigma^2 / (2 k_B theta_ij), 1/theta_ij the mean of
//! 1/theta_i and 1/theta_j; heat kappa w^2 (1/theta_i - 1/theta_j) dt + sqrt(2 k_B kappa)
//! w xibar sqrt(dt) into i (uCond); -dK/2 into each u (uMech).
//! Velocity-Verlet DPDE (pair dpd/fdt/energy, no shardlow): the dpd force with gamma_ij
//! = sigma^2 / (2 k_B theta_ij); duMech_i and duMech_j += [gamma w^2 (e.v)^2 - sigma^2
//! mu_ij w^2 / 2 - sigma w (e.v) xi / sqrt(dt)] / 2 with mu_ij = 1/m_i + 1/m_j (the work
//! of friction and noise, with the Ito term); duCond_i (-duCond_j) += kappa w^2 (1/theta_i -
//! 1/theta_j) + sqrt(2 k_B kappa) w xibar / sqrt(dt); fix dpd/energy: u += dt/2 du
//! before the first and before the second half kick (fix_dpd_energy.cpp), eos/cv after
//! the drift and at the end of the step.
//! Every coefficient and cutoff is per type pair ([`TypeTable`], LAMMPS's `a0[itype][jtype]`);
//! the lists reach the largest cutoff and each pair is cut at its own.

mod sums;

use crate::passes::barostat::{Nph, NphState};
use crate::error::{lowest, StepError};
use crate::passes::heat::{Original, Temps};
use crate::passes::noise::{isothermal_gamma, isothermal_sigma, Harmonic};
use crate::passes::pair_update::{pair_update, PairDrive, PairState};
use crate::physics::{Physics, SetupError};
use crate::rng::{stream, Normals, LANES};
use crate::settings::Settings;
use crate::simd::avx2_fn;
use crate::passes::sweep::SWEPT;
use crate::system::{FixRecord, System};
use crate::type_table::TypeTable;
use crate::passes::pair_tables::PairTables;
use crate::passes::verlet;
use sums::{density, tally, velocity, within, Terms};
use gendpde_engine::{dot, sub, Fields, Particles, Vec3};
use gendpde_potentials::pair_table::Outside;
use gendpde_potentials::{Lucy, Weight};

/// `pair dpd` coefficients of one type pair: a0 w(rc) with in-force friction `gamma`
/// and noise `sigma` (both 0 under Shardlow).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DpdCoeff {
    pub a0: f64,
    pub rc: f64,
    pub gamma: f64,
    pub sigma: f64,
    inv_rc: f64,
}

impl DpdCoeff {
    pub fn new(a0: f64, rc: f64, gamma: f64, sigma: f64) -> Self {
        Self { a0, rc, gamma, sigma, inv_rc: 1.0 / rc }
    }

    /// `pair dpd T`: friction `gamma` and the noise of the fluctuation-dissipation
    /// relation at temperature `temperature` (Espanol and Warren 1995, sigma^2 = 2 gamma
    /// k_B T; [`isothermal_sigma`]).
    pub fn isothermal(a0: f64, rc: f64, gamma: f64, kb: f64, temperature: f64) -> Self {
        Self::new(a0, rc, gamma, isothermal_sigma(kb, temperature, gamma))
    }

    /// `pair dpd/fdt T` integrated by velocity Verlet: noise `sigma` and the friction of
    /// the fluctuation-dissipation relation at temperature `temperature` (Espanol and
    /// Warren 1995, gamma = sigma^2 / (2 k_B T); [`isothermal_gamma`]).
    pub fn from_sigma(a0: f64, rc: f64, sigma: f64, kb: f64, temperature: f64) -> Self {
        Self::new(a0, rc, isothermal_gamma(kb, temperature, sigma), sigma)
    }
}

/// `pair dpd/ext` (and dpd/tstat, dpd/ext/tstat: a0 = 0) coefficients of one type pair:
/// a0 w(rc), parallel and perpendicular friction and their weight exponents; the noise
/// amplitudes sqrt(2 k_B T gamma) follow from the temperature of the step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DpdExtCoeff {
    pub a0: f64,
    pub rc: f64,
    pub gamma_par: f64,
    pub gamma_perp: f64,
    pub s_par: f64,
    pub s_perp: f64,
}

/// The dpd/ext family's force: its coefficients and the target temperature, fixed
/// (dpd/ext) or ramped from `start` to `stop` over each run (pair_dpd_tstat.cpp compute:
/// T = start + (step - first)/(last - first) (stop - start) at the step of the forces).
#[derive(Clone, Debug)]
pub struct DpdExt {
    pub coeff: TypeTable<DpdExtCoeff>,
    pub start: f64,
    pub stop: f64,
}

impl DpdExt {
    /// The target temperature of the forces of `step` in the run `[first, last]`.
    pub fn temperature(&self, step: u64, [first, last]: [u64; 2]) -> f64 {
        let delta = if step > first && last > first { (step - first) as f64 / (last - first) as f64 } else { 0.0 };
        self.start + delta * (self.stop - self.start)
    }
}

/// Velocity-Verlet `pair dpd/fdt/energy` coefficients of one type pair: a0 w(rc),
/// friction from `sigma` and theta_ij, heat `kappa`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DpdEnergyCoeff {
    pub a0: f64,
    pub rc: f64,
    pub sigma: f64,
    pub kappa: f64,
}

/// `pair mdpd` (with `mdpd/rhosum`) coefficients of one type pair.
#[derive(Clone, Copy, Debug)]
pub struct MdpdCoeff {
    pub a: f64,
    pub b: f64,
    pub rc: f64,
    pub rd: f64,
    pub gamma: f64,
    pub sigma: f64,
    /// The Lucy kernel of `mdpd/rhosum` (support h) this pair adds to rho.
    pub kernel: Lucy,
}

impl MdpdCoeff {
    /// `pair mdpd T`: friction `gamma` and the noise of the fluctuation-dissipation
    /// relation at temperature `temperature` (Espanol and Warren 1995, sigma^2 = 2 gamma
    /// k_B T; [`isothermal_sigma`]).
    #[allow(clippy::too_many_arguments)]
    pub fn isothermal(a: f64, b: f64, rc: f64, rd: f64, gamma: f64, kb: f64, temperature: f64, kernel: Lucy) -> Self {
        Self { a, b, rc, rd, gamma, sigma: isothermal_sigma(kb, temperature, gamma), kernel }
    }
}

/// The pair force computed in the force pass.
#[derive(Clone, Debug)]
pub enum PairForce {
    Dpd(TypeTable<DpdCoeff>),
    /// Warren's many-body DPD; rho from the Lucy kernels.
    Mdpd(TypeTable<MdpdCoeff>),
    /// dpd/ext, dpd/tstat, dpd/ext/tstat.
    DpdExt(DpdExt),
    /// Velocity-Verlet DPDE (dpd/fdt/energy without fix shardlow).
    DpdEnergy(TypeTable<DpdEnergyCoeff>),
    /// `pair multi/lucy`: pressure-density tables of the type pairs, each with its cutoff.
    MultiLucy(PairTables),
    /// No pairwise DPD force: the tables alone (`pair_style table`).
    Off,
}

impl PairForce {
    fn cutoff(&self) -> f64 {
        match self {
            Self::Dpd(t) => t.max_of(|c| c.rc),
            Self::Mdpd(t) => t.max_of(|c| c.rc.max(c.rd).max(c.kernel.cutoff())),
            Self::DpdEnergy(t) => t.max_of(|c| c.rc),
            Self::DpdExt(e) => e.coeff.max_of(|c| c.rc),
            Self::MultiLucy(t) => t.cutoff(),
            Self::Off => 0.0,
        }
    }
}

/// Shardlow coefficients of one type pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShardlowCoeff {
    pub sigma: f64,
    pub kappa: f64,
    pub rc: f64,
    inv_rc: f64,
}

impl ShardlowCoeff {
    pub fn new(sigma: f64, kappa: f64, rc: f64) -> Self {
        Self { sigma, kappa, rc, inv_rc: 1.0 / rc }
    }
}

/// `fix shardlow` with `pair dpd/fdt` (fixed T) or `dpd/fdt/energy` (per-particle theta).
#[derive(Clone, Debug, PartialEq)]
pub struct ShardlowDpd {
    pub coeff: TypeTable<ShardlowCoeff>,
    /// `dpd/fdt`: the temperature of the friction; None: theta of the particles.
    pub temperature: Option<f64>,
}

impl ShardlowDpd {
    fn cutoff(&self) -> f64 {
        self.coeff.max_of(|c| c.rc)
    }
}

/// How positions and momenta advance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Integration {
    /// `fix nve`: velocity Verlet.
    Nve,
    /// `fix mvv/dpd lambda`: modified velocity Verlet of Groot and Warren.
    Mvv { lambda: f64 },
}

/// A LAMMPS-style pairwise DPD scene.
pub struct ClassicDpd {
    pub force: PairForce,
    /// `pair_style table`, alone or overlaid on `force` (hybrid/overlay).
    pub tables: Option<PairTables>,
    pub shardlow: Option<ShardlowDpd>,
    pub integration: Integration,
    /// `fix eos/cv`: theta = u / C_V.
    pub cv: Option<f64>,
    /// `fix dpd/energy`: u integrated from the rates of [`PairForce::DpdEnergy`].
    pub energy: bool,
    /// `fix nph`: velocity Verlet under LAMMPS's Nose-Hoover barostat (its state is
    /// in [`System::fixes`]).
    pub barostat: Option<Nph>,
    pub kb: f64,
    pub seed: u64,
    pub settings: Settings,
}

impl ClassicDpd {
    fn radius(&self) -> f64 {
        self.cutoff() + self.settings.skin
    }

    /// theta = u / C_V for owned particles (fix eos/cv), and 1/theta, which the sweep
    /// reads for theta_ij and the heat flow, in `inv_tau` where kept.
    fn eos(&self, sys: &mut System) -> Result<(), StepError> {
        let s = &mut sys.store;
        let mut outcome = Ok(());
        for i in 0..s.nlocal {
            if let Some(cv) = self.cv {
                let theta = s.u[i] / cv;
                if !(theta > 0.0 && theta.is_finite()) {
                    let e = gendpde_potentials::EosError::NonPositiveTheta { u: s.u[i], n: 0.0, theta };
                    outcome = lowest(outcome, Err(StepError::eos(s, i, sys.clock.step, e)));
                }
                s.theta[i] = theta;
            }
            if !s.inv_tau.is_empty() {
                s.inv_tau[i] = 1.0 / s.theta[i];
            }
        }
        outcome
    }

    /// The many-body densities of owned particles, then of ghosts: MDPD's rho_i = sum_{j
    /// != i} m_j W(r_ij; h_ij), or multi/lucy's rho_i = sum_{j != i} W(r_ij; rc_ij), without
    /// a self term, as the reference LAMMPS (22 Jul 2025) sums them. One pass over the
    /// half list (see [`gendpde_engine::NeighborList::pairs`]).
    fn rho(&self, sys: &mut System) {
        match &self.force {
            PairForce::Mdpd(t) => density(sys, |s, i, j, r2| {
                let w = &t.get(s.kind[i], s.kind[j]).kernel;
                let h = w.cutoff();
                if r2 < h * h {
                    let wij = w.eval(r2.sqrt()).0;
                    (s.mass[j] * wij, s.mass[i] * wij)
                } else {
                    (0.0, 0.0)
                }
            }),
            PairForce::MultiLucy(t) => density(sys, |s, i, j, r2| {
                let Some(table) = t.of(s.kind[i], s.kind[j]) else { return (0.0, 0.0) };
                let rc = table.cut;
                if r2 < rc * rc {
                    let x = r2.sqrt() / rc;
                    let w = 84.0 / (5.0 * std::f64::consts::PI * rc * rc * rc) * (1.0 + 1.5 * x) * (1.0 - x).powi(4);
                    (w, w)
                } else {
                    (0.0, 0.0)
                }
            }),
            _ => return,
        }
        sys.comm.forward(&mut sys.store, Fields::RHO);
    }

    /// multi/lucy: the energy e(rho_i) pi rc_ii^4 / 84 of each owned particle added to its
    /// pair energy; a density outside a table of its type (LAMMPS: "Density < table
    /// inner cutoff", "Density > table outer cutoff") stops the step on every rank.
    fn many_body_energy(&self, sys: &mut System) -> Result<(), StepError> {
        let PairForce::MultiLucy(t) = &self.force else { return Ok(()) };
        let s = &mut sys.store;
        let mut outcome = Ok(());
        for i in 0..s.nlocal {
            let rsq = s.rho[i] * s.rho[i];
            let outside = (1..=t.ntypes as u32).filter_map(|tj| t.of(s.kind[i], tj)).find_map(|table| table.eval(rsq).err().map(|side| (side, table)));
            if let Some((side, table)) = outside {
                let (limit, bound) = match side {
                    Outside::Inner => ("< table inner", table.innersq.sqrt()),
                    Outside::Outer => ("> table outer", table.rsq_max().sqrt()),
                };
                let what = format!("density {:.9e} {limit} bound {bound}", s.rho[i]);
                outcome = lowest(outcome, Err(StepError::state(s, i, sys.clock.step, &what)));
                continue;
            }
            if let Some(table) = t.of(s.kind[i], s.kind[i]) {
                let rc2 = table.cut * table.cut;
                s.epair[i] += table.density_energy(rsq).unwrap_or(f64::NAN) * std::f64::consts::PI * rc2 * rc2 / 84.0;
            }
        }
        sys.settle(outcome)
    }

    /// Pair forces at the current positions and velocities; the noise of step `step`.
    /// Built for AVX2 where the processor has it (through [`built_forces`]).
    fn forces(&self, sys: &mut System, step: u64) {
        built_forces(self, sys, step)
    }

    #[inline(always)]
    fn forces_any(&self, sys: &mut System, step: u64) {
        // fix nph reads the virial every step
        let energies = sys.control.tally || self.barostat.is_some();
        sys.control.tallied = energies;
        let inv_sqrt_dt = 1.0 / self.settings.dt.sqrt();
        let key = sys.noise_step(step);
        let (seed, pairs, s) = (self.seed, &sys.nlist.pairs, &mut sys.store);
        let normals = Normals::get();
        let noise = move |s: &Particles, i: usize, j: usize| normals.pair(seed, key, s.tag[i].min(s.tag[j]), s.tag[i].max(s.tag[j]), stream::FORCE);
        match &self.force {
            // the pairs within the largest cutoff selected without a branch (at rc = 1 more
            // than half the list lies in the skin), then w = 0 beyond each pair's own rc
            // (the pairs left out would add exact zeros)
            PairForce::Dpd(t) if t.iter().all(|c| c.gamma == 0.0 && c.sigma == 0.0) => {
                within(s, pairs, t.max_of(|c| c.rc), &mut sys.scratch.active);
                tally::<true, false, false>(s, energies, sys.scratch.active.iter(), |_, _| f64::INFINITY, |s, i, j, _, r| {
                    let DpdCoeff { a0, rc, inv_rc, .. } = *t.get(s.kind[i], s.kind[j]);
                    let w = (1.0 - r * inv_rc).max(0.0);
                    Terms::conservative(a0 * w, 0.25 * a0 * rc * w * w)
                })
            }
            PairForce::Dpd(t) => tally::<false, false, false>(s, energies, pairs, |s, k| t.get(s.kind[k[0]], s.kind[k[1]]).rc, |s, i, j, d, r| {
                let DpdCoeff { a0, rc, gamma, sigma, inv_rc } = *t.get(s.kind[i], s.kind[j]);
                let w = 1.0 - r * inv_rc;
                let fp = a0 * w - gamma * w * w * dot(d, sub(velocity(s, i), velocity(s, j))) / r + sigma * w * noise(s, i, j).0 * inv_sqrt_dt;
                Terms::conservative(fp, 0.25 * a0 * rc * w * w)
            }),
            PairForce::Mdpd(t) => tally::<false, false, false>(s, energies, pairs, |s, k| t.get(s.kind[k[0]], s.kind[k[1]]).rc, |s, i, j, d, r| {
                let MdpdCoeff { a, b, rc, rd, gamma, sigma, .. } = *t.get(s.kind[i], s.kind[j]);
                let wc = 1.0 - r * (1.0 / rc);
                let wd = (1.0 - r / rd).max(0.0);
                let rho = s.rho[i] + s.rho[j];
                let mut fp = a * wc + b * rho * wd;
                if gamma > 0.0 || sigma > 0.0 {
                    fp += -gamma * wc * wc * dot(d, sub(velocity(s, i), velocity(s, j))) / r + sigma * wc * noise(s, i, j).0 * inv_sqrt_dt;
                }
                Terms::conservative(fp, 0.25 * (a * rc * wc * wc + b * rd * rho * wd * wd))
            }),
            PairForce::DpdExt(e) => {
                let (t, kb, normals) = (e.temperature(step, sys.clock.run), self.kb, Normals::get());
                let noise = move |s: &Particles, i: usize, j: usize, stream| normals.pair(seed, key, s.tag[i].min(s.tag[j]), s.tag[i].max(s.tag[j]), stream);
                let ext_pair = move |s: &Particles, i: usize, j: usize, d: Vec3, r: f64, perp: bool| {
                    let c = *e.coeff.get(s.kind[i], s.kind[j]);
                    let w = 1.0 - r / c.rc;
                    // pow(w, 1) is w: the common exponent skips the call
                    let pow = |s: f64| if s == 1.0 { w } else { w.powf(s) };
                    let dv = sub(velocity(s, i), velocity(s, j));
                    let inv_r = 1.0 / r;
                    let (xi, xi_x) = noise(s, i, j, stream::FORCE);
                    let w_par = pow(c.s_par);
                    let sigma_par = isothermal_sigma(kb, t, c.gamma_par);
                    let force = c.a0 * w - c.gamma_par * w_par * w_par * dot(d, dv) * inv_r + sigma_par * w_par * xi * inv_sqrt_dt;
                    let mut terms = Terms::conservative(force, 0.25 * c.a0 * c.rc * w * w);
                    if perp {
                        // P x = x - e (e.x): the perpendicular friction on v_ij and noise on xi_vec
                        let w_perp = pow(c.s_perp);
                        let (xi_y, xi_z) = noise(s, i, j, stream::FORCE_PERP);
                        let sigma_perp = isothermal_sigma(kb, t, c.gamma_perp);
                        let (g, n) = (c.gamma_perp * w_perp * w_perp, sigma_perp * w_perp * inv_sqrt_dt);
                        let (e_ij, xi_v) = ([d[0] * inv_r, d[1] * inv_r, d[2] * inv_r], [xi_x, xi_y, xi_z]);
                        let (ev, exi) = (dot(e_ij, dv), dot(e_ij, xi_v));
                        terms.perp = std::array::from_fn(|k| -g * (dv[k] - e_ij[k] * ev) + n * (xi_v[k] - e_ij[k] * exi));
                    }
                    terms
                };
                let rc = |s: &Particles, k: [usize; 2]| e.coeff.get(s.kind[k[0]], s.kind[k[1]]).rc;
                // dpd/tstat (no perpendicular terms) draws one pair of normals and skips them
                if e.coeff.iter().all(|c| c.gamma_perp == 0.0) {
                    tally::<false, false, false>(s, energies, pairs, rc, |s, i, j, d, r| ext_pair(s, i, j, d, r, false))
                } else {
                    tally::<false, false, true>(s, energies, pairs, rc, |s, i, j, d, r| ext_pair(s, i, j, d, r, true))
                }
            }
            PairForce::MultiLucy(t) => {
                // A = f(rho) of every particle (owned and ghost) in each table, read once;
                // densities outside a table (NaN here) are reported by many_body_energy
                let (nt, a) = (t.tables.len(), &mut sys.scratch.pair_sums);
                a.clear();
                for &rho in &s.rho {
                    a.extend(t.tables.iter().map(|table| table.eval(rho * rho).map_or(f64::NAN, |v| v.0)));
                }
                let a = &*a;
                tally::<false, false, false>(s, energies, pairs, |s, k| t.of(s.kind[k[0]], s.kind[k[1]]).map_or(0.0, |t| t.cut), |s, i, j, _, r| {
                    let Some(m) = t.slot(s.kind[i], s.kind[j]) else { return Terms::conservative(0.0, 0.0) };
                    let x = r / t.tables[m].cut;
                    let w = 1.0 - x;
                    Terms::conservative(0.5 * (a[i * nt + m] + a[j * nt + m]) * (1.0 + 3.0 * x) * w * w * w, 0.0)
                })
            }
            PairForce::Off => tally::<false, false, false>(s, energies, &[], |_, _| 0.0, |_, _, _, _, _| Terms::conservative(0.0, 0.0)),
            PairForce::DpdEnergy(t) => {
                let kb = self.kb;
                tally::<false, true, false>(s, energies, pairs, |s, k| t.get(s.kind[k[0]], s.kind[k[1]]).rc, |s, i, j, d, r| {
                    let DpdEnergyCoeff { a0, rc, sigma, kappa } = *t.get(s.kind[i], s.kind[j]);
                    let w = 1.0 - r * (1.0 / rc);
                    let wd = w * w;
                    let (inv_i, inv_j) = (1.0 / s.theta[i], 1.0 / s.theta[j]);
                    let gamma = sigma * sigma * 0.5 * (inv_i + inv_j) / (2.0 * kb);
                    let ev = dot(d, sub(velocity(s, i), velocity(s, j))) / r;
                    let (xi, xibar) = noise(s, i, j);
                    let random = sigma * w * xi * inv_sqrt_dt;
                    let mu = 1.0 / s.mass[i] + 1.0 / s.mass[j];
                    // the heat noise goes + into the particle of lower tag
                    let xibar = if s.tag[i] < s.tag[j] { xibar } else { -xibar };
                    Terms {
                        force: a0 * w - gamma * wd * ev + random,
                        perp: [0.0; 3],
                        energy: 0.25 * a0 * rc * wd,
                        du_mech: 0.5 * (gamma * wd * ev * ev - 0.5 * sigma * sigma * mu * wd - ev * random),
                        du_cond: kappa * (inv_i - inv_j) * wd + (2.0 * kb * kappa).sqrt() * w * xibar * inv_sqrt_dt,
                    }
                })
            }
        }
    }

    /// `fix dpd/energy`: u += h du for owned particles (uCond += h duCond).
    fn energy_half(&self, sys: &mut System, h: f64) {
        if !self.energy {
            return;
        }
        let s = &mut sys.store;
        for i in 0..s.nlocal {
            s.u_cond[i] += h * s.du_cond[i];
            s.u[i] += h * (s.du_cond[i] + s.du_mech[i]);
        }
    }

    /// The table forces added to those of [`Self::forces`]; every rank agrees whether a
    /// pair lies outside its table.
    fn table_forces(&self, sys: &mut System) -> Result<(), StepError> {
        let Some(t) = &self.tables else { return Ok(()) };
        let outcome = t.add_forces(&mut sys.store, &sys.nlist.pairs, sys.clock.step);
        sys.settle(outcome)
    }

    /// The Shardlow sweep with LAMMPS's DPDE (or isothermal) pair update.
    /// Returns the fields whose ghosts are left to the end-of-step forward: the last
    /// colour's values return to their owners but travel on only then, when nothing reads
    /// ghost momenta or energies before (the forces are conservative).
    /// Built for AVX2 where the processor has it (through [`built_sweep`]).
    fn sweep(&self, sys: &mut System, p: &ShardlowDpd) -> Fields {
        built_sweep(self, sys, p)
    }

    #[inline(always)]
    fn sweep_any(&self, sys: &mut System, p: &ShardlowDpd) -> Fields {
        let (dt, kb) = (self.settings.dt, self.kb);
        let sqrt_dt = dt.sqrt();
        let (step, normals, reach) = (sys.noise_step(sys.clock.step), Normals::get(), p.cutoff());
        let fields = Fields::MOMENTUM | Fields::ENERGY | Fields::U_COND;
        let defer = self.read_by_forces().is_empty();
        let inv_2kb = 1.0 / (2.0 * kb);
        sys.take_inverse_masses();
        let inv_m = &sys.scratch.inv_mass;
        for colour in 0..sys.sweep.colours() {
            let (pairs, displacement) = sys.sweep.within_displaced(colour, &sys.store, reach);
            // every per-particle column cut to one length: a pair checked against it once
            // reads and writes them without further bounds checks
            let s = &mut sys.store;
            let len = s.p.len();
            let (kind, tag, inv_m) = (&s.kind[..len], &s.tag[..len], &inv_m[..len]);
            let (mom, u) = (&mut s.p[..len], &mut s.u[..len]);
            let inv_tau = if p.temperature.is_none() { &s.inv_tau[..len] } else { &[] };
            let mut u_cond = (!s.u_cond.is_empty()).then(|| &mut s.u_cond[..len]);
            // the pairs' noises LANES at a time, their Philox blocks side by side (a pair
            // beyond its types' cutoff draws its numbers unused: they are counter-based)
            for (block, displaced) in pairs.chunks(LANES).zip(displacement.chunks(LANES)) {
                let last = block.len() - 1;
                let tags: [(u64, u64); LANES] = std::array::from_fn(|l| block[l.min(last)].map(|k| tag[k as usize]).into());
                let noises = normals.pairs(self.seed, step, tags, stream::PAIR);
                for ((&[i, j], &(xi, xibar)), &[dx, dy, dz, r2]) in block.iter().zip(&noises).zip(displaced) {
                    let (i, j) = (i as usize, j as usize);
                    assert!(i < len && j < len, "sweep pair outside the store");
                    let c = *p.coeff.get(kind[i], kind[j]);
                    if r2 >= c.rc * c.rc {
                        continue;
                    }
                    let r = r2.sqrt();
                    let inv_r = 1.0 / r;
                    let w = 1.0 - r * c.inv_rc;
                    let (inv_i, inv_j) = match p.temperature {
                        Some(t) => (1.0 / t, 1.0 / t),
                        None => (inv_tau[i], inv_tau[j]),
                    };
                    // friction from sigma and theta_ij; heat on 1/theta (the Original law reads
                    // `inv_tau`, here set to 1/theta as LAMMPS's dpd/fdt/energy does)
                    let drive = PairDrive {
                        e: [dx * inv_r, dy * inv_r, dz * inv_r],
                        gamma: c.sigma * c.sigma * w * w * inv_2kb,
                        kappa: if p.temperature.is_none() { c.kappa * w * w } else { 0.0 },
                        ti: Temps { theta: 0.0, inv_tau: inv_i },
                        tj: Temps { theta: 0.0, inv_tau: inv_j },
                        xi,
                        xibar,
                    };
                    let (mut p_i, mut p_j, mut u_i, mut u_j) = (mom[i], mom[j], u[i], u[j]);
                    let state = PairState { p_i: &mut p_i, p_j: &mut p_j, u_i: &mut u_i, u_j: &mut u_j, inv_m_i: inv_m[i], inv_m_j: inv_m[j] };
                    let moved = pair_update::<Original, Harmonic>(state, &drive, kb, dt, sqrt_dt);
                    (mom[i], mom[j], u[i], u[j]) = (p_i, p_j, u_i, u_j);
                    if let Some(u_cond) = u_cond.as_deref_mut() {
                        u_cond[i] += moved.heat;
                        u_cond[j] -= moved.heat;
                    }
                }
            }
            // theta (and 1/theta) stay as they are until the sweep is over
            if defer && colour + 1 == sys.sweep.colours() {
                sys.comm.reverse_colour(&mut sys.store, &sys.sweep, colour, fields);
            } else {
                sys.comm.after_colour(&mut sys.store, &sys.sweep, colour, fields);
            }
        }
        if defer {
            fields
        } else {
            Fields::NONE
        }
    }

    /// Positions, cells, ghosts, densities and forces after the particles moved; a
    /// non-finite position (`drifted`) stops the step on every rank.
    fn after_drift(&self, sys: &mut System, drifted: Result<(), StepError>) -> Result<(), StepError> {
        if self.barostat.is_some() {
            sys.settle(drifted)?;
            // the box changed: the grid is laid again for it (from the box alone, so the
            // same on every rank count) and the lists rebuilt every step
            let laid = sys.lay_grid(self.radius()).map_err(|e| StepError::global(sys.clock.step, &format!("fix nph changed the box: {e}")));
            sys.settle(laid)?;
            self.rebuild(sys, sys.clock.step + 1);
        } else {
            self.relist(sys, drifted)?;
        }
        let read = self.read_by_forces();
        if !read.is_empty() {
            sys.comm.forward(&mut sys.store, read);
        }
        self.rho(sys);
        self.forces(sys, sys.clock.step + 1);
        self.many_body_energy(sys)?;
        self.table_forces(sys)
    }

    /// Velocity Verlet under `fix nph` (after the sweep, as LAMMPS runs fix shardlow's
    /// initial_integrate before fix nph's): [`Nph::initial`] (chain, P, omega_dot, scaled
    /// momenta, half kick, remap, drift, remap), the grid and lists for the new box, the
    /// forces, then [`Nph::last`] (half kick, scaled momenta, T and P, omega_dot, chain);
    /// the state is in [`System::fixes`].
    fn barostat_step(&self, sys: &mut System, b: &Nph) -> Result<(), StepError> {
        let Some(mut st) = sys.fixes.take_barostat(&b.id) else {
            return Err(StepError::global(sys.clock.step, &format!("fix {}: the barostat has no state", b.id)));
        };
        let outcome = self.verlet(sys, Some((b, &mut st)));
        sys.fixes.set(&b.id, FixRecord::Nph(Box::new(st)));
        outcome
    }

    /// fix dpd/energy, fix nve or nph (initial_integrate), fix eos/cv (post_integrate);
    /// the forces; final_integrate, then fix eos/cv (end_of_step).
    fn verlet(&self, sys: &mut System, mut barostat: Option<(&Nph, &mut NphState)>) -> Result<(), StepError> {
        let dt = self.settings.dt;
        self.energy_half(sys, 0.5 * dt);
        let mut drifted = match &mut barostat {
            Some((b, st)) => b.initial(sys, st, dt),
            None => {
                verlet::kick(sys, 0.5 * dt);
                verlet::drift(sys, dt)
            }
        };
        if self.vv_dpde() {
            drifted = lowest(drifted, self.eos(sys));
        }
        self.after_drift(sys, drifted)?;
        self.energy_half(sys, 0.5 * dt);
        match barostat {
            Some((b, st)) => {
                let outcome = b.last(sys, st, dt);
                sys.settle(outcome)?;
            }
            None => verlet::kick(sys, 0.5 * dt),
        }
        if self.vv_dpde() {
            let state = self.eos(sys);
            sys.settle(state)?;
        }
        Ok(())
    }

    /// Whether the pair pass reads theta (velocity-Verlet DPDE).
    fn vv_dpde(&self) -> bool {
        matches!(self.force, PairForce::DpdEnergy { .. })
    }

    /// What the forces read of ghosts besides positions: the momenta when they include
    /// friction or noise, and the energies and theta of velocity-Verlet DPDE.
    fn read_by_forces(&self) -> Fields {
        let conservative = |gamma: f64, sigma: f64| gamma == 0.0 && sigma == 0.0;
        match &self.force {
            PairForce::DpdEnergy(_) => self.moved(),
            PairForce::Dpd(t) if t.iter().all(|c| conservative(c.gamma, c.sigma)) => Fields::NONE,
            PairForce::Mdpd(t) if t.iter().all(|c| conservative(c.gamma, c.sigma)) => Fields::NONE,
            PairForce::MultiLucy(_) | PairForce::Off => Fields::NONE,
            PairForce::Dpd(_) | PairForce::Mdpd(_) | PairForce::DpdExt(_) => Fields::MOMENTUM,
        }
    }

    /// What ghosts need after the particles moved: momenta, and the energies and theta
    /// of velocity-Verlet DPDE.
    fn moved(&self) -> Fields {
        if self.vv_dpde() {
            Fields::MOMENTUM | Fields::ENERGY | Fields::U_COND | Fields::THETA
        } else {
            Fields::MOMENTUM
        }
    }
}

impl Physics for ClassicDpd {
    fn settings(&self) -> &Settings {
        &self.settings
    }

    /// Lists and ghosts for the current positions. 1/theta is derived state that
    /// migration does not carry: it is re-derived from theta (owned and ghosts) here.
    fn rebuild(&self, sys: &mut System, at_step: u64) {
        let r = self.radius();
        sys.rebuild(Some(r), self.shardlow.as_ref().map(|_| r), at_step);
        let s = &mut sys.store;
        if !s.inv_tau.is_empty() {
            for (inv, theta) in s.inv_tau.iter_mut().zip(&s.theta) {
                *inv = 1.0 / theta;
            }
        }
    }

    fn cutoff(&self) -> f64 {
        let tables = self.tables.as_ref().map_or(0.0, PairTables::cutoff);
        self.force.cutoff().max(self.shardlow.as_ref().map_or(0.0, ShardlowDpd::cutoff)).max(tables)
    }

    fn setup(&self, sys: &mut System) -> Result<(), SetupError> {
        sys.lay_grid(self.radius()).map_err(SetupError::Grid)?;
        let mut fields = Fields::THETA | Fields::PAIR_ENERGY;
        if self.shardlow.as_ref().is_some_and(|s| s.temperature.is_none()) {
            fields = fields | Fields::U_COND | Fields::INV_TAU;
        }
        if self.vv_dpde() {
            fields = fields | Fields::U_COND | Fields::DU;
        }
        if matches!(self.force, PairForce::Mdpd(_) | PairForce::MultiLucy(_)) {
            fields = fields | Fields::RHO;
        }
        sys.store.enable(fields);
        self.rebuild(sys, sys.clock.step);
        if let Some(cv) = self.cv {
            // fix eos/cv: uCond = 0, uMech = C_V theta from the given dpdTheta
            let s = &mut sys.store;
            for i in 0..s.nlocal {
                if s.theta_given[i] {
                    s.u[i] = cv * s.theta[i];
                    if !s.u_cond.is_empty() {
                        s.u_cond[i] = 0.0;
                    }
                    s.theta_given[i] = false;
                }
            }
        }
        let state = self.eos(sys);
        sys.comm.forward(&mut sys.store, SWEPT | Fields::U_COND);
        self.rho(sys);
        self.forces(sys, sys.clock.step);
        sys.settle(state).map_err(SetupError::State)?;
        self.many_body_energy(sys).map_err(SetupError::State)?;
        self.table_forces(sys).map_err(SetupError::State)?;
        if let Some(b) = &self.barostat {
            let Some(mut st) = sys.fixes.take_barostat(&b.id) else {
                return Err(SetupError::Grid(format!("fix {}: the barostat has no state (define the fix after the box)", b.id)));
            };
            let outcome = b.setup(sys, &mut st, (sys.clock.run[0], sys.clock.run[1]));
            sys.fixes.set(&b.id, FixRecord::Nph(Box::new(st)));
            outcome.map_err(SetupError::Grid)?;
        }
        Ok(())
    }

    fn step(&self, sys: &mut System) -> Result<(), StepError> {
        let dt = self.settings.dt;
        // theta and 1/theta of the ghosts (and u, if fix dpd/energy moves it, and what
        // the sweep's last colour left) travel with the momenta at the end of the step, as
        // nothing between reads them
        let mut ends = self.moved();
        if let Some(p) = &self.shardlow {
            let deferred = self.sweep(sys, p);
            let outcome = self.eos(sys);
            sys.settle(outcome)?;
            ends = ends | deferred | Fields::THETA | Fields::INV_TAU;
            if self.energy {
                ends = ends | Fields::ENERGY | Fields::U_COND;
            }
        }
        match (self.integration, &self.barostat) {
            (Integration::Nve, Some(b)) => self.barostat_step(sys, b)?,
            (Integration::Nve, None) => self.verlet(sys, None)?,
            (Integration::Mvv { lambda }, _) => {
                // fix mvv/dpd: the estimate v + lambda dt f/m is what the dissipative force reads
                let drifted = verlet::mvv_first_half(sys, dt, lambda, |_, _| {});
                self.after_drift(sys, drifted)?;
                verlet::mvv_second_half(sys, dt, |_, _| {});
            }
        }
        sys.comm.forward(&mut sys.store, ends);
        Ok(())
    }
}

avx2_fn! {
    /// [`ClassicDpd::sweep`] as a function of its own, built for AVX2 where the processor
    /// has it ([`crate::simd`]).
    fn built_sweep(dpd: &ClassicDpd, sys: &mut System, p: &ShardlowDpd) -> Fields {
        dpd.sweep_any(sys, p)
    }
}

avx2_fn! {
    /// [`ClassicDpd::forces`] likewise.
    fn built_forces(dpd: &ClassicDpd, sys: &mut System, step: u64) {
        dpd.forces_any(sys, step)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fluctuation-dissipation constructors give the bits of sqrt(2 k_B T gamma) and
    /// sigma^2 / (2 k_B T) written out, and recover each other.
    #[test]
    fn isothermal_coefficients_follow_the_fluctuation_dissipation_relation() {
        for (kb, t, gamma, sigma) in [(1.0, 1.0, 4.5, 3.0), (1.380649e-23, 300.0, 0.7, 1.3e-10), (0.0019872, 1.7, 12.0, 0.2)] {
            let d = DpdCoeff::isothermal(25.0, 1.0, gamma, kb, t);
            assert_eq!(d.sigma.to_bits(), (2.0 * kb * t * gamma).sqrt().to_bits());
            assert_eq!((d.a0, d.rc, d.gamma), (25.0, 1.0, gamma));
            let f = DpdCoeff::from_sigma(25.0, 1.0, sigma, kb, t);
            assert_eq!(f.gamma.to_bits(), (sigma * sigma / (2.0 * kb * t)).to_bits());
            assert_eq!(f.sigma, sigma);
            let back = DpdCoeff::isothermal(25.0, 1.0, f.gamma, kb, t).sigma;
            assert!((back - sigma).abs() <= 1e-15 * sigma, "{back} {sigma}");
            let m = MdpdCoeff::isothermal(-40.0, 25.0, 1.0, 0.75, gamma, kb, t, Lucy::new(0.75));
            assert_eq!(m.sigma.to_bits(), d.sigma.to_bits());
            assert_eq!((m.a, m.b, m.rc, m.rd, m.gamma), (-40.0, 25.0, 1.0, 0.75, gamma));
        }
    }
}
