//! Thermal SDPD: the GENERIC SPH model of Serrano and Espanol (Sec VII; docs/models/sdpd.md).
//! Particles of constant mass with volume 1/d_mu from the kernel density
//! (eqs 92-93; the density pass of GenDPDE, W = w/[w], plus the self term W(0)) or the
//! normalised volume of eq 97;
//! the reversible part is eq 96 (GenDPDE's many-body force at fixed entropy) or eq 99,
//! the irreversible part eq 82 with the SPH Omega_{mu nu} = dV_nu/dR_mu of eq 94 (shear
//! and bulk viscosity, heat conduction) and the noise of eqs 76-80 with k_B a parameter.
//!
//! The internal energy u is the state variable. In energy form the irreversible step is
//! (derivation in docs/models/sdpd.md), with L_mu = sum_nu Omega_{nu mu} v_nu^T
//! = d_mu^-2 sum_nu omega_{mu nu} (v_nu - v_mu)^T and omega_{mu nu} = W'(r) e_{mu nu}:
//!
//! dsigma_mu = -[2 eta/V (L_mu)^S0 + zeta/V tr L_mu 1] dt + dsigma~_mu   (eqs 60, 77-78)
//! dP_mu = sum_nu Omega_{mu nu} . dsigma_nu = -sum_nu omega_{mu nu} . (dsigma_nu/d_nu^2 + dsigma_mu/d_mu^2)
//! du_mu = -dsigma_mu : L_mu(v + dP/2M)     (viscous heating, its noise and the
//!                                            k_B T/m Ito drift of eq 82, exactly)
//! X_mu = (kappa T^2/V) sum_lambda Omega_{lambda mu}/tau_lambda dt + T (2 k_B kappa/V)^1/2 dV_mu
//!        + 2 k_B kappa T/(C V) Omega_{mu mu} dt,      1/tau = (1 - k_B/C)/T  (eq 83)
//! du_mu += sum_nu Omega_{mu nu} . X_nu
//!
//! Both increments are pairwise antisymmetric, so total momentum and energy are conserved
//! to round-off by the irreversible step; the reversible velocity-Verlet step at fixed
//! entropy conserves energy to O(dt^2).

use crate::error::{lowest, StepError};
use crate::passes::many_body::{self, velocity};
use crate::rng::Normals;
use crate::settings::Settings;
use crate::passes::species::Species;
use crate::system::System;
use crate::passes::{isentropic, verlet};
use crate::{FixedEntropy, Physics, SetupError};
use gendpde_engine::{exact_sums, sub, Fields, Vec3};
use gendpde_potentials::{Eos, Weight};
use std::cell::RefCell;

/// Transport coefficients and fluctuation strength of `pair sdpd/generic`.
#[derive(Clone, Debug, PartialEq)]
pub struct SdpdParams {
    /// Shear viscosity eta, bulk viscosity zeta, thermal conductivity kappa (eq 78).
    pub eta: f64,
    pub zeta: f64,
    pub kappa: f64,
    /// Boltzmann's constant of the fluctuations (0: deterministic SPH).
    pub kb: f64,
    pub seed: u64,
    /// The normalised volume of eq 97 and the remnant-free force of eq 99.
    pub normalized: bool,
}

/// The thermal SDPD dynamics with EOS `E` and kernel `W`.
pub struct Sdpd<E: Eos, W: Weight> {
    pub eos: Species<E>,
    pub weight: W,
    pub params: SdpdParams,
    pub settings: Settings,
    scratch: RefCell<Scratch>,
}

/// Per-step work arrays (owned particles; `inv_tau` owned and ghosts).
#[derive(Default)]
struct Scratch {
    /// L_mu (row-major 3x3).
    grad: Vec<[f64; 9]>,
    dp: Vec<Vec3>,
    /// sum_lambda Omega_{lambda mu}/tau_lambda d_mu^2 and -Omega_{mu mu} d_mu^2.
    a: Vec<Vec3>,
    b: Vec<Vec3>,
    inv_tau: Vec<f64>,
    /// V_T / sum_k d_k^-1 (eq 97), 1 for the plain volume.
    alpha: f64,
}

