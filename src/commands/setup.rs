//! Setup and settings: units, dimension, boundary, atom_style, lattice, region,
//! processors, create_box, create_atoms, mass, timestep, neighbor, neigh_modify,
//! reset_timestep, run_style and atom_modify.

use crate::base::args::Args;
use crate::base::lattice::{random_points, Lattice, LatticeOptions, Overlap};
use crate::base::park::MAX_SEED;
use crate::base::region::{Region, Shape};
use crate::base::memory;
use crate::base::units::Units;
use crate::model::sim::Sim;
use crate::output::thermo::ThermoConfig;
use gendpde_engine::{Comm, Domain, Fields, ProcGrid, Vec3};
use gendpde_integrators::System;
use gendpde_io::{AtomStyle, ScriptError};

/// `units lj|real|metal|micro`: before the box; resets the timestep, skin and thermo norm to the
/// units' defaults.
pub fn units(sim: &mut Sim, thermo: &mut ThermoConfig, a: &mut Args) -> Result<(), ScriptError> {
    let known = Units::ALL.map(|u| u.name).join(", ");
    let w = a.word(&format!("a unit style ({known})"))?;
    let units = Units::parse(w).ok_or_else(|| a.err(format!("units {w}: known are {known}")))?;
    a.done()?;
    if sim.system.is_some() && units != sim.units {
        return Err(a.err("units must come before the box is created"));
    }
    if units != sim.units {
        sim.units = units;
        sim.dt = units.default_dt;
        sim.skin = units.default_skin;
        thermo.norm = units.default_norm;
    }
    Ok(())
}

/// `dimension 3`.
pub fn dimension(a: &mut Args) -> Result<(), ScriptError> {
    match a.word("the dimension")? {
        "3" => a.done(),
        d => Err(a.err(format!("dimension {d}: only 3 is supported"))),
    }
}

/// `boundary p p p`.
pub fn boundary(a: &mut Args) -> Result<(), ScriptError> {
    for axis in ["x", "y", "z"] {
        match a.word(&format!("the boundary along {axis}"))? {
            "p" => {}
            b => return Err(a.err(format!("boundary '{b}' along {axis}: only periodic (p) is supported"))),
        }
    }
    a.done()
}

/// `atom_style atomic|dpd|gendpde|mdpd|edpd|sph`: the columns of data files (edpd: and
/// the per-particle temperature, heat capacity and flux of eDPD; sph: the SPH density
/// and its rate).
pub fn atom_style(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    sim.atom_style = match a.word("an atom style")? {
        "gendpde" => AtomStyle::Dpd,
        s => AtomStyle::from_name(s).ok_or_else(|| a.err(format!("unknown atom style '{s}'; known: atomic, dpd, gendpde, mdpd, edpd, sph")))?,
    };
    a.done()
}

/// `lattice none S | STYLE SCALE [origin x y z] [orient x|y|z i j k] [spacing x y z]`.
pub fn lattice(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let style = a.word("a lattice style (none, sc, bcc, fcc, hcp, diamond)")?;
    let scale = a.positive(if sim.units == Units::LJ { "the reduced density" } else { "the lattice constant" })?;
    if style == "none" {
        a.done()?;
        sim.lattice = Some(Lattice::none(scale));
        return Ok(());
    }
    let mut o = LatticeOptions::default();
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "origin" => o.origin = [a.f64("the origin's x fraction")?, a.f64("the origin's y fraction")?, a.f64("the origin's z fraction")?],
            "orient" => {
                let d = axis(a, "orient")?;
                for k in 0..3 {
                    let w = a.word("an integer component of the orient vector")?;
                    o.orient[d][k] = w.parse().map_err(|_| a.err(format!("expected an integer component of the orient vector, got '{w}'")))?;
                }
            }
            "spacing" => o.spacing = Some([a.positive("the x spacing")?, a.positive("the y spacing")?, a.positive("the z spacing")?]),
            k => return Err(a.err(format!("unknown keyword '{k}'; known: origin, orient, spacing"))),
        }
    }
    sim.lattice = Some(Lattice::new(style, scale, sim.units == Units::LJ, &o).map_err(|e| a.err(e))?);
    Ok(())
}

