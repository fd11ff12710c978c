//! The many-body conservative passes over the half pair list (each pair once; the sums
//! of every owned particle come out as over its full list, see
//! [`gendpde_engine::NeighborList`]): local density (eq 2, or the corrected density of
//! the argon paper, eqs 2-3),
//! particle state from the EOS, force (eq 51) with the virial (eq 52), and the
//! reversible work split (eq 84): u_i -= c sum_j v_ij . f_ij.
//!
//! The density pass keeps, per pair, the geometric factor g_ij = w'(r_ij)/([w] r_ij);
//! the force pass F_ij = -(pi_i/n_i^2 + pi_j/n_j^2) g_ij, so f_ij = F_ij r_ij; with the corrected
//! volume pi_i/n_i^2 carries the factor zeta_i = dn_i/dn^b_i (argon paper eq 27). After the Shardlow
//! sweep has changed the particle temperatures, `refresh_forces` rebuilds F_ij
//! from g_ij and the new pi/n^2 without evaluating the weight again.

use crate::error::{lowest, StepError};
use crate::simd::avx2_fn;
use crate::passes::species::Species;
use crate::system::System;
use gendpde_engine::{dot, sub, Particles, Vec3};
use gendpde_potentials::volume::PartitionVolume;
use gendpde_potentials::{Eos, Weight, ISOLATED_DENSITY};

avx2_fn! {
    /// n_i = sum_j w(r_ij)/[w] for owned particles (eq 2), keeping g_ij = w'(r_ij)/([w] r_ij)
    /// per pair for the force pass, or with `volume` the corrected
    /// n_i = 1/Vol(n^b_i) of the argon paper (eqs 2-3) from that sum n^b_i, keeping
    /// zeta_i = dn_i/dn^b_i (eq 24) in `sys.scratch.zeta` for [`refresh_state`].
    pub fn density<W: Weight>(w: &W, volume: Option<&PartitionVolume>, sys: &mut System) {
        let rc2 = w.cutoff() * w.cutoff();
        let s = &mut sys.store;
        let n = s.nlocal;
        s.n[..n].fill(0.0);
        // the pairs inside the cutoff, selected without a branch per pair (a quarter of the
        // list lies in the skin, a branch the processor cannot predict), with r^2 kept in
        // their g slot; the later passes walk this compact list
        // (written into spare capacity: no zeros written first)
        let (pairs, active, geometry, r) = (&sys.nlist.pairs, &mut sys.scratch.active, &mut sys.scratch.pair_geometry, &s.r[..]);
        active.clear();
        geometry.clear();
        active.reserve(pairs.len());
        geometry.reserve(pairs.len());
        let (slots, r2s) = (&mut active.spare_capacity_mut()[..pairs.len()], &mut geometry.spare_capacity_mut()[..pairs.len()]);
        let mut m = 0;
        for &[i, j] in pairs {
            let d = sub(r[i as usize], r[j as usize]);
            let r2 = dot(d, d);
            slots[m].write([i, j]);
            r2s[m].write(r2);
            m += (r2 < rc2) as usize;
        }
        // SAFETY: entries 0..m were written (entry m was written before m passed it)
        unsafe {
            active.set_len(m);
            geometry.set_len(m);
        }
        let weights = &mut sys.scratch.pair_sums;
        weigh(w, geometry, weights);
        let density = &mut s.n[..n];
        for (&[i, j], &wij) in active.iter().zip(weights.iter()) {
            add(density, i as usize, j as usize, wij);
        }
        let zeta = &mut sys.scratch.zeta;
        zeta.clear();
        if let Some(v) = volume {
            zeta.resize(n, 0.0);
            for (nb, z) in s.n[..n].iter_mut().zip(zeta.iter_mut()) {
                let d = v.density(*nb);
                (*nb, *z) = (d.n, d.zeta);
            }
        }
    }
}

