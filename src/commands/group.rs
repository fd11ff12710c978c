//! `group ID STYLE args`: named sets of particles, static as in LAMMPS (membership is
//! decided when the command runs, and a second command with the same ID adds to the
//! group), carried as bits of the particles' group masks. Styles: region, type, id
//! (values, ranges A:B:C or a logical condition), variable, subtract, union, intersect,
//! empty, clear, delete and static; LAMMPS's "N atoms in group ID" follows each one that
//! assigns.

use crate::base::args::Args;
use crate::base::groups::{mask, MAX_GROUPS};
use crate::model::per_atom;
use crate::model::sim::Sim;
use crate::output::console::Output;
use crate::output::thermo::ThermoConfig;
use gendpde_io::{ScriptError, Variables};

/// Runs a `group` command.
pub fn group(sim: &mut Sim, vars: &Variables, thermo: &ThermoConfig, out: &mut Output, a: &mut Args) -> Result<(), ScriptError> {
    let name = a.word("a group ID")?.to_string();
    let style = a.word("a group style (region, type, id, variable, subtract, union, intersect, empty, clear, delete)")?;
    if sim.system.is_none() {
        return Err(a.err("Group command before simulation box is defined"));
    }
    let found = sim.groups.iter().position(|g| *g == name);
    if let s @ ("delete" | "clear") = style {
        a.done()?;
        if name == "all" {
            return Err(a.err(format!("Cannot {s} group all")));
        }
        let k = found.ok_or_else(|| a.err(format!("Could not find group {s} group ID {name}")))?;
        let bit = 1u32 << k;
        if let Some(sys) = &mut sim.system {
            sys.store.groups.iter_mut().for_each(|m| *m &= !bit);
        }
        if s == "delete" {
            sim.groups[k].clear();
        }
        return Ok(());
    }
    let sys = sim.system.as_ref().expect("the box exists");
    let s = &sys.store;
    let in_group = |a: &Args, g: &str| mask(&sim.groups, g, a).map_err(|_| a.err(format!("Group ID {g} does not exist")));
    // per owned particle: Some(true) joins the group, Some(false) leaves it (subtract)
    let change: Vec<Option<bool>> = match style {
        "region" => {
            let id = a.word("a region ID")?;
            let region = sim.regions.get(id).ok_or_else(|| a.err(format!("Region {id} for group region does not exist")))?;
            a.done()?;
            (0..s.nlocal).map(|i| region.contains(s.r[i]).then_some(true)).collect()
        }
        "type" | "id" => {
            let select = values(a)?;
            let value = |i: usize| if style == "type" { s.kind[i] as i64 } else { s.tag[i] as i64 };
            (0..s.nlocal).map(|i| select(value(i)).then_some(true)).collect()
        }
        "molecule" => return Err(a.err("Group molecule command requires atom attribute molecule")),
        "include" => return Err(a.err("Group include molecule command requires atom attribute molecule")),
        "variable" => {
            let v = a.word("an atom-style variable")?;
            a.done()?;
            match vars.style(v) {
                Some("atom") => {}
                Some(_) => return Err(a.err(format!("Variable {v} for group is invalid style"))),
                None => return Err(a.err(format!("Variable name {v} for group does not exist"))),
            }
            let global = |n: &str| super::resolve(sim, thermo, vars, n);
            let values = per_atom::variable(vars, v, sys, sim.units.mvv2e, &global).map_err(|e| a.err(e))?;
            values.iter().map(|&x| (x != 0.0).then_some(true)).collect()
        }
        op @ ("subtract" | "union" | "intersect") => {
            let least = if op == "union" { 1 } else { 2 };
            if a.remaining() < least {
                return Err(a.err(format!("Illegal group {op} command: missing argument(s)")));
            }
            let mut masks = Vec::new();
            while a.remaining() > 0 {
                let g = a.word("a group ID")?;
                masks.push(in_group(a, g)?);
            }
            (0..s.nlocal)
                .map(|i| {
                    let member = |m: &u32| s.in_group(i, *m);
                    match op {
                        // LAMMPS: add the first group's members, then take out every
                        // member of the others (the group's own earlier members too)
                        "subtract" if masks[1..].iter().any(member) => Some(false),
                        "subtract" => member(&masks[0]).then_some(true),
                        "union" => masks.iter().any(member).then_some(true),
                        _ => masks.iter().all(member).then_some(true),
                    }
                })
                .collect()
        }
        "empty" | "static" => {
            if a.remaining() > 0 {
                return Err(a.err(format!("Illegal group {style} command")));
            }
            vec![None; s.nlocal]
        }
        "dynamic" => return Err(a.err("group dynamic is not supported: groups are static (membership is decided when the group command runs)")),
        other => return Err(a.err(format!("Illegal group command: unknown style '{other}'; known: region, type, id, variable, subtract, union, intersect, empty, clear, delete, static"))),
    };
    let k = match (name.as_str(), found) {
        ("all", _) => None,
        (_, Some(k)) => Some(k),
        _ => match sim.groups.iter().position(String::is_empty) {
            Some(k) => Some(k),
            None if sim.groups.len() < MAX_GROUPS => {
                sim.groups.push(String::new());
                Some(sim.groups.len() - 1)
            }
            None => return Err(a.err("Too many groups")),
        },
    };
    let sys = sim.system.as_mut().expect("the box exists");
    let members = match k {
        None => sys.store.nlocal,
        Some(k) => {
            sim.groups[k] = name.clone();
            let bit = 1u32 << k;
            for (m, c) in sys.store.groups.iter_mut().zip(change) {
                match c {
                    Some(true) => *m |= bit,
                    Some(false) => *m &= !bit,
                    None => {}
                }
            }
            sys.store.groups[..sys.store.nlocal].iter().filter(|&&m| m & bit != 0).count()
        }
    };
    out.line(&format!("{} atoms in group {name}", sys.comm.count(members)));
    Ok(())
}

