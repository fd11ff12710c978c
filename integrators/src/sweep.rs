//! The Shardlow sweep (eq 82): every pair within the cutoff in colour order, theta
//! (and 1/tau) of i and j refreshed from the EOS after each pair; then the reservoir.
//!
//! Between colours the ghosts written in the colour return their values to their
//! owners, and the owners forward the new values to all ghosts (ARCHITECTURE.md).

use crate::error::StepError;
use crate::heat::{HeatFlow, Temps};
use crate::pair_update::{pair_update, PairDrive, PairState};
use crate::rng::{normal_pair, stream};
use crate::settings::{Dissipation, Reservoir};
use crate::system::System;
use gendpde_engine::{dot, sub, Fields, Particles};
use gendpde_potentials::Eos;

/// Fields the sweep writes, exchanged between colours.
pub const SWEPT: Fields = Fields::MOMENTUM.union(Fields::ENERGY).union(Fields::THETA).union(Fields::INV_TAU);

/// One full sweep over all pairs of all colours. After a failure this rank stops
/// updating pairs but keeps taking part in the exchanges, and reports the failure.
pub fn sweep<E: Eos, H: HeatFlow>(eos: &E, d: &Dissipation, sys: &mut System, dt: f64) -> Result<(), StepError> {
    let kb = eos.kb();
    let sqrt_dt = dt.sqrt();
    let rc = d.cutoff();
    let (inv_rcd, inv_rch) = (1.0 / d.rc_friction, 1.0 / d.rc_heat);
    let step = sys.step;
    let mut outcome = Ok(());
    for colour in 0..8 {
        let s = &mut sys.store;
        let pairs = if outcome.is_ok() { sys.sweep.colour(colour) } else { &[] };
        for &[i, j] in pairs {
            let (i, j) = (i as usize, j as usize);
            let dr = sub(s.r[i], s.r[j]);
            let r2 = dot(dr, dr);
            if r2 >= rc * rc || r2 == 0.0 {
                continue;
            }
            let r = r2.sqrt();
            let wd = (1.0 - r * inv_rcd).max(0.0);
            let wh = (1.0 - r * inv_rch).max(0.0);
            let (xi, xibar) = normal_pair(d.seed, step, s.tag[i], s.tag[j], stream::PAIR);
            let drive = PairDrive {
                e: [dr[0] / r, dr[1] / r, dr[2] / r],
                gamma: d.gamma * wd * wd,
                kappa: d.kappa * wh * wh,
                ti: temps::<H>(s, i),
                tj: temps::<H>(s, j),
                xi,
                xibar,
            };
            let (mut p_i, mut p_j, mut u_i, mut u_j) = (s.p[i], s.p[j], s.u[i], s.u[j]);
            let state = PairState {
                p_i: &mut p_i,
                p_j: &mut p_j,
                u_i: &mut u_i,
                u_j: &mut u_j,
                inv_m_i: 1.0 / s.mass[i],
                inv_m_j: 1.0 / s.mass[j],
            };
            pair_update::<H>(state, &drive, kb, dt, sqrt_dt);
            s.p[i] = p_i;
            s.p[j] = p_j;
            s.u[i] = u_i;
            s.u[j] = u_j;
            outcome = refresh::<E, H>(eos, s, i, step).and_then(|_| refresh::<E, H>(eos, s, j, step));
            if outcome.is_err() {
                break;
            }
        }
        let ghosts = &sys.sweep.ghost_writes[colour];
        sys.comm.reverse(&mut sys.store, ghosts, SWEPT);
        sys.comm.forward(&mut sys.store, SWEPT);
    }
    outcome
}

/// Heat exchange of every owned particle with the reservoir (eq 72), then a forward
/// exchange of the new values.
pub fn reservoir<E: Eos, H: HeatFlow>(eos: &E, res: &Reservoir, sys: &mut System, dt: f64) -> Result<(), StepError> {
    let kb = eos.kb();
    let sqrt_dt = dt.sqrt();
    let step = sys.step;
    let s = &mut sys.store;
    let mut outcome = Ok(());
    for i in 0..s.nlocal {
        let (q, alpha) = H::reservoir(kb, res.kappa, temps::<H>(s, i), res.temperature);
        let xi = normal_pair(res.seed, step, s.tag[i], 0, stream::RESERVOIR).0;
        s.u[i] += dt * q + sqrt_dt * alpha * xi;
        if let Err(e) = refresh::<E, H>(eos, s, i, step) {
            outcome = outcome.and(Err(e));
        }
    }
    sys.comm.forward(&mut sys.store, SWEPT);
    outcome
}

#[inline(always)]
fn temps<H: HeatFlow>(s: &Particles, i: usize) -> Temps {
    Temps { theta: s.theta[i], inv_tau: if H::NEEDS_INV_TAU { s.inv_tau[i] } else { 0.0 } }
}

/// theta(u, n) at fixed n after a pair update, and 1/tau where the heat law reads it.
#[inline(always)]
fn refresh<E: Eos, H: HeatFlow>(eos: &E, s: &mut Particles, i: usize, step: u64) -> Result<(), StepError> {
    let n = crate::many_body::density_of(s, i).max(gendpde_potentials::ISOLATED_DENSITY);
    let theta = eos.theta(s.u[i], n, s.theta[i]);
    if !(theta > 0.0 && theta.is_finite()) {
        let e = gendpde_potentials::EosError::NonPositiveTheta { u: s.u[i], n, theta };
        return Err(StepError::eos(s, i, step, e));
    }
    s.theta[i] = theta;
    if H::NEEDS_INV_TAU {
        s.inv_tau[i] = eos.inv_tau(theta, eos.cv(theta, n));
    }
    Ok(())
}