/// w(r_ij)/[w] into `weights` and g_ij = w'(r_ij)/([w] r_ij) into `geometry` (which
/// holds r_ij^2) for every pair inside the cutoff: a loop that writes no particle, which
/// the compiler runs in packed lanes (square roots and divisions 4 at a time, the same
/// IEEE operations per lane, so the same bits).
#[inline(always)]
fn weigh<W: Weight>(w: &W, geometry: &mut [f64], weights: &mut Vec<f64>) {
    weights.clear();
    weights.extend(geometry.iter_mut().map(|g| {
        let r2 = *g;
        let r = r2.sqrt();
        let (w_r, dw) = w.eval(r);
        *g = if r2 > 0.0 { dw / r } else { 0.0 };
        w_r
    }));
}

/// Local density of particle i as the EOS reads it (0 in pairwise scenes).
#[inline(always)]
pub fn density_of(s: &Particles, i: usize) -> f64 {
    if s.n.is_empty() { 0.0 } else { s.n[i] }
}

/// Derives u from theta where `set theta` asked for it, at the current density.
pub fn resolve_theta<E: Eos>(eos: &Species<E>, sys: &mut System) {
    let s = &mut sys.store;
    for i in 0..s.nlocal {
        if s.theta_given[i] {
            s.u[i] = eos.of(s.kind[i]).u(s.theta[i], density_of(s, i).max(ISOLATED_DENSITY));
            s.theta_given[i] = false;
        }
    }
}

/// theta, the force factor pi/n^2 (times zeta_i with the corrected volume, eq 27; where
/// kept) and 1/tau (where kept) of owned particles from (u, n). On a failure it carries on
/// and reports the failing particle of lowest tag.
pub fn refresh_state<E: Eos>(eos: &Species<E>, sys: &mut System) -> Result<(), StepError> {
    let step = sys.clock.step;
    let (s, zeta) = (&mut sys.store, &sys.scratch.zeta);
    let (keep_pressure, keep_tau) = (!s.pn2.is_empty(), !s.inv_tau.is_empty());
    let mut first = Ok(());
    for i in 0..s.nlocal {
        let eos = eos.of(s.kind[i]);
        match eos.state(s.u[i], density_of(s, i), s.theta[i]) {
            Ok(st) => {
                s.theta[i] = st.theta;
                if keep_pressure {
                    s.pn2[i] = if zeta.is_empty() { st.pn2 } else { st.pn2 * zeta[i] };
                }
                if keep_tau {
                    s.inv_tau[i] = eos.inv_tau(st.theta, st.cv);
                }
            }
            Err(e) => first = lowest(first, Err(StepError::eos(s, i, step, e))),
        }
    }
    first
}

avx2_fn! {
    /// f_i = sum_j F_ij r_ij (eq 51) from the g_ij of the density pass, keeping F_ij per pair
    /// and the per-particle diagonal virial sum_j F_ij (x_ij^2, y_ij^2, z_ij^2) / 2 (eq 52).
    pub fn forces(sys: &mut System) {
        let s = &mut sys.store;
        let n = s.nlocal;
        s.f[..n].fill([0.0; 3]);
        s.virial[..n].fill([0.0; 3]);
        let len = s.len();
        let (active, geometry, r, pn2) = (&sys.scratch.active[..], &sys.scratch.pair_geometry[..], &s.r[..len], &s.pn2[..len]);
        let (f, virial) = (&mut s.f[..n], &mut s.virial[..n]);
        sys.scratch.pair_force.resize(active.len(), 0.0);
        for ((&[i, j], &g), big_f_out) in active.iter().zip(geometry).zip(sys.scratch.pair_force.iter_mut()) {
            let (i, j) = in_store(i, j, len);
            let d = sub(r[i], r[j]);
            let big_f = -(pn2[i] + pn2[j]) * g;
            kick(f, i, j, big_f, d);
            let dd = [big_f * d[0] * d[0], big_f * d[1] * d[1], big_f * d[2] * d[2]];
            for o in [i, j] {
                if o < n {
                    for c in 0..3 {
                        virial[o][c] += dd[c];
                    }
                }
            }
            *big_f_out = big_f;
        }
        for v in &mut s.virial[..n] {
            *v = v.map(|x| 0.5 * x);
        }
    }
}

