//! Structure-of-arrays particle store: owned particles first (0..nlocal), then ghosts.
//!
//! Every per-particle field is one row of the table in `particle_fields!` below: its
//! element type, the comm key that forward/reverse exchanges name it by, the stages it
//! takes part in and the name restart files and dumps know it by. The store, migration,
//! ghost records, reordering, snapshots and restart columns all derive from that table,
//! so adding a field is one row plus its physics (LAMMPS's `fields_grow`, `fields_comm`,
//! `fields_border`, `fields_exchange` and `fields_restart` lists, checked by the compiler).

use crate::{Fields, Vec3};

/// The stages a per-particle field takes part in (bit set).
pub mod stage {
    /// Travels with an owned particle to its new rank.
    pub const MIGRATE: u32 = 1;
    /// Copied into the ghost record when the ghost layer is built.
    pub const GHOST: u32 = 2;
    /// A column of restart files.
    pub const RESTART: u32 = 4;
    /// Computed by a step in a way its set-up cannot redo to the bit (forces and virials
    /// from that step's velocities and noise; theta, solved by Newton iterations started
    /// from the previous theta): a continuation keeps the stored values.
    pub const RESUME: u32 = 8;
}

/// Element types of per-particle fields: `WIDTH` values in an f64 record. Integers
/// travel as f64, exact below 2^53.
pub trait Column: Copy + Default {
    const WIDTH: usize;
    /// Whether the values are integers (restart files store them as integers).
    const INTEGER: bool;
    fn pack(self, buf: &mut Vec<f64>);
    fn unpack(rec: &[f64]) -> Self;
    /// Value `k` (below `WIDTH`).
    fn get(self, k: usize) -> f64;

    /// Appends the records of `col[i]` for each i of `idx` to `buf` (a forward or
    /// reverse message), written in place: no capacity check per value, no zeroing.
    #[inline]
    fn gather(col: &[Self], idx: &[u32], buf: &mut Vec<f64>) {
        let n = idx.len() * Self::WIDTH;
        buf.reserve(n);
        let spare = &mut buf.spare_capacity_mut()[..n];
        for (&i, rec) in idx.iter().zip(spare.chunks_exact_mut(Self::WIDTH)) {
            let v = col[i as usize];
            for (k, x) in rec.iter_mut().enumerate() {
                x.write(v.get(k));
            }
        }
        // SAFETY: the loop wrote all n values after the old length (idx.len() records of
        // WIDTH values each), within the capacity reserved above.
        unsafe { buf.set_len(buf.len() + n) };
    }
}

impl Column for f64 {
    const WIDTH: usize = 1;
    const INTEGER: bool = false;
    fn pack(self, buf: &mut Vec<f64>) {
        buf.push(self);
    }
    fn unpack(rec: &[f64]) -> Self {
        rec[0]
    }
    fn get(self, _k: usize) -> f64 {
        self
    }
}

macro_rules! integer_column {
    ($($t:ty),*) => {$(
        impl Column for $t {
            const WIDTH: usize = 1;
            const INTEGER: bool = true;
            fn pack(self, buf: &mut Vec<f64>) {
                buf.push(self as f64);
            }
            fn unpack(rec: &[f64]) -> Self {
                rec[0] as $t
            }
            fn get(self, _k: usize) -> f64 {
                self as f64
            }
        }
    )*};
}
integer_column!(u64, u32);

impl Column for bool {
    const WIDTH: usize = 1;
    const INTEGER: bool = true;
    fn pack(self, buf: &mut Vec<f64>) {
        buf.push(self as u8 as f64);
    }
    fn unpack(rec: &[f64]) -> Self {
        rec[0] != 0.0
    }
    fn get(self, _k: usize) -> f64 {
        self as u8 as f64
    }
}

impl Column for [f64; 3] {
    const WIDTH: usize = 3;
    const INTEGER: bool = false;
    fn pack(self, buf: &mut Vec<f64>) {
        buf.extend_from_slice(&self);
    }
    fn unpack(rec: &[f64]) -> Self {
        [rec[0], rec[1], rec[2]]
    }
    fn get(self, k: usize) -> f64 {
        self[k]
    }
}

impl Column for [i32; 3] {
    const WIDTH: usize = 3;
    const INTEGER: bool = true;
    fn pack(self, buf: &mut Vec<f64>) {
        buf.extend(self.iter().map(|&x| x as f64));
    }
    fn unpack(rec: &[f64]) -> Self {
        [rec[0] as i32, rec[1] as i32, rec[2] as i32]
    }
    fn get(self, k: usize) -> f64 {
        self[k] as f64
    }
}

