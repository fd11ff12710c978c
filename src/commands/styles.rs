//! Style commands: pair_style, pair_coeff, fix, fix_modify, unfix and compute. The styles parse
//! themselves (`styles`); these bodies keep the model's lists of them.

use crate::base::args::Args;
use crate::base::script::echo;
use crate::model::sim::Sim;
use crate::output::fix::{self as output_fix, OutputFixContext};
use crate::output::Outputs;
use crate::styles::compute::{self, ComputeContext, Definition};
use crate::styles::fix::{parse_fix_in, FixStyle};
use crate::styles::pair::parse_pair_style;
use gendpde_integrators::{FixRecord, Nph, NphState};
use gendpde_io::{ScriptError, Variables};

/// `pair_style STYLE args...` (before or after the box, as LAMMPS). The style in force
/// named again keeps its coefficients (see `Pair::keep_coefficients`); the restart's
/// command text then replays both lines.
pub fn pair_style(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let mut pair = parse_pair_style(a.command())?;
    let kept = sim.pair.as_deref().is_some_and(|old| pair.keep_coefficients(old));
    if !kept {
        sim.pair_text.clear();
    }
    sim.pair_text.push(echo(a.command()));
    sim.pair = Some(pair);
    Ok(())
}

/// `pair_coeff I J args...` for the pair style in force (also a line of a data file's
/// `Pair Coeffs` or `PairIJ Coeffs`, located in the data file).
pub fn pair_coeff(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    if sim.system.is_none() {
        return Err(a.err("pair_coeff before the box exists (create_box, read_data or read_restart)"));
    }
    let pair = sim.pair.as_mut().ok_or_else(|| a.err("pair_coeff before pair_style"))?;
    pair.coeff(a.command(), sim.ntypes)?;
    sim.pair_text.push(echo(a.command()));
    Ok(())
}

/// `fix ID GROUP STYLE args...`: a style fix (redefining an ID of the same style replaces
/// it) or an output fix (`output::fix`, into `outputs`; redefining one replaces it).
pub fn fix(sim: &mut Sim, outputs: &mut Outputs, vars: &Variables, a: &mut Args) -> Result<(), ScriptError> {
    let cmd = a.command();
    let style = cmd.args.get(2).map(String::as_str).unwrap_or("");
    if output_fix::is_output_fix(style) {
        let id = a.word("a fix ID")?.to_string();
        let group = a.word("a group")?;
        a.word("a fix style")?;
        let other_style = outputs.fix(&id).is_some_and(|f| f.style() != style);
        if other_style || sim.fixes.iter().any(|f| f.id == id) {
            return Err(a.err(format!("fix ID '{id}' is in use by another style (unfix it first)")));
        }
        let step = sim.system.as_ref().map_or(0, |s| s.clock.step);
        let context = OutputFixContext { id, group, sim, vars, step };
        let fix = output_fix::parse(style, a, &context)?;
        let id = fix.id().to_string();
        match fix.published() {
            Some(values) => sim.fix_values.insert(id.clone(), values.clone()),
            None => sim.fix_values.remove(&id),
        };
        outputs.fixes.retain(|f| f.id() != id);
        outputs.fixes.push(fix);
        return Ok(());
    }
    let mut fix = parse_fix_in(cmd, sim.units.kb, &sim.groups, &sim.regions)?;
    if let FixStyle::Nph { nph, fixedpoint } = &mut fix.style {
        define_barostat(sim, nph, *fixedpoint).map_err(|e| a.err(e))?;
    }
    if outputs.fix(&fix.id).is_some() {
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

/// A new `fix nph`: the units' pressure conversion and its state at rest with the fixed
/// point (by default the box centre now). gendpde's boxes are periodic, as LAMMPS requires
/// along barostatted dimensions.
fn define_barostat(sim: &mut Sim, nph: &mut Nph, fixedpoint: Option<[f64; 3]>) -> Result<(), String> {
    nph.nktv2p = sim.units.nktv2p;
    let sys = sim.system.as_mut().ok_or("fix nph before the box exists (create_box, read_data or read_restart)")?;
    let d = &sys.domain;
    let centre = [0, 1, 2].map(|k| 0.5 * (d.lo[k] + d.hi[k]));
    sys.fixes.set(&nph.id, FixRecord::Nph(Box::new(NphState::new(&nph.id, nph.pchain, fixedpoint.unwrap_or(centre)))));
    Ok(())
}

/// `fix_modify ID temp CID` of a `fix nph`: the compute temp (of a group) whose temperature
/// sets T0, the MTK term and the kinetic part of the barostat's pressure. Its group and
/// extra dof are read now (a later compute_modify does not reach the fix).
pub fn fix_modify(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a fix ID")?;
    let Some(fix) = sim.fixes.iter_mut().find(|f| f.id == id) else {
        return Err(a.err(format!("Could not find fix_modify ID {id}")));
    };
    let FixStyle::Nph { nph, .. } = &mut fix.style else {
        return Err(a.err(format!("fix {id}: gendpde's fix_modify takes temp for fix nph only")));
    };
    if a.remaining() == 0 {
        return Err(a.err("expected a keyword: temp"));
    }
    while let Some(k) = a.peek() {
        a.word("keyword")?;
        match k {
            "temp" => {
                let cid = a.word("a compute temp ID")?;
                let c = compute::find(&sim.computes, cid).ok_or_else(|| a.err(format!("Could not find fix_modify temperature ID {cid}")))?;
                let Some((mask, extra_dof)) = c.temp_group() else {
                    return Err(a.err(format!("Fix_modify temperature ID {cid} does not compute temperature")));
                };
                (nph.temp_mask, nph.extra_dof) = (mask, extra_dof);
            }
            "press" => {
                a.word("a compute pressure ID")?;
                return Err(a.err(
                    "fix_modify press: gendpde has no compute pressure; fix nph reads the virial pressure of all particles with the kinetic part of its temperature compute (fix_modify temp)",
                ));
            }
            _ => return Err(a.err(format!("unknown fix_modify keyword '{k}' for fix nph; known: temp, press"))),
        }
    }
    Ok(())
}

/// `unfix ID`: a style fix or an output fix.
pub fn unfix(sim: &mut Sim, outputs: &mut Outputs, a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a fix ID")?;
    a.done()?;
    if !sim.fixes.iter().any(|f| f.id == id) && outputs.fix(id).is_none() {
        return Err(a.err(format!("no fix with ID '{id}'")));
    }
    sim.fixes.retain(|f| f.id != id);
    if let Some(sys) = &mut sim.system {
        sys.fixes.remove(id);
    }
    outputs.fixes.retain(|f| f.id() != id);
    sim.fix_values.remove(id);
    Ok(())
}

/// `compute ID GROUP STYLE args...` (redefining an ID replaces it).
pub fn compute(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let context = ComputeContext {
        id: String::new(),
        group: "",
        groups: &sim.groups,
        computes: &sim.computes,
        regions: &sim.regions,
        ntypes: sim.ntypes,
        spacing: sim.lattice_spacing(),
        system: sim.system.as_ref(),
        max_tag: sim.max_tag,
    };
    let def = compute::parse(a, context)?;
    sim.computes.retain(|c| c.id() != def.id());
    sim.rdfs.retain(|r| r.id != def.id());
    sim.chunks.retain(|r| r.id != def.id());
    match def {
        Definition::Compute(c) => sim.computes.push(c),
        Definition::Rdf(r) => sim.rdfs.push(r),
        Definition::Chunk(c) => sim.chunks.push(c),
    }
    Ok(())
}
