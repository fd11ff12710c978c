//! `velocity GROUP create|set|scale|ramp|zero ... [keyword value ...]`, LAMMPS's velocity
//! command (velocity.cpp semantics): random velocities from LAMMPS's Park–Miller generator
//! looped as `loop all|local|geom` says, so a seed gives LAMMPS's velocities; the
//! temperature is that of a compute temp (the group's own, 3N - 3 degrees of freedom,
//! or `temp ID`); linear and angular momentum removal from unwrapped positions.

use crate::base::args::Args;
use crate::base::groups;
use crate::base::park::{Park, MAX_SEED};
use crate::model::per_atom;
use crate::model::sim::Sim;
use crate::output::thermo::ThermoConfig;
use crate::styles::compute::{self, temp::group_temperature};
use gendpde_engine::{exact_sums, Vec3};
use gendpde_integrators::System;
use gendpde_io::{ScriptError, Variables};

/// RNG warm-up of `loop local` (LAMMPS's WARMUP).
const WARMUP: usize = 100;

#[derive(Clone, Copy, PartialEq)]
enum Loop {
    All,
    Local,
    Geom,
}

/// A component of `velocity set`: a number, `NULL` (left alone) or `v_name`.
enum Component {
    Value(f64),
    Keep,
    Variable(String),
}

enum Style {
    Create { t: f64, seed: u64 },
    Set([Component; 3]),
    Scale(f64),
    Ramp { dim: usize, v: [f64; 2], coord: usize, c: [f64; 2] },
    Zero { angular: bool },
}

struct Options {
    gaussian: bool,
    sum: bool,
    mom: bool,
    rot: bool,
    /// The compute temp's group bit and extra dof (`temp ID`; None: the velocity group's).
    temp: Option<(u32, f64)>,
    lp: Loop,
    lattice_units: bool,
}

fn axis(a: &mut Args, what: &str, prefix: &str) -> Result<usize, ScriptError> {
    let w = a.word(what)?;
    match w.strip_prefix(prefix) {
        Some("x") => Ok(0),
        Some("y") => Ok(1),
        Some("z") => Ok(2),
        _ => Err(a.err(format!("expected {prefix}x, {prefix}y or {prefix}z, got '{w}'"))),
    }
}

fn style(a: &mut Args) -> Result<Style, ScriptError> {
    Ok(match a.word("a velocity style (create, set, scale, ramp or zero)")? {
        "create" => {
            let t = a.non_negative("the temperature")?;
            let seed = a.u64("the random seed")?;
            if seed == 0 || seed > MAX_SEED {
                return Err(a.err(format!("the random seed must be in 1..{MAX_SEED}")));
            }
            Style::Create { t, seed }
        }
        "set" => {
            let mut c = [Component::Keep, Component::Keep, Component::Keep];
            for (d, c) in c.iter_mut().enumerate() {
                let w = a.word(&format!("the {} velocity (a number, NULL or v_name)", ["x", "y", "z"][d]))?;
                *c = match w {
                    "NULL" => Component::Keep,
                    _ => match w.strip_prefix("v_") {
                        Some(name) => Component::Variable(name.to_string()),
                        None => Component::Value(w.parse::<f64>().ok().filter(|x| x.is_finite()).ok_or_else(|| a.err(format!("expected a number, NULL or v_name, got '{w}'")))?),
                    },
                };
            }
            Style::Set(c)
        }
        "scale" => Style::Scale(a.non_negative("the temperature")?),
        "ramp" => {
            let dim = axis(a, "vx, vy or vz", "v")?;
            let v = [a.f64("vlo")?, a.f64("vhi")?];
            let coord = axis(a, "x, y or z", "")?;
            let c = [a.f64("the lower coordinate")?, a.f64("the upper coordinate")?];
            if c[0] == c[1] {
                return Err(a.err("the ramp's coordinates must differ"));
            }
            Style::Ramp { dim, v, coord, c }
        }
        "zero" => match a.word("linear or angular")? {
            "linear" => Style::Zero { angular: false },
            "angular" => Style::Zero { angular: true },
            w => return Err(a.err(format!("expected linear or angular, got '{w}'"))),
        },
        s => return Err(a.err(format!("unknown velocity style '{s}'; known: create, set, scale, ramp, zero"))),
    })
}