/// The selection of `group ID type|id args`: a logical condition (`< N`, `<= N`, `> N`,
/// `>= N`, `== N`, `!= N`, `<> A B` inclusive) or values and ranges `A`, `A:B`, `A:B:C`.
fn values(a: &mut Args) -> Result<Box<dyn Fn(i64) -> bool>, ScriptError> {
    let int = |a: &mut Args| {
        let w = a.word("an integer")?;
        w.parse::<i64>().map_err(|_| a.err(format!("Expected integer parameter instead of '{w}' in input script or data file")))
    };
    if a.remaining() == 0 {
        return Err(a.err("Illegal group command: missing argument(s)"));
    }
    let op = a.peek().unwrap_or_default();
    if ["<", "<=", ">", ">=", "==", "!=", "<>"].contains(&op) && a.remaining() > 1 {
        a.word("a condition")?;
        let x = int(a)?;
        let y = if op == "<>" { int(a)? } else { 0 };
        if a.remaining() > 0 {
            return Err(a.err("Illegal group command"));
        }
        return Ok(match op {
            "<" => Box::new(move |v| v < x),
            "<=" => Box::new(move |v| v <= x),
            ">" => Box::new(move |v| v > x),
            ">=" => Box::new(move |v| v >= x),
            "==" => Box::new(move |v| v == x),
            "!=" => Box::new(move |v| v != x),
            _ => Box::new(move |v| v >= x && v <= y),
        });
    }
    let mut ranges = Vec::new();
    while a.remaining() > 0 {
        let w = a.word("a value or range A:B:C")?;
        let parts: Vec<Option<i64>> = w.split(':').map(|p| p.parse().ok()).collect();
        let range = match parts[..] {
            [Some(x)] => (x, x, 1),
            [Some(x), Some(y)] => (x, y, 1),
            [Some(x), Some(y), Some(z)] => (x, y, z),
            [_] => return Err(a.err(format!("Incorrect range string '{w}': Not a valid integer number: '{w}'"))),
            _ => return Err(a.err(format!("Incorrect range string '{w}': Syntax error"))),
        };
        if range.2 <= 0 {
            return Err(a.err("Illegal range increment value"));
        }
        ranges.push(range);
    }
    Ok(Box::new(move |v| ranges.iter().any(|&(lo, hi, step)| v >= lo && v <= hi && (v - lo) % step == 0)))
}