/// An axis `x`, `y` or `z` as 0, 1 or 2; `what` names it in the error.
fn axis(a: &mut Args, what: &str) -> Result<usize, ScriptError> {
    match a.word(&format!("{what} (x, y or z)"))? {
        "x" => Ok(0),
        "y" => Ok(1),
        "z" => Ok(2),
        w => Err(a.err(format!("expected {what} x, y or z, got '{w}'"))),
    }
}

/// `region ID block xlo xhi ylo yhi zlo zhi | sphere x y z r | cylinder dim c1 c2 r lo hi`
/// with keywords `side in|out` and `units box|lattice`.
pub fn region(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a region ID")?.to_string();
    // INF, -INF and EDGE (LAMMPS) leave a side open; create_atoms clips regions to the box
    let bound = |a: &mut Args, what: &str, upper: bool| match a.peek() {
        Some("INF" | "-INF" | "EDGE") => {
            a.word(what)?;
            Ok(if upper { f64::INFINITY } else { f64::NEG_INFINITY })
        }
        _ => a.f64(what),
    };
    let style = a.word("a region style (block, sphere or cylinder)")?;
    let shape = match style {
        "block" => {
            let mut b = [0.0; 6];
            for (k, what) in ["xlo", "xhi", "ylo", "yhi", "zlo", "zhi"].iter().enumerate() {
                b[k] = bound(a, what, k % 2 == 1)?;
            }
            Shape::Block { lo: [b[0], b[2], b[4]], hi: [b[1], b[3], b[5]] }
        }
        "sphere" => {
            let centre = [a.f64("the centre's x")?, a.f64("the centre's y")?, a.f64("the centre's z")?];
            Shape::Sphere { centre, radius: a.positive("the radius")? }
        }
        "cylinder" => {
            let axis = axis(a, "the axis")?;
            let c = [a.f64("the first coordinate of the axis")?, a.f64("the second coordinate of the axis")?];
            let radius = a.positive("the radius")?;
            Shape::Cylinder { axis, c, radius, lo: bound(a, "the lower end", false)?, hi: bound(a, "the upper end", true)? }
        }
        s => return Err(a.err(format!("unknown region style '{s}'; known: block, sphere, cylinder"))),
    };
    let (mut scale, mut outside) = (None, false);
    while a.remaining() > 0 {
        match a.word("keyword")? {
            "units" => match a.word("box or lattice")? {
                "box" => scale = Some(1.0),
                "lattice" => scale = None,
                u => return Err(a.err(format!("expected units box or lattice, got '{u}'"))),
            },
            "side" => match a.word("in or out")? {
                "in" => outside = false,
                "out" => outside = true,
                w => return Err(a.err(format!("expected side in or out, got '{w}'"))),
            },
            k => return Err(a.err(format!("unknown keyword '{k}'; known: side, units"))),
        }
    }
    // lattice spacings, as LAMMPS scales each style
    let f = scale.map_or_else(|| sim.lattice_spacing(), |s| [s; 3]);
    let shape = match shape {
        Shape::Block { lo, hi } => Shape::Block { lo: std::array::from_fn(|d| lo[d] * f[d]), hi: std::array::from_fn(|d| hi[d] * f[d]) },
        Shape::Sphere { centre, radius } => Shape::Sphere { centre: std::array::from_fn(|d| centre[d] * f[d]), radius: radius * f[0] },
        Shape::Cylinder { axis, c, radius, lo, hi } => {
            let (a, b) = Region::others(axis);
            Shape::Cylinder { axis, c: [c[0] * f[a], c[1] * f[b]], radius: radius * f[a], lo: lo * f[axis], hi: hi * f[axis] }
        }
    };
    let ordered = match &shape {
        Shape::Block { lo, hi } => (0..3).all(|d| hi[d] > lo[d]),
        Shape::Sphere { .. } => true,
        Shape::Cylinder { lo, hi, .. } => hi > lo,
    };
    if !ordered {
        return Err(a.err("each upper bound must exceed its lower bound"));
    }
    if sim.regions.contains_key(&id) {
        return Err(a.err(format!("region ID '{id}' is in use")));
    }
    sim.regions.insert(id, Region { shape, outside });
    Ok(())
}