/// Philox streams of a particle's normals in a step: 0-4 the random stress (9 used),
/// 5-6 the random heat flux (3 used).
const HEAT_STREAMS: [u32; 2] = [5, 6];

impl<E: FixedEntropy, W: Weight> Sdpd<E, W> {
    pub fn new(eos: Species<E>, weight: W, params: SdpdParams, settings: Settings) -> Self {
        Self { eos, weight, params, settings, scratch: RefCell::new(Scratch { alpha: 1.0, ..Scratch::default() }) }
    }

    /// Kernel density d_mu of particle i (the EOS reads 1/V = d/alpha); never below
    /// W(0) > 0, so no particle is isolated.
    #[inline(always)]
    fn d(alpha: f64, sys: &System, i: usize) -> f64 {
        alpha * sys.store.n[i]
    }

    /// Density pass with the self term W(0) of eq 92 (GenDPDE's n_i has none), then the
    /// normalised volume (eq 97): n = 1/V = d/alpha.
    fn density(&self, sys: &mut System) {
        many_body::density(&self.weight, None, sys);
        let nl = sys.store.nlocal;
        let w0 = self.weight.eval(0.0).0;
        for n in &mut sys.store.n[..nl] {
            *n += w0;
        }
        if self.params.normalized {
            let [inv_d] = exact_sums(sys.comm.transport(), sys.store.n[..nl].iter().map(|&d| [1.0 / d]));
            let alpha = sys.domain.volume() / inv_d;
            self.scratch.borrow_mut().alpha = alpha;
            for n in &mut sys.store.n[..nl] {
                *n /= alpha;
            }
        }
    }

    /// The particle states and forces after [`Self::density`]; with `held`, u at the
    /// entropies [`isentropic::hold`] kept first.
    fn conservative(&self, sys: &mut System, held: bool) -> Result<(), StepError> {
        let released = if held { isentropic::release(&self.eos, sys) } else { Ok(()) };
        let state = self.forces(sys);
        lowest(released, state)
    }

    /// theta and pi/n^2 from (u, n), forwarded, and the forces: eq 96, or with the
    /// normalised volume eq 99, F_mu = -sum_nu [q_mu + q_nu] omega_{mu nu} with
    /// q = (P - Pbar) V/d and Pbar of eq 100 (one more exact all-reduce).
    fn forces(&self, sys: &mut System) -> Result<(), StepError> {
        let state = many_body::refresh_state(&self.eos, sys);
        if self.params.normalized {
            let alpha = self.scratch.borrow().alpha;
            let s = &mut sys.store;
            let nl = s.nlocal;
            // V P = pi/n^2 * n with n = 1/V
            let [vp] = exact_sums(sys.comm.transport(), (0..nl).map(|i| [s.pn2[i] * s.n[i]]));
            let pbar = vp / sys.domain.volume();
            for i in 0..nl {
                let n = s.n[i];
                s.pn2[i] = (s.pn2[i] * n * n - pbar) / (alpha * n * n);
            }
        }
        sys.comm.forward(&mut sys.store, Fields::DENSITY | Fields::PRESSURE | Fields::THETA);
        many_body::forces(sys);
        state
    }

    /// L_mu = d_mu^-2 sum_nu omega_{mu nu} (v_nu - v_mu)^T of owned particles: each pair
    /// adds the same term to both (omega and v_nu - v_mu both change sign).
    fn gradients(&self, sys: &mut System, sc: &mut Scratch) {
        let nl = sys.store.nlocal;
        fill_velocities(sys);
        let (v, s) = (&sys.scratch.velocity, &sys.store);
        sc.grad.clear();
        sc.grad.resize(nl, [0.0; 9]);
        for (i, j, w) in omegas(&sys.scratch.active, &sys.scratch.pair_geometry, &s.r) {
            let dv = sub(v[j], v[i]);
            for o in [i, j].into_iter().filter(|&o| o < nl) {
                for a in 0..3 {
                    for b in 0..3 {
                        sc.grad[o][3 * a + b] += w[a] * dv[b];
                    }
                }
            }
        }
        for i in 0..nl {
            let d = Self::d(sc.alpha, sys, i);
            let inv = 1.0 / (d * d);
            sc.grad[i].iter_mut().for_each(|x| *x *= inv);
        }
    }

