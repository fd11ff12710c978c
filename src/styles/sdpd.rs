//! The dynamics of a `pair sdpd/generic` run: thermal SDPD monomorphised over its EOS and
//! kernel, integrated by `fix nve/sdpd`; and of a `pair sdpd/taitwater/isothermal` run,
//! integrated by `fix sph`.

use crate::styles::fix::eos::{each_eos, EosModel};
use crate::styles::fix::{Fix, FixStyle};
use crate::styles::pair::sdpd::PairSdpd;
use crate::styles::pair::sdpd_taitwater::PairTaitwater;
use gendpde_integrators::{FixedEntropy, Physics, RebuildPolicy, Sdpd, SdpdParams, SdpdTaitwater, Settings, Species, TypeTable};
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::{CubicSpline, Linear, Lucy, Quadratic, Tait, WeightKind};

/// Assembles thermal SDPD from the pair style, one EOS fix and `fix nve/sdpd`; `kb` is
/// Boltzmann's constant of the units (the default of the pair style's `kB`).
pub fn build_sdpd(cmd: &Command, pair: &PairSdpd, fixes: &[Fix], dt: f64, skin: f64, rebuild: RebuildPolicy, kb: f64) -> Result<Box<dyn Physics>, ScriptError> {
    let err = |m: &str| ScriptError::at(cmd, m);
    let [eta, zeta, kappa] = pair.coeff.ok_or_else(|| err("pair sdpd/generic has no coefficients (pair_coeff * * ETA ZETA KAPPA)"))?;
    if let Some(f) = fixes.iter().find(|f| !matches!(f.style, FixStyle::Eos(_) | FixStyle::NveSdpd)) {
        return Err(err(&format!("fix {} does not work with pair sdpd/generic (it takes one fix eos/... and fix nve/sdpd)", f.id)));
    }
    match fixes.iter().filter(|f| f.style == FixStyle::NveSdpd).count() {
        0 => return Err(err("pair sdpd/generic needs fix nve/sdpd")),
        1 => {}
        _ => return Err(err("more than one fix nve/sdpd is defined")),
    }
    let eos: Vec<&EosModel> = fixes.iter().filter_map(|f| if let FixStyle::Eos(e) = &f.style { Some(e) } else { None }).collect();
    let eos = match eos.as_slice() {
        [e] => (*e).clone(),
        [] => return Err(err("no EOS fix is defined (fix ID all eos/...)")),
        _ => return Err(err("more than one EOS fix is defined")),
    };
    let params = SdpdParams { eta, zeta, kappa, kb: pair.kb.unwrap_or(kb), seed: pair.seed, normalized: pair.normalized };
    let settings = Settings { dt, skin, rebuild };
    if let EosModel::PerType(v) = eos {
        return Ok(with_weight(v, pair, params, settings));
    }
    Ok(each_eos!(eos, e => with_weight(vec![e.clone()], pair, params, settings)))
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

/// Assembles LAMMPS's isothermal Tait-water SDPD from the pair style and `fix sph`; `kb`
/// and `mvv2e` are those of the units.
pub fn build_taitwater(cmd: &Command, pair: &PairTaitwater, fixes: &[Fix], settings: Settings, kb: f64, mvv2e: f64) -> Result<Box<dyn Physics>, ScriptError> {
    let err = |m: &str| ScriptError::at(cmd, m);
    let (water, cut) = pair.table().map_err(|e| err(&e))?;
    if let Some(f) = fixes.iter().find(|f| f.style != FixStyle::Sph) {
        return Err(err(&format!("fix {} does not work with pair sdpd/taitwater/isothermal (fix sph integrates it)", f.id)));
    }
    match fixes.len() {
        0 => return Err(err("pair sdpd/taitwater/isothermal needs fix sph")),
        1 => {}
        _ => return Err(err("more than one fix sph is defined")),
    }
    Ok(Box::new(SdpdTaitwater {
        eos: water.iter().map(|w| Tait::new(w.rho0, w.c0)).collect(),
        kernel: TypeTable::new(pair.ntypes, cut.iter().map(|&h| Lucy::new(h)).collect()).ok_or_else(|| err("pair sdpd/taitwater/isothermal has no coefficients (pair_coeff)"))?,
        kbt: kb * pair.temperature,
        viscosity: pair.viscosity,
        seed: pair.seed,
        mvv2e,
        settings,
    }))
}
