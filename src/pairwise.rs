//! LAMMPS's pairwise DPD styles, with their names, arguments and semantics:
//!
//! - `pair_style dpd T CUTOFF SEED`, `pair_coeff I J A GAMMA [CUTOFF]` with `fix nve`;
//! - `pair_style dpd/fdt T CUTOFF SEED`, `pair_coeff I J A SIGMA [CUTOFF]` with
//!   `fix shardlow` + `fix nve`;
//! - `pair_style dpd/fdt/energy CUTOFF SEED`, `pair_coeff I J A SIGMA KAPPA [CUTOFF]` with
//!   `fix shardlow` + `fix nve` + `fix eos/cv CV`;
//! - `pair_style hybrid/overlay mdpd/rhosum mdpd T CUTOFF SEED`,
//!   `pair_coeff I J mdpd/rhosum H`, `pair_coeff I J mdpd A B GAMMA CUTOFF CUTOFF_R` with
//!   `fix mvv/dpd [LAMBDA]`.
//!
//! One coefficient set serves all type pairs (`pair_coeff * *`, or `1 1` with one type).

use crate::args::Args;
use crate::styles::{EosModel, Fix, FixStyle};
use gendpde_integrators::{ClassicDpd, Integration, PairForce, Physics, Settings, ShardlowDpd};
use gendpde_io::{Command, ScriptError};

#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    Dpd { temperature: f64 },
    DpdFdt { temperature: f64 },
    DpdFdtEnergy,
    Mdpd { temperature: f64 },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Pairwise {
    pub kind: Kind,
    pub cutoff: f64,
    pub seed: u64,
    /// A (a0), B (mdpd), gamma (dpd, mdpd) or sigma (dpd/fdt*), kappa, cutoff, cutoff_r.
    pub coeff: Option<Coeff>,
    /// Kernel support of `mdpd/rhosum`.
    pub rhosum: Option<f64>,
}

#[derive(Clone, Debug, PartialEq, Default)]
pub struct Coeff {
    pub a: f64,
    pub b: f64,
    pub gamma: f64,
    pub sigma: f64,
    pub kappa: f64,
    pub rc: f64,
    pub rd: f64,
}

pub const STYLES: &str = "gendpde, dpd, dpd/fdt, dpd/fdt/energy, hybrid/overlay mdpd/rhosum mdpd";

/// A pairwise `pair_style` line (the words after the style name in `a`).
pub fn parse_style(style: &str, a: &mut Args) -> Result<Pairwise, ScriptError> {
    let kind = match style {
        "dpd" => Kind::Dpd { temperature: a.positive("the temperature T")? },
        "dpd/fdt" => Kind::DpdFdt { temperature: a.positive("the temperature T")? },
        "dpd/fdt/energy" => Kind::DpdFdtEnergy,
        "hybrid/overlay" => {
            for expect in ["mdpd/rhosum", "mdpd"] {
                let w = a.word(expect)?;
                if w != expect {
                    return Err(a.err(format!("pair_style hybrid/overlay supports 'mdpd/rhosum mdpd ...' only, got '{w}'")));
                }
            }
            Kind::Mdpd { temperature: a.positive("the temperature T")? }
        }
        other => return Err(a.err(format!("unknown pair style '{other}'; known: {STYLES}"))),
    };
    let cutoff = a.positive("the cutoff")?;
    let seed = a.u64("the random seed")?;
    if seed == 0 {
        return Err(a.err("the random seed must be positive"));
    }
    a.done()?;
    Ok(Pairwise { kind, cutoff, seed, coeff: None, rhosum: None })
}

/// A `pair_coeff` line for a pairwise style.
pub fn parse_coeff(p: &mut Pairwise, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
    let mut a = Args::new(cmd);
    let (ti, tj) = (a.types(ntypes)?, a.types(ntypes)?);
    if *ti.start() != 1 || *ti.end() != ntypes || *tj.start() != 1 || *tj.end() != ntypes {
        return Err(a.err("one coefficient set for all type pairs: use 'pair_coeff * *' (or '1 1' with one type)"));
    }
    let mut c = p.coeff.clone().unwrap_or_default();
    let optional_cutoff = |a: &mut Args, default: f64| if a.remaining() > 0 { a.positive("the cutoff") } else { Ok(default) };
    match p.kind {
        Kind::Dpd { .. } => {
            c.a = a.f64("A (a0)")?;
            c.gamma = a.non_negative("gamma")?;
            c.rc = optional_cutoff(&mut a, p.cutoff)?;
        }
        Kind::DpdFdt { .. } => {
            c.a = a.f64("A (a0)")?;
            c.sigma = a.non_negative("sigma")?;
            c.rc = optional_cutoff(&mut a, p.cutoff)?;
        }
        Kind::DpdFdtEnergy => {
            c.a = a.f64("A (a0)")?;
            c.sigma = a.non_negative("sigma")?;
            c.kappa = a.non_negative("kappa")?;
            c.rc = optional_cutoff(&mut a, p.cutoff)?;
        }
        Kind::Mdpd { .. } => match a.word("mdpd/rhosum or mdpd")? {
            "mdpd/rhosum" => {
                p.rhosum = Some(a.positive("the kernel cutoff h")?);
                a.done()?;
                return Ok(());
            }
            "mdpd" => {
                c.a = a.f64("A")?;
                c.b = a.f64("B")?;
                c.gamma = a.non_negative("gamma")?;
                c.rc = a.positive("the cutoff")?;
                c.rd = a.positive("the cutoff of the repulsive term")?;
            }
            w => return Err(a.err(format!("expected mdpd/rhosum or mdpd, got '{w}'"))),
        },
    }
    a.done()?;
    p.coeff = Some(c);
    Ok(())
}

