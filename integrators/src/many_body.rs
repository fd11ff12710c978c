//! The many-body conservative passes over full neighbour lists: local density (eq 2),
//! particle state from the EOS, force (eq 51) with the virial (eq 52), and the
//! reversible work split (eq 84): u_i -= c sum_j v_ij . f_ij.
//!
//! The force pass keeps, per list entry, the geometric factor g_ij = w'(r_ij)/([w] r_ij)
//! and F_ij = -(pi_i/n_i^2 + pi_j/n_j^2) g_ij, so f_ij = F_ij r_ij. After the Shardlow
//! sweep has changed the particle temperatures, `refresh_forces_and_work` rebuilds F_ij
//! from g_ij and the new pi/n^2 without evaluating the weight again.

use crate::error::StepError;
use crate::system::System;
use gendpde_engine::{dot, sub, Particles, Vec3};
use gendpde_potentials::{Eos, Weight, ISOLATED_DENSITY};

/// n_i = sum_j w(r_ij)/[w] for owned particles.
pub fn density<W: Weight>(w: &W, sys: &mut System) {
    let rc2 = w.cutoff() * w.cutoff();
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        let ri = s.r[i];
        let mut n = 0.0;
        for &j in sys.nlist.of(i) {
            let d = sub(ri, s.r[j as usize]);
            let r2 = dot(d, d);
            if r2 < rc2 {
                n += w.eval(r2.sqrt()).0;
            }
        }
        s.n[i] = n;
    }
}

/// Local density of particle i as the EOS reads it (0 in pairwise scenes).
#[inline(always)]
pub fn density_of(s: &Particles, i: usize) -> f64 {
    if s.n.is_empty() { 0.0 } else { s.n[i] }
}

/// Derives u from theta where `set theta` asked for it, at the current density.
pub fn resolve_theta<E: Eos>(eos: &E, sys: &mut System) {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        if s.theta_given[i] {
            s.u[i] = eos.u(s.theta[i], density_of(s, i).max(ISOLATED_DENSITY));
            s.theta_given[i] = false;
        }
    }
}

/// theta, pi/n^2 (where kept) and 1/tau (where kept) of owned particles from (u, n).
/// On a failure it carries on and reports the first failing particle.
pub fn refresh_state<E: Eos>(eos: &E, sys: &mut System) -> Result<(), StepError> {
    let step = sys.step;
    let s = &mut sys.store;
    let (keep_pressure, keep_tau) = (!s.pn2.is_empty(), !s.inv_tau.is_empty());
    let mut first = Ok(());
    for i in 0..s.nlocal {
        match eos.state(s.u[i], density_of(s, i), s.theta[i]) {
            Ok(st) => {
                s.theta[i] = st.theta;
                if keep_pressure {
                    s.pn2[i] = st.pn2;
                }
                if keep_tau {
                    s.inv_tau[i] = eos.inv_tau(st.theta, st.cv);
                }
            }
            Err(e) => {
                if first.is_ok() {
                    first = Err(StepError::eos(s, i, step, e));
                }
            }
        }
    }
    first
}

/// f_i = sum_j F_ij r_ij (eq 51), keeping g_ij and F_ij per list entry and the
/// per-particle virial sum_j F_ij r_ij^2 / 2 (eq 52).
pub fn forces<W: Weight>(w: &W, sys: &mut System) {
    let rc2 = w.cutoff() * w.cutoff();
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        let (ri, pi) = (s.r[i], s.pn2[i]);
        let start = sys.nlist.offsets[i] as usize;
        let mut f = [0.0; 3];
        let mut virial = 0.0;
        for (k, &j) in sys.nlist.of(i).iter().enumerate() {
            let j = j as usize;
            let d = sub(ri, s.r[j]);
            let r2 = dot(d, d);
            let mut g = 0.0;
            if r2 < rc2 && r2 > 0.0 {
                let r = r2.sqrt();
                g = w.eval(r).1 / r;
            }
            let big_f = -(pi + s.pn2[j]) * g;
            for c in 0..3 {
                f[c] += big_f * d[c];
            }
            virial += big_f * r2;
            sys.pair_geometry[start + k] = g;
            sys.pair_force[start + k] = big_f;
        }
        s.f[i] = f;
        s.virial[i] = 0.5 * virial;
    }
}

/// u_i -= c sum_j (v_i - v_j) . f_ij, with the F_ij of the last force pass.
pub fn work(sys: &mut System, c: f64) {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        let (ri, vi) = (s.r[i], velocity(s, i));
        let start = sys.nlist.offsets[i] as usize;
        let mut sum = 0.0;
        for (k, &j) in sys.nlist.of(i).iter().enumerate() {
            let big_f = sys.pair_force[start + k];
            if big_f != 0.0 {
                let j = j as usize;
                sum += big_f * dot(sub(vi, velocity(s, j)), sub(ri, s.r[j]));
            }
        }
        s.u[i] -= c * sum;
    }
}

/// After the sweep changed theta, and so pi: F_ij from g_ij and the current pi/n^2
/// (which ghosts must hold), f_i anew, and u_i -= c sum_j v_ij . f_ij in the same pass.
pub fn refresh_forces_and_work(sys: &mut System, c: f64) {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        let (ri, vi, pi) = (s.r[i], velocity(s, i), s.pn2[i]);
        let start = sys.nlist.offsets[i] as usize;
        let (mut f, mut sum) = ([0.0; 3], 0.0);
        for (k, &j) in sys.nlist.of(i).iter().enumerate() {
            let g = sys.pair_geometry[start + k];
            let j = j as usize;
            let big_f = -(pi + s.pn2[j]) * g;
            sys.pair_force[start + k] = big_f;
            if big_f != 0.0 {
                let d = sub(ri, s.r[j]);
                for c in 0..3 {
                    f[c] += big_f * d[c];
                }
                sum += big_f * dot(sub(vi, velocity(s, j)), d);
            }
        }
        s.f[i] = f;
        s.u[i] -= c * sum;
    }
}

#[inline(always)]
fn velocity(s: &Particles, i: usize) -> Vec3 {
    let inv_m = 1.0 / s.mass[i];
    [s.p[i][0] * inv_m, s.p[i][1] * inv_m, s.p[i][2] * inv_m]
}