/// One row of the field table.
#[derive(Clone, Copy, Debug)]
pub struct FieldInfo {
    /// The name restart files and dumps use.
    pub name: &'static str,
    /// Values per particle.
    pub width: usize,
    pub integer: bool,
    /// Allocated only when one of these fields is enabled (`Fields::NONE`: always).
    pub gate: Fields,
    /// The key forward and reverse exchanges name it by (`Fields::NONE`: not exchanged).
    pub comm: Fields,
    /// Bit set of [`stage`] constants.
    pub stages: u32,
}

/// The layout of a ghost record (see [`Particles::ghost_layout`]).
#[derive(Clone, Copy, Debug)]
pub struct GhostLayout {
    pub width: usize,
    /// Offsets of the position and of the cell.
    pub r: usize,
    pub cell: usize,
}

/// One column of a stage's record: a field and where its values start.
#[derive(Clone, Copy, Debug)]
pub struct RecordColumn {
    pub field: FieldInfo,
    pub offset: usize,
}

/// Value k of a field of particle i (see [`Particles::reader`]).
pub type FieldReader = fn(&Particles, usize, usize) -> f64;

macro_rules! particle_fields {
    ($( $(#[$doc:meta])* $name:ident : $ty:ty, $key:literal, gate $gate:expr, comm $comm:expr, stages $stages:expr; )*) => {
        /// Per-particle state; see the module documentation for the field table.
        #[derive(Clone, Debug, Default)]
        pub struct Particles {
            /// Number of owned particles; indices nlocal.. are ghosts.
            pub nlocal: usize,
            $( $(#[$doc])* pub $name: Vec<$ty>, )*
            enabled: Fields,
        }

        /// The field table, in record order.
        pub const FIELDS: &[FieldInfo] = &[
            $( FieldInfo { name: $key, width: <$ty as Column>::WIDTH, integer: <$ty as Column>::INTEGER, gate: $gate, comm: $comm, stages: $stages }, )*
        ];

        impl Particles {
            /// Reads value k of field `name` of a particle (dumps): None for an unknown or
            /// unallocated field.
            pub fn reader(&self, name: &str) -> Option<FieldReader> {
                $( if name == $key {
                    return self.allocates($gate).then_some((|p: &Particles, i: usize, k: usize| p.$name[i].get(k)) as FieldReader);
                } )*
                None
            }

            /// Sets every allocated field to length `len` (new entries default).
            fn resize(&mut self, len: usize) {
                $( let n = if self.allocates($gate) { len } else { 0 }; self.$name.resize(n, <$ty>::default()); )*
            }

            /// Removes particle `i` from every field (the last takes its index).
            fn swap_remove_all(&mut self, i: usize) {
                $( if !self.$name.is_empty() { self.$name.swap_remove(i); } )*
            }

            /// Becomes a copy of the owned particles of `from` (every allocated field, no
            /// ghosts), reusing its memory: a column at a time, so a snapshot taken every
            /// step costs a few copies of contiguous memory.
            pub fn copy_owned_from(&mut self, from: &Particles) {
                let n = from.nlocal;
                $( self.$name.clear(); self.$name.extend_from_slice(&from.$name[..n.min(from.$name.len())]); )*
                (self.nlocal, self.enabled) = (n, from.enabled);
            }

            /// Puts every field in the order `order` (a permutation of 0..len).
            fn permute(&mut self, order: &[u32]) {
                $( permute(&mut self.$name, order); )*
            }

            /// Appends the fields of `stages` of particle `i` (unallocated fields of the
            /// stage: skipped when `dense`, defaults otherwise).
            pub fn pack(&self, i: usize, stages: u32, dense: bool, buf: &mut Vec<f64>) {
                $( if shares($stages, stages) {
                    match self.$name.get(i) {
                        Some(&v) => v.pack(buf),
                        None if !dense => <$ty>::default().pack(buf),
                        None => {}
                    }
                } )*
            }

            /// Reads a `pack` record into particle `i`; returns the values read.
            pub fn unpack(&mut self, i: usize, stages: u32, dense: bool, rec: &[f64]) -> usize {
                let mut k = 0;
                $( if shares($stages, stages) {
                    let allocated = !self.$name.is_empty();
                    if allocated || !dense {
                        if allocated {
                            self.$name[i] = <$ty as Column>::unpack(&rec[k..]);
                        }
                        k += <$ty as Column>::WIDTH;
                    }
                } )*
                k
            }

            /// Appends the exchanged fields `fields` of the particles `idx`, field by field
            /// (in table order), each field's values in the order of `idx`.
            fn pack_comm(&self, idx: &[u32], fields: Fields, buf: &mut Vec<f64>) {
                $( if !$comm.is_empty() && fields.contains($comm) && !self.$name.is_empty() {
                    <$ty as Column>::gather(&self.$name, idx, buf);
                } )*
            }

            /// Reads a [`Particles::pack_fields`] message into the particles `to` (a list of
            /// indices, or a range: a swap's ghosts are contiguous).
            pub fn unpack_fields(&mut self, to: impl ExactSizeIterator<Item = usize> + Clone, fields: Fields, msg: &[f64]) {
                let mut k = 0;
                $( if !$comm.is_empty() && fields.contains($comm) && !self.$name.is_empty() {
                    let column = &mut self.$name;
                    for (i, rec) in to.clone().zip(msg[k..].chunks_exact(<$ty as Column>::WIDTH)) {
                        column[i] = <$ty as Column>::unpack(rec);
                    }
                    k += to.len() * <$ty as Column>::WIDTH;
                } )*
                debug_assert_eq!(k, msg.len());
            }

            /// Copies the exchanged fields `fields` of the particles `from` into the
            /// particles `to..` in order (all of `from` lying below `to`).
            fn gather_comm(&mut self, from: &[u32], to: usize, fields: Fields) {
                $( if !$comm.is_empty() && fields.contains($comm) && !self.$name.is_empty() {
                    let (src, dst) = self.$name.split_at_mut(to);
                    for (d, &i) in dst[..from.len()].iter_mut().zip(from) {
                        *d = src[i as usize];
                    }
                } )*
            }

            /// Copies the exchanged fields `fields` from particle `from` to particle `to`
            /// for each (from, to) of `moves` (a reverse swap of a rank with itself).
            pub fn copy_fields(&mut self, moves: impl Iterator<Item = (usize, usize)> + Clone, fields: Fields) {
                $( if !$comm.is_empty() && fields.contains($comm) && !self.$name.is_empty() {
                    for (from, to) in moves.clone() {
                        self.$name[to] = self.$name[from];
                    }
                } )*
            }
        }
    };
}

const NONE: Fields = Fields::NONE;
use stage::{GHOST, MIGRATE, RESTART, RESUME};

particle_fields! {
    /// Global particle id (LAMMPS "tag"), 1-based.
    tag: u64, "id", gate NONE, comm NONE, stages MIGRATE | GHOST | RESTART;
    /// Particle type, 1-based as in LAMMPS.
    kind: u32, "type", gate NONE, comm NONE, stages MIGRATE | GHOST | RESTART;
    mass: f64, "mass", gate NONE, comm NONE, stages MIGRATE | GHOST | RESTART;
    r: Vec3, "x", gate NONE, comm Fields::POSITION, stages MIGRATE | GHOST | RESTART;
    p: Vec3, "p", gate NONE, comm Fields::MOMENTUM, stages MIGRATE | GHOST | RESTART;
    /// Internal energy u (the dynamic variable).
    u: f64, "u", gate NONE, comm Fields::ENERGY, stages MIGRATE | GHOST | RESTART;
    /// Particle temperature theta(u, n).
    theta: f64, "theta", gate NONE, comm Fields::THETA, stages MIGRATE | GHOST | RESTART | RESUME;
    /// Global cell coordinates at the last rebuild (ghosts: outside 0..n).
    cell: [i32; 3], "cell", gate NONE, comm NONE, stages MIGRATE | GHOST | RESTART;
    /// Octant of the position within the cell at the last rebuild (`CellGrid::octant`;
    /// ghosts: their owner's), which orders the cell's particles in the pair search.
    octant: u32, "octant", gate NONE, comm NONE, stages MIGRATE | GHOST | RESTART;
    /// True where u is still to be derived from theta at the next setup (`set theta`).
    theta_given: bool, "theta_given", gate NONE, comm NONE, stages MIGRATE | RESTART;
    /// Bit mask of the groups the particle belongs to (ghosts carry their owner's:
    /// neighbour computes of a group read them).
    groups: u32, "groups", gate NONE, comm NONE, stages MIGRATE | GHOST | RESTART;
    /// Periodic image counters of owned particles.
    image: [i32; 3], "image", gate NONE, comm NONE, stages MIGRATE | RESTART;
    /// Position at the last rebuild (owned particles), for the skin criterion.
    r_build: Vec3, "r_at_build", gate NONE, comm NONE, stages MIGRATE | RESTART;
    /// Half-step momentum estimate of the modified velocity Verlet (owned particles).
    vest: Vec3, "vest", gate NONE, comm NONE, stages MIGRATE | RESTART;
    /// Conductive part of u (classic DPDE, LAMMPS's uCond; uMech = u - uCond).
    u_cond: f64, "uCond", gate Fields::U_COND, comm Fields::U_COND, stages MIGRATE | GHOST | RESTART;
    /// Conservative force (pairwise styles: with the friction and noise of `pair dpd`).
    f: Vec3, "f", gate NONE, comm NONE, stages RESTART | RESUME;
    /// Local density n (eq 2); empty for pairwise scenes.
    n: f64, "n", gate Fields::DENSITY, comm Fields::DENSITY, stages GHOST;
    /// pi/n^2 (eq 51); empty for pairwise scenes.
    pn2: f64, "pn2", gate Fields::PRESSURE, comm Fields::PRESSURE, stages GHOST;
    /// 1/tau (eq 19); only for the original heat-flow model.
    inv_tau: f64, "inv_tau", gate Fields::INV_TAU, comm Fields::INV_TAU, stages GHOST;
    /// MDPD density rho_i = sum_j m_j W(r_ij) (LAMMPS mdpd/rhosum), or the SPH density
    /// of atom_style sph, integrated from drho (a dynamic variable: it migrates and
    /// restarts; mdpd recomputes it every step).
    rho: f64, "rho", gate Fields::RHO, comm Fields::RHO, stages MIGRATE | GHOST | RESTART;
    /// drho/dt of owned particles from the last force pass (atom_style sph's drho).
    drho: f64, "drho", gate Fields::SPH, comm NONE, stages RESTART | RESUME;
    /// eDPD temperature T (LAMMPS atom_style edpd's edpd_temp).
    edpd_temp: f64, "edpd_temp", gate Fields::EDPD, comm Fields::EDPD, stages MIGRATE | GHOST | RESTART;
    /// eDPD heat capacity C_V (edpd_cv).
    edpd_cv: f64, "edpd_cv", gate Fields::EDPD, comm NONE, stages MIGRATE | GHOST | RESTART;
    /// eDPD heat flux Q = dT/dt C_V of owned particles (edpd_flux), from that step's noise.
    edpd_flux: f64, "edpd_flux", gate Fields::EDPD, comm NONE, stages RESTART | RESUME;
    /// Half-step temperature estimate of fix mvv/edpd (vest_temp, owned particles).
    vest_temp: f64, "vest_temp", gate Fields::EDPD, comm NONE, stages MIGRATE | RESTART;
    /// SDPD stress increment of the step, diagonal (xx, yy, zz) and off-diagonal
    /// (xy, xz, yz) parts (Serrano-Espanol eqs 77, 82; scratch of pair sdpd/generic).
    sdpd_stress: Vec3, "sdpd_stress", gate Fields::SDPD_STRESS, comm Fields::SDPD_STRESS, stages 0;
    sdpd_shear: Vec3, "sdpd_shear", gate Fields::SDPD_STRESS, comm Fields::SDPD_STRESS, stages 0;
    /// SDPD heat-flux increment of the step (eqs 77, 83; scratch of pair sdpd/generic).
    sdpd_flux: Vec3, "sdpd_flux", gate Fields::SDPD_FLUX, comm Fields::SDPD_FLUX, stages 0;
    /// Entropy S of a Voronoi cell (pair voronoi/fv; Serrano-Espanol eq 64).
    entropy: f64, "entropy", gate Fields::ENTROPY, comm NONE, stages MIGRATE | RESTART;
    /// Volume of a Voronoi cell, rewritten from the tessellation after every step and at
    /// set-up (allocated with the entropy; dump keyword `vol`).
    volume: f64, "vol", gate Fields::ENTROPY, comm NONE, stages 0;
    /// Per-particle diagonal virial sum_j F_ij (x_ij^2, y_ij^2, z_ij^2) / 2 of owned
    /// particles (its trace is the scalar virial); for a Voronoi cell p dV/d epsilon_aa.
    virial: Vec3, "virial", gate Fields::PRESSURE.union(Fields::PAIR_ENERGY).union(Fields::ENTROPY), comm NONE, stages RESTART | RESUME;
    /// Half the pair energy of each pair a particle is in (pairwise styles).
    epair: f64, "epair", gate Fields::PAIR_ENERGY, comm NONE, stages RESTART | RESUME;
    /// duCond/dt of velocity-Verlet DPDE from the last force pass (LAMMPS's duCond).
    du_cond: f64, "duCond", gate Fields::DU, comm NONE, stages RESTART | RESUME;
    /// duMech/dt of velocity-Verlet DPDE from the last force pass (LAMMPS's duMech).
    du_mech: f64, "duMech", gate Fields::DU, comm NONE, stages RESTART | RESUME;
}

/// Whether a field of stages `field` (0 for none) belongs to any of `stages`.
#[inline(always)]
const fn shares(field: u32, stages: u32) -> bool {
    field & stages != 0
}

fn permute<T: Copy>(v: &mut Vec<T>, order: &[u32]) {
    if v.len() == order.len() {
        // the new column keeps the old one's capacity (room for the ghosts that follow),
        // so the next borders do not grow it again
        let old = std::mem::replace(v, Vec::with_capacity(v.capacity()));
        v.extend(order.iter().map(|&k| old[k as usize]));
    }
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

    /// Whether a field gated on `gate` is allocated.
    fn allocates(&self, gate: Fields) -> bool {
        gate.is_empty() || self.enabled.intersects(gate)
    }

    /// Appends an owned particle (no ghosts may exist yet); its other fields default.
    pub fn push(&mut self, tag: u64, kind: u32, mass: f64, r: Vec3) {
        debug_assert_eq!(self.nlocal, self.len(), "push before ghosts are built");
        let i = self.len();
        self.resize(i + 1);
        (self.tag[i], self.kind[i], self.mass[i], self.r[i], self.r_build[i]) = (tag, kind, mass, r, r);
        self.nlocal += 1;
    }

    /// Allocates the gated fields of `fields` (DENSITY, PRESSURE, INV_TAU, ...).
    pub fn enable(&mut self, fields: Fields) {
        self.enabled = self.enabled | fields;
        self.resize(self.len());
    }

    /// The fields enabled so far (restart files keep them).
    pub fn enabled(&self) -> Fields {
        self.enabled
    }

    pub fn has(&self, field: Fields) -> bool {
        self.enabled.contains(field)
    }

    /// Drops all ghosts.
    pub fn truncate_ghosts(&mut self) {
        self.resize(self.nlocal);
    }

    /// The columns of the record of `stages` (`dense`: the allocated fields only).
    pub fn record(&self, stages: u32, dense: bool) -> Vec<RecordColumn> {
        let mut offset = 0;
        let mut out = Vec::new();
        for field in FIELDS.iter().filter(|f| f.stages & stages != 0 && (!dense || self.allocates(f.gate))) {
            out.push(RecordColumn { field: *field, offset });
            offset += field.width;
        }
        out
    }

    /// Values per particle of the record of `stages`.
    pub fn record_width(&self, stages: u32, dense: bool) -> usize {
        self.record(stages, dense).iter().map(|c| c.field.width).sum()
    }

    /// Appends owned particle `i` for migration (every MIGRATE field).
    pub fn pack_owned(&self, i: usize, buf: &mut Vec<f64>) {
        self.pack(i, MIGRATE, false, buf);
    }

    /// Length of one `pack_owned` record.
    pub fn owned_record(&self) -> usize {
        self.record_width(MIGRATE, false)
    }

    /// Appends an owned particle from a `pack_owned` record (no ghosts may exist).
    pub fn unpack_owned(&mut self, rec: &[f64]) {
        debug_assert_eq!(self.nlocal, self.len(), "unpack before ghosts are dropped");
        let i = self.len();
        self.resize(i + 1);
        self.unpack(i, MIGRATE, false, rec);
        self.nlocal += 1;
    }

    /// Removes owned particle `i` (the last owned particle takes its index; no ghosts
    /// may exist).
    pub fn remove_owned(&mut self, i: usize) {
        debug_assert_eq!(self.nlocal, self.len(), "remove before ghosts are dropped");
        self.swap_remove_all(i);
        self.nlocal -= 1;
    }

    /// Width of a ghost record and where its position and cell start.
    pub fn ghost_layout(&self) -> GhostLayout {
        let cols = self.record(GHOST, true);
        let at = |name| cols.iter().find(|c| c.field.name == name).map(|c| c.offset).expect("ghosts carry x and cell");
        GhostLayout { width: self.record_width(GHOST, true), r: at("x"), cell: at("cell") }
    }

    /// Appends particle `i` as a ghost record, its position shifted by `shift` along `dim`
    /// and its cell by `cell_shift`.
    pub fn pack_ghost(&self, i: usize, layout: &GhostLayout, dim: usize, shift: f64, cell_shift: i32, buf: &mut Vec<f64>) {
        let start = buf.len();
        self.pack(i, GHOST, true, buf);
        buf[start + layout.r + dim] += shift;
        buf[start + layout.cell + dim] += cell_shift as f64;
    }

    /// Appends a ghost from each `pack_ghost` record of `records`, `width` values each
    /// (their owned-only fields default).
    pub fn unpack_ghosts(&mut self, records: &[f64], width: usize) {
        let start = self.len();
        self.resize(start + records.len() / width);
        for (i, rec) in (start..).zip(records.chunks_exact(width)) {
            self.unpack(i, GHOST, true, rec);
            self.r_build[i] = self.r[i];
        }
    }

    /// Puts the owned particles in the order `order` (a permutation of 0..nlocal; no
    /// ghosts may exist): neighbouring particles then sit close in memory.
    pub fn reorder_owned(&mut self, order: &[u32]) {
        debug_assert_eq!(self.nlocal, self.len(), "reorder before ghosts are built");
        self.permute(order);
    }
}

/// The fields of one stage of the owned particles, keyed by tag (see
/// [`Particles::save_by_tag`]).
#[derive(Clone, Debug, Default)]
pub struct SavedByTag {
    stages: u32,
    /// (tag, record index), sorted by tag.
    index: Vec<(u64, usize)>,
    records: Vec<f64>,
}

impl Particles {
    /// Saves the fields of `stages` of the owned particles, keyed by tag.
    pub fn save_by_tag(&self, stages: u32) -> SavedByTag {
        let mut saved = SavedByTag { stages, ..Default::default() };
        for i in 0..self.nlocal {
            saved.index.push((self.tag[i], i));
            self.pack(i, stages, true, &mut saved.records);
        }
        saved.index.sort_unstable();
        saved
    }

    /// Puts saved fields back into the owned particles of the same tags (the particles
    /// may have been reordered since; tags not saved are left alone). Returns the
    /// exchanged fields among them, which the ghosts must be sent again.
    pub fn restore_by_tag(&mut self, saved: &SavedByTag) -> Fields {
        let width = self.record_width(saved.stages, true);
        for i in 0..self.nlocal {
            if let Ok(k) = saved.index.binary_search_by_key(&self.tag[i], |&(t, _)| t) {
                let at = saved.index[k].1 * width;
                self.unpack(i, saved.stages, true, &saved.records[at..at + width]);
            }
        }
        self.record(saved.stages, true).iter().fold(Fields::NONE, |f, c| f | c.field.comm)
    }
}

/// Forward and reverse exchanges: records of the fields named by a `Fields` set.
impl Particles {
    /// Appends `fields` of the particles `idx` (a message of `idx.len()` records stored
    /// field by field), the positions shifted by `shift` (dimension, length) when given:
    /// the positions lead the message.
    pub fn pack_fields(&self, idx: &[u32], fields: Fields, shift: Option<(usize, f64)>, buf: &mut Vec<f64>) {
        let start = buf.len();
        self.pack_comm(idx, fields, buf);
        if let (Some((d, s)), true) = (shift, fields.contains(Fields::POSITION)) {
            for r in buf[start..start + 3 * idx.len()].chunks_exact_mut(3) {
                r[d] += s;
            }
        }
    }

    /// Copies `fields` of the particles `from` into the ghosts `to..` in order (a forward
    /// swap of a rank with itself: its sources lie below its ghosts), with the position
    /// shift of `pack_fields`.
    pub fn copy_to_ghosts(&mut self, from: &[u32], to: usize, fields: Fields, (d, shift): (usize, f64)) {
        self.gather_comm(from, to, fields);
        if fields.contains(Fields::POSITION) {
            for r in &mut self.r[to..to + from.len()] {
                r[d] += shift;
            }
        }
    }
}