fn options(sim: &Sim, a: &mut Args) -> Result<Options, ScriptError> {
    let mut o = Options { gaussian: false, sum: false, mom: true, rot: false, temp: None, lp: Loop::All, lattice_units: true };
    while a.remaining() > 0 {
        match a.word("a keyword")? {
            "dist" => match a.word("uniform or gaussian")? {
                "uniform" => o.gaussian = false,
                "gaussian" => o.gaussian = true,
                d => return Err(a.err(format!("expected dist uniform or gaussian, got '{d}'"))),
            },
            "sum" => o.sum = a.yes_no("sum")?,
            "mom" => o.mom = a.yes_no("mom")?,
            "rot" => o.rot = a.yes_no("rot")?,
            "temp" => {
                let id = a.word("a compute ID")?;
                let c = compute::find(&sim.computes, id).ok_or_else(|| a.err(format!("no compute with ID '{id}'")))?;
                match c.temp_group() {
                    Some(group) => o.temp = Some(group),
                    None if c.style().starts_with("temp") => return Err(a.err(format!("compute {id} is {}: velocity temp takes a compute temp", c.style()))),
                    None => return Err(a.err(format!("compute {id} does not compute a temperature"))),
                }
            }
            "bias" => {
                if a.yes_no("bias")? {
                    return Err(a.err("bias yes: no compute temp of gendpde removes a velocity bias"));
                }
            }
            "loop" => {
                o.lp = match a.word("all, local or geom")? {
                    "all" => Loop::All,
                    "local" => Loop::Local,
                    "geom" => Loop::Geom,
                    l => return Err(a.err(format!("expected loop all, local or geom, got '{l}'"))),
                }
            }
            "units" => {
                o.lattice_units = match a.word("box or lattice")? {
                    "box" => false,
                    "lattice" => true,
                    u => return Err(a.err(format!("expected units box or lattice, got '{u}'"))),
                }
            }
            "rigid" => return Err(a.err("keyword rigid: gendpde has no rigid bodies")),
            k => return Err(a.err(format!("unknown keyword '{k}'; known: dist, sum, mom, rot, temp, bias, loop, units"))),
        }
    }
    Ok(o)
}

pub fn velocity(sim: &mut Sim, vars: &Variables, thermo: &ThermoConfig, a: &mut Args) -> Result<(), ScriptError> {
    let group = a.word("a group")?;
    let mask = groups::mask(&sim.groups, group, a)?;
    let style = style(a)?;
    let o = options(sim, a)?;
    let scale = if o.lattice_units { sim.lattice_spacing() } else { [1.0; 3] };
    let mvv2e = sim.units.mvv2e;
    let kb = sim.units.kb;
    // `velocity set`: the variables are evaluated before anything changes (as LAMMPS);
    // per particle (atom-style) or once (equal-style)
    let sys = sim.system.as_ref().ok_or_else(|| a.err("velocity before create_box"))?;
    let global = |n: &str| super::resolve(sim, thermo, vars, n);
    let mut fields: [Option<Vec<f64>>; 3] = [None, None, None];
    let mut value = [None; 3];
    if let Style::Set(c) = &style {
        for d in 0..3 {
            match &c[d] {
                Component::Value(x) => value[d] = Some(x * scale[d]),
                Component::Variable(name) if vars.style(name) == Some("atom") => fields[d] = Some(per_atom::variable(vars, name, sys, mvv2e, &global).map_err(|e| a.err(e))?),
                Component::Variable(name) => value[d] = Some(per_atom::equal(vars, name, &global).map_err(|e| a.err(e))?),
                Component::Keep => {}
            }
        }
    }
    let sys = sim.system.as_mut().ok_or_else(|| a.err("velocity before create_box"))?;
    if sys.comm.count(sys.store.nlocal) == 0 {
        return Err(a.err("no particles exist"));
    }
    let s = &sys.store;
    if let Some(i) = (0..s.nlocal).find(|&i| !s.mass[i].is_finite()) {
        return Err(a.err(format!("the mass of type {} is not set", s.kind[i])));
    }
    let members: Vec<usize> = (0..s.nlocal).filter(|&i| s.in_group(i, mask)).collect();
    let (tmask, extra_dof) = o.temp.unwrap_or((mask, 3.0));
    match style {
        Style::Create { t, seed } => {
            let old: Vec<Vec3> = members.iter().map(|&i| sys.store.p[i]).collect();
            let v = draw(sys, &members, seed, &o, sim.max_tag).map_err(|e| a.err(e))?;
            for (k, &i) in members.iter().enumerate() {
                sys.store.p[i] = v[k].map(|c| c * sys.store.mass[i]);
            }
            if (o.mom || o.rot) && sys.comm.count(members.len()) == 0 {
                return Err(a.err("cannot zero the momentum of no particles (the group is empty)"));
            }
            if o.mom {
                zero_linear(sys, &members);
            }
            if o.rot {
                zero_angular(sys, &members);
            }
            rescale(sys, &members, tmask, extra_dof, kb, t).map_err(|e| a.err(e))?;
            if o.sum {
                for (k, &i) in members.iter().enumerate() {
                    sys.store.p[i] = [0, 1, 2].map(|d| sys.store.p[i][d] + old[k][d]);
                }
            }
        }
        Style::Set(_) => {
            let s = &mut sys.store;
            for &i in &members {
                let mut v = s.p[i].map(|p| p / s.mass[i]);
                for d in 0..3 {
                    let x = match (&fields[d], value[d]) {
                        (Some(f), _) => f[i],
                        (None, Some(x)) => x,
                        (None, None) => continue,
                    };
                    v[d] = if o.sum { v[d] + x } else { x };
                }
                s.p[i] = v.map(|c| c * s.mass[i]);
            }
        }
        Style::Scale(t) => rescale(sys, &members, tmask, extra_dof, kb, t).map_err(|e| a.err(e))?,
        Style::Ramp { dim, v, coord, c } => {
            let (vlo, vhi) = (v[0] * scale[dim], v[1] * scale[dim]);
            let (clo, chi) = (c[0] * scale[coord], c[1] * scale[coord]);
            let s = &mut sys.store;
            for &i in &members {
                let fraction = ((s.r[i][coord] - clo) / (chi - clo)).clamp(0.0, 1.0);
                let ramp = vlo + fraction * (vhi - vlo);
                let m = s.mass[i];
                s.p[i][dim] = if o.sum { s.p[i][dim] + m * ramp } else { m * ramp };
            }
        }
        Style::Zero { angular } => {
            if sys.comm.count(members.len()) == 0 {
                return Err(a.err("cannot zero the momentum of no particles (the group is empty)"));
            }
            if angular {
                zero_angular(sys, &members)
            } else {
                zero_linear(sys, &members)
            }
        }
    }
    Ok(())
}

