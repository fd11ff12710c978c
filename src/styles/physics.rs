//! The dynamics of a `run`, assembled from the pair style and the fixes: GenDPDE
//! monomorphised over its EOS and weight function, or LAMMPS's pairwise DPD styles.

use crate::styles::fix::eos::{each_eos, EosModel};
use crate::styles::fix::{Fix, FixStyle};
use crate::styles::pair::gendpde::{PairCoeff, PairGendpde};
use crate::styles::pair::pairwise::{Kind, Pairwise};
use crate::styles::pair::PairStyle;
use gendpde_integrators::{
    ClassicDpd, Dissipation, FixedEntropy, GenDpde, HeatModel, Integration, Motion, PairForce, Physics, RebuildPolicy, Reservoir, Settings, ShardlowDpd, Species,
};
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::volume::PartitionVolume;
use gendpde_potentials::{CubicSpline, Linear, Lucy, Quadratic, WeightKind};

/// Assembles the dynamics of a `run` from the pair style and the fixes.
pub fn build_physics(
    cmd: &Command,
    pair: Option<&PairStyle>,
    fixes: &[Fix],
    dt: f64,
    skin: f64,
    rebuild: RebuildPolicy,
    kb: f64,
) -> Result<Box<dyn Physics>, ScriptError> {
    let err = |m: String| ScriptError::at(cmd, m);
    let pair = match pair.ok_or_else(|| err("no pair style is defined (pair_style)".into()))? {
        PairStyle::Gendpde(p) => p,
        PairStyle::Pairwise(p) => {
            let settings = Settings { dt, skin, rebuild, motion: Motion::Fixed, dissipation: None, reservoirs: Vec::new() };
            return pairwise(cmd, p, fixes, settings, kb);
        }
        PairStyle::Sdpd(p) => return crate::styles::sdpd::build_sdpd(cmd, p, fixes, dt, skin, rebuild, kb),
    };
    if let Some(f) = fixes.iter().find(|f| f.style == FixStyle::NveSdpd) {
        return Err(err(format!("fix {} (nve/sdpd) integrates pair sdpd/generic", f.id)));
    }
    if fixes.iter().any(|f| matches!(f.style, FixStyle::Nve | FixStyle::Mvv { .. })) {
        return Err(err("pair gendpde integrates with fix nve/gendpde or vv/euler (fix nve and mvv/dpd belong to LAMMPS's pairwise styles)".into()));
    }
    let eos: Vec<&EosModel> = fixes.iter().filter_map(|f| if let FixStyle::Eos(e) = &f.style { Some(e) } else { None }).collect();
    let eos = match eos.as_slice() {
        [e] => (*e).clone(),
        [] => return Err(err("no EOS fix is defined (fix ID all eos/...)".into())),
        _ => return Err(err("more than one EOS fix is defined".into())),
    };
    let find = |pred: fn(&FixStyle) -> bool| fixes.iter().find(|f| pred(&f.style));
    for (name, pred) in [
        ("nve/gendpde", (|s: &FixStyle| matches!(s, FixStyle::Verlet { .. })) as fn(&FixStyle) -> bool),
        ("shardlow", |s| matches!(s, FixStyle::Shardlow { .. })),
        ("vv/euler", |s| matches!(s, FixStyle::VvEuler { .. })),
    ] {
        if fixes.iter().filter(|f| pred(&f.style)).count() > 1 {
            return Err(err(format!("more than one fix {name} is defined")));
        }
    }
    let coeff = |name: &str| {
        pair.coeff.as_ref().ok_or_else(|| err(format!("fix {name} needs the pair coefficients (pair_coeff * * GAMMA KAPPA)")))
    };
    let dissipation_of = |c: &PairCoeff, heat: HeatModel, substeps: u32, reject: bool| Dissipation {
        gamma: c.gamma,
        rc_friction: c.rc_friction,
        kappa: c.kappa,
        rc_heat: c.rc_heat,
        heat,
        seed: pair.seed,
        substeps,
        reject,
    };
    let shardlow = find(|s| matches!(s, FixStyle::Shardlow { .. }));
    let (motion, dissipation) = match (find(|s| matches!(s, FixStyle::Verlet { .. })), find(|s| matches!(s, FixStyle::VvEuler { .. }))) {
        (Some(v), Some(e)) => {
            return Err(err(format!("fix {} (nve/gendpde) and fix {} (vv/euler) both move the particles: keep one", v.id, e.id)));
        }
        (_, Some(e)) => {
            if let Some(f) = shardlow {
                return Err(err(format!("fix {} (vv/euler) applies friction, noise and heat flow itself: unfix {} (shardlow)", e.id, f.id)));
            }
            let FixStyle::VvEuler { heat } = e.style else { unreachable!("matched above") };
            (Motion::VvEuler, Some(dissipation_of(coeff("vv/euler")?, heat, 0, false)))
        }
        (verlet, _) => {
            let motion = match verlet {
                Some(Fix { style: FixStyle::Verlet { work }, .. }) => Motion::Verlet(*work),
                _ => Motion::Fixed,
            };
            let dissipation = match shardlow {
                Some(Fix { style: FixStyle::Shardlow { heat, substeps, reject }, .. }) => Some(dissipation_of(coeff("shardlow")?, *heat, *substeps, *reject)),
                _ => None,
            };
            (motion, dissipation)
        }
    };
    let pair_heat = dissipation.as_ref().map(|d| d.heat);
    let reservoirs: Vec<Reservoir> = fixes
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
            return Err(err(format!("fix {} (heat/reservoir) and fix {other} must use the same heat model", r.id)));
        }
    }
    let settings = Settings { dt, skin, rebuild, motion, dissipation, reservoirs };
    if let EosModel::PerType(v) = eos {
        return Ok(with_weight(v, pair, settings));
    }
    Ok(each_eos!(eos, e => with_weight(vec![e.clone()], pair, settings)))
}

/// Monomorphises the dynamics over the weight function; `per_type` holds one EOS for
/// all types or one per type.
fn with_weight<E: FixedEntropy + 'static>(per_type: Vec<E>, pair: &PairGendpde, settings: Settings) -> Box<dyn Physics> {
    let Some(eos) = Species::new(per_type) else { unreachable!("an EOS model holds at least one EOS") };
    let rc = pair.cutoff;
    let volume = pair.volume.map(|fcut| PartitionVolume::new(rc, fcut));
    match pair.weight {
        WeightKind::Quadratic => Box::new(GenDpde { eos, weight: Quadratic::new(rc), volume, settings }),
        WeightKind::Linear => Box::new(GenDpde { eos, weight: Linear::new(rc), volume, settings }),
        WeightKind::Lucy => Box::new(GenDpde { eos, weight: Lucy::new(rc), volume, settings }),
        WeightKind::CubicSpline => Box::new(GenDpde { eos, weight: CubicSpline::new(rc), volume, settings }),
    }
}

/// The dynamics of a pairwise scene from the pair style and the fixes.
fn pairwise(cmd: &Command, p: &Pairwise, fixes: &[Fix], settings: Settings, kb: f64) -> Result<Box<dyn Physics>, ScriptError> {
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
    if has(|s| matches!(s, FixStyle::Verlet { .. } | FixStyle::VvEuler { .. } | FixStyle::Reservoir { .. } | FixStyle::NveSdpd)) {
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