    /// The viscous part: stress increments, the momentum update and the heat that keeps
    /// K + U exact (midpoint velocities).
    fn viscous(&self, sys: &mut System, sc: &mut Scratch) {
        let (dt, p) = (self.settings.dt, &self.params);
        let (normals, key) = (Normals::get(), sys.noise_step(sys.clock.step));
        self.gradients(sys, sc);
        let nl = sys.store.nlocal;
        for i in 0..nl {
            let vol = 1.0 / sys.store.n[i];
            let l = sc.grad[i];
            let tr = l[0] + l[4] + l[8];
            let (ce, cz) = (2.0 * p.eta / vol, p.zeta / vol);
            let mut sig = stress(&l, |sym, diag| -dt * (ce * sym + if diag { cz * tr - ce * tr / 3.0 } else { 0.0 }));
            if p.kb > 0.0 {
                let t = sys.store.theta[i];
                let a = (4.0 * p.kb * t * p.eta / vol * dt).sqrt();
                let b = (6.0 * p.kb * t * p.zeta / vol * dt).sqrt();
                let tag = sys.store.tag[i];
                let mut draws = [0.0; 10];
                for c in 0..5 {
                    (draws[2 * c], draws[2 * c + 1]) = normals.pair(p.seed, key, tag, 0, c as u32);
                }
                let w: [f64; 9] = std::array::from_fn(|k| draws[k]);
                let trw = w[0] + w[4] + w[8];
                let noise = stress(&w, |sym, diag| a * sym + if diag { (b - a) * trw / 3.0 } else { 0.0 });
                for c in 0..6 {
                    sig[c] += noise[c];
                }
            }
            sys.store.sdpd_stress[i] = [sig[0], sig[1], sig[2]];
            sys.store.sdpd_shear[i] = [sig[3], sig[4], sig[5]];
        }
        sys.comm.forward(&mut sys.store, Fields::SDPD_STRESS);
        sc.dp.clear();
        sc.dp.resize(nl, [0.0; 3]);
        {
            let s = &sys.store;
            for (i, j, w) in omegas(&sys.scratch.active, &sys.scratch.pair_geometry, &s.r) {
                let (di, dj) = (Self::d(sc.alpha, sys, i), Self::d(sc.alpha, sys, j));
                let (mi, mj) = (tensor(s.sdpd_stress[i], s.sdpd_shear[i]), tensor(s.sdpd_stress[j], s.sdpd_shear[j]));
                let mut t = [0.0; 3];
                for b in 0..3 {
                    for a in 0..3 {
                        t[b] -= w[a] * (mi[3 * a + b] / (di * di) + mj[3 * a + b] / (dj * dj));
                    }
                }
                many_body::kick(&mut sc.dp[..nl], i, j, 1.0, t);
            }
        }
        self.half_kick(sys, sc);
        self.gradients(sys, sc);
        let s = &mut sys.store;
        for i in 0..nl {
            let sig = tensor(s.sdpd_stress[i], s.sdpd_shear[i]);
            let work: f64 = sig.iter().zip(&sc.grad[i]).map(|(x, y)| x * y).sum();
            s.u[i] -= work;
        }
        self.half_kick(sys, sc);
    }

