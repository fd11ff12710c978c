//! `write_restart FILE`, `read_restart FILE` and `checkpoint N FILE`: HDF5 restart files
//! holding everything a continuation needs (clock, box, every restart field of the
//! particle table with the particles' cells, build positions, group bits and the forces
//! of the last step, group names, the state of fixes, the style commands), so that a
//! run continued from a restart is bit-identical to the uninterrupted run. Files are
//! written to FILE.tmp and renamed.

use crate::base::gather::sorted_rows;
use crate::model::sim::Sim;
use gendpde_engine::{stage, Comm, Domain, Fields, Particles, ProcGrid, Transport};
use gendpde_integrators::System;
use gendpde_io::{row_width, ColumnSpec, RestartHeader, RestartReader, RestartWriter};
use std::path::Path;

/// The restart columns of the store: every RESTART field of the particle table.
fn columns(store: &Particles) -> Vec<ColumnSpec> {
    store.record(stage::RESTART, true).iter().map(|c| ColumnSpec { name: c.field.name.into(), width: c.field.width, integer: c.field.integer }).collect()
}

/// Columns a restart file of an earlier gendpde may lack: a fresh set-up derives them (the
/// octant of the list order, added in part 5 of issue 21; the per-cell virial of the
/// Voronoi cells).
const DERIVED: [&str; 2] = ["octant", "virial"];

/// How a file's rows map onto this table's: the file's columns are this table's without
/// some [`DERIVED`] ones, which are filled with zeros.
struct Spread {
    /// (width, Some(offset in the file's row) or None for a column the file lacks).
    parts: Vec<(usize, Option<usize>)>,
    filled: usize,
    missing: Vec<String>,
}

impl Spread {
    fn row(&self, file_row: &[f64]) -> Vec<f64> {
        let mut row = Vec::with_capacity(file_row.len() + self.filled);
        for &(width, from) in &self.parts {
            match from {
                Some(k) => row.extend_from_slice(&file_row[k..k + width]),
                None => row.extend(std::iter::repeat_n(0.0, width)),
            }
        }
        row
    }
}

/// The [`Spread`] of a file with columns `file` onto `ours`, if its columns are ours less
/// some derived ones, in order.
fn spread(ours: &[ColumnSpec], file: &[ColumnSpec]) -> Option<Spread> {
    let mut theirs = file.iter().scan(0, |at, c| {
        let start = *at;
        *at += c.width;
        Some((c, start))
    });
    let mut next = theirs.next();
    let mut out = Spread { parts: Vec::new(), filled: 0, missing: Vec::new() };
    for c in ours {
        match next {
            Some((f, start)) if f == c => {
                out.parts.push((c.width, Some(start)));
                next = theirs.next();
            }
            _ if DERIVED.contains(&c.name.as_str()) => {
                out.parts.push((c.width, None));
                out.filled += c.width;
                out.missing.push(c.name.clone());
            }
            _ => return None,
        }
    }
    next.is_none().then_some(out)
}

/// Writes the current state (rank 0 writes; every rank must call).
pub fn write(sim: &Sim, file: &str) -> Result<(), String> {
    let sys = sim.system.as_ref().ok_or("no box to write")?;
    let header = RestartHeader {
        step: sys.clock.step,
        time: sys.clock.time,
        dt: sim.dt,
        natoms: sys.comm.count(sys.store.nlocal),
        max_tag: sim.max_tag,
        ntypes: sim.ntypes,
        lo: sys.domain.lo,
        hi: sys.domain.hi,
        masses: sim.masses.clone(),
        energy0: sim.energy0,
        last_build: sys.lists.last,
        noise_shift: sys.clock.noise_shift,
        stale_tallies: !sys.control.tallied,
        cell_counts: sys.grid.as_ref().map(|g| g.count),
        commands: sim.style_commands(),
        creator_version: env!("CARGO_PKG_VERSION").into(),
        columns: columns(&sys.store),
        enabled: sys.store.enabled().bits(),
        groups: sim.groups.clone(),
        state: sim.fix_state(),
    };
    let mut writer = if sys.comm.rank() == 0 { Some(RestartWriter::create(Path::new(file), &header).map_err(|e| e.0)?) } else { None };
    let s = &sys.store;
    let row = |i: usize, b: &mut Vec<f64>| s.pack(i, stage::RESTART, true, b);
    let mut emit = |buf: &[f64]| -> Result<(), String> {
        match writer.as_mut() {
            Some(w) => w.write_rows(buf).map_err(|e| e.0),
            None => Ok(()),
        }
    };
    sorted_rows(sys, sim.max_tag, row_width(&header.columns), row, &mut emit)?;
    match writer {
        Some(w) => w.finish().map_err(|e| e.0),
        None => Ok(()),
    }
}

