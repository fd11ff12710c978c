//! Atom-style variables (LAMMPS `variable NAME atom EXPR`): the expression evaluated for
//! each owned particle, with LAMMPS's per-atom names `id type mass x y z vx vy vz fx fy
//! fz` read from that particle and every other name (thermo keywords, `v_name` of
//! equal-style variables) global.

use gendpde_integrators::System;
use gendpde_io::Variables;

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
    (0..sys.store.nlocal).map(|i| vars.evaluate_atom(name, &|n| particle_value(sys, i, mvv2e, n).or_else(|| global(n)))).collect()
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
