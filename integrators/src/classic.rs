//! LAMMPS's pairwise DPD styles, with LAMMPS's semantics, for users who compare with it:
//! `pair dpd` (isothermal DPD, friction and noise in the force), `pair dpd/fdt` and
//! `dpd/fdt/energy` (conservative force only; friction, noise and heat in `fix shardlow`,
//! theta from `fix eos/cv`), and many-body DPD (`pair mdpd/rhosum` + `mdpd`, integrated
//! by `fix mvv/dpd`). As in LAMMPS the sweep runs at the start of the step and theta is
//! not refreshed between pairs (it follows the sweep through eos/cv).
//!
//! Formulas (LAMMPS documentation and sources): w = 1 - r/rc;
//! dpd: F = [a0 w - gamma w^2 (e.v) + sigma w xi / sqrt(dt)] e, sigma = sqrt(2 k_B T gamma);
//! mdpd: F = [A w_c + B (rho_i + rho_j) w_d - gamma w_c^2 (e.v) + sigma w_c xi / sqrt(dt)] e
//! with rho_i = sum_j m_j W_Lucy(r_ij; h); pair energy a0 rc w^2 / 2 (dpd).
//! Shardlow DPDE pair update: gamma = sigma^2 / (2 k_B theta_ij), 1/theta_ij the mean of
//! 1/theta_i and 1/theta_j; heat kappa w^2 (1/theta_i - 1/theta_j) dt + sqrt(2 k_B kappa)
//! w xibar sqrt(dt) into i (uCond); -dK/2 into each u (uMech).

use crate::error::{lowest, StepError};
use crate::heat::{Original, Temps};
use crate::pair_update::{pair_update, PairDrive, PairState};
use crate::physics::{Physics, SetupError};
use crate::rng::{normal_pair, stream, Normals};
use crate::settings::Settings;
use crate::sweep::SWEPT;
use crate::system::System;
use crate::tables::PairTables;
use crate::verlet;
use gendpde_engine::{dot, sub, Fields, Particles, Vec3};
use gendpde_potentials::{Lucy, Weight};

/// The pair force computed in the force pass.
#[derive(Clone, Debug, PartialEq)]
pub enum PairForce {
    /// a0 w(rc) with in-force friction `gamma` and noise `sigma` (both 0 under Shardlow).
    Dpd { a0: f64, rc: f64, gamma: f64, sigma: f64 },
    /// Warren's many-body DPD; rho from the Lucy kernel of support `h`.
    Mdpd { a: f64, b: f64, rc: f64, rd: f64, gamma: f64, sigma: f64, h: f64 },
    /// No pairwise DPD force: the tables alone (`pair_style table`).
    Off,
}

impl PairForce {
    fn cutoff(&self) -> f64 {
        match self {
            Self::Dpd { rc, .. } => *rc,
            Self::Mdpd { rc, rd, h, .. } => rc.max(*rd).max(*h),
            Self::Off => 0.0,
        }
    }
}

/// `fix shardlow` with `pair dpd/fdt` (fixed T) or `dpd/fdt/energy` (per-particle theta).
#[derive(Clone, Debug, PartialEq)]
pub struct ShardlowDpd {
    pub sigma: f64,
    pub kappa: f64,
    pub rc: f64,
    /// `dpd/fdt`: the temperature of the friction; None: theta of the particles.
    pub temperature: Option<f64>,
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
    pub kb: f64,
    pub seed: u64,
    pub settings: Settings,
}

