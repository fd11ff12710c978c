//! The dynamics of a `run`, assembled from the pair style and the fixes: GenDPDE
//! monomorphised over its EOS and weight function, or LAMMPS's pairwise DPD styles.

use crate::styles::fix::eos::{each_eos, EosModel};
use crate::styles::fix::{Fix, FixStyle, Source};
use crate::styles::pair::edpd::PairEdpd;
use crate::styles::pair::gendpde::{PairCoeff, PairGendpde};
use crate::styles::pair::pairwise::{Kind, Pairwise};
use crate::styles::pair::table::{tables_for_run, Tabulated};
use crate::styles::pair::PairStyle;
use gendpde_integrators::{
    ClassicDpd, Dissipation, DpdCoeff, DpdEnergyCoeff, DpdExt, DpdExtCoeff, Edpd, FixedEntropy, GenDpde, HeatModel, HeatSource, Integration, MdpdCoeff, Motion, NoiseForm, PairForce, Physics,
    RebuildPolicy, Reservoir, Settings, ShardlowCoeff, ShardlowDpd, SourceShape, Species, TypeTable,
};
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::volume::PartitionVolume;
use gendpde_potentials::{CubicSpline, FixedDensity, Linear, Lucy, Quadratic, WeightKind};

/// Assembles the dynamics of a `run` from the pair style and the fixes.
pub fn build_physics(
    cmd: &Command,
    pair: Option<&PairStyle>,
    fixes: &[Fix],
    dt: f64,
    skin: f64,
    rebuild: RebuildPolicy,
    kb: f64,
    mvv2e: f64,
    ntypes: usize,
) -> Result<Box<dyn Physics>, ScriptError> {
    let err = |m: String| ScriptError::at(cmd, m);
    if let Some(f) = fixes.iter().find(|f| f.style == FixStyle::Sph).filter(|_| !matches!(pair, Some(PairStyle::Taitwater(_)))) {
        return Err(err(format!("fix {} (sph) integrates pair sdpd/taitwater/isothermal", f.id)));
    }
    let pair = match pair.ok_or_else(|| err("no pair style is defined (pair_style)".into()))? {
        PairStyle::Gendpde(p) => p,
        PairStyle::Pairwise(p) => {
            let settings = Settings { dt, skin, rebuild };
            return Ok(Box::new(pairwise(cmd, p, fixes, settings, kb, ntypes)?));
        }
        PairStyle::Edpd(p) => {
            let settings = Settings { dt, skin, rebuild };
            return edpd(cmd, p, fixes, settings, kb);
        }
        PairStyle::Table(t) | PairStyle::MultiLucy(t) => {
            let settings = Settings { dt, skin, rebuild };
            return tabulated(cmd, t, None, fixes, settings, kb, ntypes);
        }
        PairStyle::Overlay(o) => {
            let settings = Settings { dt, skin, rebuild };
            return match (&o.table, &o.pairwise) {
                (Some(t), p) => tabulated(cmd, t, p.as_ref().map(|(_, p)| p), fixes, settings, kb, ntypes),
                (None, Some((_, p))) => Ok(Box::new(pairwise(cmd, p, fixes, settings, kb, ntypes)?)),
                (None, None) => Err(err("pair_style hybrid/overlay has no sub-styles".into())),
            };
        }
        PairStyle::Sdpd(p) => return crate::styles::sdpd::build_sdpd(cmd, p, fixes, dt, skin, rebuild, kb),
        PairStyle::Taitwater(p) => {
            let settings = Settings { dt, skin, rebuild };
            return crate::styles::sdpd::build_taitwater(cmd, p, fixes, settings, kb, mvv2e);
        }
        PairStyle::Voronoi(p) => return crate::styles::voronoi::build_voronoi(cmd, p, fixes, dt, skin, rebuild, kb),
    };
    if let Some(f) = fixes.iter().find(|f| matches!(f.style, FixStyle::MvvEdpd { .. } | FixStyle::EdpdSource { .. })) {
        return Err(err(format!("fix {} belongs to pair edpd", f.id)));
    }
    if let Some(f) = fixes.iter().find(|f| f.style == FixStyle::NveSdpd) {
        return Err(err(format!("fix {} (nve/sdpd) integrates pair sdpd/generic", f.id)));
    }
    if let Some(f) = fixes.iter().find(|f| f.style == FixStyle::NveVoronoi) {
        return Err(err(format!("fix {} (nve/voronoi) integrates pair voronoi/fv", f.id)));
    }
    if fixes.iter().any(|f| matches!(f.style, FixStyle::Nve | FixStyle::Mvv { .. } | FixStyle::DpdEnergy | FixStyle::Nph { .. })) {
        return Err(err("pair gendpde integrates with fix nve/gendpde or vv/euler (fix nve, nph, mvv/dpd and dpd/energy belong to LAMMPS's pairwise styles)".into()));
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
    let dissipation_of = |c: &PairCoeff, heat: HeatModel, noise: NoiseForm, substeps: u32, reject: bool| Dissipation {
        gamma: c.gamma,
        rc_friction: c.rc_friction,
        kappa: c.kappa,
        rc_heat: c.rc_heat,
        heat,
        noise,
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
            (Motion::VvEuler, Some(dissipation_of(coeff("vv/euler")?, heat, NoiseForm::Arithmetic, 0, false)))
        }
        (verlet, _) => {
            let motion = match verlet {
                Some(Fix { style: FixStyle::Verlet { work }, .. }) => Motion::Verlet(*work),
                _ => Motion::Fixed,
            };
            let dissipation = match shardlow {
                Some(Fix { style: FixStyle::Shardlow { heat, noise, substeps, reject }, .. }) => {
                    Some(dissipation_of(coeff("shardlow")?, *heat, *noise, *substeps, *reject))
                }
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
    let scheme = Scheme { settings: Settings { dt, skin, rebuild }, motion, dissipation, reservoirs };
    if let EosModel::PerType(v) = eos {
        return Ok(with_weight(v, pair, scheme));
    }
    Ok(each_eos!(eos, e => with_weight(vec![e.clone()], pair, scheme)))
}

/// Monomorphises the dynamics over the weight function; `per_type` holds one EOS for
/// all types or one per type.
fn with_weight<E: FixedEntropy + FixedDensity + 'static>(per_type: Vec<E>, pair: &PairGendpde, scheme: Scheme) -> Box<dyn Physics> {
    let Some(eos) = Species::new(per_type) else { unreachable!("an EOS model holds at least one EOS") };
    let rc = pair.cutoff;
    let volume = pair.volume.map(|fcut| PartitionVolume::new(rc, fcut));
    let Scheme { settings, motion, dissipation, reservoirs } = scheme;
    macro_rules! gendpde {
        ($weight:expr) => {
            Box::new(GenDpde { eos, weight: $weight, volume, settings, motion, dissipation, reservoirs })
        };
    }
    match pair.weight {
        WeightKind::Quadratic => gendpde!(Quadratic::new(rc)),
        WeightKind::Linear => gendpde!(Linear::new(rc)),
        WeightKind::Lucy => gendpde!(Lucy::new(rc)),
        WeightKind::CubicSpline => gendpde!(CubicSpline::new(rc)),
    }
}

/// What GenDPDE's step does besides its EOS and weight, gathered from the fixes.
struct Scheme {
    settings: Settings,
    motion: Motion,
    dissipation: Option<Dissipation>,
    reservoirs: Vec<Reservoir>,
}

/// The dynamics of a pairwise scene from the pair style and the fixes.
fn pairwise(cmd: &Command, p: &Pairwise, fixes: &[Fix], settings: Settings, kb: f64, ntypes: usize) -> Result<ClassicDpd, ScriptError> {
    let err = |m: &str| ScriptError::at(cmd, m);
    // LAMMPS's Pair::init and init_one: no mixing in these styles
    let unset = |(i, j): (usize, usize), what: &str| err(&format!("All {what}coeffs are not set: no pair_coeff for types {i} {j}"));
    let c = p.coeff.complete(ntypes).map_err(|ij| unset(ij, "pair "))?;
    let has = |pred: fn(&FixStyle) -> bool| fixes.iter().any(|f| pred(&f.style));
    let shardlow = has(|s| matches!(s, FixStyle::Shardlow { .. }));
    if has(|s| matches!(s, FixStyle::Shardlow { noise: NoiseForm::Harmonic { .. }, .. })) {
        return Err(err("fix shardlow: 'noise' belongs to pair gendpde (dpd/fdt/energy's noise is already the harmonic form on theta)"));
    }
    let nve = has(|s| matches!(s, FixStyle::Nve));
    let mut barostats = fixes.iter().filter_map(|f| if let FixStyle::Nph { nph, .. } = &f.style { Some((**nph).clone()) } else { None });
    let barostat = barostats.next();
    if barostats.next().is_some() {
        return Err(err("more than one fix nph is defined"));
    }
    let mvv = fixes.iter().find_map(|f| if let FixStyle::Mvv { lambda } = f.style { Some(lambda) } else { None });
    let cv = fixes.iter().find_map(|f| match &f.style {
        FixStyle::Eos(EosModel::Linear(e)) if !gendpde_potentials::Eos::density_dependent(e) && e.q == 0.0 => Some(e.cv),
        _ => None,
    });
    if let Some(f) = fixes.iter().find(|f| matches!(f.style, FixStyle::MvvEdpd { .. } | FixStyle::EdpdSource { .. })) {
        return Err(err(&format!("fix {} belongs to pair edpd", f.id)));
    }
    if has(|s| matches!(s, FixStyle::Verlet { .. } | FixStyle::VvEuler { .. } | FixStyle::Reservoir { .. } | FixStyle::NveSdpd | FixStyle::NveVoronoi)) {
        return Err(err("fix nve/gendpde, vv/euler and heat/reservoir belong to pair gendpde; LAMMPS's pairwise styles use fix nve, shardlow, eos/cv, mvv/dpd"));
    }
    if nve && barostat.is_some() {
        return Err(err("fix nve and fix nph both integrate: keep one"));
    }
    let integration = match (nve || barostat.is_some(), mvv) {
        (true, None) => Integration::Nve,
        (false, Some(lambda)) => Integration::Mvv { lambda },
        (true, Some(_)) => return Err(err("fix mvv/dpd and fix nve (or nph) both integrate: keep one")),
        (false, None) => return Err(err("no integrator: add fix nve or nph (or fix mvv/dpd for mdpd)")),
    };
    let energy = has(|s| matches!(s, FixStyle::DpdEnergy));
    fn table<T>(cmd: &Command, ntypes: usize, v: Vec<T>) -> Result<TypeTable<T>, ScriptError> {
        TypeTable::new(ntypes, v).ok_or_else(|| ScriptError::at(cmd, "the box has no particle types"))
    }
    let sigma_of = |t: f64, gamma: f64| (2.0 * kb * t * gamma).sqrt();
    let conservative = || table(cmd, ntypes, c.iter().map(|c| DpdCoeff::new(c.a, c.rc, 0.0, 0.0)).collect());
    let sweep_of = |temperature: Option<f64>| {
        let kappa = |k: f64| if temperature.is_some() { 0.0 } else { k };
        table(cmd, ntypes, c.iter().map(|c| ShardlowCoeff::new(c.sigma, kappa(c.kappa), c.rc)).collect()).map(|coeff| ShardlowDpd { coeff, temperature })
    };
    // dpd/ext and the thermostats (a0 = 0, gamma_perp = 0 and s = 1 for dpd/tstat)
    let ext = |start: f64, stop: f64| {
        let coeff = c.iter().map(|c| DpdExtCoeff { a0: c.a, rc: c.rc, gamma_par: c.gamma, gamma_perp: c.gamma_perp, s_par: c.s_par, s_perp: c.s_perp });
        table(cmd, ntypes, coeff.collect()).map(|coeff| DpdExt { coeff, start, stop })
    };
    let (force, sweep) = match p.kind {
        Kind::Dpd { temperature } => (PairForce::Dpd(table(cmd, ntypes, c.iter().map(|c| DpdCoeff::new(c.a, c.rc, c.gamma, sigma_of(temperature, c.gamma))).collect())?), None),
        Kind::DpdExt { temperature } => (PairForce::DpdExt(ext(temperature, temperature)?), None),
        Kind::DpdTstat { start, stop } | Kind::DpdExtTstat { start, stop } => (PairForce::DpdExt(ext(start, stop)?), None),
        // velocity Verlet (pair_dpd_fdt.cpp without fix shardlow): gamma = sigma^2 / (2 k_B T)
        Kind::DpdFdt { temperature } if !shardlow => {
            let coeff = c.iter().map(|c| DpdCoeff::new(c.a, c.rc, c.sigma * c.sigma / (2.0 * kb * temperature), c.sigma));
            (PairForce::Dpd(table(cmd, ntypes, coeff.collect())?), None)
        }
        Kind::DpdFdtEnergy if !shardlow => {
            let coeff = c.iter().map(|c| DpdEnergyCoeff { a0: c.a, rc: c.rc, sigma: c.sigma, kappa: c.kappa });
            (PairForce::DpdEnergy(table(cmd, ntypes, coeff.collect())?), None)
        }
        Kind::DpdFdt { temperature } => (PairForce::Dpd(conservative()?), Some(sweep_of(Some(temperature))?)),
        Kind::DpdFdtEnergy => (PairForce::Dpd(conservative()?), Some(sweep_of(None)?)),
        Kind::Mdpd { temperature } => {
            if p.rhosum.ntypes() == 0 {
                return Err(err("pair mdpd needs 'pair_coeff * * mdpd/rhosum H'"));
            }
            let h = p.rhosum.complete(ntypes).map_err(|ij| unset(ij, "pair mdpd/rhosum "))?;
            let coeff = c.iter().zip(h).map(|(c, h)| MdpdCoeff { a: c.a, b: c.b, rc: c.rc, rd: c.rd, gamma: c.gamma, sigma: sigma_of(temperature, c.gamma), kernel: Lucy::new(h) });
            (PairForce::Mdpd(table(cmd, ntypes, coeff.collect())?), None)
        }
    };
    if shardlow && matches!(p.kind, Kind::Dpd { .. } | Kind::DpdExt { .. } | Kind::DpdTstat { .. } | Kind::DpdExtTstat { .. } | Kind::Mdpd { .. }) {
        return Err(err("fix shardlow works with pair dpd/fdt and dpd/fdt/energy"));
    }
    if energy && (shardlow || !matches!(p.kind, Kind::DpdFdtEnergy)) {
        return Err(err("fix dpd/energy integrates pair dpd/fdt/energy without fix shardlow (with it the sweep moves u)"));
    }
    if matches!(p.kind, Kind::DpdFdtEnergy) && cv.is_none() {
        return Err(err("pair dpd/fdt/energy needs fix eos/cv"));
    }
    if matches!(integration, Integration::Mvv { .. }) && !matches!(p.kind, Kind::Mdpd { .. }) {
        return Err(err("fix mvv/dpd integrates pair mdpd"));
    }
    Ok(ClassicDpd { force, tables: None, shardlow: sweep, integration, cv, energy, barostat, kb, seed: p.seed, settings })
}

/// The dynamics of an eDPD scene: pair edpd, fix mvv/edpd and any fix edpd/source.
fn edpd(cmd: &Command, p: &PairEdpd, fixes: &[Fix], settings: Settings, kb: f64) -> Result<Box<dyn Physics>, ScriptError> {
    let err = |m: String| ScriptError::at(cmd, m);
    let coeff = TypeTable::new(p.ntypes, p.table().map_err(err)?).ok_or_else(|| err("pair edpd has no coefficients (pair_coeff)".into()))?;
    let mut lambda = None;
    let mut sources = Vec::new();
    for f in fixes {
        match &f.style {
            FixStyle::MvvEdpd { lambda: l } if lambda.is_none() => lambda = Some(*l),
            FixStyle::MvvEdpd { .. } => return Err(err("more than one fix mvv/edpd is defined".into())),
            FixStyle::EdpdSource { shape, value, mask } => {
                let shape = match shape.clone() {
                    Source::Sphere { centre, radius } => SourceShape::Sphere { centre, radius },
                    Source::Cuboid { centre, edges } => SourceShape::Cuboid { centre, edges },
                    Source::Region(r) => SourceShape::Region(std::sync::Arc::new(move |x| r.contains(x))),
                };
                sources.push(HeatSource { mask: *mask, shape, value: *value });
            }
            _ => return Err(err(format!("fix {} does not act on pair edpd (its fixes: mvv/edpd, edpd/source)", f.id))),
        }
    }
    let lambda = lambda.ok_or_else(|| err("pair edpd integrates with fix mvv/edpd".into()))?;
    Ok(Box::new(Edpd { coeff, seed: p.seed, kb, lambda, sources, settings }))
}

/// `pair_style table` or `multi/lucy` alone (integrated by fix nve), or a table overlaid
/// on the pairwise style `p` (which sets the fixes it works with).
fn tabulated(cmd: &Command, t: &Tabulated, p: Option<&Pairwise>, fixes: &[Fix], settings: Settings, kb: f64, ntypes: usize) -> Result<Box<dyn Physics>, ScriptError> {
    let err = |m: &str| ScriptError::at(cmd, m);
    let tables = tables_for_run(t, p.is_some()).map_err(|e| err(&e))?;
    if let Some(p) = p {
        let dynamics = pairwise(cmd, p, fixes, settings, kb, ntypes)?;
        return Ok(Box::new(ClassicDpd { tables: Some(tables), ..dynamics }));
    }
    for f in fixes {
        match f.style {
            FixStyle::Nve | FixStyle::Eos(_) => {}
            _ if t.multi_lucy => return Err(err(&format!("fix {} does not work with pair multi/lucy (fix nve integrates it)", f.id))),
            _ => return Err(err(&format!("fix {} does not work with pair table alone (fix nve integrates it; overlay dpd/fdt for fix shardlow)", f.id))),
        }
    }
    if !fixes.iter().any(|f| f.style == FixStyle::Nve) {
        return Err(err("no integrator: add fix nve"));
    }
    let (force, tables) = if t.multi_lucy { (PairForce::MultiLucy(tables), None) } else { (PairForce::Off, Some(tables)) };
    Ok(Box::new(ClassicDpd { force, tables, shardlow: None, integration: Integration::Nve, cv: None, energy: false, barostat: None, kb, seed: 1, settings }))
}
