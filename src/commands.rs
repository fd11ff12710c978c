//! The script interpreter: reads commands one at a time and applies them to the model.

use crate::args::Args;
use crate::lattice::{Block, Lattice};
use crate::output::Output;
use crate::sim::Sim;
use crate::styles::{self, FixStyle};
use crate::thermo::{Observables, ThermoContext};
use crate::{run, velocity};
use gendpde_engine::{exact_sums, Comm, Domain, Local, ProcGrid, Transport};
use gendpde_integrators::{StepError, System};
use gendpde_io::{AtomStyle, Command, ScriptError, ScriptReader, Variables};
use std::fmt;
use std::path::Path;

/// Whether `run` advances time or only validates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    Run,
    Check,
}

/// A failure that stops the script.
#[derive(Debug)]
pub enum AppError {
    Script(ScriptError),
    Step { cmd: Command, err: StepError },
}

impl fmt::Display for AppError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Script(e) => e.fmt(f),
            Self::Step { cmd, err } => write!(f, "{}: run stopped: {err}", cmd.loc),
        }
    }
}

impl From<ScriptError> for AppError {
    fn from(e: ScriptError) -> Self {
        Self::Script(e)
    }
}

pub struct Interpreter {
    pub sim: Sim,
    pub vars: Variables,
    pub out: Output,
    pub mode: Mode,
    /// The ranks' transport, handed to the box's communicator by `create_box`.
    transport: Option<Box<dyn Transport>>,
    /// A `next` exhausted its variables: the next `jump` falls through.
    skip_jump: bool,
}

impl Interpreter {
    /// A single-rank interpreter.
    pub fn new(mode: Mode, out: Output) -> Self {
        Self::with_transport(mode, out, Box::new(Local))
    }

    /// An interpreter whose box is split over the ranks of `transport`.
    pub fn with_transport(mode: Mode, out: Output, transport: Box<dyn Transport>) -> Self {
        Self { sim: Sim::default(), vars: Variables::new(), out, mode, transport: Some(transport), skip_jump: false }
    }

    /// Executes a script file to its end.
    pub fn execute_file(&mut self, path: &Path) -> Result<(), AppError> {
        self.execute_reader(ScriptReader::open(path)?)
    }

    /// Executes a script held in memory; `name` stands for its file name in errors.
    pub fn execute_str(&mut self, name: &str, text: &str) -> Result<(), AppError> {
        self.execute_reader(ScriptReader::from_string(name, text))
    }

    fn execute_reader(&mut self, mut reader: ScriptReader) -> Result<(), AppError> {
        loop {
            let next = {
                let (sim, vars) = (&self.sim, &self.vars);
                reader.next_command(vars, &|name| resolve(sim, name))?
            };
            let Some(cmd) = next else { return Ok(()) };
            self.out.log_line(&echo(&cmd));
            match cmd.name.as_str() {
                // LAMMPS loops: `label L`, `next V ...`, `jump SELF L`; a `next` that
                // exhausts its variables makes the following `jump` fall through
                "label" => {}
                "next" => {
                    if cmd.args.is_empty() {
                        return Err(ScriptError::at(&cmd, "missing argument: expected variable names").into());
                    }
                    self.skip_jump = self.vars.next(&cmd.args).map_err(|mut e| {
                        e.loc = Some(cmd.loc.clone());
                        e
                    })?;
                }
                "jump" => {
                    if !std::mem::take(&mut self.skip_jump) {
                        reader.jump(&cmd)?;
                    }
                }
                _ => self.execute(&cmd)?,
            }
        }
    }

