//! Atom-style variables (LAMMPS `variable NAME atom EXPR`): the expression evaluated for
//! each owned particle, with LAMMPS's per-atom names `id type mass x y z vx vy vz fx fy
//! fz` read from that particle and every other name (thermo keywords, `v_name` of
//! equal-style variables) global; and the inputs computes read ([`evaluate`]).

use crate::base::particle_keywords::Keyword;
use crate::model::sim::Sim;
use crate::styles::compute::{self, Eval};
use gendpde_integrators::System;
use gendpde_io::Variables;
use std::cell::RefCell;
use std::collections::HashMap;

/// The per-atom names [`particle_value`] reads.
const PARTICLE_NAMES: [&str; 12] = ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "mass", "type", "id"];

/// The value of per-atom name `name` of owned particle `i` (masses in the script's units:
/// the store's carry the factor `mvv2e`).
fn particle_value(sys: &System, i: usize, mvv2e: f64, name: &str) -> Option<f64> {
    let s = &sys.store;
    let axis = |c: u8| usize::from(c - b'x');
    Some(match name.as_bytes() {
        [c @ b'x'..=b'z'] => s.r[i][axis(*c)],
        [b'v', c @ b'x'..=b'z'] => s.p[i][axis(*c)] / s.mass[i],
        [b'f', c @ b'x'..=b'z'] => s.f[i][axis(*c)],
        b"mass" => s.mass[i] / mvv2e,
        b"type" => s.kind[i] as f64,
        b"id" => s.tag[i] as f64,
        _ => return None,
    })
}

/// The values of equal- or atom-style variable `name` for the owned particles (index:
/// the particle's slot); `global` resolves the names that are not per-particle.
pub fn variable(vars: &Variables, name: &str, sys: &System, mvv2e: f64, global: &dyn Fn(&str) -> Option<f64>) -> Result<Vec<f64>, String> {
    match vars.style(name) {
        Some("atom" | "atomfile" | "equal" | "internal" | "timer") => {}
        Some(style) => return Err(format!("variable '{name}' is {style}-style; expected an atom- or equal-style variable")),
        None => return Err(format!("unknown variable '{name}'")),
    }
    // The global names are collective (thermo keywords, group functions): each is
    // evaluated once, on every rank alike, by a first evaluation in which every
    // per-particle name reads the same value (the parser evaluates every operand), and
    // read from the cache for the particles, so ranks holding different numbers of
    // particles make the same reductions.
    let cache: RefCell<HashMap<String, Option<f64>>> = RefCell::default();
    let cached = |n: &str| {
        if let Some(&v) = cache.borrow().get(n) {
            return v;
        }
        let v = global(n);
        cache.borrow_mut().insert(n.to_string(), v);
        v
    };
    let probe = 0.5377;
    let _ = vars.evaluate_atom(name, &|n| if PARTICLE_NAMES.contains(&n) { Some(probe) } else { cached(n) });
    (0..sys.store.nlocal).map(|i| vars.evaluate_atom(name, &|n| particle_value(sys, i, mvv2e, n).or_else(|| cached(n)))).collect()
}

/// The value of equal-style variable `name`.
pub fn equal(vars: &Variables, name: &str, global: &dyn Fn(&str) -> Option<f64>) -> Result<f64, String> {
    match vars.style(name) {
        Some("equal" | "internal" | "timer") => vars.evaluate_atom(name, global),
        Some(style) => Err(format!("variable '{name}' is {style}-style; expected an equal-style variable")),
        None => Err(format!("unknown variable '{name}'")),
    }
}

/// The values of atom-style variable `name` for the owned particles (the inputs of dumps,
/// compute reduce and fix ave/chunk, which LAMMPS limits to atom-style variables).
pub fn atom_variable(vars: &Variables, name: &str, sys: &System, mvv2e: f64, global: &dyn Fn(&str) -> Option<f64>) -> Result<Vec<f64>, String> {
    match vars.style(name) {
        Some("atom" | "atomfile") => variable(vars, name, sys, mvv2e, global),
        Some(style) => Err(format!("variable '{name}' is {style}-style, not atom-style")),
        None => Err(format!("unknown variable '{name}'")),
    }
}

/// Runs `f` with the [`Eval`] the computes of `sim` read: its per-atom inputs are the
/// particle keywords, `c_ID`/`c_ID[k]` of per-atom computes and `v_name` of atom-style
/// variables; `global` resolves the names of the variables that are not per-particle.
pub fn evaluate<R>(sim: &Sim, sys: &System, vars: &Variables, global: &dyn Fn(&str) -> Option<f64>, f: impl FnOnce(&Eval) -> R) -> R {
    let input = |name: &str| input(sim, sys, vars, global, name);
    f(&Eval { sys, units: &sim.units, pair_energy: sim.pe_is_pair(), input: &input })
}

/// The per-atom values of `name` by owned particle: a particle keyword (x, vx, fx, ...),
/// `c_ID` or `c_ID[k]` of a per-atom compute, `v_name` of an atom-style variable.
pub fn input(sim: &Sim, sys: &System, vars: &Variables, global: &dyn Fn(&str) -> Option<f64>, name: &str) -> Result<Vec<f64>, String> {
    if let Some(v) = name.strip_prefix("v_") {
        return atom_variable(vars, v, sys, sim.units.mvv2e, global);
    }
    if name.starts_with("f_") {
        let (ncol, col, values) = fix_values(sim, name).ok_or_else(|| format!("{name}: no fix with per-atom values of that ID (or no such column)"))?;
        let s = &sys.store;
        return Ok((0..s.nlocal).map(|i| values.get((s.tag[i] as usize - 1) * ncol + col).copied().unwrap_or(0.0)).collect());
    }
    if name.starts_with("c_") {
        return evaluate(sim, sys, vars, global, |e| compute::per_atom(&sim.computes, e, name)).unwrap_or_else(|| Err(format!("{name}: no per-atom compute of that ID (or no such column)")));
    }
    let keyword = Keyword::find(name).ok_or_else(|| format!("unknown per-atom input '{name}'"))?;
    let reader = keyword.reader(&sys.store)?;
    Ok((0..sys.store.nlocal).map(|i| reader.get(sys, i)).collect())
}

/// The per-atom values `f_ID` (one column) or `f_ID[k]` name: the fix's column count,
/// the column (from 0) and its values by tag; None if it names none.
pub fn fix_values<'a>(sim: &'a Sim, name: &str) -> Option<(usize, usize, &'a [f64])> {
    let ('f', id, index) = compute::reference(name)? else { return None };
    let (ncol, values) = sim.fix_values.get(id)?.per_atom.as_ref()?;
    let col = match index {
        None if *ncol == 1 => 0,
        Some(k) if (1..=*ncol).contains(&k) => k - 1,
        _ => return None,
    };
    Some((*ncol, col, values))
}