/// `processors Px Py Pz` (each a count or `*`): the shape of the grid of ranks.
pub fn processors(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    if sim.system.is_some() {
        return Err(a.err("processors must come before create_box"));
    }
    for d in 0..3 {
        sim.procs[d] = match a.word("a rank count or *")? {
            "*" => None,
            w => match w.parse::<usize>() {
                Ok(p) if p > 0 => Some(p),
                _ => return Err(a.err(format!("expected a positive rank count or *, got '{w}'"))),
            },
        };
    }
    a.done()
}

/// `create_box N REGION`.
pub fn create_box(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let transport = sim.take_transport().map_err(|e| a.err(e))?;
    let n = a.u64("the number of particle types")? as usize;
    if n == 0 {
        return Err(a.err("the number of particle types must be at least 1"));
    }
    let id = a.word("a region ID")?;
    a.done()?;
    let (lo, hi) = match sim.regions.get(id).ok_or_else(|| a.err(format!("no region with ID '{id}'")))? {
        Region { shape: Shape::Block { lo, hi }, outside: false } => (*lo, *hi),
        _ => return Err(a.err(format!("region '{id}': a box needs a block region (side in)"))),
    };
    if !lo.iter().chain(&hi).all(|x| x.is_finite()) {
        return Err(a.err(format!("region '{id}' is open (INF/EDGE): a box needs finite bounds")));
    }
    let domain = Domain::new(lo, hi);
    let procs = ProcGrid::choose(transport.size(), domain.len(), sim.procs).map_err(|e| a.err(e))?;
    sim.ntypes = n;
    sim.masses = vec![None; n];
    let mut sys = System::new(domain, Comm::new(transport, procs));
    sys.store.enable(sim.atom_style_fields());
    sim.system = Some(sys);
    Ok(())
}

