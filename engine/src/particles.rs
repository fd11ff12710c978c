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
    /// Periodic image counters of owned particles.
    pub image: Vec<[i32; 3]>,
    /// Global cell coordinates at the last rebuild (ghosts: outside 0..n).
    pub cell: Vec<[i32; 3]>,
    /// Conservative force.
    pub f: Vec<Vec3>,
    /// Local density n (eq 2); empty for pairwise scenes.
    pub n: Vec<f64>,
    /// pi/n^2 (eq 51); empty for pairwise scenes.
    pub pn2: Vec<f64>,
    /// 1/tau (eq 19); only for the original heat-flow model.
    pub inv_tau: Vec<f64>,
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
        self.image.push([0; 3]);
        self.cell.push([0; 3]);
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

    /// Appends a ghost copy of particle `src` shifted by `shift`, in cell `cell`.
    pub fn push_ghost(&mut self, src: usize, shift: Vec3, cell: [i32; 3]) {
        let r = self.r[src];
        self.tag.push(self.tag[src]);
        self.kind.push(self.kind[src]);
        self.mass.push(self.mass[src]);
        self.r.push([r[0] + shift[0], r[1] + shift[1], r[2] + shift[2]]);
        self.p.push(self.p[src]);
        self.u.push(self.u[src]);
        self.theta.push(self.theta[src]);
        self.theta_given.push(false);
        self.image.push([0; 3]);
        self.cell.push(cell);
        let len = self.len();
        self.resize_derived(len);
        for v in [&mut self.n, &mut self.pn2, &mut self.inv_tau] {
            if !v.is_empty() {
                v[len - 1] = v[src];
            }
        }
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
        self.image.truncate(len);
        self.cell.truncate(len);
        self.resize_derived(len);
    }

    fn resize_derived(&mut self, len: usize) {
        self.f.resize(len, [0.0; 3]);
        let on = |f| self.enabled.is_some_and(|e| e.contains(f));
        let (dens, pres, tau) = (on(Fields::DENSITY), on(Fields::PRESSURE), on(Fields::INV_TAU));
        self.n.resize(if dens { len } else { 0 }, 0.0);
        self.pn2.resize(if pres { len } else { 0 }, 0.0);
        self.inv_tau.resize(if tau { len } else { 0 }, 0.0);
    }

    /// Kinetic energy sum p^2/2m over owned particles.
    pub fn kinetic_energy(&self) -> f64 {
        (0..self.nlocal).map(|i| crate::dot(self.p[i], self.p[i]) / (2.0 * self.mass[i])).sum()
    }
}
