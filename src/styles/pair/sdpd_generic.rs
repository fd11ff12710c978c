//! `pair_style sdpd/generic CUTOFF SEED [kB KB] [weight W] [volume plain|normalized]` with
//! `pair_coeff * * ETA ZETA KAPPA`: thermal SDPD, the SPH model of Serrano and Espanol
//! (Sec VII); its EOS comes from a `fix eos/...`, its integrator is `fix nve/sdpd`.

use super::{Pair, RunInputs};
use crate::base::args::Args;
use crate::styles::fix::eos::{each_eos, EosModel};
use crate::styles::fix::one_eos;
use crate::styles::fix::FixStyle;
use gendpde_integrators::{FixedEntropy, Physics, Sdpd, SdpdParams, Settings, Species};
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::{CubicSpline, Linear, Lucy, Quadratic, WeightKind};

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
fn parse(a: &mut Args) -> Result<PairSdpd, ScriptError> {
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
fn parse_coeff(cmd: &Command, ntypes: usize) -> Result<[f64; 3], ScriptError> {
    let mut a = Args::new(cmd);
    a.all_type_pairs(ntypes, "sdpd/generic")?;
    let eta = a.non_negative("the shear viscosity eta")?;
    let zeta = a.non_negative("the bulk viscosity zeta")?;
    let kappa = a.non_negative("the thermal conductivity kappa")?;
    a.done()?;
    Ok([eta, zeta, kappa])
}

/// `pair_style sdpd/generic ...`.
pub fn parse_style(_name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError> {
    parse(a).map(|p| Box::new(p) as Box<dyn Pair>)
}

impl Pair for PairSdpd {
    fn name(&self) -> &str {
        "sdpd/generic"
    }

    fn coeff(&mut self, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
        self.coeff = Some(parse_coeff(cmd, ntypes)?);
        Ok(())
    }

    fn accepts(&self, fix: &FixStyle) -> bool {
        matches!(fix, FixStyle::Eos(_) | FixStyle::NveSdpd)
    }

    fn fixes(&self) -> &'static str {
        "one eos/... and nve/sdpd"
    }

    fn pe_is_pair(&self) -> bool {
        false
    }

    /// Thermal SDPD from the pair style, one EOS fix and `fix nve/sdpd`; the units' k_B
    /// is the default of the style's `kB`.
    fn build(&self, run: &RunInputs) -> Result<Box<dyn Physics>, String> {
        let [eta, zeta, kappa] = self.coeff.ok_or("pair sdpd/generic has no coefficients (pair_coeff * * ETA ZETA KAPPA)")?;
        if run.one("nve/sdpd", |s| (*s == FixStyle::NveSdpd).then_some(()))?.is_none() {
            return Err("pair sdpd/generic needs fix nve/sdpd".into());
        }
        let eos = one_eos(run.fixes)?;
        let params = SdpdParams { eta, zeta, kappa, kb: self.kb.unwrap_or(run.kb), seed: self.seed, normalized: self.normalized };
        let settings = run.settings();
        if let EosModel::PerType(v) = eos {
            return Ok(with_weight(v, self, params, settings));
        }
        Ok(each_eos!(eos, e => with_weight(vec![e.clone()], self, params, settings)))
    }
}

fn with_weight<E: FixedEntropy + 'static>(per_type: Vec<E>, pair: &PairSdpd, params: SdpdParams, settings: Settings) -> Box<dyn Physics> {
    let Some(eos) = Species::new(per_type) else { unreachable!("an EOS model holds at least one EOS") };
    let rc = pair.cutoff;
    match pair.weight {
        WeightKind::Quadratic => Box::new(Sdpd::new(eos, Quadratic::new(rc), params, settings)),
        WeightKind::Linear => Box::new(Sdpd::new(eos, Linear::new(rc), params, settings)),
        WeightKind::Lucy => Box::new(Sdpd::new(eos, Lucy::new(rc), params, settings)),
        WeightKind::CubicSpline => Box::new(Sdpd::new(eos, CubicSpline::new(rc), params, settings)),
    }
}