/// `create_atoms TYPE box | region ID | single x y z | random N SEED REGION|NULL` with
/// keywords `basis M T`, `units box|lattice`, `remap yes|no` (single), `overlap D` and
/// `maxtry N` (random): on the lattice points in the box (and region), one particle, or
/// N points in the region (NULL: the box) drawn as LAMMPS's add_random draws them, which
/// every rank replays in full, keeping its own.
pub fn create_atoms(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let kind = a.u64("a particle type")? as usize;
    let sys = sim.system.as_mut().ok_or_else(|| a.err("create_atoms before the box exists (create_box, read_data or read_restart)"))?;
    if kind < 1 || kind > sim.ntypes {
        return Err(a.err(format!("type {kind} is outside 1..{}", sim.ntypes)));
    }
    let region_named = |a: &Args, id: &str| sim.regions.get(id).ok_or_else(|| a.err(format!("no region with ID '{id}'")));
    let style = a.word("box, region, single or random")?;
    let mut single = None;
    let (region, random) = match style {
        "box" => (None, None),
        "region" => {
            let id = a.word("a region ID")?;
            (Some(region_named(a, id)?), None)
        }
        "single" => {
            single = Some([a.f64("the x coordinate")?, a.f64("the y coordinate")?, a.f64("the z coordinate")?]);
            (None, None)
        }
        "random" => {
            let n = a.u64("the number of particles")?;
            let seed = a.u64("a positive random seed")?;
            if seed == 0 || seed > MAX_SEED {
                return Err(a.err(format!("Illegal create_atoms random seed {seed}: the random seed must be positive and at most {MAX_SEED}")));
            }
            let region = match a.word("a region ID or NULL")? {
                "NULL" => None,
                id => Some(region_named(a, id)?),
            };
            (region, Some((n, seed)))
        }
        s => return Err(a.err(format!("Unknown create_atoms command option {s}; known: box, region, single, random"))),
    };
    let nbasis = sim.lattice.as_ref().map_or(0, |l| l.basis.len());
    let (mut basis_kind, mut lattice_units, mut overlap, mut maxtry, mut remap) = (vec![kind as u32; nbasis], true, None, 1000, false);
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "basis" => {
                let (m, t) = (a.u64("a basis atom")? as usize, a.u64("a particle type")? as usize);
                if m < 1 || m > nbasis || t < 1 || t > sim.ntypes {
                    return Err(a.err(format!("Out of range basis setting '{m} {t}' in create_atoms command")));
                }
                basis_kind[m - 1] = t as u32;
            }
            "units" => match a.word("box or lattice")? {
                "box" => lattice_units = false,
                "lattice" => lattice_units = true,
                u => return Err(a.err(format!("Unknown create_atoms units option {u}"))),
            },
            k @ ("overlap" | "maxtry") if random.is_none() => return Err(a.err(format!("Create_atoms {k} can only be used with random style"))),
            "overlap" => {
                let d = a.f64("the overlap distance")?;
                if d <= 0.0 {
                    return Err(a.err(format!("Illegal create_atoms overlap value: {d}")));
                }
                overlap = Some(d);
            }
            "maxtry" => {
                maxtry = a.u64("the number of tries")?;
                if maxtry == 0 {
                    return Err(a.err("create_atoms maxtry must be positive"));
                }
            }
            k @ ("subset" | "ratio") => return Err(a.err(format!("create_atoms keyword '{k}' is not supported: LAMMPS draws the subset from a generator per rank, so it depends on the rank count"))),
            "remap" => remap = a.yes_no("remap")?,
            k @ ("mol" | "var" | "set" | "rotate" | "meshmode" | "radscale") => {
                return Err(a.err(format!("create_atoms keyword '{k}' is not supported")))
            }
            k => return Err(a.err(format!("Illegal create_atoms command option {k}; known: basis, units, remap, overlap, maxtry"))),
        }
    }
    let size = sys.comm.size() as f64;
    let check_memory = |a: &Args, bound: f64| {
        memory::check(24.0 * bound + memory::STORE_BYTES_PER_PARTICLE * bound / size, &format!("create_atoms of up to {bound:.3e} particles"))
            .map_err(|e| a.err(e))
    };
    let (d, len) = (&sys.domain, sys.domain.len());
    let points: Vec<(Vec3, u32)> = match (random, single) {
        // LAMMPS's add_single: in the box (half-open), after remap into it if asked
        (None, Some(x)) => {
            let spacing = if lattice_units { sim.lattice.as_ref().map_or([1.0; 3], |l| l.spacing) } else { [1.0; 3] };
            let mut r: Vec3 = std::array::from_fn(|k| x[k] * spacing[k]);
            if remap {
                d.wrap(&mut r, &mut [0; 3]);
            }
            let inside = (0..3).all(|k| r[k] >= d.lo[k] && r[k] < d.hi[k]);
            if inside { vec![(r, kind as u32)] } else { Vec::new() }
        }
        (None, None) => {
            // a region's bounding box clipped to the box; a region's upper face inside
            // the box belongs to it (the box is half-open)
            let (mut lo, mut hi) = (d.lo, d.hi);
            if let Some((rlo, rhi)) = region.and_then(Region::extent) {
                for k in 0..3 {
                    lo[k] = lo[k].max(rlo[k]);
                    if rhi[k] < d.hi[k] {
                        hi[k] = (rhi[k] + 1e-6 * len[k]).min(d.hi[k]);
                    }
                }
                // as LAMMPS's add_lattice: a region outside the box creates no particle
                if (0..3).any(|k| hi[k] <= lo[k]) {
                    return Ok(());
                }
            }
            let lattice = sim.lattice.as_ref().filter(|l| !l.basis.is_empty()).ok_or_else(|| a.err("create_atoms needs a lattice with points (a lattice command other than none)"))?;
            check_memory(a, lattice.count_bound(lo, hi))?;
            // in the box as LAMMPS: a point on both periodic faces is created once
            let in_box = |r: Vec3| (0..3).all(|k| r[k] >= d.lo[k] - 1e-6 * len[k] && r[k] < d.hi[k] - 2e-6 * len[k]);
            let points = lattice.points(lo, hi, |r| in_box(r) && region.map(|g| g.contains(r)) != Some(false));
            points.into_iter().map(|(r, m)| (r, basis_kind[m])).collect()
        }
        (Some((n, seed)), _) => {
            // LAMMPS's bounding box: the box, clipped by the region's extent
            let (mut lo, mut hi) = (d.lo, d.hi);
            if let Some((rlo, rhi)) = region.and_then(Region::extent) {
                lo = std::array::from_fn(|k| lo[k].max(rlo[k]));
                hi = std::array::from_fn(|k| hi[k].min(rhi[k]));
            }
            if (0..3).any(|k| lo[k] > hi[k]) {
                return Err(a.err("No overlap of box and region for create_atoms"));
            }
            check_memory(a, n as f64)?;
            // units lattice (the default) scales the overlap by the x lattice spacing
            let mut near = overlap.map(|o| {
                let mut near = Overlap::new(d.lo, len, if lattice_units { o * sim.lattice.as_ref().map_or(1.0, |l| l.spacing[0]) } else { o });
                all_positions(sys).into_iter().for_each(|r| near.add(r));
                near
            });
            // a point that rounds onto the box's upper face is on no rank's sub-box in
            // LAMMPS: inserted, yet not created
            let in_box = |r: Vec3| (0..3).all(|k| r[k] < d.hi[k]);
            let points = random_points(n, seed, lo, hi, maxtry, |r| {
                if region.is_some_and(|g| !g.contains(r)) || near.as_ref().is_some_and(|o| o.hits(r)) {
                    return false;
                }
                if let Some(o) = near.as_mut().filter(|_| in_box(r)) {
                    o.add(r);
                }
                true
            });
            if (points.len() as u64) < n && sys.comm.rank() == 0 {
                log::warn!("Only inserted {} particles out of {n}", points.len());
            }
            points.into_iter().filter(|&r| in_box(r)).map(|r| (r, kind as u32)).collect()
        }
    };
    if sim.max_tag + points.len() as u64 > u32::MAX as u64 {
        return Err(a.err(format!("more than {} particles: particle IDs must fit in 32 bits", u32::MAX)));
    }
    sys.store.truncate_ghosts();
    for (r, kind) in points {
        sim.max_tag += 1;
        if sys.comm.keeps(&sys.domain, r) {
            let mass = sim.masses[kind as usize - 1].map_or(f64::NAN, |m| m * sim.units.mvv2e);
            sys.store.push(sim.max_tag, kind, mass, r);
            if sys.store.has(Fields::EDPD) {
                // LAMMPS's atom_vec_edpd create_atom_post
                let i = sys.store.nlocal - 1;
                (sys.store.edpd_temp[i], sys.store.edpd_cv[i], sys.store.vest_temp[i]) = (1.0, 1.0e5, 1.0);
            }
        }
    }
    sim.check_density_cap().map_err(|e| a.err(e))
}

