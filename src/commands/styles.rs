//! Style commands: pair_style, pair_coeff, fix, unfix and compute. The styles parse
//! themselves (`styles`); these bodies keep the model's lists of them.

use crate::base::args::Args;
use crate::base::script::echo;
use crate::model::sim::Sim;
use crate::output::ave_time::AveTime;
use crate::styles::compute::{self, Definition};
use crate::styles::fix::parse_fix;
use crate::styles::pair::{parse_pair_coeff, parse_pair_style};
use gendpde_io::ScriptError;

/// `pair_style STYLE args...` (before or after the box, as LAMMPS).
pub fn pair_style(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    sim.pair = Some(parse_pair_style(a.command())?);
    sim.pair_text = vec![echo(a.command())];
    Ok(())
}

/// `pair_coeff I J args...` for the pair style in force.
pub fn pair_coeff(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    if sim.system.is_none() {
        return Err(a.err("pair_coeff before the box exists (create_box, read_data or read_restart)"));
    }
    let pair = sim.pair.as_mut().ok_or_else(|| a.err("pair_coeff before pair_style"))?;
    parse_pair_coeff(a.command(), pair, sim.ntypes)?;
    sim.pair_text.push(echo(a.command()));
    Ok(())
}

/// `fix ID GROUP STYLE args...`: a style fix (redefining an ID of the same style replaces
/// it) or a `fix ave/time` output (into `averages`).
pub fn fix(sim: &mut Sim, averages: &mut Vec<AveTime>, a: &mut Args) -> Result<(), ScriptError> {
    let cmd = a.command();
    if cmd.args.get(2).map(String::as_str) == Some("ave/time") {
        let id = a.word("a fix ID")?.to_string();
        let group = a.word("a group")?;
        if group != "all" {
            return Err(a.err(format!("group '{group}': fixes act on group all")));
        }
        a.word("ave/time")?;
        if sim.fixes.iter().any(|f| f.id == id) {
            return Err(a.err(format!("fix ID '{id}' is in use by another style (unfix it first)")));
        }
        let step = sim.system.as_ref().map_or(0, |s| s.step);
        let fix = AveTime::parse(id, a, &sim.rdfs, step)?;
        averages.retain(|f| f.id != fix.id);
        averages.push(fix);
        return Ok(());
    }
    let fix = parse_fix(cmd, sim.units.kb, &sim.groups)?;
    if averages.iter().any(|f| f.id == fix.id) {
        return Err(a.err(format!("fix ID '{}' is in use by another style (unfix it first)", fix.id)));
    }
    match sim.fixes.iter_mut().find(|f| f.id == fix.id) {
        Some(old) if std::mem::discriminant(&old.style) != std::mem::discriminant(&fix.style) => {
            return Err(a.err(format!("fix ID '{}' is in use by another style (unfix it first)", fix.id)));
        }
        Some(old) => *old = fix,
        None => sim.fixes.push(fix),
    }
    sim.check_density_cap().map_err(|e| a.err(e))
}

/// `unfix ID`: a style fix or a fix ave/time.
pub fn unfix(sim: &mut Sim, averages: &mut Vec<AveTime>, a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a fix ID")?;
    a.done()?;
    let before = sim.fixes.len() + averages.len();
    sim.fixes.retain(|f| f.id != id);
    averages.retain(|f| f.id != id);
    if sim.fixes.len() + averages.len() == before {
        return Err(a.err(format!("no fix with ID '{id}'")));
    }
    Ok(())
}

/// `compute ID GROUP STYLE args...` (redefining an ID replaces it).
pub fn compute(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let def = compute::parse(a, &sim.groups)?;
    sim.computes.retain(|c| c.id != def.id());
    sim.rdfs.retain(|r| r.id != def.id());
    match def {
        Definition::Value(c) => sim.computes.push(c),
        Definition::Rdf(r) => sim.rdfs.push(r),
    }
    Ok(())
}
