//! `delete_atoms group G | region R [compress yes|no]`, as LAMMPS's: deletes the
//! particles of a group or in a region, prints "Deleted N atoms, new total = M", and with
//! `compress yes` (the default) renumbers the remaining IDs 1..M in the order of their old
//! IDs (LAMMPS's order on one rank before any run; gendpde's on any rank count).
//! `overlap`, `porosity`, `random`, `variable` and the molecule keywords are refused.

use crate::base::args::Args;
use crate::base::gather::all_ranks;
use crate::model::sim::Sim;
use crate::output::console::Output;
use gendpde_io::ScriptError;

pub fn delete_atoms(sim: &mut Sim, out: &mut Output, a: &mut Args) -> Result<(), ScriptError> {
    let style = a.word("group or region")?;
    let sys = sim.system.as_mut().ok_or_else(|| a.err("Delete_atoms command before simulation box is defined"))?;
    let s = &sys.store;
    let doomed: Vec<bool> = match style {
        "group" => {
            let g = a.word("a group ID")?;
            let mask = crate::base::groups::mask(&sim.groups, g, a).map_err(|_| a.err(format!("Could not find delete_atoms group ID {g}")))?;
            (0..s.nlocal).map(|i| s.in_group(i, mask)).collect()
        }
        "region" => {
            let r = a.word("a region ID")?;
            let region = sim.regions.get(r).ok_or_else(|| a.err(format!("Could not find delete_atoms region ID {r}")))?;
            (0..s.nlocal).map(|i| region.contains(s.r[i])).collect()
        }
        s @ ("overlap" | "porosity" | "random" | "variable") => return Err(a.err(format!("delete_atoms {s} is not supported (group and region are)"))),
        s => return Err(a.err(format!("Unknown delete_atoms sub-command: {s}; expected group or region"))),
    };
    let mut compress = true;
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "compress" => compress = a.yes_no("compress")?,
            k @ ("bond" | "mol") => return Err(a.err(format!("delete_atoms {k}: gendpde's particles have no bonds or molecules"))),
            k => return Err(a.err(format!("Illegal delete_atoms command: unknown keyword {k}; known: compress"))),
        }
    }
    // references held by particle ID would point at other particles after renumbering
    let by_tag = sim.computes.iter().find(|c| matches!(c.style(), "msd" | "vacf")).map(|c| format!("compute {} {}", c.id(), c.style()));
    let by_tag = by_tag.or_else(|| sim.fix_values.iter().find(|(_, v)| v.per_atom.is_some()).map(|(id, _)| format!("fix {id} ave/atom")));
    if let (true, Some(what)) = (compress, by_tag) {
        return Err(a.err(format!("delete_atoms compress yes after {what}, which holds values by particle ID: define it after delete_atoms, or use compress no")));
    }
    let before = sys.comm.count(sys.store.nlocal);
    // (tag, deleted) of every owned particle, for the renumbering
    let gone: Vec<u64> = (0..doomed.len()).flat_map(|i| [sys.store.tag[i], u64::from(doomed[i])]).collect();
    sys.store.truncate_ghosts();
    for i in (0..doomed.len()).rev().filter(|&i| doomed[i]) {
        sys.store.remove_owned(i);
    }
    let after = sys.comm.count(sys.store.nlocal);
    if compress {
        let order = lammps_order(&all_ranks(sys, &gone));
        for t in &mut sys.store.tag[..sys.store.nlocal] {
            let k = order.binary_search_by_key(t, |&(tag, _)| tag).expect("every rank's tags are gathered");
            *t = order[k].1;
        }
        sim.max_tag = after;
    }
    out.line(&format!("Deleted {} atoms, new total = {after}", before - after));
    Ok(())
}

/// The new ID of each kept tag, sorted by tag, from `(tag, deleted)` pairs of every
/// particle: LAMMPS's delete loop (the last particle moves into a deleted one's place,
/// which is looked at again) over the particles in tag order, then IDs by place.
fn lammps_order(pairs: &[u64]) -> Vec<(u64, u64)> {
    let mut list: Vec<(u64, bool)> = pairs.chunks_exact(2).map(|c| (c[0], c[1] != 0)).collect();
    list.sort_unstable();
    let mut i = 0;
    while i < list.len() {
        if list[i].1 {
            list.swap_remove(i);
        } else {
            i += 1;
        }
    }
    let mut order: Vec<(u64, u64)> = list.iter().enumerate().map(|(k, &(tag, _))| (tag, k as u64 + 1)).collect();
    order.sort_unstable();
    order
}