/// The positions of the particles of all ranks (every rank gets all of them).
fn all_positions(sys: &System) -> Vec<Vec3> {
    let local: Vec<u64> = sys.store.r[..sys.store.nlocal].iter().flat_map(|r| r.map(f64::to_bits)).collect();
    crate::base::gather::all_ranks(sys, &local).chunks_exact(3).map(|c| [0, 1, 2].map(|k| f64::from_bits(c[k]))).collect()
}

/// `mass TYPES M`.
pub fn mass(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    if sim.ntypes == 0 {
        return Err(a.err("mass before create_box"));
    }
    let types = a.types(sim.ntypes)?;
    let m = a.positive("the mass")?;
    a.done()?;
    for t in types.clone() {
        sim.masses[t - 1] = Some(m);
    }
    let internal = m * sim.units.mvv2e;
    if let Some(sys) = &mut sim.system {
        let s = &mut sys.store;
        for i in 0..s.nlocal {
            if types.contains(&(s.kind[i] as usize)) {
                if !s.mass[i].is_finite() {
                    // read_data kept the velocity in p while the mass was unknown
                    s.p[i] = s.p[i].map(|v| v * internal);
                } else {
                    s.p[i] = s.p[i].map(|p| p / s.mass[i] * internal);
                }
                s.mass[i] = internal;
            }
        }
    }
    Ok(())
}