/// The raw velocities x / sqrt(m) of `members`, x uniform in (-1/2, 1/2) or normal, drawn
/// as LAMMPS's `loop` option says: `all` one stream over the IDs 1..N (every rank draws
/// all of them), `local` one stream per rank (seed + rank) over its particles in store
/// order, `geom` a stream per particle keyed by its position.
fn draw(sys: &System, members: &[usize], seed: u64, o: &Options, max_tag: u64) -> Result<Vec<Vec3>, String> {
    let s = &sys.store;
    let next = |p: &mut Park| if o.gaussian { [p.gaussian(), p.gaussian(), p.gaussian()] } else { [p.uniform() - 0.5, p.uniform() - 0.5, p.uniform() - 0.5] };
    let x: Vec<Vec3> = match o.lp {
        Loop::All => {
            let n = sys.comm.count(s.nlocal);
            if n != max_tag {
                return Err(format!("loop all needs the particle IDs 1..N ({n} particles, largest ID {max_tag}); use loop geom"));
            }
            let mut order: Vec<usize> = (0..members.len()).collect();
            order.sort_unstable_by_key(|&k| s.tag[members[k]]);
            let mut out = vec![[0.0; 3]; members.len()];
            let mut p = Park::new(seed);
            let mut pending = order.iter().peekable();
            for tag in 1..=n {
                let x = next(&mut p);
                if let Some(&&k) = pending.peek() {
                    if s.tag[members[k]] == tag {
                        out[k] = x;
                        pending.next();
                    }
                }
            }
            out
        }
        Loop::Local => {
            let seed = seed + sys.comm.rank() as u64;
            if seed > MAX_SEED {
                return Err(format!("loop local: seed + rank exceeds {MAX_SEED}"));
            }
            let mut p = Park::new(seed);
            for _ in 0..WARMUP {
                p.uniform();
            }
            members.iter().map(|_| next(&mut p)).collect()
        }
        Loop::Geom => members.iter().map(|&i| next(&mut Park::at(seed, s.r[i]))).collect(),
    };
    // the stored mass carries the units' factor mvv2e, which the rescale cancels
    Ok(members.iter().zip(x).map(|(&i, x)| x.map(|c| c / s.mass[i].sqrt())).collect())
}

/// LAMMPS's zero_momentum: subtracts the group's centre-of-mass velocity.
fn zero_linear(sys: &mut System, members: &[usize]) {
    let s = &sys.store;
    let [px, py, pz, m] = exact_sums(sys.comm.transport(), members.iter().map(|&i| [s.p[i][0], s.p[i][1], s.p[i][2], s.mass[i]]));
    let vcm = [px / m, py / m, pz / m];
    let s = &mut sys.store;
    for &i in members {
        s.p[i] = [0, 1, 2].map(|d| s.p[i][d] - s.mass[i] * vcm[d]);
    }
}

