//! The dynamics of a `pair voronoi/fv` run: the Voronoi finite-volume model with its cell
//! relation, integrated by `fix nve/voronoi`.

use crate::styles::fix::{Fix, FixStyle};
use crate::styles::pair::voronoi::{CellRelation, PairVoronoi};
use gendpde_integrators::models::voronoi::{CellDissipation, FiniteVolume, CellTransport, VoronoiFv};
use gendpde_integrators::{Physics, RebuildPolicy, Settings};
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::{IdealCell, VdwCell};

/// Assembles the model from the pair style and `fix nve/voronoi`; `kb` is Boltzmann's
/// constant of the units (the default of the pair style's `kB`).
pub fn build_voronoi(cmd: &Command, pair: &PairVoronoi, fixes: &[Fix], dt: f64, skin: f64, rebuild: RebuildPolicy, kb: f64) -> Result<Box<dyn Physics>, ScriptError> {
    let err = |m: &str| ScriptError::at(cmd, m);
    let ([eta, zeta, kappa], relation) = pair.coeff.ok_or_else(|| err("pair voronoi/fv has no coefficients (pair_coeff * * ETA ZETA KAPPA vdw|ideal C)"))?;
    if let Some(f) = fixes.iter().find(|f| f.style != FixStyle::NveVoronoi) {
        return Err(err(&format!("fix {} does not work with pair voronoi/fv (it takes fix nve/voronoi only)", f.id)));
    }
    match fixes.len() {
        0 => return Err(err("pair voronoi/fv needs fix nve/voronoi")),
        1 => {}
        _ => return Err(err("more than one fix nve/voronoi is defined")),
    }
    let transport = CellTransport { eta, zeta, kappa, kb: pair.kb.unwrap_or(kb) };
    let settings = Settings { dt, skin, rebuild };
    let seed = pair.seed;
    let dissipation = if pair.dpd { CellDissipation::Dpd { gamma: eta } } else { CellDissipation::Hydrodynamic };
    Ok(match relation {
        CellRelation::Vdw { c } => Box::new(VoronoiFv::new(FiniteVolume { energy: VdwCell { c }, transport, dissipation, seed }, settings)),
        CellRelation::Ideal { c } => Box::new(VoronoiFv::new(FiniteVolume { energy: IdealCell { c }, transport, dissipation, seed }, settings)),
    })
}