/// The dynamics of a pairwise scene from the pair style and the fixes.
pub fn build(cmd: &Command, p: &Pairwise, fixes: &[Fix], settings: Settings, kb: f64) -> Result<Box<dyn Physics>, ScriptError> {
    let err = |m: &str| ScriptError::at(cmd, m);
    let c = p.coeff.as_ref().ok_or_else(|| err("the pair style has no coefficients (pair_coeff)"))?;
    let has = |pred: fn(&FixStyle) -> bool| fixes.iter().any(|f| pred(&f.style));
    let shardlow = has(|s| matches!(s, FixStyle::Shardlow { .. }));
    let nve = has(|s| matches!(s, FixStyle::Nve));
    let mvv = fixes.iter().find_map(|f| if let FixStyle::Mvv { lambda } = f.style { Some(lambda) } else { None });
    let cv = fixes.iter().find_map(|f| match &f.style {
        FixStyle::Eos(EosModel::Linear(e)) if !gendpde_potentials::Eos::density_dependent(e) && e.q == 0.0 => Some(e.cv),
        _ => None,
    });
    if has(|s| matches!(s, FixStyle::Verlet { .. } | FixStyle::VvEuler { .. } | FixStyle::Reservoir { .. })) {
        return Err(err("fix nve/gendpde, vv/euler and heat/reservoir belong to pair gendpde; LAMMPS's pairwise styles use fix nve, shardlow, eos/cv, mvv/dpd"));
    }
    let integration = match (nve, mvv) {
        (true, None) => Integration::Nve,
        (false, Some(lambda)) => Integration::Mvv { lambda },
        (true, Some(_)) => return Err(err("fix nve and fix mvv/dpd both integrate: keep one")),
        (false, None) => return Err(err("no integrator: add fix nve (or fix mvv/dpd for mdpd)")),
    };
    let sigma_of = |t: f64| (2.0 * kb * t * c.gamma).sqrt();
    let (force, sweep) = match p.kind {
        Kind::Dpd { temperature } => (PairForce::Dpd { a0: c.a, rc: c.rc, gamma: c.gamma, sigma: sigma_of(temperature) }, None),
        Kind::DpdFdt { temperature } => (
            PairForce::Dpd { a0: c.a, rc: c.rc, gamma: 0.0, sigma: 0.0 },
            Some(ShardlowDpd { sigma: c.sigma, kappa: 0.0, rc: c.rc, temperature: Some(temperature) }),
        ),
        Kind::DpdFdtEnergy => (
            PairForce::Dpd { a0: c.a, rc: c.rc, gamma: 0.0, sigma: 0.0 },
            Some(ShardlowDpd { sigma: c.sigma, kappa: c.kappa, rc: c.rc, temperature: None }),
        ),
        Kind::Mdpd { temperature } => {
            let h = p.rhosum.ok_or_else(|| err("pair mdpd needs 'pair_coeff * * mdpd/rhosum H'"))?;
            let force = PairForce::Mdpd { a: c.a, b: c.b, rc: c.rc, rd: c.rd, gamma: c.gamma, sigma: sigma_of(temperature), h };
            (force, None)
        }
    };
    match (&p.kind, shardlow) {
        (Kind::DpdFdt { .. } | Kind::DpdFdtEnergy, false) => return Err(err("pair dpd/fdt and dpd/fdt/energy need fix shardlow")),
        (Kind::Dpd { .. } | Kind::Mdpd { .. }, true) => return Err(err("fix shardlow works with pair dpd/fdt and dpd/fdt/energy")),
        _ => {}
    }
    if matches!(p.kind, Kind::DpdFdtEnergy) && cv.is_none() {
        return Err(err("pair dpd/fdt/energy needs fix eos/cv"));
    }
    if matches!(integration, Integration::Mvv { .. }) && !matches!(p.kind, Kind::Mdpd { .. }) {
        return Err(err("fix mvv/dpd integrates pair mdpd"));
    }
    Ok(Box::new(ClassicDpd { force, shardlow: sweep, integration, cv, kb, seed: p.seed, settings }))
}
