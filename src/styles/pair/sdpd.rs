//! `pair_style sdpd/generic CUTOFF SEED [kB KB] [weight W] [volume plain|normalized]` with
//! `pair_coeff * * ETA ZETA KAPPA`: thermal SDPD, the SPH model of Serrano and Espanol
//! (Sec VII); its EOS comes from a `fix eos/...`, its integrator is `fix nve/sdpd`.

use crate::base::args::Args;
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::WeightKind;

#[derive(Clone, Debug, PartialEq)]
pub struct PairSdpd {
    pub cutoff: f64,
    pub seed: u64,
    /// Boltzmann's constant of the fluctuations (None: that of the units).
    pub kb: Option<f64>,
    pub weight: WeightKind,
    /// The normalised volume of eq 97 (remnant-free force, eq 99).
    pub normalized: bool,
    /// Shear viscosity, bulk viscosity, thermal conductivity (eq 78).
    pub coeff: Option<[f64; 3]>,
}

/// The words after `pair_style sdpd/generic`.
pub fn parse_style(a: &mut Args) -> Result<PairSdpd, ScriptError> {
    let cutoff = a.positive("the kernel cutoff h")?;
    let seed = a.u64("the random seed")?;
    if seed == 0 {
        return Err(a.err("the random seed must be positive"));
    }
    let mut p = PairSdpd { cutoff, seed, kb: None, weight: WeightKind::Lucy, normalized: false, coeff: None };
    while let Some(key) = a.peek() {
        a.word("keyword")?;
        match key {
            "kB" => p.kb = Some(a.non_negative("Boltzmann's constant of the fluctuations")?),
            "weight" => {
                let w = a.word("a weight function")?;
                p.weight = WeightKind::parse(w).ok_or_else(|| a.err(format!("unknown weight '{w}'; known: quadratic, linear, lucy, spline")))?;
            }
            "volume" => {
                p.normalized = match a.word("plain or normalized")? {
                    "plain" => false,
                    "normalized" => true,
                    v => return Err(a.err(format!("unknown particle volume '{v}'; known: plain, normalized"))),
                }
            }
            _ => return Err(a.err(format!("unknown keyword '{key}'; known: kB, weight, volume"))),
        }
    }
    Ok(p)
}

/// `pair_coeff * * ETA ZETA KAPPA`.
pub fn parse_coeff(cmd: &Command, ntypes: usize) -> Result<[f64; 3], ScriptError> {
    let mut a = Args::new(cmd);
    a.all_type_pairs(ntypes, "sdpd/generic")?;
    let eta = a.non_negative("the shear viscosity eta")?;
    let zeta = a.non_negative("the bulk viscosity zeta")?;
    let kappa = a.non_negative("the thermal conductivity kappa")?;
    a.done()?;
    Ok([eta, zeta, kappa])
}