    /// p += dP/2 for owned particles, forwarded to the ghosts.
    fn half_kick(&self, sys: &mut System, sc: &Scratch) {
        let s = &mut sys.store;
        for i in 0..s.nlocal {
            for c in 0..3 {
                s.p[i][c] += 0.5 * sc.dp[i][c];
            }
        }
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM);
    }

    /// Heat conduction with its noise and Ito drift (eqs 82-83 in energy form).
    fn conduction(&self, sys: &mut System, sc: &mut Scratch) {
        let (dt, p) = (self.settings.dt, &self.params);
        let (normals, key) = (Normals::get(), sys.noise_step(sys.clock.step));
        let nl = sys.store.nlocal;
        {
            let s = &sys.store;
            sc.inv_tau.clear();
            sc.inv_tau.extend((0..s.len()).map(|i| {
                let (t, n) = (s.theta[i], s.n[i]);
                (1.0 - p.kb / self.eos.of(s.kind[i]).cv(t, n)) / t
            }));
            sc.a.clear();
            sc.a.resize(nl, [0.0; 3]);
            sc.b.clear();
            sc.b.resize(nl, [0.0; 3]);
            for (i, j, w) in omegas(&sys.scratch.active, &sys.scratch.pair_geometry, &s.r) {
                let dt_inv = sc.inv_tau[j] - sc.inv_tau[i];
                for o in [i, j].into_iter().filter(|&o| o < nl) {
                    for c in 0..3 {
                        sc.a[o][c] += w[c] * dt_inv;
                    }
                }
                many_body::kick(&mut sc.b[..nl], i, j, 1.0, w);
            }
        }
        for i in 0..nl {
            let s = &sys.store;
            let d = Self::d(sc.alpha, sys, i);
            let (t, n) = (s.theta[i], s.n[i]);
            let (vol, cv) = (1.0 / n, self.eos.of(s.kind[i]).cv(t, n));
            let cj = p.kappa * t * t / vol * dt / (d * d);
            let cself = -2.0 * p.kb * p.kappa * t / (cv * vol) * dt / (d * d);
            let mut x = [0.0; 3];
            for c in 0..3 {
                x[c] = cj * sc.a[i][c] + cself * sc.b[i][c];
            }
            if p.kb > 0.0 {
                let amp = t * (2.0 * p.kb * p.kappa / vol * dt).sqrt();
                let (x0, x1) = normals.pair(p.seed, key, s.tag[i], 0, HEAT_STREAMS[0]);
                let (x2, _) = normals.pair(p.seed, key, s.tag[i], 0, HEAT_STREAMS[1]);
                for (c, xi) in [x0, x1, x2].into_iter().enumerate() {
                    x[c] += amp * xi;
                }
            }
            sys.store.sdpd_flux[i] = x;
        }
        sys.comm.forward(&mut sys.store, Fields::SDPD_FLUX);
        let s = &mut sys.store;
        let sums = &mut sys.scratch.pair_sums;
        sums.clear();
        sums.resize(nl, 0.0);
        for (i, j, w) in omegas(&sys.scratch.active, &sys.scratch.pair_geometry, &s.r) {
            let (di, dj) = (sc.alpha * s.n[i], sc.alpha * s.n[j]);
            let du: f64 = (0..3).map(|c| -w[c] * (s.sdpd_flux[i][c] / (di * di) + s.sdpd_flux[j][c] / (dj * dj))).sum();
            if i < nl {
                sums[i] += du;
            }
            if j < nl {
                sums[j] -= du;
            }
        }
        for i in 0..nl {
            s.u[i] += sums[i];
        }
    }

    /// The irreversible step at fixed positions, then the state and forces it leaves.
    fn irreversible(&self, sys: &mut System) -> Result<(), StepError> {
        let mut sc = self.scratch.borrow_mut();
        let p = &self.params;
        let mut outcome = Ok(());
        if p.eta > 0.0 || p.zeta > 0.0 {
            self.viscous(sys, &mut sc);
            outcome = many_body::refresh_state(&self.eos, sys);
            sys.comm.forward(&mut sys.store, Fields::THETA);
        }
        if p.kappa > 0.0 {
            self.conduction(sys, &mut sc);
        }
        drop(sc);
        lowest(outcome, self.forces(sys))
    }
}

