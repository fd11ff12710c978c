//! `pair_style gendpde CUTOFF SEED [weight W] [volume plain|corrected FCUT]` with
//! `pair_coeff * * GAMMA KAPPA [RC_D [RC_H]]`: the GenDPDE pair style (its EOS comes from
//! a `fix eos/...`).

use super::{Pair, RunInputs};
use crate::base::args::Args;
use crate::styles::fix::eos::{each_eos, EosModel};
use crate::styles::fix::one_eos;
use crate::styles::fix::FixStyle;
use gendpde_integrators::{Dissipation, FixedEntropy, GenDpde, HeatModel, Motion, NoiseForm, Physics, Reservoir, Settings, Species};
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::volume::PartitionVolume;
use gendpde_potentials::{CubicSpline, FixedDensity, Linear, Lucy, Quadratic, Weight, WeightKind};

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
fn parse(a: &mut Args) -> Result<PairGendpde, ScriptError> {
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
fn parse_coeff(cmd: &Command, pair: &PairGendpde, ntypes: usize) -> Result<PairCoeff, ScriptError> {
    let mut a = Args::new(cmd);
    a.all_type_pairs(ntypes, "gendpde")?;
    let gamma = a.non_negative("the friction gamma")?;
    let kappa = a.non_negative("the conductivity kappa")?;
    let rc_friction = if a.remaining() > 0 { a.positive("the friction cutoff")? } else { pair.cutoff };
    let rc_heat = if a.remaining() > 0 { a.positive("the heat cutoff")? } else { rc_friction };
    a.done()?;
    Ok(PairCoeff { gamma, kappa, rc_friction, rc_heat })
}

/// `pair_style gendpde ...`.
pub fn parse_style(_name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError> {
    parse(a).map(|p| Box::new(p) as Box<dyn Pair>)
}

impl Pair for PairGendpde {
    fn name(&self) -> &str {
        "gendpde"
    }

    fn coeff(&mut self, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
        self.coeff = Some(parse_coeff(cmd, self, ntypes)?);
        Ok(())
    }

    fn accepts(&self, fix: &FixStyle) -> bool {
        matches!(fix, FixStyle::Eos(_) | FixStyle::Verlet { .. } | FixStyle::VvEuler { .. } | FixStyle::Shardlow { .. } | FixStyle::Reservoir { .. })
    }

    fn fixes(&self) -> &'static str {
        "eos/..., nve/gendpde, shardlow, vv/euler, heat/reservoir"
    }

    fn pe_is_pair(&self) -> bool {
        false
    }

    fn keep_coefficients(&mut self, old: &dyn Pair) -> bool {
        let Some(old) = old.as_any().downcast_ref::<Self>() else { return false };
        self.coeff = old.coeff.clone().map(|c| PairCoeff { rc_friction: self.cutoff, rc_heat: self.cutoff, ..c });
        true
    }

    fn build(&self, run: &RunInputs) -> Result<Box<dyn Physics>, String> {
        let eos = one_eos(run.fixes)?;
        let verlet = run.one("nve/gendpde", |s| if let FixStyle::Verlet { work } = s { Some(*work) } else { None })?;
        let shardlow = run.one("shardlow", |s| if let FixStyle::Shardlow { heat, noise, substeps, reject } = s { Some((*heat, *noise, *substeps, *reject)) } else { None })?;
        let vv_euler = run.one("vv/euler", |s| if let FixStyle::VvEuler { heat } = s { Some(*heat) } else { None })?;
        let coeff = |name: &str| self.coeff.as_ref().ok_or_else(|| format!("fix {name} needs the pair coefficients (pair_coeff * * GAMMA KAPPA)"));
        let dissipation_of = |c: &PairCoeff, heat: HeatModel, noise: NoiseForm, substeps: u32, reject: bool| Dissipation {
            gamma: c.gamma,
            rc_friction: c.rc_friction,
            kappa: c.kappa,
            rc_heat: c.rc_heat,
            heat,
            noise,
            seed: self.seed,
            substeps,
            reject,
        };
        let (motion, dissipation) = match (verlet, vv_euler) {
            (Some((v, _)), Some((e, _))) => {
                return Err(format!("fix {} (nve/gendpde) and fix {} (vv/euler) both move the particles: keep one", v.id, e.id));
            }
            (_, Some((e, heat))) => {
                if let Some((f, _)) = shardlow {
                    return Err(format!("fix {} (vv/euler) applies friction, noise and heat flow itself: unfix {} (shardlow)", e.id, f.id));
                }
                (Motion::VvEuler, Some(dissipation_of(coeff("vv/euler")?, heat, NoiseForm::Arithmetic, 0, false)))
            }
            (verlet, None) => {
                let motion = verlet.map_or(Motion::Fixed, |(_, work)| Motion::Verlet(work));
                let dissipation = match shardlow {
                    Some((_, (heat, noise, substeps, reject))) => Some(dissipation_of(coeff("shardlow")?, heat, noise, substeps, reject)),
                    None => None,
                };
                (motion, dissipation)
            }
        };
        let pair_heat = dissipation.as_ref().map(|d| d.heat);
        let reservoirs: Vec<Reservoir> = run
            .fixes
            .iter()
            .filter_map(|f| match &f.style {
                FixStyle::Reservoir { temperature, kappa, seed, heat, mask } => Some(Reservoir {
                    id: f.id.clone(),
                    mask: *mask,
                    temperature: *temperature,
                    kappa: *kappa,
                    seed: *seed,
                    heat: heat.or(pair_heat).unwrap_or(HeatModel::Original),
                }),
                _ => None,
            })
            .collect();
        if let Some(first) = reservoirs.first() {
            let (model, other) = match pair_heat {
                Some(h) => (h, if motion == Motion::VvEuler { "vv/euler" } else { "shardlow" }.to_string()),
                None => (first.heat, format!("{} (heat/reservoir)", first.id)),
            };
            if let Some(r) = reservoirs.iter().find(|r| r.heat != model) {
                return Err(format!("fix {} (heat/reservoir) and fix {other} must use the same heat model", r.id));
            }
        }
        let scheme = Scheme { settings: run.settings(), motion, dissipation, reservoirs };
        if let EosModel::PerType(v) = eos {
            return Ok(with_weight(v, self, scheme));
        }
        Ok(each_eos!(eos, e => with_weight(vec![e.clone()], self, scheme)))
    }
}

/// What GenDPDE's step does besides its EOS and weight, gathered from the fixes.
struct Scheme {
    settings: Settings,
    motion: Motion,
    dissipation: Option<Dissipation>,
    reservoirs: Vec<Reservoir>,
}

/// Monomorphises the dynamics over the weight function; `per_type` holds one EOS for
/// all types or one per type.
fn with_weight<E: FixedEntropy + FixedDensity + 'static>(per_type: Vec<E>, pair: &PairGendpde, scheme: Scheme) -> Box<dyn Physics> {
    let Some(eos) = Species::new(per_type) else { unreachable!("an EOS model holds at least one EOS") };
    let rc = pair.cutoff;
    let volume = pair.volume.map(|fcut| PartitionVolume::new(rc, fcut));
    match pair.weight {
        WeightKind::Quadratic => model(eos, Quadratic::new(rc), volume, scheme),
        WeightKind::Linear => model(eos, Linear::new(rc), volume, scheme),
        WeightKind::Lucy => model(eos, Lucy::new(rc), volume, scheme),
        WeightKind::CubicSpline => model(eos, CubicSpline::new(rc), volume, scheme),
    }
}

fn model<E: FixedEntropy + FixedDensity + 'static, W: Weight + 'static>(eos: Species<E>, weight: W, volume: Option<PartitionVolume>, scheme: Scheme) -> Box<dyn Physics> {
    let Scheme { settings, motion, dissipation, reservoirs } = scheme;
    Box::new(GenDpde { eos, weight, volume, settings, motion, dissipation, reservoirs })
}
