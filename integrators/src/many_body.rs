//! The many-body conservative passes over full neighbour lists: local density (eq 2),
//! particle state from the EOS, force (eq 51) with the virial (eq 52), and the
//! reversible work split (eq 84): u_i -= c sum_j v_ij . f_ij.

use crate::error::StepError;
use crate::system::System;
use gendpde_engine::{dot, sub};
use gendpde_potentials::{Eos, Weight};

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

/// Derives u from theta where `set theta` asked for it, at the current density.
pub fn resolve_theta<E: Eos>(eos: &E, sys: &mut System) {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        if s.theta_given[i] {
            let n = s.n.get(i).copied().unwrap_or(0.0).max(gendpde_potentials::ISOLATED_DENSITY);
            s.u[i] = eos.u(s.theta[i], n);
            s.theta_given[i] = false;
        }
    }
}

/// theta, pi/n^2 (and 1/tau where kept) of owned particles from (u, n).
pub fn refresh_state<E: Eos>(eos: &E, sys: &mut System, with_pressure: bool) -> Result<(), StepError> {
    let step = sys.step;
    let s = &mut sys.store;
    let keep_tau = !s.inv_tau.is_empty();
    for i in 0..s.nlocal {
        let n = if s.n.is_empty() { 0.0 } else { s.n[i] };
        let st = eos.state(s.u[i], n, s.theta[i]).map_err(|e| StepError::eos(s, i, step, e))?;
        s.theta[i] = st.theta;
        if with_pressure {
            s.pn2[i] = st.pn2;
        }
        if keep_tau {
            s.inv_tau[i] = eos.inv_tau(st.theta, st.cv);
        }
    }
    Ok(())
}

/// f_i = sum_j F_ij r_ij with F_ij = -(pi_i/n_i^2 + pi_j/n_j^2) w'(r)/([w] r) (eq 51);
/// keeps F_ij per list entry and the virial sum_{i<j} r_ij . f_ij.
pub fn forces<W: Weight>(w: &W, sys: &mut System) {
    let rc2 = w.cutoff() * w.cutoff();
    let s = &mut sys.store;
    let mut virial = 0.0;
    for i in 0..s.nlocal {
        let (ri, pi) = (s.r[i], s.pn2[i]);
        let start = sys.nlist.offsets[i] as usize;
        let mut f = [0.0; 3];
        for (k, &j) in sys.nlist.of(i).iter().enumerate() {
            let j = j as usize;
            let d = sub(ri, s.r[j]);
            let r2 = dot(d, d);
            let mut big_f = 0.0;
            if r2 < rc2 && r2 > 0.0 {
                let r = r2.sqrt();
                big_f = -(pi + s.pn2[j]) * w.eval(r).1 / r;
                for c in 0..3 {
                    f[c] += big_f * d[c];
                }
                virial += big_f * r2;
            }
            sys.pair_force[start + k] = big_f;
        }
        s.f[i] = f;
    }
    // each pair was seen from both sides
    sys.virial = 0.5 * virial;
}

/// u_i -= c sum_j (v_i - v_j) . f_ij, with the F_ij of the last force pass.
pub fn work(sys: &mut System, c: f64) {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        let ri = s.r[i];
        let inv_mi = 1.0 / s.mass[i];
        let vi = [s.p[i][0] * inv_mi, s.p[i][1] * inv_mi, s.p[i][2] * inv_mi];
        let start = sys.nlist.offsets[i] as usize;
        let mut sum = 0.0;
        for (k, &j) in sys.nlist.of(i).iter().enumerate() {
            let big_f = sys.pair_force[start + k];
            if big_f != 0.0 {
                let j = j as usize;
                let inv_mj = 1.0 / s.mass[j];
                let vij = [vi[0] - s.p[j][0] * inv_mj, vi[1] - s.p[j][1] * inv_mj, vi[2] - s.p[j][2] * inv_mj];
                sum += big_f * dot(vij, sub(ri, s.r[j]));
            }
        }
        s.u[i] -= c * sum;
    }
}
