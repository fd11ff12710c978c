//! `write_restart FILE`, `read_restart FILE` and `checkpoint N FILE`: HDF5 restart files
//! holding everything the dynamics needs (clock, box, particles with their cells and
//! build positions, the style commands), so that a run continued from a restart is
//! bit-identical to the uninterrupted run. Files are written to FILE.tmp and renamed.

use crate::base::gather::sorted_rows;
use crate::model::sim::Sim;
use gendpde_engine::{Comm, Domain, ProcGrid, Transport};
use gendpde_integrators::System;
use gendpde_io::{ParticleRows, RestartHeader, RestartReader, RestartWriter};
use std::path::Path;

/// Values per particle in the gathered rows: tag, type, mass, r, p, u, theta, image,
/// cell, r_build.
const WIDTH: usize = 20;

/// Writes the current state (rank 0 writes; every rank must call).
pub fn write(sim: &Sim, file: &str) -> Result<(), String> {
    let sys = sim.system.as_ref().ok_or("no box to write")?;
    let header = RestartHeader {
        step: sys.step,
        time: sys.time,
        dt: sim.dt,
        natoms: crate::output::thermo::Observables::measure(sys).atoms as u64,
        max_tag: sim.max_tag,
        ntypes: sim.ntypes,
        lo: sys.domain.lo,
        hi: sys.domain.hi,
        masses: sim.masses.clone(),
        energy0: sim.energy0,
        last_build: sys.last_build,
        cell_counts: sys.grid.as_ref().map(|g| g.count),
        commands: sim.style_commands(),
        creator_version: env!("CARGO_PKG_VERSION").into(),
    };
    let mut writer = if sys.comm.rank() == 0 { Some(RestartWriter::create(Path::new(file), &header).map_err(|e| e.0)?) } else { None };
    let s = &sys.store;
    let row = |i: usize, b: &mut Vec<f64>| {
        b.extend_from_slice(&[s.tag[i] as f64, s.kind[i] as f64, s.mass[i]]);
        b.extend_from_slice(&s.r[i]);
        b.extend_from_slice(&s.p[i]);
        b.extend_from_slice(&[s.u[i], s.theta[i]]);
        b.extend(s.image[i].iter().chain(&s.cell[i]).map(|&x| x as f64));
        b.extend_from_slice(&s.r_build[i]);
    };
    let mut rows = ParticleRows::default();
    let mut emit = |buf: &[f64]| -> Result<(), String> {
        let Some(w) = writer.as_mut() else { return Ok(()) };
        rows.clear();
        for r in buf.chunks_exact(WIDTH) {
            rows.tag.push(r[0] as u64);
            rows.kind.push(r[1] as u32);
            rows.mass.push(r[2]);
            rows.r.push([r[3], r[4], r[5]]);
            rows.p.push([r[6], r[7], r[8]]);
            rows.u.push(r[9]);
            rows.theta.push(r[10]);
            rows.image.push([r[11] as i32, r[12] as i32, r[13] as i32]);
            rows.cell.push([r[14] as i32, r[15] as i32, r[16] as i32]);
            rows.r_at_build.push([r[17], r[18], r[19]]);
        }
        w.write_rows(&rows).map_err(|e| e.0)
    };
    sorted_rows(sys, sim.max_tag, WIDTH, row, &mut emit)?;
    match writer {
        Some(w) => w.finish().map_err(|e| e.0),
        None => Ok(()),
    }
}

/// Creates the box and particles of a restart file and returns the style commands to
/// execute. Every rank reads the file in blocks and keeps the particles of its part.
pub fn read(sim: &mut Sim, file: &str, transport: Box<dyn Transport>) -> Result<Vec<String>, String> {
    let reader = RestartReader::open(Path::new(file)).map_err(|e| e.0)?;
    let h = reader.header().clone();
    let domain = Domain::new(h.lo, h.hi);
    let procs = ProcGrid::choose(transport.size(), domain.len(), sim.procs)?;
    let mut sys = System::new(domain, Comm::new(transport, procs));
    let mut rows = ParticleRows::default();
    let mut start = 0;
    while start < h.natoms {
        reader.read_rows(start, crate::base::gather::BLOCK, &mut rows).map_err(|e| e.0)?;
        for k in 0..rows.len() {
            if !sys.comm.keeps(&sys.domain, rows.r[k]) {
                continue;
            }
            let s = &mut sys.store;
            s.push(rows.tag[k], rows.kind[k], rows.mass[k], rows.r[k]);
            let i = s.nlocal - 1;
            s.p[i] = rows.p[k];
            s.u[i] = rows.u[k];
            s.theta[i] = rows.theta[k];
            s.image[i] = rows.image[k];
            s.cell[i] = rows.cell[k];
            s.r_build[i] = rows.r_at_build[k];
        }
        start += crate::base::gather::BLOCK;
    }
    sys.step = h.step;
    sys.time = h.time;
    sys.last_build = h.last_build;
    sys.restored = true;
    sys.restored_grid = h.cell_counts;
    sim.ntypes = h.ntypes;
    sim.masses = h.masses;
    sim.max_tag = h.max_tag;
    sim.energy0 = h.energy0;
    sim.dt = h.dt;
    sim.system = Some(sys);
    Ok(h.commands)
}
