//! `set atom|type|group|region ID KEYWORD VALUES ...`, LAMMPS's set command for the
//! fields gendpde's particles have: type, type/fraction, x y z, vx vy vz, image,
//! dpd/theta (theta) and gendpde's u. Values may be `v_name` of an atom- or equal-style
//! variable, evaluated when its keyword is reached (as LAMMPS). `type/fraction` draws
//! LAMMPS's position-keyed Park–Miller numbers, so it picks LAMMPS's particles.

use crate::base::args::Args;
use crate::base::groups;
use crate::base::park::{Park, MAX_SEED};
use crate::model::per_atom;
use crate::model::sim::Sim;
use crate::output::thermo::ThermoConfig;
use gendpde_engine::{Fields, Particles};
use gendpde_io::{ScriptError, Variables};

const KEYWORDS: &str = "type, type/fraction, x, y, z, vx, vy, vz, image, dpd/theta (theta), u, edpd/temp, edpd/cv, sph/rho";

/// Gives owned particle `i` type `kind` and that type's mass (NaN while unset), keeping
/// its velocity (p holds the velocity while the mass is unknown, as after read_data).
fn retype(s: &mut Particles, i: usize, kind: u32, masses: &[Option<f64>], mvv2e: f64) {
    let new = masses[kind as usize - 1].map_or(f64::NAN, |m| m * mvv2e);
    let velocity = velocity(s, i);
    s.p[i] = if new.is_finite() { velocity.map(|v| v * new) } else { velocity };
    s.kind[i] = kind;
    s.mass[i] = new;
}

/// The velocity of owned particle `i` (p holds it while the mass is unknown).
fn velocity(s: &Particles, i: usize) -> [f64; 3] {
    let m = s.mass[i];
    if m.is_finite() { s.p[i].map(|p| p / m) } else { s.p[i] }
}

/// The owned particles the style and ID select.
fn selection(sim: &Sim, a: &mut Args) -> Result<Vec<usize>, ScriptError> {
    let style = a.word("atom, type, mol, group or region")?;
    let s = &sim.system.as_ref().ok_or_else(|| a.err("set before create_box"))?.store;
    Ok(match style {
        "group" => {
            let m = groups::mask(&sim.groups, a.word("a group ID")?, a)?;
            (0..s.nlocal).filter(|&i| s.in_group(i, m)).collect()
        }
        "region" => {
            let id = a.word("a region ID")?;
            let r = sim.regions.get(id).ok_or_else(|| a.err(format!("no region with ID '{id}'")))?;
            (0..s.nlocal).filter(|&i| r.contains(s.r[i])).collect()
        }
        "type" => {
            let t = a.range("a particle type", sim.ntypes as u64)?;
            (0..s.nlocal).filter(|&i| t.contains(&(s.kind[i] as u64))).collect()
        }
        "atom" => {
            let t = a.range("a particle ID", sim.max_tag)?;
            (0..s.nlocal).filter(|&i| t.contains(&s.tag[i])).collect()
        }
        "mol" => return Err(a.err("style mol: gendpde's particles have no molecule IDs")),
        _ => return Err(a.err(format!("expected atom, type, mol, group or region, got '{style}'"))),
    })
}

/// A keyword's value: a number or the values of a variable per owned particle.
enum Value {
    Number(f64),
    PerParticle(Vec<f64>),
}

impl Value {
    fn at(&self, i: usize) -> f64 {
        match self {
            Value::Number(x) => *x,
            Value::PerParticle(v) => v[i],
        }
    }
}

/// The next word as a number or `v_name`, evaluated now (the earlier keywords have acted).
fn value(a: &mut Args, sim: &Sim, vars: &Variables, thermo: &ThermoConfig, what: &str) -> Result<Value, ScriptError> {
    match a.peek().and_then(|w| w.strip_prefix("v_")) {
        Some(name) => {
            a.word(what)?;
            let sys = sim.system.as_ref().ok_or_else(|| a.err("set before create_box"))?;
            let global = |n: &str| super::resolve(sim, thermo, vars, n);
            per_atom::variable(vars, name, sys, sim.units.mvv2e, &global).map(Value::PerParticle).map_err(|e| a.err(e))
        }
        None => a.f64(what).map(Value::Number),
    }
}

