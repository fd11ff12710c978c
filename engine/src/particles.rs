//! Structure-of-arrays particle store: owned particles first (0..nlocal), then ghosts.

use crate::{Fields, Vec3};

/// Per-particle state. Primary fields are always present; derived fields (n, pi/n^2,
/// 1/tau) are allocated only when a style in use asks for them (`enable`).
#[derive(Clone, Debug, Default)]
pub struct Particles {
    /// Number of owned particles; indices nlocal.. are ghosts.
    pub nlocal: usize,
    /// Global particle id (LAMMPS "tag"), 1-based.
    pub tag: Vec<u64>,
    /// Particle type, 1-based as in LAMMPS.
    pub kind: Vec<u32>,
    pub mass: Vec<f64>,
    pub r: Vec<Vec3>,
    pub p: Vec<Vec3>,
    /// Internal energy u (the dynamic variable).
    pub u: Vec<f64>,
    /// Particle temperature theta(u, n).
    pub theta: Vec<f64>,
    /// True where u is still to be derived from theta at the next setup (`set theta`).
    pub theta_given: Vec<bool>,
    /// Bit mask of the groups the particle belongs to (owned particles).
    pub groups: Vec<u32>,
    /// Periodic image counters of owned particles.
    pub image: Vec<[i32; 3]>,
    /// Global cell coordinates at the last rebuild (ghosts: outside 0..n).
    pub cell: Vec<[i32; 3]>,
    /// Position at the last rebuild (owned particles), for the skin criterion.
    pub r_build: Vec<Vec3>,
    /// Half-step momentum estimate of the modified velocity Verlet (owned particles).
    pub vest: Vec<Vec3>,
    /// Conservative force.
    pub f: Vec<Vec3>,
    /// Local density n (eq 2); empty for pairwise scenes.
    pub n: Vec<f64>,
    /// pi/n^2 (eq 51); empty for pairwise scenes.
    pub pn2: Vec<f64>,
    /// 1/tau (eq 19); only for the original heat-flow model.
    pub inv_tau: Vec<f64>,
    /// Per-particle diagonal virial sum_j F_ij (x_ij^2, y_ij^2, z_ij^2) / 2 of owned
    /// particles (its trace is the scalar virial).
    pub virial: Vec<Vec3>,
    /// Conductive part of u (classic DPDE, LAMMPS's uCond; uMech = u - uCond).
    pub u_cond: Vec<f64>,
    /// Half the pair energy of each pair a particle is in (pairwise styles).
    pub epair: Vec<f64>,
    /// MDPD density rho_i = sum_j m_j W(r_ij) (LAMMPS mdpd/rhosum).
    pub rho: Vec<f64>,
    enabled: Option<Fields>,
}

impl Particles {
    /// Number of owned plus ghost particles.
    pub fn len(&self) -> usize {
        self.tag.len()
    }

    pub fn is_empty(&self) -> bool {
        self.tag.is_empty()
    }

    pub fn nghost(&self) -> usize {
        self.len() - self.nlocal
    }

    /// Whether owned particle `i` belongs to the group of bit `mask` (`u32::MAX`: group all).
    #[inline]
    pub fn in_group(&self, i: usize, mask: u32) -> bool {
        mask == u32::MAX || self.groups[i] & mask != 0
    }

    /// Appends an owned particle (no ghosts may exist yet).
    pub fn push(&mut self, tag: u64, kind: u32, mass: f64, r: Vec3) {
        debug_assert_eq!(self.nlocal, self.len(), "push before ghosts are built");
        self.tag.push(tag);
        self.kind.push(kind);
        self.mass.push(mass);
        self.r.push(r);
        self.p.push([0.0; 3]);
        self.u.push(0.0);
        self.theta.push(0.0);
        self.theta_given.push(false);
        self.groups.push(0);
        self.image.push([0; 3]);
        self.cell.push([0; 3]);
        self.r_build.push(r);
        self.vest.push([0.0; 3]);
        self.nlocal += 1;
        self.resize_derived(self.len());
    }

    /// Allocates the derived fields of `fields` (DENSITY, PRESSURE, INV_TAU).
    pub fn enable(&mut self, fields: Fields) {
        self.enabled = Some(self.enabled.map_or(fields, |e| e | fields));
        self.resize_derived(self.len());
    }

