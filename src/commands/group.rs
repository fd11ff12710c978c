//! `group ID region RID | type T... | id A[:B] ... | delete`: named sets of particles,
//! static as in LAMMPS (membership is decided when the command runs), carried as bits of
//! the particles' group masks.

use crate::base::args::Args;
use crate::base::groups::MAX_GROUPS;
use crate::model::sim::Sim;
use gendpde_io::ScriptError;

/// Runs a `group` command.
pub fn group(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let name = a.word("a group ID")?.to_string();
    if name == "all" {
        return Err(a.err("group all exists and cannot be changed"));
    }
    let style = a.word("region, type, id or delete")?;
    if style == "delete" {
        a.done()?;
        let k = sim.groups.iter().position(|g| *g == name).ok_or_else(|| a.err(format!("no group '{name}'")))?;
        let bit = 1u32 << k;
        if let Some(sys) = &mut sim.system {
            for m in &mut sys.store.groups {
                *m &= !bit;
            }
        }
        sim.groups[k].clear();
        return Ok(());
    }
    let sys = sim.system.as_mut().ok_or_else(|| a.err("group before create_box"))?;
    let s = &sys.store;
    let member: Vec<bool> = match style {
        "region" => {
            let id = a.word("a region ID")?;
            let region = sim.regions.get(id).ok_or_else(|| a.err(format!("no region with ID '{id}'")))?;
            (0..s.nlocal).map(|i| region.contains(s.r[i])).collect()
        }
        "type" => {
            let mut m = vec![false; s.nlocal];
            while a.remaining() > 0 {
                let r = a.range("a particle type", sim.ntypes as u64)?;
                (0..s.nlocal).filter(|&i| r.contains(&(s.kind[i] as u64))).for_each(|i| m[i] = true);
            }
            m
        }
        "id" => {
            let mut m = vec![false; s.nlocal];
            while a.remaining() > 0 {
                let w = a.word("an ID or range A:B")?;
                let (lo, hi) = match w.split_once(':') {
                    Some((x, y)) => (x.parse::<u64>(), y.parse::<u64>()),
                    None => (w.parse::<u64>(), w.parse::<u64>()),
                };
                let (Ok(lo), Ok(hi)) = (lo, hi) else { return Err(a.err(format!("expected an ID or a range A:B, got '{w}'"))) };
                (0..s.nlocal).filter(|&i| (lo..=hi).contains(&s.tag[i])).for_each(|i| m[i] = true);
            }
            m
        }
        other => return Err(a.err(format!("unknown group style '{other}'; known: region, type, id, delete"))),
    };
    a.done()?;
    let k = match sim.groups.iter().position(|g| *g == name) {
        Some(k) => k,
        None => match sim.groups.iter().position(String::is_empty) {
            Some(k) => k,
            None if sim.groups.len() < MAX_GROUPS => {
                sim.groups.push(String::new());
                sim.groups.len() - 1
            }
            None => return Err(a.err(format!("more than {MAX_GROUPS} groups"))),
        },
    };
    sim.groups[k] = name;
    // a group command adds to an existing group, as in LAMMPS
    for (i, yes) in member.into_iter().enumerate() {
        if yes {
            sys.store.groups[i] |= 1 << k;
        }
    }
    Ok(())
}