    fn execute(&mut self, cmd: &Command) -> Result<(), AppError> {
        let mut a = Args::new(cmd);
        let sim = &mut self.sim;
        match cmd.name.as_str() {
            "units" => {
                let w = a.word("a unit style (lj or metal)")?;
                let units = crate::units::Units::parse(w).ok_or_else(|| a.err(format!("units {w}: known are lj and metal")))?;
                a.done()?;
                if sim.system.is_some() && units != sim.units {
                    return Err(a.err("units must come before the box is created").into());
                }
                if units != sim.units {
                    sim.units = units;
                    sim.dt = units.default_dt;
                    sim.skin = units.default_skin;
                    sim.thermo.norm = units.default_norm;
                }
            }
            "comm_modify" | "newton" => {
                // LAMMPS communication settings: gendpde always exchanges what its styles
                // need (ghost velocities included) and uses full lists; accepted for
                // compatibility.
            }
            "compute" => crate::computes::compute(sim, &mut a)?,
            "dimension" => match a.word("the dimension")? {
                "3" => a.done()?,
                d => return Err(a.err(format!("dimension {d}: only 3 is supported")).into()),
            },
            "boundary" => {
                for axis in ["x", "y", "z"] {
                    match a.word(&format!("the boundary along {axis}"))? {
                        "p" => {}
                        b => return Err(a.err(format!("boundary '{b}' along {axis}: only periodic (p) is supported")).into()),
                    }
                }
                a.done()?;
            }
            "atom_style" => {
                sim.atom_style = match a.word("an atom style")? {
                    "atomic" => AtomStyle::Atomic,
                    "dpd" | "gendpde" => AtomStyle::Dpd,
                    "mdpd" => AtomStyle::Mdpd,
                    s => return Err(a.err(format!("unknown atom style '{s}'; known: atomic, dpd, gendpde, mdpd")).into()),
                };
                a.done()?;
            }
            "echo" => match a.word("none, screen, log or both")? {
                "none" | "screen" | "log" | "both" => a.done()?,
                s => return Err(a.err(format!("expected none, screen, log or both, got '{s}'")).into()),
            },
            "lattice" => {
                let style = a.word("a lattice style (sc, bcc, fcc)")?;
                let rho = a.positive("the reduced density")?;
                a.done()?;
                sim.lattice = Some(Lattice::new(style, rho).ok_or_else(|| a.err(format!("unknown lattice '{style}'; known: sc, bcc, fcc")))?);
            }
            "region" => region(sim, &mut a)?,
            "processors" => processors(sim, &mut a)?,
            "create_box" => {
                let t = self.transport.take().ok_or_else(|| a.err("the box exists already"))?;
                create_box(sim, &mut a, t)?
            }
            "create_atoms" => create_atoms(sim, &mut a)?,
            "read_data" => {
                if sim.system.is_some() {
                    return Err(a.err("read_data: the box exists already").into());
                }
                let t = self.transport.take().ok_or_else(|| a.err("the box exists already"))?;
                crate::data::read(sim, &mut a, t)?;
                check_density_cap(sim, &a)?;
            }
            "write_data" => crate::data::write(sim, &mut a)?,
            "write_restart" => {
                let file = a.word("a restart file")?.to_string();
                a.done()?;
                crate::restart::write(sim, &file).map_err(|e| a.err(e))?;
            }
            "read_restart" => {
                let file = a.word("a restart file")?.to_string();
                a.done()?;
                if sim.system.is_some() {
                    return Err(a.err("read_restart: the box exists already").into());
                }
                let t = self.transport.take().ok_or_else(|| a.err("the box exists already"))?;
                let (system, commands) = crate::restart::read(sim, &file, t).map_err(|e| a.err(e))?;
                let name = format!("{file} (stored commands)");
                let before_box = commands.iter().take_while(|c| c.starts_with("units ") || c.starts_with("atom_style ")).count();
                self.execute_str(&name, &(commands[..before_box].join("\n") + "\n"))?;
                self.sim.system = Some(system);
                self.execute_str(&name, &(commands[before_box..].join("\n") + "\n"))?;
                self.sim.restore_fix_state();
            }
            "checkpoint" => {
                let every = a.u64("the checkpoint interval N (0: off)")?;
                let file = a.word("a restart file")?.to_string();
                a.done()?;
                sim.checkpoint = (every > 0).then_some((every, file));
            }
            "dump" => {
                let dump = crate::h5md_out::H5mdDump::parse(&mut a)?;
                if sim.dumps.iter().any(|d| d.id == dump.id) {
                    return Err(a.err(format!("dump ID '{}' is in use (undump it first)", dump.id)).into());
                }
                sim.dumps.push(dump);
            }
            "undump" => {
                let id = a.word("a dump ID")?;
                a.done()?;
                let before = sim.dumps.len();
                sim.dumps.retain(|d| d.id != id);
                if sim.dumps.len() == before {
                    return Err(a.err(format!("no dump with ID '{id}'")).into());
                }
            }
            "mass" => mass(sim, &mut a)?,
            "velocity" => velocity::velocity(sim, &mut a)?,
            "group" => crate::groups::group(sim, &mut a)?,
            "set" => set(sim, &mut a)?,
            "pair_style" => {
                if sim.system.is_none() {
                    return Err(a.err("pair_style comes after create_box").into());
                }
                sim.pair = Some(styles::parse_pair_style(cmd)?);
                sim.pair_text = vec![echo(cmd)];
            }
            "pair_coeff" => {
                let pair = sim.pair.as_mut().ok_or_else(|| a.err("pair_coeff before pair_style"))?;
                styles::parse_pair_coeff(cmd, pair, sim.ntypes)?;
                sim.pair_text.push(echo(cmd));
            }
            "fix" if cmd.args.get(2).map(String::as_str) == Some("ave/time") => {
                let id = a.word("a fix ID")?.to_string();
                let group = a.word("a group")?;
                if group != "all" {
                    return Err(a.err(format!("group '{group}': fixes act on group all")).into());
                }
                a.word("ave/time")?;
                if sim.fixes.iter().any(|f| f.id == id) {
                    return Err(a.err(format!("fix ID '{id}' is in use by another style (unfix it first)")).into());
                }
                let step = sim.system.as_ref().map_or(0, |s| s.step);
                let fix = crate::ave_time::AveTime::parse(id, &mut a, &sim.rdfs, step)?;
                sim.averages.retain(|f| f.id != fix.id);
                sim.averages.push(fix);
            }
            "fix" => {
                let fix = styles::parse_fix(cmd, sim.units.kb, &sim.groups)?;
                if sim.averages.iter().any(|f| f.id == fix.id) {
                    return Err(a.err(format!("fix ID '{}' is in use by another style (unfix it first)", fix.id)).into());
                }
                match sim.fixes.iter_mut().find(|f| f.id == fix.id) {
                    Some(old) if std::mem::discriminant(&old.style) != std::mem::discriminant(&fix.style) => {
                        return Err(a.err(format!("fix ID '{}' is in use by another style (unfix it first)", fix.id)).into());
                    }
                    Some(old) => *old = fix,
                    None => sim.fixes.push(fix),
                }
                check_density_cap(sim, &a)?;
            }
            "unfix" => {
                let id = a.word("a fix ID")?;
                a.done()?;
                let before = sim.fixes.len() + sim.averages.len();
                sim.fixes.retain(|f| f.id != id);
                sim.averages.retain(|f| f.id != id);
                if sim.fixes.len() + sim.averages.len() == before {
                    return Err(a.err(format!("no fix with ID '{id}'")).into());
                }
            }
            "reset_timestep" => {
                let n = a.u64("the new step number")?;
                a.done()?;
                let sys = sim.system.as_mut().ok_or_else(|| a.err("reset_timestep before create_box"))?;
                // positions and lists stay; the build step follows the clock
                sys.last_build = sys.last_build.saturating_sub(sys.step).saturating_add(n).min(n);
                sys.step = n;
            }
            "timestep" => {
                sim.dt = a.positive("the timestep")?;
                a.done()?;
            }
            "neighbor" => {
                sim.skin = a.non_negative("the skin distance")?;
                match a.word("the neighbour style (bin)")? {
                    "bin" | "nsq" => a.done()?,
                    s => return Err(a.err(format!("unknown neighbour style '{s}'; known: bin")).into()),
                }
            }
            "neigh_modify" => neigh_modify(sim, &mut a)?,
            "thermo" => {
                sim.thermo.every = a.u64("the thermo interval")?;
                a.done()?;
            }
            "thermo_style" => thermo_style(sim, &self.vars, &mut a)?,
            "thermo_modify" => thermo_modify(sim, &mut a)?,
            "variable" => self.vars.define(cmd)?,
            "print" => {
                let text = a.word("the text to print")?.to_string();
                let mut screen = true;
                while a.remaining() > 0 {
                    match a.word("keyword")? {
                        "screen" => screen = a.yes_no("screen")?,
                        k => return Err(a.err(format!("unknown keyword '{k}'; known: screen")).into()),
                    }
                }
                if screen { self.out.line(&text) } else { self.out.log_line(&text) }
            }
            "log" => {
                let file = a.word("a log file name")?.to_string();
                let append = match a.peek() {
                    Some("append") => {
                        a.word("append")?;
                        true
                    }
                    _ => false,
                };
                a.done()?;
                if file == "none" {
                    self.out.close_log();
                } else if self.mode == Mode::Run {
                    self.out.open_log(Path::new(&file), append).map_err(|e| a.err(format!("cannot open log file '{file}': {e}")))?;
                }
            }
            "write_dump" => crate::dump::write_dump(sim, &mut a)?,
            "run" => {
                let n = a.u64("the number of steps")?;
                a.done()?;
                run::run(self, cmd, n)?;
            }
            other => return Err(a.err(format!("unknown command '{other}' (see docs/commands/ for the commands gendpde knows)")).into()),
        }
        Ok(())
    }
}