    pub fn has(&self, field: Fields) -> bool {
        self.enabled.is_some_and(|e| e.contains(field))
    }

    /// Drops all ghosts.
    pub fn truncate_ghosts(&mut self) {
        self.resize(self.nlocal);
    }

    fn resize(&mut self, len: usize) {
        self.tag.truncate(len);
        self.kind.truncate(len);
        self.mass.truncate(len);
        self.r.truncate(len);
        self.p.truncate(len);
        self.u.truncate(len);
        self.theta.truncate(len);
        self.theta_given.truncate(len);
        self.groups.truncate(len);
        self.image.truncate(len);
        self.cell.truncate(len);
        self.r_build.truncate(len);
        self.vest.truncate(len);
        self.resize_derived(len);
    }

    fn resize_derived(&mut self, len: usize) {
        self.f.resize(len, [0.0; 3]);
        let on = |f| self.enabled.is_some_and(|e| e.contains(f));
        let (dens, pres, tau) = (on(Fields::DENSITY), on(Fields::PRESSURE), on(Fields::INV_TAU));
        let (cond, epair, rho) = (on(Fields::U_COND), on(Fields::PAIR_ENERGY), on(Fields::RHO));
        self.n.resize(if dens { len } else { 0 }, 0.0);
        self.pn2.resize(if pres { len } else { 0 }, 0.0);
        self.virial.resize(if pres || epair { len } else { 0 }, [0.0; 3]);
        self.inv_tau.resize(if tau { len } else { 0 }, 0.0);
        self.u_cond.resize(if cond { len } else { 0 }, 0.0);
        self.epair.resize(if epair { len } else { 0 }, 0.0);
        self.rho.resize(if rho { len } else { 0 }, 0.0);
    }
}

/// Packing of particles into f64 buffers for the communication layer. Integers travel
/// as f64, exact below 2^53.
impl Particles {
    /// Appends owned particle `i` (primary fields) for migration.
    pub fn pack_owned(&self, i: usize, buf: &mut Vec<f64>) {
        buf.extend_from_slice(&[self.tag[i] as f64, self.kind[i] as f64, self.mass[i]]);
        buf.extend_from_slice(&self.r[i]);
        buf.extend_from_slice(&self.p[i]);
        buf.extend_from_slice(&[self.u[i], self.theta[i], self.theta_given[i] as u8 as f64]);
        buf.extend(self.image[i].iter().map(|&x| x as f64));
        buf.extend(self.cell[i].iter().map(|&x| x as f64));
        buf.extend_from_slice(&self.r_build[i]);
        buf.push(self.u_cond.get(i).copied().unwrap_or(0.0));
        buf.extend_from_slice(&self.vest[i]);
        buf.push(self.groups[i] as f64);
    }

    /// Length of one `pack_owned` record.
    pub const OWNED_RECORD: usize = 26;

    /// The cell a `pack_owned` record carries.
    pub fn record_cell(rec: &[f64]) -> [i32; 3] {
        [rec[15] as i32, rec[16] as i32, rec[17] as i32]
    }

    /// Appends an owned particle from a `pack_owned` record (no ghosts may exist).
    pub fn unpack_owned(&mut self, rec: &[f64]) {
        self.push(rec[0] as u64, rec[1] as u32, rec[2], [rec[3], rec[4], rec[5]]);
        let i = self.nlocal - 1;
        self.p[i] = [rec[6], rec[7], rec[8]];
        self.u[i] = rec[9];
        self.theta[i] = rec[10];
        self.theta_given[i] = rec[11] != 0.0;
        self.image[i] = [rec[12] as i32, rec[13] as i32, rec[14] as i32];
        self.r_build[i] = [rec[18], rec[19], rec[20]];
        if !self.u_cond.is_empty() {
            self.u_cond[i] = rec[21];
        }
        self.vest[i] = [rec[22], rec[23], rec[24]];
        self.groups[i] = rec[25] as u32;
    }