pub fn set(sim: &mut Sim, vars: &Variables, thermo: &ThermoConfig, a: &mut Args) -> Result<(), ScriptError> {
    let selected = selection(sim, a)?;
    if a.remaining() == 0 {
        return Err(a.err(format!("missing argument: expected a keyword ({KEYWORDS}) and its value")));
    }
    let (mvv2e, kb) = (sim.units.mvv2e, sim.units.kb);
    while a.remaining() > 0 {
        let key = a.word("a keyword")?;
        let value = |a: &mut Args, sim: &Sim, what: &str| value(a, sim, vars, thermo, what);
        match key {
            "type" => {
                let v = value(a, sim, "the new type")?;
                let ntypes = sim.ntypes as f64;
                let s = &mut sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?.store;
                for &i in &selected {
                    let t = v.at(i);
                    if t.fract() != 0.0 || t < 1.0 || t > ntypes {
                        return Err(a.err(format!("type {t} of particle {} is not one of 1..{ntypes}", s.tag[i])));
                    }
                    retype(s, i, t as u32, &sim.masses, mvv2e);
                }
            }
            "type/fraction" => {
                let t = a.range("a particle type", sim.ntypes as u64)?;
                let fraction = a.f64("the fraction")?;
                let seed = a.u64("the random seed")?;
                if t.start() != t.end() || !(0.0..=1.0).contains(&fraction) || seed == 0 || seed > MAX_SEED {
                    return Err(a.err(format!("set type/fraction takes one type, a fraction in [0, 1] and a seed in 1..{MAX_SEED}")));
                }
                let s = &mut sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?.store;
                for &i in &selected {
                    // LAMMPS: a stream keyed by (seed, position), so any rank count agrees
                    if Park::at(seed, s.r[i]).uniform() < fraction {
                        retype(s, i, *t.start() as u32, &sim.masses, mvv2e);
                    }
                }
            }
            "x" | "y" | "z" => {
                let d = usize::from(key.as_bytes()[0] - b'x');
                let v = value(a, sim, "the coordinate")?;
                let s = &mut sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?.store;
                // the next run wraps them into the box (as LAMMPS's next reneighbouring)
                for &i in &selected {
                    s.r[i][d] = v.at(i);
                }
            }
            "vx" | "vy" | "vz" => {
                let d = usize::from(key.as_bytes()[1] - b'x');
                let v = value(a, sim, "the velocity")?;
                let s = &mut sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?.store;
                for &i in &selected {
                    let m = s.mass[i];
                    s.p[i][d] = if m.is_finite() { m * v.at(i) } else { v.at(i) };
                }
            }
            "image" => {
                let mut flags = [None; 3];
                for (d, f) in flags.iter_mut().enumerate() {
                    let w = a.word(&format!("the {} image flag (an integer or NULL)", ["x", "y", "z"][d]))?;
                    if w != "NULL" {
                        *f = Some(w.parse::<i32>().map_err(|_| a.err(format!("image flag: expected an integer or NULL, got '{w}'")))?);
                    }
                }
                let s = &mut sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?.store;
                for &i in &selected {
                    for d in 0..3 {
                        if let Some(f) = flags[d] {
                            s.image[i][d] = f;
                        }
                    }
                }
            }
            "theta" | "dpd/theta" => {
                // NULL: the particle's kinetic temperature m v^2 / (3 k_B) (LAMMPS)
                let v = if a.peek() == Some("NULL") {
                    a.word("NULL")?;
                    None
                } else {
                    Some(value(a, sim, "the particle temperature theta")?)
                };
                let s = &mut sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?.store;
                for &i in &selected {
                    let t = match &v {
                        Some(v) => v.at(i),
                        None => {
                            let u = velocity(s, i);
                            s.mass[i] * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) / (3.0 * kb)
                        }
                    };
                    if !(t > 0.0) {
                        return Err(a.err(format!("theta {t} of particle {} is not positive", s.tag[i])));
                    }
                    s.theta[i] = t;
                    s.theta_given[i] = true;
                }
            }
            "u" => {
                let v = value(a, sim, "the internal energy u")?;
                let s = &mut sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?.store;
                for &i in &selected {
                    s.u[i] = v.at(i);
                    s.theta_given[i] = false;
                }
            }
            "edpd/temp" | "edpd/cv" => {
                let what = if key == "edpd/temp" { "the eDPD temperature" } else { "the eDPD heat capacity" };
                let v = value(a, sim, what)?;
                let s = &mut sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?.store;
                if !s.has(Fields::EDPD) {
                    return Err(a.err(format!("set {key} needs atom_style edpd")));
                }
                for &i in &selected {
                    let x = v.at(i);
                    if !(x > 0.0) {
                        return Err(a.err(format!("{what} {x} of particle {} is not positive", s.tag[i])));
                    }
                    if key == "edpd/temp" {
                        (s.edpd_temp[i], s.vest_temp[i]) = (x, x);
                    } else {
                        s.edpd_cv[i] = x;
                    }
                }
            }
            "sph/rho" => {
                let v = value(a, sim, "the SPH density")?;
                let s = &mut sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?.store;
                if !s.has(Fields::SPH) {
                    return Err(a.err("set sph/rho needs atom_style sph"));
                }
                for &i in &selected {
                    s.rho[i] = v.at(i);
                }
            }
            "mass" => return Err(a.err(format!("keyword mass: atom style {} has no per-particle mass (as in LAMMPS; use the mass command)", sim.atom_style.name()))),
            k => return Err(a.err(format!("unknown set keyword '{k}'; known: {KEYWORDS}"))),
        }
    }
    Ok(())
}
