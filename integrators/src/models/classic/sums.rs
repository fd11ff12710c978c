//! The half-list pair passes of the classic styles: forces, energies, virials and energy
//! rates summed into the owned particles ([`tally`]), the in-range selection of the
//! conservative-only force ([`within`]), and the many-body densities ([`density`]).

use crate::system::System;
use gendpde_engine::{dot, sub, Particles, Vec3};

#[inline(always)]
pub(super) fn velocity(s: &Particles, i: usize) -> [f64; 3] {
    let k = 1.0 / s.mass[i];
    [s.p[i][0] * k, s.p[i][1] * k, s.p[i][2] * k]
}

/// What a pair adds to its particles: the scalar force F (f_ij = F e_ij) and a force
/// across the pair axis (dpd/ext), the pair energy, and for velocity-Verlet DPDE duMech
/// (to both) and duCond (+ to i, - to j).
pub(super) struct Terms {
    pub force: f64,
    pub perp: Vec3,
    pub energy: f64,
    pub du_mech: f64,
    pub du_cond: f64,
}

impl Terms {
    #[inline(always)]
    pub fn conservative(force: f64, energy: f64) -> Self {
        Self { force, perp: [0.0; 3], energy, du_mech: 0.0, du_cond: 0.0 }
    }
}

/// Sums pair forces, energies and virials (and with `DU` the energy rates) over the half
/// list into the owned particles (see [`gendpde_engine::NeighborList::pairs`]); with
/// `energies` false the energies and virials are left at zero (a step nothing reads them
/// after). `pair(s, i, j, r_ij, r)` gives the [`Terms`] of a pair closer than its cutoff
/// `rc(s, [i, j])`; with `CLAMPED` it is called for every pair of `pairs` and must give
/// zeros beyond the cutoff; with `PERP` its force across the axis is added.
#[inline(always)]
pub(super) fn tally<'a, const CLAMPED: bool, const DU: bool, const PERP: bool>(
    s: &mut Particles,
    energies: bool,
    pairs: impl IntoIterator<Item = &'a [u32; 2]>,
    rc: impl Fn(&Particles, [usize; 2]) -> f64,
    pair: impl Fn(&Particles, usize, usize, Vec3, f64) -> Terms,
) {
    if energies {
        tally_with::<CLAMPED, DU, PERP, true>(s, pairs, rc, pair)
    } else {
        tally_with::<CLAMPED, DU, PERP, false>(s, pairs, rc, pair)
    }
}

/// [`tally`] with the energies and virials summed or not (`ENERGIES`).
#[inline(always)]
fn tally_with<'a, const CLAMPED: bool, const DU: bool, const PERP: bool, const ENERGIES: bool>(
    s: &mut Particles,
    pairs: impl IntoIterator<Item = &'a [u32; 2]>,
    rc: impl Fn(&Particles, [usize; 2]) -> f64,
    pair: impl Fn(&Particles, usize, usize, Vec3, f64) -> Terms,
) {
    let n = s.nlocal;
    // the sums leave the store while the pairs are read (`pair` reads none of them)
    let take = |v: &mut Vec<f64>| if DU { std::mem::take(v) } else { Vec::new() };
    let (mut f, mut virial, mut epair) = (std::mem::take(&mut s.f), std::mem::take(&mut s.virial), std::mem::take(&mut s.epair));
    let (mut du_mech, mut du_cond) = (take(&mut s.du_mech), take(&mut s.du_cond));
    f[..n].fill([0.0; 3]);
    epair[..n].fill(0.0);
    virial[..n].fill([0.0; 3]);
    if DU {
        du_mech[..n].fill(0.0);
        du_cond[..n].fill(0.0);
    }
    for &[i, j] in pairs {
        let (i, j) = (i as usize, j as usize);
        let d = sub(s.r[i], s.r[j]);
        let r2 = dot(d, d);
        if r2 < 1e-20 || (!CLAMPED && r2 >= rc(s, [i, j]).powi(2)) {
            continue;
        }
        let r = r2.sqrt();
        let inv_r = 1.0 / r;
        let t = pair(s, i, j, d, r);
        let fpair = t.force * inv_r;
        let mut df = [fpair * d[0], fpair * d[1], fpair * d[2]];
        if PERP {
            for c in 0..3 {
                df[c] += t.perp[c];
            }
        }
        let w = [0.5 * df[0] * d[0], 0.5 * df[1] * d[1], 0.5 * df[2] * d[2]];
        // + df into i, - df into j (the same bits as adding -1 df)
        if i < n {
            let fi = &mut f[i];
            (fi[0], fi[1], fi[2]) = (fi[0] + df[0], fi[1] + df[1], fi[2] + df[2]);
            if ENERGIES {
                let vi = &mut virial[i];
                (vi[0], vi[1], vi[2]) = (vi[0] + w[0], vi[1] + w[1], vi[2] + w[2]);
                epair[i] += t.energy;
            }
            if DU {
                du_mech[i] += t.du_mech;
                du_cond[i] += t.du_cond;
            }
        }
        if j < n {
            let fj = &mut f[j];
            (fj[0], fj[1], fj[2]) = (fj[0] - df[0], fj[1] - df[1], fj[2] - df[2]);
            if ENERGIES {
                let vj = &mut virial[j];
                (vj[0], vj[1], vj[2]) = (vj[0] + w[0], vj[1] + w[1], vj[2] + w[2]);
                epair[j] += t.energy;
            }
            if DU {
                du_mech[j] += t.du_mech;
                du_cond[j] -= t.du_cond;
            }
        }
    }
    (s.f, s.virial, s.epair) = (f, virial, epair);
    if DU {
        (s.du_mech, s.du_cond) = (du_mech, du_cond);
    }
}

/// The list pairs closer than `rc` (and farther than 1e-10), in list
/// order, into `active`, selected without a branch per pair.
pub(super) fn within(s: &Particles, pairs: &[[u32; 2]], rc: f64, active: &mut Vec<[u32; 2]>) {
    active.resize(pairs.len(), [0; 2]);
    let mut m = 0;
    for &[i, j] in pairs {
        let d = sub(s.r[i as usize], s.r[j as usize]);
        let r2 = dot(d, d);
        active[m] = [i, j];
        m += (r2 < rc * rc && r2 >= 1e-20) as usize;
    }
    active.truncate(m);
}

/// rho of owned particles from the half list: `w(s, i, j, r^2)` gives what the pair adds
/// to rho_i and to rho_j.
#[inline(always)]
pub(super) fn density(sys: &mut System, w: impl Fn(&Particles, usize, usize, f64) -> (f64, f64)) {
    let s = &mut sys.store;
    let n = s.nlocal;
    s.rho[..n].fill(0.0);
    for &[i, j] in &sys.nlist.pairs {
        let (i, j) = (i as usize, j as usize);
        let d = sub(s.r[i], s.r[j]);
        let (to_i, to_j) = w(s, i, j, dot(d, d));
        if i < n {
            s.rho[i] += to_i;
        }
        if j < n {
            s.rho[j] += to_j;
        }
    }
}