/// The command as LAMMPS echoes it to the log.
pub fn echo(cmd: &Command) -> String {
    std::iter::once(cmd.name.as_str()).chain(cmd.args.iter().map(String::as_str)).collect::<Vec<_>>().join(" ")
}

/// Values of thermo keywords inside variables and `$(...)`.
fn resolve(sim: &Sim, name: &str) -> Option<f64> {
    let sys = sim.system.as_ref()?;
    let ctx = ThermoContext {
        sys,
        obs: Observables::measure(sys),
        norm: sim.thermo.norm,
        dt: sim.dt,
        energy0: sim.energy0,
        elapsed: 0,
        cpu: 0.0,
        units: sim.units,
        pe_is_pair: sim.pe_is_pair(),
        computes: &sim.computes,
    };
    ctx.keyword(name)
}

fn region(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let id = a.word("a region ID")?.to_string();
    match a.word("a region style (block)")? {
        "block" => {}
        s => return Err(a.err(format!("unknown region style '{s}'; known: block"))),
    }
    // INF and EDGE (LAMMPS) leave a side open; create_atoms clips regions to the box
    let mut b = [0.0; 6];
    for (k, what) in ["xlo", "xhi", "ylo", "yhi", "zlo", "zhi"].iter().enumerate() {
        b[k] = match a.peek() {
            Some("INF" | "EDGE") => {
                a.word(what)?;
                if k % 2 == 0 { f64::NEG_INFINITY } else { f64::INFINITY }
            }
            _ => a.f64(what)?,
        };
    }
    let mut scale = None;
    while a.remaining() > 0 {
        match a.word("keyword")? {
            "units" => match a.word("box or lattice")? {
                "box" => scale = Some(1.0),
                "lattice" => scale = None,
                u => return Err(a.err(format!("expected units box or lattice, got '{u}'"))),
            },
            k => return Err(a.err(format!("unknown keyword '{k}'; known: units"))),
        }
    }
    let scale = match scale {
        Some(s) => s,
        None => sim.lattice.as_ref().map(|l| l.constant).ok_or_else(|| a.err("region in lattice units needs a lattice command first (or use 'units box')"))?,
    };
    let block = Block { lo: [b[0] * scale, b[2] * scale, b[4] * scale], hi: [b[1] * scale, b[3] * scale, b[5] * scale] };
    if (0..3).any(|d| block.hi[d] <= block.lo[d]) {
        return Err(a.err("each upper bound must exceed its lower bound"));
    }
    if sim.regions.contains_key(&id) {
        return Err(a.err(format!("region ID '{id}' is in use")));
    }
    sim.regions.insert(id, block);
    Ok(())
}