/// LAMMPS's zero_rotation: omega = I^-1 L about the centre of mass (unwrapped
/// positions), then v -= omega x (r - r_cm). A singular inertia tensor (|I| <= 1e-6, e.g.
/// collinear particles) leaves the velocities unchanged.
fn zero_angular(sys: &mut System, members: &[usize]) {
    let (s, d) = (&sys.store, &sys.domain);
    let t = sys.comm.transport();
    let x = |i: usize| d.unwrap(s.r[i], s.image[i]);
    let [mx, my, mz, m] = exact_sums(t, members.iter().map(|&i| {
        let (r, mi) = (x(i), s.mass[i]);
        [mi * r[0], mi * r[1], mi * r[2], mi]
    }));
    let cm = [mx / m, my / m, mz / m];
    let dx = |i: usize| {
        let r = x(i);
        [r[0] - cm[0], r[1] - cm[1], r[2] - cm[2]]
    };
    let sums = exact_sums(t, members.iter().map(|&i| {
        let (r, p, mi) = (dx(i), s.p[i], s.mass[i]);
        [
            r[1] * p[2] - r[2] * p[1],
            r[2] * p[0] - r[0] * p[2],
            r[0] * p[1] - r[1] * p[0],
            mi * (r[1] * r[1] + r[2] * r[2]),
            mi * (r[0] * r[0] + r[2] * r[2]),
            mi * (r[0] * r[0] + r[1] * r[1]),
            -mi * r[0] * r[1],
            -mi * r[1] * r[2],
            -mi * r[0] * r[2],
        ]
    }));
    let l = [sums[0], sums[1], sums[2]];
    let i = [[sums[3], sums[6], sums[8]], [sums[6], sums[4], sums[7]], [sums[8], sums[7], sums[5]]];
    let Some(w) = solve(i, l) else { return };
    let shifts: Vec<Vec3> = members.iter().map(|&k| dx(k)).collect();
    let s = &mut sys.store;
    for (&k, r) in members.iter().zip(shifts) {
        let wxr = [w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2], w[0] * r[1] - w[1] * r[0]];
        s.p[k] = [0, 1, 2].map(|c| s.p[k][c] - s.mass[k] * wxr[c]);
    }
}

/// I^-1 L by the adjugate, as LAMMPS's Group::omega for a non-singular tensor.
fn solve(i: [[f64; 3]; 3], l: Vec3) -> Option<Vec3> {
    let det = i[0][0] * i[1][1] * i[2][2] + i[0][1] * i[1][2] * i[2][0] + i[0][2] * i[1][0] * i[2][1]
        - i[0][0] * i[1][2] * i[2][1]
        - i[0][1] * i[1][0] * i[2][2]
        - i[2][0] * i[1][1] * i[0][2];
    if det <= 1.0e-6 {
        return None;
    }
    let inv = [
        [i[1][1] * i[2][2] - i[1][2] * i[2][1], -(i[0][1] * i[2][2] - i[0][2] * i[2][1]), i[0][1] * i[1][2] - i[0][2] * i[1][1]],
        [-(i[1][0] * i[2][2] - i[1][2] * i[2][0]), i[0][0] * i[2][2] - i[0][2] * i[2][0], -(i[0][0] * i[1][2] - i[0][2] * i[1][0])],
        [i[1][0] * i[2][1] - i[1][1] * i[2][0], -(i[0][0] * i[2][1] - i[0][1] * i[2][0]), i[0][0] * i[1][1] - i[0][1] * i[1][0]],
    ];
    Some([0, 1, 2].map(|r| (inv[r][0] * l[0] + inv[r][1] * l[1] + inv[r][2] * l[2]) / det))
}

/// Scales the group's velocities by sqrt(T / T_now), T_now from the compute temp of group
/// bit `tmask` with 3N - `extra_dof` degrees of freedom (LAMMPS refuses T_now = 0).
fn rescale(sys: &mut System, members: &[usize], tmask: u32, extra_dof: f64, kb: f64, t: f64) -> Result<(), String> {
    let now = group_temperature(sys, tmask, extra_dof).value(kb);
    if now == 0.0 {
        return Err("cannot rescale a temperature of 0 (no kinetic energy or no degrees of freedom)".into());
    }
    let factor = (t / now).sqrt();
    for &i in members {
        sys.store.p[i] = sys.store.p[i].map(|c| c * factor);
    }
    Ok(())
}