    /// Removes owned particle `i` (the last owned particle takes its index; no ghosts
    /// may exist).
    pub fn remove_owned(&mut self, i: usize) {
        debug_assert_eq!(self.nlocal, self.len(), "remove before ghosts are dropped");
        self.tag.swap_remove(i);
        self.kind.swap_remove(i);
        self.mass.swap_remove(i);
        self.r.swap_remove(i);
        self.p.swap_remove(i);
        self.u.swap_remove(i);
        self.theta.swap_remove(i);
        self.theta_given.swap_remove(i);
        self.groups.swap_remove(i);
        self.image.swap_remove(i);
        self.cell.swap_remove(i);
        self.r_build.swap_remove(i);
        self.vest.swap_remove(i);
        if !self.u_cond.is_empty() {
            self.u_cond.swap_remove(i);
        }
        self.nlocal -= 1;
        self.resize_derived(self.nlocal);
    }

    /// Length of one `pack_ghost` record.
    pub fn ghost_record(&self) -> usize {
        14 + [&self.n, &self.pn2, &self.inv_tau, &self.u_cond, &self.rho].iter().filter(|v| !v.is_empty()).count()
    }

    /// Appends particle `i` as a ghost record, its position shifted by `shift` along `dim`
    /// and its cell by `cell_shift`.
    pub fn pack_ghost(&self, i: usize, dim: usize, shift: f64, cell_shift: i32, buf: &mut Vec<f64>) {
        let mut r = self.r[i];
        r[dim] += shift;
        let mut c = self.cell[i];
        c[dim] += cell_shift;
        buf.extend_from_slice(&[self.tag[i] as f64, self.kind[i] as f64, self.mass[i]]);
        buf.extend_from_slice(&r);
        buf.extend_from_slice(&self.p[i]);
        buf.extend_from_slice(&[self.u[i], self.theta[i]]);
        buf.extend(c.iter().map(|&x| x as f64));
        for v in [&self.n, &self.pn2, &self.inv_tau, &self.u_cond, &self.rho] {
            if !v.is_empty() {
                buf.push(v[i]);
            }
        }
    }

    /// Appends a ghost from a `pack_ghost` record.
    pub fn unpack_ghost(&mut self, rec: &[f64]) {
        self.tag.push(rec[0] as u64);
        self.kind.push(rec[1] as u32);
        self.mass.push(rec[2]);
        self.r.push([rec[3], rec[4], rec[5]]);
        self.p.push([rec[6], rec[7], rec[8]]);
        self.u.push(rec[9]);
        self.theta.push(rec[10]);
        self.theta_given.push(false);
        self.groups.push(0);
        self.image.push([0; 3]);
        self.cell.push([rec[11] as i32, rec[12] as i32, rec[13] as i32]);
        self.r_build.push([rec[3], rec[4], rec[5]]);
        self.vest.push([0.0; 3]);
        let len = self.len();
        self.resize_derived(len);
        let mut k = 14;
        for v in [&mut self.n, &mut self.pn2, &mut self.inv_tau, &mut self.u_cond, &mut self.rho] {
            if !v.is_empty() {
                v[len - 1] = rec[k];
                k += 1;
            }
        }
    }
}

impl Particles {
    /// Puts the owned particles in the order `order` (a permutation of 0..nlocal; no
    /// ghosts may exist): neighbouring particles then sit close in memory.
    pub fn reorder_owned(&mut self, order: &[u32]) {
        debug_assert_eq!(self.nlocal, self.len(), "reorder before ghosts are built");
        fn apply<T: Copy>(v: &mut Vec<T>, order: &[u32]) {
            if v.len() == order.len() {
                let old = std::mem::take(v);
                v.extend(order.iter().map(|&k| old[k as usize]));
            }
        }
        apply(&mut self.tag, order);
        apply(&mut self.kind, order);
        apply(&mut self.mass, order);
        apply(&mut self.r, order);
        apply(&mut self.p, order);
        apply(&mut self.u, order);
        apply(&mut self.theta, order);
        apply(&mut self.theta_given, order);
        apply(&mut self.groups, order);
        apply(&mut self.image, order);
        apply(&mut self.cell, order);
        apply(&mut self.r_build, order);
        apply(&mut self.vest, order);
        apply(&mut self.f, order);
        apply(&mut self.virial, order);
        for v in [&mut self.n, &mut self.pn2, &mut self.inv_tau, &mut self.u_cond, &mut self.epair, &mut self.rho] {
            apply(v, order);
        }
    }
}