/// `timestep DT`.
pub fn timestep(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    sim.dt = a.positive("the timestep")?;
    a.done()
}

/// `neighbor SKIN bin`.
pub fn neighbor(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    sim.skin = a.non_negative("the skin distance")?;
    match a.word("the neighbour style (bin)")? {
        "bin" | "nsq" => a.done(),
        s => Err(a.err(format!("unknown neighbour style '{s}'; known: bin"))),
    }
}

/// `neigh_modify every N delay N check yes|no [once no]`: the list rebuild rules.
pub fn neigh_modify(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    if a.remaining() == 0 {
        return Err(a.err(format!("missing argument: expected {NEIGH_KEYWORDS}")));
    }
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "every" => sim.rebuild.every = a.u64("the rebuild interval")?.max(1),
            "delay" => sim.rebuild.delay = a.u64("the rebuild delay")?,
            "check" => sim.rebuild.check = a.yes_no("check")?,
            "once" => {
                if a.yes_no("once")? {
                    return Err(a.err("once yes is not supported: lists must follow the particles"));
                }
            }
            // LAMMPS's bounds of its neighbour pages; gendpde's lists grow as needed, so
            // they bound nothing but are checked as LAMMPS's Neighbor::init checks them
            k @ ("one" | "page") => {
                let n = a.u64(if k == "one" { "the neighbours of one atom" } else { "the neighbour page size" })?;
                if n == 0 {
                    return Err(a.err(format!("neigh_modify {k} must be positive")));
                }
                sim.neigh_pages[usize::from(k == "page")] = n;
            }
            // the bin size sets LAMMPS's speed, not its lists; gendpde sizes its cells itself
            "binsize" => {
                a.non_negative("the bin size")?;
            }
            k @ ("exclude" | "include" | "cluster" | "collection/type" | "collection/interval") => {
                return Err(a.err(format!("keyword {k} is not supported: every pair within the cutoff interacts")));
            }
            k => return Err(a.err(format!("unknown keyword '{k}'; known: {NEIGH_KEYWORDS}"))),
        }
    }
    let [one, page] = sim.neigh_pages;
    if page < 10 * one {
        return Err(a.err("Neighbor page size must be >= 10x the one atom setting"));
    }
    Ok(())
}

/// The keywords of `neigh_modify`.
const NEIGH_KEYWORDS: &str = "every, delay, check, once, one, page, binsize";