/// `processors Px Py Pz` (each a count or `*`): the shape of the grid of ranks.
fn processors(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
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

fn create_box(sim: &mut Sim, a: &mut Args, transport: Box<dyn Transport>) -> Result<(), ScriptError> {
    let n = a.u64("the number of particle types")? as usize;
    if n == 0 {
        return Err(a.err("the number of particle types must be at least 1"));
    }
    let id = a.word("a region ID")?;
    a.done()?;
    let block = sim.regions.get(id).ok_or_else(|| a.err(format!("no region with ID '{id}'")))?;
    if !block.lo.iter().chain(&block.hi).all(|x| x.is_finite()) {
        return Err(a.err(format!("region '{id}' is open (INF/EDGE): a box needs finite bounds")));
    }
    let domain = Domain::new(block.lo, block.hi);
    let procs = ProcGrid::choose(transport.size(), domain.len(), sim.procs).map_err(|e| a.err(e))?;
    sim.ntypes = n;
    sim.masses = vec![None; n];
    sim.system = Some(System::new(domain, Comm::new(transport, procs)));
    Ok(())
}

fn create_atoms(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let kind = a.u64("a particle type")? as usize;
    if kind < 1 || kind > sim.ntypes {
        return Err(a.err(format!("type {kind} is outside 1..{}", sim.ntypes)));
    }
    let sys = sim.system.as_mut().ok_or_else(|| a.err("create_atoms before create_box"))?;
    let (lo, hi) = match a.word("box or region")? {
        "box" => (sys.domain.lo, sys.domain.hi),
        "region" => {
            let id = a.word("a region ID")?;
            let b = sim.regions.get(id).ok_or_else(|| a.err(format!("no region with ID '{id}'")))?;
            let (d, mut lo, mut hi) = (&sys.domain, b.lo, b.hi);
            for k in 0..3 {
                lo[k] = lo[k].max(d.lo[k]);
                hi[k] = hi[k].min(d.hi[k]);
            }
            (lo, hi)
        }
        s => return Err(a.err(format!("expected box or region, got '{s}'"))),
    };
    a.done()?;
    let lattice = sim.lattice.as_ref().ok_or_else(|| a.err("create_atoms needs a lattice command first"))?;
    let mass = sim.masses[kind - 1].map_or(f64::NAN, |m| m * sim.units.mvv2e);
    let bound = lattice.count_bound(lo, hi);
    crate::memory::check(24.0 * bound + crate::memory::STORE_BYTES_PER_PARTICLE * bound / sys.comm.size() as f64, &format!("create_atoms of up to {bound:.3e} particles"))
        .map_err(|e| a.err(e))?;
    let points = lattice.points(lo, hi);
    if sim.max_tag + points.len() as u64 > u32::MAX as u64 {
        return Err(a.err(format!("more than {} particles: particle IDs must fit in 32 bits", u32::MAX)));
    }
    sys.store.truncate_ghosts();
    for r in points {
        sim.max_tag += 1;
        if sys.comm.keeps(&sys.domain, r) {
            sys.store.push(sim.max_tag, kind as u32, mass, r);
        }
    }
    check_density_cap(sim, a)
}

/// A mean density at or above an EOS's cap (vdW: 1/b) cannot start a run.
fn check_density_cap(sim: &Sim, a: &Args) -> Result<(), ScriptError> {
    let Some(sys) = &sim.system else { return Ok(()) };
    let [count] = exact_sums(sys.comm.transport(), (0..sys.store.nlocal).map(|_| [1.0]));
    let n = count / sys.domain.volume();
    for f in &sim.fixes {
        if let FixStyle::Eos(e) = &f.style {
            if let Some(max) = e.max_density() {
                if n >= max {
                    return Err(a.err(format!(
                        "mean number density N/V = {n:.6} lies beyond the density limit {max:.6} of the EOS of fix {} (van der Waals: 1/b)",
                        f.id
                    )));
                }
            }
        }
    }
    Ok(())
}

fn mass(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
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

/// Gives owned particle `i` type `kind` and that type's mass (NaN while unset), keeping
/// its velocity (p holds the velocity while the mass is unknown, as after read_data).
fn retype(s: &mut gendpde_engine::Particles, i: usize, kind: u32, masses: &[Option<f64>], mvv2e: f64) {
    let new = masses[kind as usize - 1].map_or(f64::NAN, |m| m * mvv2e);
    let old = s.mass[i];
    let velocity = if old.is_finite() { s.p[i].map(|p| p / old) } else { s.p[i] };
    s.p[i] = if new.is_finite() { velocity.map(|v| v * new) } else { velocity };
    s.kind[i] = kind;
    s.mass[i] = new;
}

/// `set atom|type|group ID KEYWORD VALUE ...` with keywords theta (dpd/theta), u, type T
/// and type/fraction T FRACTION SEED (as LAMMPS: each selected particle becomes type T
/// with probability FRACTION).
fn set(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    let style = a.word("atom, type or group")?;
    let group_mask = if style == "group" { Some(crate::groups::mask(sim, a.word("a group ID")?, a)?) } else { None };
    let sys = sim.system.as_mut().ok_or_else(|| a.err("set before create_box"))?;
    let s = &mut sys.store;
    let selected: Vec<usize> = match style {
        "group" => {
            let m = group_mask.unwrap_or(0);
            (0..s.nlocal).filter(|&i| s.in_group(i, m)).collect()
        }
        "type" => {
            let range = a.range("a particle type", sim.ntypes as u64)?;
            (0..s.nlocal).filter(|&i| range.contains(&(s.kind[i] as u64))).collect()
        }
        "atom" => {
            let range = a.range("a particle ID", sim.max_tag)?;
            (0..s.nlocal).filter(|&i| range.contains(&s.tag[i])).collect()
        }
        _ => return Err(a.err(format!("expected atom, type or group, got '{style}'"))),
    };
    if a.remaining() == 0 {
        return Err(a.err("missing argument: expected a keyword (theta or u) and its value"));
    }
    while a.remaining() > 0 {
        let key = a.word("a keyword")?;
        match key {
            "theta" | "dpd/theta" => {
                let t = a.positive("the particle temperature theta")?;
                for &i in &selected {
                    s.theta[i] = t;
                    s.theta_given[i] = true;
                }
            }
            "u" => {
                let u = a.f64("the internal energy u")?;
                for &i in &selected {
                    s.u[i] = u;
                    s.theta_given[i] = false;
                }
            }
            "type" => {
                let t = a.range("a particle type", sim.ntypes as u64)?;
                if t.start() != t.end() {
                    return Err(a.err("set type takes one type"));
                }
                for &i in &selected {
                    retype(s, i, *t.start() as u32, &sim.masses, sim.units.mvv2e);
                }
            }
            "type/fraction" => {
                let t = a.range("a particle type", sim.ntypes as u64)?;
                let fraction = a.f64("the fraction")?;
                let seed = a.u64("the random seed")?;
                if t.start() != t.end() || !(0.0..=1.0).contains(&fraction) || seed == 0 {
                    return Err(a.err("set type/fraction takes one type, a fraction in [0, 1] and a positive seed"));
                }
                for &i in &selected {
                    // keyed by the tag: the same particles on any number of ranks
                    let x = gendpde_integrators::rng::uniform4(seed, 0, s.tag[i], 0, gendpde_integrators::rng::stream::SET_TYPE)[0];
                    if x < fraction {
                        retype(s, i, *t.start() as u32, &sim.masses, sim.units.mvv2e);
                    }
                }
            }
            k => return Err(a.err(format!("unknown set keyword '{k}'; known: theta, dpd/theta, u, type, type/fraction"))),
        }
    }
    Ok(())
}

fn neigh_modify(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    if a.remaining() == 0 {
        return Err(a.err("missing argument: expected every, delay, check or once"));
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
            k => return Err(a.err(format!("unknown keyword '{k}'; known: every, delay, check, once"))),
        }
    }
    Ok(())
}

fn thermo_style(sim: &mut Sim, vars: &Variables, a: &mut Args) -> Result<(), ScriptError> {
    match a.word("a thermo style (custom)")? {
        "custom" => {}
        s => return Err(a.err(format!("unknown thermo style '{s}'; known: custom"))),
    }
    let mut keys = Vec::new();
    while a.remaining() > 0 {
        let k = a.word("a keyword")?;
        let known = crate::thermo::heading(k) != k || k.starts_with("v_") || k.starts_with("c_") || k.starts_with("f_");
        if !known {
            return Err(a.err(format!(
                "unknown thermo keyword '{k}'; known: step elapsed time dt cpu atoms temp tint press pe ke etotal edrift vol density lx ly lz pxtot pytot pztot v_NAME c_ID[k] f_ID"
            )));
        }
        if let Some(name) = k.strip_prefix("v_") {
            if !vars.contains(name) {
                return Err(a.err(format!("thermo keyword {k}: no variable named '{name}'")));
            }
        }
        keys.push(k.to_string());
    }
    if keys.is_empty() {
        return Err(a.err("missing argument: expected thermo keywords"));
    }
    sim.thermo.keywords = keys;
    Ok(())
}

fn thermo_modify(sim: &mut Sim, a: &mut Args) -> Result<(), ScriptError> {
    if a.remaining() == 0 {
        return Err(a.err("missing argument: expected norm, format or flush"));
    }
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "norm" => sim.thermo.norm = a.yes_no("norm")?,
            "flush" => {
                a.yes_no("flush")?;
            }
            "format" => match a.word("float or line")? {
                "float" => {
                    let f = a.word("a printf format such as %15.10f")?;
                    gendpde_io::format_printf(f, 1.0).map_err(|e| a.err(format!("bad format '{f}': {e}")))?;
                    sim.thermo.float_format = Some(f.to_string());
                }
                k => return Err(a.err(format!("thermo_modify format {k}: only 'format float' is supported"))),
            },
            k => return Err(a.err(format!("unknown keyword '{k}'; known: norm, format, flush"))),
        }
    }
    Ok(())
}

impl Interpreter {
    /// The dynamics of the styles defined so far, set up on the current system, for
    /// programs that step it themselves (tests, benchmarks).
    pub fn dynamics(&mut self) -> Result<Box<dyn gendpde_integrators::Physics>, AppError> {
        let cmd = Command { name: "run".into(), args: vec![], loc: gendpde_io::Location { file: "<api>".into(), line: 0 } };
        run::prepare(self, &cmd)
    }

    /// The system built by the script.
    pub fn system(&mut self) -> Option<&mut System> {
        self.sim.system.as_mut()
    }
}