avx2_fn! {
    /// u_i -= c sum_j (v_i - v_j) . f_ij, with the F_ij of the last force pass.
    pub fn work(sys: &mut System, c: f64) {
        let s = &mut sys.store;
        let n = s.nlocal;
        let len = s.len();
        let (sums, v) = (&mut sys.scratch.pair_sums, &velocities(s, &mut sys.scratch.velocity)[..len]);
        sums.clear();
        sums.resize(n, 0.0);
        let r = &s.r[..len];
        for (&[i, j], &big_f) in sys.scratch.active.iter().zip(&sys.scratch.pair_force) {
            if big_f != 0.0 {
                let (i, j) = in_store(i, j, len);
                add(sums, i, j, big_f * dot(sub(v[i], v[j]), sub(r[i], r[j])));
            }
        }
        for i in 0..n {
            s.u[i] -= c * sums[i];
        }
    }
}

avx2_fn! {
    /// After the sweep changed theta, and so pi: F_ij from g_ij and the current pi/n^2
    /// (which ghosts must hold) and f_i anew; with `work = Some(c)` also
    /// u_i -= c sum_j v_ij . f_ij in the same pass.
    pub fn refresh_forces(sys: &mut System, work: Option<f64>) {
        let s = &mut sys.store;
        let n = s.nlocal;
        let sums = &mut sys.scratch.pair_sums;
        sums.clear();
        sums.resize(n, 0.0);
        let len = s.len();
        let v = if work.is_some() { &velocities(s, &mut sys.scratch.velocity)[..len] } else { &[] };
        s.f[..n].fill([0.0; 3]);
        let (active, geometry, r, pn2, f) = (&sys.scratch.active[..], &sys.scratch.pair_geometry[..], &s.r[..len], &s.pn2[..len], &mut s.f[..n]);
        sys.scratch.pair_force.resize(active.len(), 0.0);
        for ((&[i, j], &g), big_f_out) in active.iter().zip(geometry).zip(sys.scratch.pair_force.iter_mut()) {
            let (i, j) = in_store(i, j, len);
            let big_f = -(pn2[i] + pn2[j]) * g;
            *big_f_out = big_f;
            if big_f != 0.0 {
                let d = sub(r[i], r[j]);
                kick(f, i, j, big_f, d);
                if work.is_some() {
                    add(sums, i, j, big_f * dot(sub(v[i], v[j]), d));
                }
            }
        }
        if let Some(c) = work {
            for i in 0..n {
                s.u[i] -= c * sums[i];
            }
        }
    }
}

/// The indices of a list pair, checked once against the store's length `len` (a list
/// entry outside the store is a bug of the list build: a panic, never a silent read);
/// slices cut to `len` then index without further checks.
#[inline(always)]
fn in_store(i: u32, j: u32, len: usize) -> (usize, usize) {
    let (i, j) = (i as usize, j as usize);
    assert!(i.max(j) < len, "pair outside the store");
    (i, j)
}

/// Adds a symmetric pair term to whichever of i, j is owned: `v` holds the owned
/// particles only (an index below its length).
#[inline(always)]
pub(crate) fn add(v: &mut [f64], i: usize, j: usize, x: f64) {
    if i < v.len() {
        v[i] += x;
    }
    if j < v.len() {
        v[j] += x;
    }
}

/// f_i += F r_ij, f_j -= F r_ij for the owned ones (`f` holds the owned particles
/// only): the same bits as f_j += F r_ji.
#[inline(always)]
pub(crate) fn kick(f: &mut [Vec3], i: usize, j: usize, big_f: f64, d: Vec3) {
    let df = [big_f * d[0], big_f * d[1], big_f * d[2]];
    let n = f.len();
    if i < n {
        for c in 0..3 {
            f[i][c] += df[c];
        }
    }
    if j < n {
        for c in 0..3 {
            f[j][c] -= df[c];
        }
    }
}

/// The velocities of all particles (owned and ghost) in `buf`: one division per
/// particle instead of two per pair.
fn velocities<'a>(s: &Particles, buf: &'a mut Vec<Vec3>) -> &'a [Vec3] {
    buf.clear();
    buf.extend((0..s.len()).map(|i| velocity(s, i)));
    buf
}

#[inline(always)]
pub(crate) fn velocity(s: &Particles, i: usize) -> Vec3 {
    let inv_m = 1.0 / s.mass[i];
    [s.p[i][0] * inv_m, s.p[i][1] * inv_m, s.p[i][2] * inv_m]
}