impl ClassicDpd {
    fn radius(&self) -> f64 {
        let tables = self.tables.as_ref().map_or(0.0, PairTables::cutoff);
        self.force.cutoff().max(self.shardlow.as_ref().map_or(0.0, |s| s.rc)).max(tables) + self.settings.skin
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
                    outcome = lowest(outcome, Err(StepError::eos(s, i, sys.step, e)));
                }
                s.theta[i] = theta;
            }
            if !s.inv_tau.is_empty() {
                s.inv_tau[i] = 1.0 / s.theta[i];
            }
        }
        outcome
    }

    /// MDPD density: rho_i = sum_{j != i} m_j W(r_ij), without a self term, as the
    /// reference LAMMPS (22 Jul 2025) sums it. One pass over the half list (see
    /// [`gendpde_engine::NeighborList::pairs`]).
    fn rho(&self, sys: &mut System, h: f64) {
        let w = Lucy::new(h);
        let s = &mut sys.store;
        let n = s.nlocal;
        s.rho[..n].fill(0.0);
        for &[i, j] in &sys.nlist.pairs {
            let (i, j) = (i as usize, j as usize);
            let d = sub(s.r[i], s.r[j]);
            let r2 = dot(d, d);
            if r2 < h * h {
                let wij = w.eval(r2.sqrt()).0;
                if i < n {
                    s.rho[i] += s.mass[j] * wij;
                }
                if j < n {
                    s.rho[j] += s.mass[i] * wij;
                }
            }
        }
    }

    /// Pair forces at the current positions and velocities; the noise of step `step`.
    fn forces(&self, sys: &mut System, step: u64) {
        let inv_sqrt_dt = 1.0 / self.settings.dt.sqrt();
        let (seed, pairs, s) = (self.seed, &sys.nlist.pairs, &mut sys.store);
        let inv_rc = match self.force {
            PairForce::Dpd { rc, .. } | PairForce::Mdpd { rc, .. } => 1.0 / rc,
            PairForce::Off => 0.0,
        };
        let noise = |s: &Particles, i: usize, j: usize| normal_pair(seed, step, s.tag[i].min(s.tag[j]), s.tag[i].max(s.tag[j]), stream::FORCE).0;
        match self.force {
            // w = 0 beyond rc: no branch to mispredict on the skin's pairs
            PairForce::Dpd { a0, rc, gamma: 0.0, sigma: 0.0 } => tally::<true>(s, pairs, rc, |_, _, _, _, r| {
                let w = (1.0 - r * inv_rc).max(0.0);
                (a0 * w, 0.25 * a0 * rc * w * w)
            }),
            PairForce::Dpd { a0, rc, gamma, sigma } => tally::<false>(s, pairs, rc, |s, i, j, d, r| {
                let w = 1.0 - r * inv_rc;
                let fp = a0 * w - gamma * w * w * dot(d, sub(velocity(s, i), velocity(s, j))) / r + sigma * w * noise(s, i, j) * inv_sqrt_dt;
                (fp, 0.25 * a0 * rc * w * w)
            }),
            PairForce::Mdpd { a, b, rc, rd, gamma, sigma, .. } => tally::<false>(s, pairs, rc, |s, i, j, d, r| {
                let wc = 1.0 - r * inv_rc;
                let wd = (1.0 - r / rd).max(0.0);
                let rho = s.rho[i] + s.rho[j];
                let mut fp = a * wc + b * rho * wd;
                if gamma > 0.0 || sigma > 0.0 {
                    fp += -gamma * wc * wc * dot(d, sub(velocity(s, i), velocity(s, j))) / r + sigma * wc * noise(s, i, j) * inv_sqrt_dt;
                }
                (fp, 0.25 * (a * rc * wc * wc + b * rd * rho * wd * wd))
            }),
            PairForce::Off => tally::<false>(s, &[], 0.0, |_, _, _, _, _| (0.0, 0.0)),
        }
    }

    /// The table forces added to those of [`Self::forces`]; every rank agrees whether a
    /// pair lies outside its table.
    fn table_forces(&self, sys: &mut System) -> Result<(), StepError> {
        let Some(t) = &self.tables else { return Ok(()) };
        let outcome = t.add_forces(&mut sys.store, &sys.nlist.pairs, sys.step);
        sys.settle(outcome)
    }

    /// The Shardlow sweep with LAMMPS's DPDE (or isothermal) pair update.
    fn sweep(&self, sys: &mut System, p: &ShardlowDpd) {
        let (dt, kb) = (self.settings.dt, self.kb);
        let sqrt_dt = dt.sqrt();
        let (step, normals, inv_rc) = (sys.step, Normals::get(), 1.0 / p.rc);
        for colour in 0..8 {
            let pairs = sys.sweep.within(colour, &sys.store, p.rc);
            let s = &mut sys.store;
            for &[i, j] in pairs {
                let (i, j) = (i as usize, j as usize);
                let dr = sub(s.r[i], s.r[j]);
                let r = dot(dr, dr).sqrt();
                let inv_r = 1.0 / r;
                let w = 1.0 - r * inv_rc;
                let (theta_ij, inv_i, inv_j) = match p.temperature {
                    Some(t) => (t, 0.0, 0.0),
                    None => (2.0 / (s.inv_tau[i] + s.inv_tau[j]), s.inv_tau[i], s.inv_tau[j]),
                };
                let (xi, xibar) = normals.pair(self.seed, step, s.tag[i], s.tag[j], stream::PAIR);
                // friction from sigma and theta_ij; heat on 1/theta (the Original law reads
                // `inv_tau`, here set to 1/theta as LAMMPS's dpd/fdt/energy does)
                let drive = PairDrive {
                    e: [dr[0] * inv_r, dr[1] * inv_r, dr[2] * inv_r],
                    gamma: p.sigma * p.sigma * w * w / (2.0 * kb * theta_ij),
                    kappa: if p.temperature.is_none() { p.kappa * w * w } else { 0.0 },
                    ti: Temps { theta: theta_ij, inv_tau: inv_i },
                    tj: Temps { theta: theta_ij, inv_tau: inv_j },
                    xi,
                    xibar,
                };
                let (mut p_i, mut p_j, mut u_i, mut u_j) = (s.p[i], s.p[j], s.u[i], s.u[j]);
                let state = PairState { p_i: &mut p_i, p_j: &mut p_j, u_i: &mut u_i, u_j: &mut u_j, inv_m_i: 1.0 / s.mass[i], inv_m_j: 1.0 / s.mass[j] };
                let moved = pair_update::<Original>(state, &drive, kb, dt, sqrt_dt);
                (s.p[i], s.p[j], s.u[i], s.u[j]) = (p_i, p_j, u_i, u_j);
                if !s.u_cond.is_empty() {
                    s.u_cond[i] += moved.heat;
                    s.u_cond[j] -= moved.heat;
                }
            }
            // theta (and 1/theta) stay as they are until the sweep is over
            let fields = Fields::MOMENTUM | Fields::ENERGY | Fields::U_COND;
            sys.comm.reverse(&mut sys.store, &sys.sweep.ghost_writes[colour], fields);
            sys.comm.forward(&mut sys.store, fields);
        }
    }

    /// Positions, cells, ghosts, densities and forces after the particles moved; a
    /// non-finite position (`drifted`) stops the step on every rank.
    fn after_drift(&self, sys: &mut System, drifted: Result<(), StepError>) -> Result<(), StepError> {
        sys.settle(drifted)?;
        self.relist(sys);
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM);
        if let PairForce::Mdpd { h, .. } = self.force {
            self.rho(sys, h);
            sys.comm.forward(&mut sys.store, Fields::RHO);
        }
        self.forces(sys, sys.step + 1);
        self.table_forces(sys)
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

    fn list_radius(&self) -> f64 {
        self.radius()
    }

    fn setup(&self, sys: &mut System) -> Result<(), SetupError> {
        sys.lay_grid(self.radius()).map_err(SetupError::Grid)?;
        let mut fields = Fields::THETA | Fields::PAIR_ENERGY;
        if self.shardlow.as_ref().is_some_and(|s| s.temperature.is_none()) {
            fields = fields | Fields::U_COND | Fields::INV_TAU;
        }
        if matches!(self.force, PairForce::Mdpd { .. }) {
            fields = fields | Fields::RHO;
        }
        sys.store.enable(fields);
        self.rebuild(sys, sys.step);
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
        if let PairForce::Mdpd { h, .. } = self.force {
            self.rho(sys, h);
            sys.comm.forward(&mut sys.store, Fields::RHO);
        }
        self.forces(sys, sys.step);
        sys.settle(state).map_err(SetupError::State)?;
        self.table_forces(sys).map_err(SetupError::State)
    }

    fn step(&self, sys: &mut System) -> Result<(), StepError> {
        let dt = self.settings.dt;
        if let Some(p) = &self.shardlow {
            self.sweep(sys, p);
            let outcome = self.eos(sys);
            sys.comm.forward(&mut sys.store, SWEPT);
            sys.settle(outcome)?;
        }
        match self.integration {
            Integration::Nve => {
                verlet::kick(sys, 0.5 * dt);
                let drifted = verlet::drift(sys, dt);
                self.after_drift(sys, drifted)?;
                verlet::kick(sys, 0.5 * dt);
            }
            Integration::Mvv { lambda } => {
                // vest = v + dt/2 f/m; r += dt vest; v += lambda dt f/m (the estimate the
                // dissipative force reads); after the forces: v = vest + dt/2 f/m
                // (vest travels with a particle that changes rank)
                let s = &mut sys.store;
                for i in 0..s.nlocal {
                    for c in 0..3 {
                        s.vest[i][c] = s.p[i][c] + 0.5 * dt * s.f[i][c];
                        s.r[i][c] += dt * s.vest[i][c] / s.mass[i];
                        s.p[i][c] += lambda * dt * s.f[i][c];
                    }
                }
                self.after_drift(sys, verlet::finite_positions(sys))?;
                let s = &mut sys.store;
                for i in 0..s.nlocal {
                    for c in 0..3 {
                        s.p[i][c] = s.vest[i][c] + 0.5 * dt * s.f[i][c];
                    }
                }
            }
        }
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM);
        sys.step += 1;
        sys.time += dt;
        Ok(())
    }
}