/// `reset_timestep N`: positions and lists stay; the build step follows the clock, the
/// noise does not (its key runs on, so no stretch of it repeats).
pub fn reset_timestep(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let n = a.u64("the new step number")?;
    a.done()?;
    let sys = sim.system.as_mut().ok_or_else(|| a.err("reset_timestep before create_box"))?;
    sys.lists.last = sys.lists.last.saturating_sub(sys.clock.step).saturating_add(n).min(n);
    sys.clock.noise_shift = sys.clock.noise_shift.wrapping_add(sys.clock.step.wrapping_sub(n));
    sys.clock.step = n;
    Ok(())
}

/// `run_style verlet`: gendpde's step is LAMMPS's verlet (its fixes split it); other run
/// styles are refused.
pub fn run_style(a: &mut Args) -> Result<(), ScriptError> {
    match a.word("a run style (verlet)")? {
        "verlet" => a.done(),
        s => Err(a.err(format!("run style '{s}' is not supported (only verlet)"))),
    }
}

/// `atom_modify map array|hash|yes | sort Nfreq binsize | id yes`: LAMMPS's storage
/// settings; gendpde manages its own storage, so they are accepted and have no effect.
pub fn atom_modify(a: &mut Args) -> Result<(), ScriptError> {
    if a.remaining() == 0 {
        return Err(a.err("missing argument: expected map, sort or id"));
    }
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "map" => match a.word("array, hash or yes")? {
                "array" | "hash" | "yes" => {}
                m => return Err(a.err(format!("expected map array, hash or yes, got '{m}'"))),
            },
            "sort" => {
                a.u64("the sort interval")?;
                a.non_negative("the sort bin size")?;
            }
            "id" => {
                if !a.yes_no("id")? {
                    return Err(a.err("id no is not supported: particles always have IDs"));
                }
            }
            "first" => return Err(a.err("atom_modify first is not supported")),
            k => return Err(a.err(format!("unknown keyword '{k}'; known: map, sort, id"))),
        }
    }
    Ok(())
}

/// `comm_modify mode single | cutoff R | vel yes|no`: checked as LAMMPS checks them and
/// accepted: gendpde's ghosts always reach the styles' cutoff plus the skin (a larger ghost
/// cutoff changes no result) and carry the velocities. Modes multi need LAMMPS's multi
/// neighbour lists and `group` its atom_modify first: refused.
pub fn comm_modify(a: &mut Args) -> Result<(), ScriptError> {
    if a.remaining() == 0 {
        return Err(a.err("Illegal comm_modify command: missing argument"));
    }
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "mode" => {
                let m = a.word("single, multi or multi/old")?;
                let why = match m {
                    "single" => continue,
                    "multi" | "multi/old" => format!("comm_modify mode {m} needs LAMMPS's multi neighbor lists, which gendpde does not have"),
                    _ => format!("Unknown comm_modify mode argument: {m}"),
                };
                return Err(a.err(why));
            }
            "cutoff" => {
                let cut = a.f64("the ghost cutoff")?;
                if cut < 0.0 {
                    return Err(a.err(format!("Invalid cutoff {cut:?} in comm_modify command")));
                }
            }
            k @ ("cutoff/multi" | "reduce/multi") => return Err(a.err(format!("comm_modify {k} needs LAMMPS's multi neighbor lists, which gendpde does not have"))),
            "group" => return Err(a.err("comm_modify group is not supported (it needs atom_modify first, which gendpde does not have)")),
            "vel" => {
                a.yes_no("vel")?;
            }
            k => return Err(a.err(format!("Unknown comm_modify keyword: {k}"))),
        }
    }
    Ok(())
}

/// `newton on|off [on|off]`: checked and accepted (gendpde's sums do not depend on it:
/// they are kept the same for every rank count).
pub fn newton(a: &mut Args) -> Result<(), ScriptError> {
    for what in ["the pairwise setting", "the bonded setting"] {
        if what == "the bonded setting" && a.remaining() == 0 {
            break;
        }
        match a.word(what)? {
            "on" | "off" => {}
            w => return Err(a.err(format!("Expected boolean parameter instead of '{w}' in input script or data file"))),
        }
    }
    a.done()
}
