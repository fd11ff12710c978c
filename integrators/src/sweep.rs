//! The Shardlow sweep (eq 82): every pair within the cutoff in colour order, theta
//! (and 1/tau) of i and j refreshed from the EOS after each pair; then the reservoir.
//!
//! Between colours the ghosts written in the colour return their values to their
//! owners, and the owners forward the new values to all ghosts (ARCHITECTURE.md).
//!
//! theta -> 0: a pair update that would leave a particle temperature non-positive (or
//! non-finite) is undone and redone as two half steps whose noises split the step's
//! Wiener increments by a Brownian bridge (dW_1,2 = dW/2 +- sqrt(dt)/2 eta, eta a fresh
//! counter-based normal), recursively up to `Dissipation::substeps` levels. Each split
//! conserves momentum and energy like a full update. A pair that still fails stops the
//! run, or with `Dissipation::reject` is left unchanged for this step (counted; like a
//! Metropolis rejection of a move outside the domain, it keeps p and K + u exact but
//! biases the dynamics at the rare states it touches).

use crate::error::{lowest, StepError};
use crate::heat::{HeatFlow, Temps};
use crate::pair_update::{pair_update, PairDrive, PairState};
use crate::rng::{normal_pair, stream, Normals};
use crate::settings::{Dissipation, Reservoir};
use crate::species::Species;
use crate::system::System;
use gendpde_engine::{dot, exact_sums, sub, Fields, Particles};
use gendpde_potentials::Eos;

/// Fields the sweep writes, exchanged between colours.
pub const SWEPT: Fields = Fields::MOMENTUM.union(Fields::ENERGY).union(Fields::THETA).union(Fields::INV_TAU);

/// One full sweep over all pairs of all colours. A pair update that fails is undone:
/// left out under `reject`, else reported after the sweep (the failure of lowest tag:
/// the pairs after it see the same states on any rank count).
pub fn sweep<E: Eos, H: HeatFlow>(eos: &Species<E>, d: &Dissipation, sys: &mut System, dt: f64) -> Result<(), StepError> {
    let kb = eos.kb();
    let rc = d.cutoff();
    let (inv_rcd, inv_rch) = (1.0 / d.rc_friction, 1.0 / d.rc_heat);
    let (step, normals) = (sys.step, Normals::get());
    let inv_m = &mut sys.inv_mass;
    inv_m.clear();
    inv_m.extend(sys.store.mass.iter().map(|m| 1.0 / m));
    let mut outcome = Ok(());
    for colour in 0..sys.sweep.colours() {
        let pairs = sys.sweep.within(colour, &sys.store, rc);
        let s = &mut sys.store;
        for &[i, j] in pairs {
            let (i, j) = (i as usize, j as usize);
            let dr = sub(s.r[i], s.r[j]);
            let r = dot(dr, dr).sqrt();
            let wd = (1.0 - r * inv_rcd).max(0.0);
            let wh = (1.0 - r * inv_rch).max(0.0);
            let (xi, xibar) = normals.pair(d.seed, step, s.tag[i], s.tag[j], stream::PAIR);
            let inv_r = 1.0 / r;
            let pair = Pair {
                i,
                j,
                e: [dr[0] * inv_r, dr[1] * inv_r, dr[2] * inv_r],
                inv_m: (inv_m[i], inv_m[j]),
                gamma: d.gamma * wd * wd,
                kappa: d.kappa * wh * wh,
                seed: d.seed,
                step,
                kb,
            };
            let saved = (s.p[i], s.p[j], s.u[i], s.u[j], s.theta[i], s.theta[j]);
            let done = pair_step::<E, H>(eos, s, &pair, xi, xibar, dt, 0, d.substeps, &mut sys.substeps);
            if done.is_err() {
                (s.p[i], s.p[j], s.u[i], s.u[j], s.theta[i], s.theta[j]) = saved;
                let undone = refresh::<E, H>(eos, s, i, step).and_then(|_| refresh::<E, H>(eos, s, j, step));
                sys.rejected += d.reject as u64;
                outcome = lowest(outcome, if d.reject { undone } else { lowest(done, undone) });
            }
        }
        let ghosts = &sys.sweep.ghost_writes[colour];
        sys.comm.reverse(&mut sys.store, ghosts, SWEPT);
        sys.comm.forward(&mut sys.store, SWEPT);
    }
    outcome
}

/// Heat exchange of the owned particles of the reservoir's group with the bath (2019
/// eq 72; the Fourier form after 2021 eq 62), then a forward exchange of the new values.
/// The energy put in, summed exactly over all particles (the same on every rank count),
/// is added to the reservoir's tally.
pub fn reservoir<E: Eos, H: HeatFlow>(eos: &Species<E>, res: &Reservoir, sys: &mut System, dt: f64) -> Result<(), StepError> {
    let kb = eos.kb();
    let sqrt_dt = dt.sqrt();
    let step = sys.step;
    let s = &mut sys.store;
    let mut outcome = Ok(());
    let mut added = Vec::new();
    for i in 0..s.nlocal {
        if !s.in_group(i, res.mask) {
            continue;
        }
        let (q, alpha) = H::reservoir(kb, res.kappa, temps::<H>(s, i), res.temperature);
        let xi = normal_pair(res.seed, step, s.tag[i], 0, stream::RESERVOIR).0;
        let du = dt * q + sqrt_dt * alpha * xi;
        s.u[i] += du;
        added.push([du]);
        outcome = lowest(outcome, refresh::<E, H>(eos, s, i, step));
    }
    let [total] = exact_sums(sys.comm.transport(), added.iter().copied());
    *sys.reservoir_tally(&res.id) += total;
    sys.comm.forward(&mut sys.store, SWEPT);
    outcome
}