/// Reads the box and particles of a restart file into a system, and the settings into
/// `sim`; returns the system and the style commands to execute (the first, `units` and
/// `atom_style`, before the box exists). Every rank reads the file in blocks and keeps
/// the particles of its part.
pub fn read(sim: &mut Sim, file: &str, transport: Box<dyn Transport>) -> Result<(System, Vec<String>), String> {
    let reader = RestartReader::open(Path::new(file)).map_err(|e| e.0)?;
    let h = reader.header().clone();
    let domain = Domain::new(h.lo, h.hi);
    let procs = ProcGrid::choose(transport.size(), domain.len(), sim.procs)?;
    let mut sys = System::new(domain, Comm::new(transport, procs));
    sys.store.enable(Fields::from_bits(h.enabled));
    let ours = columns(&sys.store);
    let Some(spread) = spread(&ours, &h.columns) else {
        let names: Vec<&str> = h.columns.iter().map(|c| c.name.as_str()).collect();
        return Err(format!("restart file {file}: its particle columns {names:?} are not those of this gendpde's particle table"));
    };
    let width = row_width(&h.columns);
    // each rank keeps the particles of the cells it will own (all of them on the grid
    // the file was written on), so the set-up moves none and keeps their forces
    let at = |name| sys.store.record(stage::RESTART, true).iter().find(|c| c.field.name == name).map_or(0, |c| c.offset);
    let (x_at, cell_at) = (at("x"), at("cell"));
    let mut rows = Vec::new();
    let mut start = 0;
    while start < h.natoms {
        reader.read_rows(start, crate::base::gather::BLOCK, &mut rows).map_err(|e| e.0)?;
        for row in rows.chunks_exact(width) {
            let mine = match h.cell_counts {
                Some(count) => sys.comm.owns_cell([0, 1, 2].map(|d| row[cell_at + d] as i32), count),
                None => sys.comm.keeps(&sys.domain, [row[x_at], row[x_at + 1], row[x_at + 2]]),
            };
            if !mine {
                continue;
            }
            let s = &mut sys.store;
            s.push(0, 0, 0.0, [0.0; 3]);
            s.unpack(s.nlocal - 1, stage::RESTART, true, &spread.row(row));
        }
        start += crate::base::gather::BLOCK;
    }
    sys.clock.step = h.step;
    sys.clock.time = h.time;
    sys.lists.last = h.last_build;
    sys.clock.noise_shift = h.noise_shift;
    sys.control.tallied = !h.stale_tallies;
    sys.control.restored = true;
    sys.control.restored_grid = h.cell_counts;
    if spread.filled > 0 {
        // a file of an earlier gendpde: its list order and last forces cannot be redone
        log::warn!(
            "restart file {file} was written before the particle columns {:?}: the run after it sets up afresh (lists, forces), \
             so it does not continue the writer's trajectory bit for bit",
            spread.missing
        );
        sys.control.restored = false;
    }
    sim.ntypes = h.ntypes;
    sim.masses = h.masses;
    sim.max_tag = h.max_tag;
    sim.energy0 = h.energy0;
    sim.dt = h.dt;
    sim.groups = h.groups;
    sim.restored_state = h.state;
    Ok((sys, h.commands))
}