#[inline(always)]
fn velocity(s: &gendpde_engine::Particles, i: usize) -> [f64; 3] {
    let k = 1.0 / s.mass[i];
    [s.p[i][0] * k, s.p[i][1] * k, s.p[i][2] * k]
}

/// Sums pair forces, energies and virials over the half list into the owned particles
/// (see [`gendpde_engine::NeighborList::pairs`]). `pair(s, i, j, r_ij, r)` gives the
/// scalar force F (f_ij = F e_ij) and the pair energy of a pair closer than `rc`; with
/// `CLAMPED` it is called for every pair of the list and must give zeros beyond `rc`.
#[inline(always)]
fn tally<const CLAMPED: bool>(s: &mut Particles, pairs: &[[u32; 2]], rc: f64, pair: impl Fn(&Particles, usize, usize, Vec3, f64) -> (f64, f64)) {
    let n = s.nlocal;
    s.f[..n].fill([0.0; 3]);
    s.epair[..n].fill(0.0);
    s.virial[..n].fill([0.0; 3]);
    for &[i, j] in pairs {
        let (i, j) = (i as usize, j as usize);
        let d = sub(s.r[i], s.r[j]);
        let r2 = dot(d, d);
        if (!CLAMPED && r2 >= rc * rc) || r2 < 1e-20 {
            continue;
        }
        let r = r2.sqrt();
        let inv_r = 1.0 / r;
        let (fp, e) = pair(s, i, j, d, r);
        let fpair = fp * inv_r;
        let df = [fpair * d[0], fpair * d[1], fpair * d[2]];
        let virial = [0.5 * df[0] * d[0], 0.5 * df[1] * d[1], 0.5 * df[2] * d[2]];
        for (k, sign) in [(i, 1.0), (j, -1.0)] {
            if k < n {
                for c in 0..3 {
                    s.f[k][c] += sign * df[c];
                    s.virial[k][c] += virial[c];
                }
                s.epair[k] += e;
            }
        }
    }
}