/// What stays fixed while one pair is updated, over any split of its step.
struct Pair {
    i: usize,
    j: usize,
    e: [f64; 3],
    /// 1/m_i, 1/m_j.
    inv_m: (f64, f64),
    gamma: f64,
    kappa: f64,
    seed: u64,
    step: u64,
    kb: f64,
}

/// Updates one pair over `dt` with Wiener increments `xi sqrt(dt)`, `xibar sqrt(dt)`;
/// splits the step by a Brownian bridge when a temperature fails (`node` numbers the
/// halves of the binary tree, `levels` how many splits remain).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn pair_step<E: Eos, H: HeatFlow>(
    eos: &Species<E>,
    s: &mut Particles,
    p: &Pair,
    xi: f64,
    xibar: f64,
    dt: f64,
    node: u32,
    levels: u32,
    splits: &mut u64,
) -> Result<(), StepError> {
    let (i, j) = (p.i, p.j);
    let saved = (s.p[i], s.p[j], s.u[i], s.u[j], s.theta[i], s.theta[j]);
    let drive = PairDrive { e: p.e, gamma: p.gamma, kappa: p.kappa, ti: temps::<H>(s, i), tj: temps::<H>(s, j), xi, xibar };
    let (mut p_i, mut p_j, mut u_i, mut u_j) = (s.p[i], s.p[j], s.u[i], s.u[j]);
    let state = PairState { p_i: &mut p_i, p_j: &mut p_j, u_i: &mut u_i, u_j: &mut u_j, inv_m_i: p.inv_m.0, inv_m_j: p.inv_m.1 };
    pair_update::<H>(state, &drive, p.kb, dt, dt.sqrt());
    (s.p[i], s.p[j], s.u[i], s.u[j]) = (p_i, p_j, u_i, u_j);
    let outcome = refresh::<E, H>(eos, s, i, p.step).and_then(|_| refresh::<E, H>(eos, s, j, p.step));
    if outcome.is_ok() || levels == 0 {
        return outcome;
    }
    split::<E, H>(eos, s, p, saved, (xi, xibar, dt, node, levels), splits)
}

/// Undoes a failed pair update and does it as two half steps.
#[cold]
fn split<E: Eos, H: HeatFlow>(
    eos: &Species<E>,
    s: &mut Particles,
    p: &Pair,
    saved: ([f64; 3], [f64; 3], f64, f64, f64, f64),
    (xi, xibar, dt, node, levels): (f64, f64, f64, u32, u32),
    splits: &mut u64,
) -> Result<(), StepError> {
    let (i, j) = (p.i, p.j);
    (s.p[i], s.p[j], s.u[i], s.u[j], s.theta[i], s.theta[j]) = saved;
    for k in [i, j] {
        refresh::<E, H>(eos, s, k, p.step)?;
    }
    *splits += 1;
    let (eta, etabar) = normal_pair(p.seed, p.step, s.tag[i], s.tag[j], stream::SUBSTEP + node);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let first = ((xi + eta) * h, (xibar + etabar) * h);
    let second = ((xi - eta) * h, (xibar - etabar) * h);
    pair_step::<E, H>(eos, s, p, first.0, first.1, 0.5 * dt, 2 * node + 1, levels - 1, splits)?;
    pair_step::<E, H>(eos, s, p, second.0, second.1, 0.5 * dt, 2 * node + 2, levels - 1, splits)
}

#[inline(always)]
pub(crate) fn temps<H: HeatFlow>(s: &Particles, i: usize) -> Temps {
    Temps { theta: s.theta[i], inv_tau: if H::NEEDS_INV_TAU { s.inv_tau[i] } else { 0.0 } }
}

/// theta(u, n) at fixed n after a pair update, and 1/tau where the heat law reads it.
#[inline(always)]
fn refresh<E: Eos, H: HeatFlow>(eos: &Species<E>, s: &mut Particles, i: usize, step: u64) -> Result<(), StepError> {
    let eos = eos.of(s.kind[i]);
    let n = crate::many_body::density_of(s, i).max(gendpde_potentials::ISOLATED_DENSITY);
    let (theta, cv) = if H::NEEDS_INV_TAU { eos.theta_cv(s.u[i], n, s.theta[i]) } else { (eos.theta(s.u[i], n, s.theta[i]), 0.0) };
    if !(theta > 0.0 && theta.is_finite()) {
        let e = gendpde_potentials::EosError::at(eos, s.u[i], n, theta);
        return Err(StepError::eos(s, i, step, e));
    }
    s.theta[i] = theta;
    if H::NEEDS_INV_TAU {
        s.inv_tau[i] = eos.inv_tau(theta, cv);
    }
    Ok(())
}
