//! The particles to and from files: `read_data FILE` and `write_data FILE [keywords]`
//! (LAMMPS data files of atom styles atomic, dpd, mdpd and edpd, whose `dpdTheta` column sets
//! the particle temperature, so LAMMPS DPDE inputs run unchanged; `Pair Coeffs` and
//! `PairIJ Coeffs` as pair_coeff commands), `read_restart FILE` and `write_restart FILE`
//! (`output::restart`).

use crate::base::args::Args;
use crate::commands::styles::pair_coeff;
use crate::model::sim::Sim;
use crate::output::restart;
use gendpde_engine::{Comm, Domain, Fields, ProcGrid};
use gendpde_integrators::System;
use gendpde_io::{Command, DataAtom, DataFile, Location, PairCoeffs, ScriptError};
use std::path::Path;

/// `read_data FILE`: creates the box, the types' masses and the particles of a data
/// file. Every rank parses the file and keeps the particles of its part of the box.
pub fn read_data(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    if sim.system.is_some() {
        return Err(a.err("the box exists already"));
    }
    let transport = sim.take_transport().map_err(|e| a.err(e))?;
    let file = a.word("a data file")?;
    a.done()?;
    let data = gendpde_io::read_data(Path::new(file), sim.atom_style).map_err(|e| if e.loc.is_some() { e } else { a.err(e.message) })?;
    let domain = Domain::new(data.lo, data.hi);
    let procs = ProcGrid::choose(transport.size(), domain.len(), sim.procs).map_err(|e| a.err(e))?;
    let mut sys = System::new(domain, Comm::new(transport, procs));
    sys.store.enable(sim.atom_style_fields());
    let max_tag = data.atoms.iter().map(|at| at.tag).max().unwrap_or(0);
    if max_tag > u32::MAX as u64 {
        return Err(a.err(format!("particle ID {max_tag} in '{file}' does not fit in 32 bits")));
    }
    let velocities: std::collections::HashMap<u64, [f64; 3]> = data.velocities.iter().flatten().copied().collect();
    for at in &data.atoms {
        if !sys.comm.keeps(&sys.domain, at.r) {
            continue;
        }
        let mass = data.masses[at.kind as usize - 1].map_or(f64::NAN, |m| m * sim.units.mvv2e);
        sys.store.push(at.tag, at.kind, mass, at.r);
        let i = sys.store.nlocal - 1;
        sys.store.image[i] = at.image;
        if let Some(v) = velocities.get(&at.tag) {
            // without a mass yet p holds the velocity; the `mass` command scales it
            sys.store.p[i] = if mass.is_finite() { v.map(|c| c * mass) } else { *v };
        }
        if let Some(theta) = at.theta {
            sys.store.theta[i] = theta;
            sys.store.theta_given[i] = true;
        }
        if let Some([t, cv]) = at.edpd {
            (sys.store.edpd_temp[i], sys.store.edpd_cv[i], sys.store.vest_temp[i]) = (t, cv, t);
        }
        if let Some(rho) = at.sph_rho {
            sys.store.rho[i] = rho;
        }
    }
    sim.ntypes = data.ntypes;
    sim.masses = data.masses;
    sim.max_tag = max_tag;
    sim.system = Some(sys);
    if let Some(section) = &data.pair_coeffs {
        pair_coeffs_of_data(sim, a, file, section)?;
    }
    sim.check_density_cap().map_err(|e| a.err(e))
}

/// The lines of a `Pair Coeffs` (`I args` = `pair_coeff I I args`) or `PairIJ Coeffs`
/// section (`I J args`), applied as pair_coeff commands located in the data file.
fn pair_coeffs_of_data(sim: &mut Sim, a: &Args, file: &str, section: &PairCoeffs) -> Result<(), ScriptError> {
    let name = if section.ij { "PairIJ Coeffs" } else { "Pair Coeffs" };
    if sim.pair.is_none() {
        return Err(a.err(format!("'{file}' has a {name} section: define the pair style (pair_style) before read_data")));
    }
    for (row, &line) in section.rows.iter().zip(&section.lines) {
        let mut args = row.clone();
        if !section.ij {
            args.insert(1, row[0].clone());
        }
        let cmd = Command { name: "pair_coeff".into(), args, loc: Location { file: file.into(), line } };
        pair_coeff(sim, &mut Args::new(&cmd))?;
    }
    Ok(())
}

