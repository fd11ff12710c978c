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

use crate::base::args::Args;
use crate::styles::PAIR_STYLES;
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
        other => return Err(a.err(format!("unknown pair style '{other}'; known: {PAIR_STYLES}"))),
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