/// (i, j, omega_ij = W'(r_ij) e_ij) for the pairs within the kernel support (from the
/// g = w'/([w] r) the density pass kept).
#[inline(always)]
fn omegas<'a>(active: &'a [[u32; 2]], geometry: &'a [f64], r: &'a [Vec3]) -> impl Iterator<Item = (usize, usize, Vec3)> + 'a {
    active.iter().zip(geometry).filter_map(move |(&[i, j], &g)| {
        let (i, j) = (i as usize, j as usize);
        (g != 0.0).then(|| (i, j, sub(r[i], r[j]).map(|x| g * x)))
    })
}

/// The symmetric 3x3 built from m: `f(sym_ab, diagonal)` per component, in the order
/// xx, yy, zz, xy, xz, yz.
#[inline(always)]
fn stress(m: &[f64; 9], f: impl Fn(f64, bool) -> f64) -> [f64; 6] {
    let sym = |a: usize, b: usize| 0.5 * (m[3 * a + b] + m[3 * b + a]);
    [f(sym(0, 0), true), f(sym(1, 1), true), f(sym(2, 2), true), f(sym(0, 1), false), f(sym(0, 2), false), f(sym(1, 2), false)]
}

/// The full 3x3 of a symmetric tensor stored as diagonal and (xy, xz, yz).
#[inline(always)]
fn tensor(d: Vec3, o: Vec3) -> [f64; 9] {
    [d[0], o[0], o[1], o[0], d[1], o[2], o[1], o[2], d[2]]
}

/// Velocities of owned and ghost particles into the system's scratch.
fn fill_velocities(sys: &mut System) {
    let s = &sys.store;
    sys.scratch.velocity.clear();
    sys.scratch.velocity.extend((0..s.len()).map(|i| velocity(s, i)));
}

impl<E: FixedEntropy, W: Weight> Physics for Sdpd<E, W> {
    fn settings(&self) -> &Settings {
        &self.settings
    }

    fn cutoff(&self) -> f64 {
        self.weight.cutoff()
    }

    fn setup(&self, sys: &mut System) -> Result<(), SetupError> {
        let max_kind = sys.store.kind[..sys.store.nlocal].iter().copied().max().unwrap_or(1);
        let max_kind = sys.comm.max(max_kind as f64) as u32;
        if !self.eos.covers(max_kind) {
            return Err(SetupError::Types(format!("the EOS fix gives fewer heat capacities than particle types ({max_kind})")));
        }
        sys.lay_grid(self.list_radius()).map_err(SetupError::Grid)?;
        sys.store.enable(Fields::THETA | Fields::DENSITY | Fields::PRESSURE | Fields::SDPD_STRESS | Fields::SDPD_FLUX);
        self.rebuild(sys, sys.clock.step);
        self.density(sys);
        many_body::resolve_theta(&self.eos, sys);
        let state = self.conservative(sys, false);
        sys.settle(state).map_err(SetupError::State)
    }

    /// Velocity Verlet at fixed entropy (eq 96 or 99; the forces of the last step are
    /// those of its final state), then the irreversible step (eq 82) at the new positions.
    fn step(&self, sys: &mut System) -> Result<(), StepError> {
        let dt = self.settings.dt;
        verlet::kick(sys, 0.5 * dt);
        let drifted = verlet::drift(sys, dt);
        sys.settle(drifted)?;
        let held = isentropic::hold(&self.eos, sys);
        self.relist(sys, held)?;
        self.density(sys);
        let state = self.conservative(sys, true);
        verlet::kick(sys, 0.5 * dt);
        sys.comm.forward(&mut sys.store, Fields::MOMENTUM);
        sys.settle(state)?;
        let outcome = self.irreversible(sys);
        sys.settle(outcome)?;
        Ok(())
    }
}