/// `write_data FILE [nocoeff] [nofix] [pair ii|ij]`: the current particles as a data
/// file (rank 0 gathers them; its memory holds the whole system, about 100 bytes per
/// particle), with the pair coefficients of `pair dpd` (the one style of ours whose LAMMPS
/// counterpart writes them) as `Pair Coeffs` (`i a0 gamma`, default) or `PairIJ Coeffs`
/// (`i j a0 gamma cutoff`).
pub fn write_data(sim: &Sim, a: &mut Args) -> Result<(), ScriptError> {
    let file = a.word("a data file")?;
    let (mut coeff, mut ij) = (true, false);
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "nocoeff" => coeff = false,
            "nofix" => {}
            "pair" => {
                ij = match a.word("ii or ij")? {
                    "ii" => false,
                    "ij" => true,
                    w => return Err(a.err(format!("expected ii or ij after pair, got '{w}'"))),
                }
            }
            w => return Err(a.err(format!("unknown keyword '{w}'; known: nocoeff, nofix, pair ii|ij"))),
        }
    }
    let sys = sim.system.as_ref().ok_or_else(|| a.err("write_data before create_box"))?;
    let pair_coeffs = match &sim.pair {
        Some(p) if coeff => p.data_section(sim.ntypes, ij).map_err(|e| a.err(e))?,
        _ => None,
    };
    if pair_coeffs.is_some() && !ij && sim.ntypes > 1 && sys.comm.rank() == 0 {
        // LAMMPS's warning: these styles do not mix, so the I != J pairs are lost
        log::warn!("write_data: Pair Coeffs keeps the I I coefficients only; use 'pair ij' to store all pair coeffs");
    }
    let s = &sys.store;
    let edpd = s.has(Fields::EDPD);
    let sph = s.has(Fields::SPH);
    let mut local = Vec::with_capacity(s.nlocal * 15);
    for i in 0..s.nlocal {
        let v = s.p[i].map(|c| c / s.mass[i]);
        local.extend_from_slice(&[s.tag[i] as f64, s.kind[i] as f64, s.theta[i], s.r[i][0], s.r[i][1], s.r[i][2]]);
        local.extend(s.image[i].iter().map(|&x| x as f64));
        local.extend_from_slice(&v);
        local.extend_from_slice(&if edpd { [s.edpd_temp[i], s.edpd_cv[i]] } else { [0.0; 2] });
        local.push(if sph { s.rho[i] } else { 0.0 });
    }
    let mut atoms = Vec::new();
    let mut velocities = Vec::new();
    sys.comm.transport().gather_to_root(&local, &mut |buf| {
        for row in buf.chunks_exact(15) {
            let tag = row[0] as u64;
            atoms.push(DataAtom {
                tag,
                kind: row[1] as u32,
                theta: Some(row[2]),
                edpd: edpd.then_some([row[12], row[13]]),
                sph_rho: sph.then_some(row[14]),
                r: [row[3], row[4], row[5]],
                image: [row[6] as i32, row[7] as i32, row[8] as i32],
            });
            velocities.push((tag, [row[9], row[10], row[11]]));
        }
    });
    let count = sys.comm.count(sys.store.nlocal);
    if sys.comm.rank() != 0 {
        return Ok(());
    }
    atoms.sort_unstable_by_key(|at| at.tag);
    velocities.sort_unstable_by_key(|v| v.0);
    let data = DataFile {
        title: format!("gendpde data file, step {}", sys.clock.step),
        natoms: count as usize,
        ntypes: sim.ntypes,
        lo: sys.domain.lo,
        hi: sys.domain.hi,
        masses: sim.masses.clone(),
        pair_coeffs,
        atoms,
        velocities: Some(velocities),
    };
    gendpde_io::write_data(Path::new(file), &data, sim.atom_style).map_err(|e| a.err(format!("writing '{file}': {e}")))
}

/// `write_restart FILE`.
pub fn write_restart(sim: &Sim, a: &mut Args) -> Result<(), ScriptError> {
    let file = a.word("a restart file")?;
    a.done()?;
    restart::write(sim, file).map_err(|e| a.err(e))
}

/// `read_restart FILE`: reads the box, particles and settings; returns the system and
/// the name and stored style commands, split into those to execute before the box
/// exists (`units`, `atom_style`) and after.
pub fn read_restart(sim: &mut Sim, a: &mut Args) -> Result<(System, String, [String; 2]), ScriptError> {
    let file = a.word("a restart file")?;
    a.done()?;
    if sim.system.is_some() {
        return Err(a.err("the box exists already"));
    }
    let transport = sim.take_transport().map_err(|e| a.err(e))?;
    let (system, commands) = restart::read(sim, file, transport).map_err(|e| a.err(e))?;
    let before_box = commands.iter().take_while(|c| c.starts_with("units ") || c.starts_with("atom_style ")).count();
    let text = |c: &[String]| c.join("\n") + "\n";
    Ok((system, format!("{file} (stored commands)"), [text(&commands[..before_box]), text(&commands[before_box..])]))
}
