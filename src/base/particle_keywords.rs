//! The per-particle keywords of LAMMPS (and gendpde's), one table, [`KEYWORDS`]: a
//! keyword that is a field of the particle table reads it (`engine::FIELDS`), the others
//! are derived (v = p/m, unwrapped and scaled positions, uMech = u - uCond). The text
//! dumps, H5MD, compute property/atom and the per-atom inputs of computes read them.

use gendpde_engine::{FieldReader, Particles};
use gendpde_integrators::System;

/// Where a keyword's value comes from.
#[derive(Clone, Copy)]
enum Source {
    /// Value k of a field of the particle table.
    Field(&'static str, usize),
    /// Computed from the system; reads the named fields.
    Derived(fn(&System, usize) -> f64, &'static [&'static str]),
}

/// A per-particle dump keyword.
#[derive(Clone, Copy)]
pub struct Keyword {
    pub name: &'static str,
    source: Source,
}

const fn field(name: &'static str, field: &'static str, k: usize) -> Keyword {
    Keyword { name, source: Source::Field(field, k) }
}

const fn derived(name: &'static str, f: fn(&System, usize) -> f64, reads: &'static [&'static str]) -> Keyword {
    Keyword { name, source: Source::Derived(f, reads) }
}

fn velocity(s: &System, i: usize, k: usize) -> f64 {
    s.store.p[i][k] / s.store.mass[i]
}

fn unwrapped(s: &System, i: usize, k: usize) -> f64 {
    s.domain.unwrap(s.store.r[i], s.store.image[i])[k]
}

fn scaled(s: &System, i: usize, k: usize) -> f64 {
    (s.store.r[i][k] - s.domain.lo[k]) / s.domain.len()[k]
}

/// LAMMPS's dump keywords and gendpde's (p, u, theta, n, eDPD's T, C_V and Q, SPH's drho and
/// the Voronoi cell volume).
pub const KEYWORDS: &[Keyword] = &[
    field("id", "id", 0),
    field("type", "type", 0),
    field("mass", "mass", 0),
    field("x", "x", 0),
    field("y", "x", 1),
    field("z", "x", 2),
    derived("xs", |s, i| scaled(s, i, 0), &[]),
    derived("ys", |s, i| scaled(s, i, 1), &[]),
    derived("zs", |s, i| scaled(s, i, 2), &[]),
    derived("xu", |s, i| unwrapped(s, i, 0), &[]),
    derived("yu", |s, i| unwrapped(s, i, 1), &[]),
    derived("zu", |s, i| unwrapped(s, i, 2), &[]),
    field("ix", "image", 0),
    field("iy", "image", 1),
    field("iz", "image", 2),
    derived("vx", |s, i| velocity(s, i, 0), &[]),
    derived("vy", |s, i| velocity(s, i, 1), &[]),
    derived("vz", |s, i| velocity(s, i, 2), &[]),
    field("px", "p", 0),
    field("py", "p", 1),
    field("pz", "p", 2),
    field("fx", "f", 0),
    field("fy", "f", 1),
    field("fz", "f", 2),
    field("u", "u", 0),
    field("theta", "theta", 0),
    field("dpdTheta", "theta", 0),
    field("uCond", "uCond", 0),
    derived("uMech", |s, i| s.store.u[i] - s.store.u_cond[i], &["uCond"]),
    field("n", "n", 0),
    field("rho", "rho", 0),
    field("edpd_temp", "edpd_temp", 0),
    field("edpd_cv", "edpd_cv", 0),
    field("edpd_flux", "edpd_flux", 0),
    field("drho", "drho", 0),
    field("vol", "vol", 0),
];

/// The keyword names, for error messages.
pub fn keyword_names() -> String {
    KEYWORDS.iter().map(|k| k.name).collect::<Vec<_>>().join(" ")
}

impl Keyword {
    pub fn find(name: &str) -> Option<Keyword> {
        KEYWORDS.iter().find(|k| k.name == name).copied()
    }

    /// Whether its values are integers (printed with `%d`).
    pub fn integer(&self) -> bool {
        match self.source {
            Source::Field(f, _) => gendpde_engine::FIELDS.iter().any(|i| i.name == f && i.integer),
            Source::Derived(..) => false,
        }
    }

    /// Its value reader on `store`, or why the scene has none.
    pub fn reader(&self, store: &Particles) -> Result<Reader, String> {
        let missing = |f: &str| format!("keyword {}: this scene has no per-particle '{f}' (its styles do not compute it)", self.name);
        match self.source {
            Source::Field(f, k) => store.reader(f).map(|r| Reader::Field(r, k)).ok_or_else(|| missing(f)),
            Source::Derived(g, reads) => match reads.iter().find(|f| store.reader(f).is_none()) {
                Some(f) => Err(missing(f)),
                None => Ok(Reader::Derived(g)),
            },
        }
    }
}

/// Reads one keyword's value of owned particle i.
#[derive(Clone, Copy)]
pub enum Reader {
    Field(FieldReader, usize),
    Derived(fn(&System, usize) -> f64),
}

impl Reader {
    pub fn get(&self, sys: &System, i: usize) -> f64 {
        match *self {
            Reader::Field(f, k) => f(&sys.store, i, k),
            Reader::Derived(g) => g(sys, i),
        }
    }
}

/// The readers of `keywords` on the system's store.
pub fn readers(keywords: &[Keyword], sys: &System) -> Result<Vec<Reader>, String> {
    keywords.iter().map(|k| k.reader(&sys.store)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn field_keywords_name_fields_of_the_particle_table() {
        let width = |f: &str| gendpde_engine::FIELDS.iter().find(|x| x.name == f).map(|x| x.width);
        for k in KEYWORDS {
            match k.source {
                Source::Field(f, i) => assert!(width(f).is_some_and(|w| i < w), "{}: value {i} of field '{f}'", k.name),
                Source::Derived(_, reads) => assert!(reads.iter().all(|f| width(f).is_some()), "{}: reads {reads:?}", k.name),
            }
        }
    }
}

