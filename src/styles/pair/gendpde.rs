//! `pair_style gendpde CUTOFF SEED [weight W] [volume plain|corrected FCUT]` with
//! `pair_coeff * * GAMMA KAPPA [RC_D [RC_H]]`: the GenDPDE pair style (its EOS comes from
//! a `fix eos/...`).

use crate::base::args::Args;
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::WeightKind;

#[derive(Clone, Debug, PartialEq)]
pub struct PairGendpde {
    pub cutoff: f64,
    pub seed: u64,
    pub weight: WeightKind,
    /// f_cut of the corrected particle volume (argon paper eqs 2-3); None: n = n^b.
    pub volume: Option<f64>,
    pub coeff: Option<PairCoeff>,
}

/// Dissipation parameters of `pair_coeff`.
#[derive(Clone, Debug, PartialEq)]
pub struct PairCoeff {
    pub gamma: f64,
    pub kappa: f64,
    pub rc_friction: f64,
    pub rc_heat: f64,
}

/// The words after `pair_style gendpde`.
pub fn parse_style(a: &mut Args) -> Result<PairGendpde, ScriptError> {
    let cutoff = a.positive("the density cutoff")?;
    let seed = a.u64("the random seed")?;
    if seed == 0 {
        return Err(a.err("the random seed must be positive"));
    }
    let (mut weight, mut volume) = (WeightKind::Quadratic, None);
    while let Some(key) = a.peek() {
        a.word("keyword")?;
        match key {
            "weight" => {
                let w = a.word("a weight function")?;
                weight = WeightKind::parse(w).ok_or_else(|| a.err(format!("unknown weight '{w}'; known: quadratic, linear, lucy, spline")))?;
            }
            "volume" => {
                volume = match a.word("plain or corrected")? {
                    "plain" => None,
                    "corrected" => Some(a.positive("the cutoff scaling factor f_cut")?),
                    v => return Err(a.err(format!("unknown particle volume '{v}'; known: plain, corrected FCUT"))),
                }
            }
            _ => return Err(a.err(format!("unknown keyword '{key}'; known: weight, volume"))),
        }
    }
    Ok(PairGendpde { cutoff, seed, weight, volume, coeff: None })
}

/// `pair_coeff * * GAMMA KAPPA [RC_D [RC_H]]`.
pub fn parse_coeff(cmd: &Command, pair: &PairGendpde, ntypes: usize) -> Result<PairCoeff, ScriptError> {
    let mut a = Args::new(cmd);
    a.all_type_pairs(ntypes, "gendpde")?;
    let gamma = a.non_negative("the friction gamma")?;
    let kappa = a.non_negative("the conductivity kappa")?;
    let rc_friction = if a.remaining() > 0 { a.positive("the friction cutoff")? } else { pair.cutoff };
    let rc_heat = if a.remaining() > 0 { a.positive("the heat cutoff")? } else { rc_friction };
    a.done()?;
    Ok(PairCoeff { gamma, kappa, rc_friction, rc_heat })
}
