//! `pair_style voronoi/fv SEED [kB KB] [dissipation hydrodynamic|dpd]` with
//! `pair_coeff * * ETA ZETA KAPPA vdw|ideal C` (with `dpd`: ETA is the friction gamma,
//! ZETA unused):
//! the Voronoi Lagrangian finite-volume model of Serrano and Espanol (Secs V-VI.A), cells
//! with dynamic mass and entropy; its integrator is `fix nve/voronoi`.

use super::{Pair, RunInputs};
use crate::base::args::Args;
use crate::styles::fix::FixStyle;
use gendpde_integrators::models::voronoi::{CellDissipation, CellTransport, FiniteVolume, VoronoiFv};
use gendpde_integrators::Physics;
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::{IdealCell, VdwCell};

/// The cell relation E(M, S, V) in the paper's reduced units (eqs 160-162).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CellRelation {
    Vdw { c: f64 },
    Ideal { c: f64 },
}

#[derive(Clone, Debug, PartialEq)]
pub struct PairVoronoi {
    pub seed: u64,
    /// Boltzmann's constant of the fluctuations (None: that of the units).
    pub kb: Option<f64>,
    /// `dissipation dpd`: the Voronoi DPD irreversible part (eqs 85-90), friction = ETA.
    pub dpd: bool,
    /// Shear viscosity, bulk viscosity, thermal conductivity (eq 78) and the cell relation.
    pub coeff: Option<([f64; 3], CellRelation)>,
}

/// The words after `pair_style voronoi/fv`.
fn parse(a: &mut Args) -> Result<PairVoronoi, ScriptError> {
    let seed = a.u64("the random seed")?;
    if seed == 0 {
        return Err(a.err("the random seed must be positive"));
    }
    let mut p = PairVoronoi { seed, kb: None, dpd: false, coeff: None };
    while let Some(key) = a.peek() {
        a.word("keyword")?;
        match key {
            "kB" => p.kb = Some(a.non_negative("Boltzmann's constant of the fluctuations")?),
            "dissipation" => {
                p.dpd = match a.word("hydrodynamic or dpd")? {
                    "hydrodynamic" => false,
                    "dpd" => true,
                    d => return Err(a.err(format!("unknown dissipation '{d}'; known: hydrodynamic, dpd"))),
                }
            }
            _ => return Err(a.err(format!("unknown keyword '{key}'; known: kB, dissipation"))),
        }
    }
    Ok(p)
}

/// `pair_coeff * * ETA ZETA KAPPA vdw|ideal C`.
fn parse_coeff(cmd: &Command, ntypes: usize) -> Result<([f64; 3], CellRelation), ScriptError> {
    let mut a = Args::new(cmd);
    a.all_type_pairs(ntypes, "voronoi/fv")?;
    let eta = a.non_negative("the shear viscosity eta")?;
    let zeta = a.non_negative("the bulk viscosity zeta")?;
    let kappa = a.non_negative("the thermal conductivity kappa")?;
    let relation = match a.word("a cell relation (vdw or ideal)")? {
        "vdw" => CellRelation::Vdw { c: a.positive("the constant c of eq 163")? },
        "ideal" => CellRelation::Ideal { c: a.positive("the constant c")? },
        r => return Err(a.err(format!("unknown cell relation '{r}'; known: vdw, ideal"))),
    };
    a.done()?;
    Ok(([eta, zeta, kappa], relation))
}

/// `pair_style voronoi/fv ...`.
pub fn parse_style(_name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError> {
    parse(a).map(|p| Box::new(p) as Box<dyn Pair>)
}

impl Pair for PairVoronoi {
    fn name(&self) -> &str {
        "voronoi/fv"
    }

    fn coeff(&mut self, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
        self.coeff = Some(parse_coeff(cmd, ntypes)?);
        Ok(())
    }

    fn accepts(&self, fix: &FixStyle) -> bool {
        *fix == FixStyle::NveVoronoi
    }

    fn fixes(&self) -> &'static str {
        "nve/voronoi"
    }

    fn pe_is_pair(&self) -> bool {
        false
    }

    /// The model with its cell relation, integrated by `fix nve/voronoi`; the units' k_B
    /// is the default of the style's `kB`.
    fn build(&self, run: &RunInputs) -> Result<Box<dyn Physics>, String> {
        let ([eta, zeta, kappa], relation) = self.coeff.ok_or("pair voronoi/fv has no coefficients (pair_coeff * * ETA ZETA KAPPA vdw|ideal C)")?;
        if run.one("nve/voronoi", |s| (*s == FixStyle::NveVoronoi).then_some(()))?.is_none() {
            return Err("pair voronoi/fv needs fix nve/voronoi".into());
        }
        let transport = CellTransport { eta, zeta, kappa, kb: self.kb.unwrap_or(run.kb) };
        let (settings, seed) = (run.settings(), self.seed);
        let dissipation = if self.dpd { CellDissipation::Dpd { gamma: eta } } else { CellDissipation::Hydrodynamic };
        Ok(match relation {
            CellRelation::Vdw { c } => Box::new(VoronoiFv::new(FiniteVolume { energy: VdwCell { c }, transport, dissipation, seed }, settings)),
            CellRelation::Ideal { c } => Box::new(VoronoiFv::new(FiniteVolume { energy: IdealCell { c }, transport, dissipation, seed }, settings)),
        })
    }
}
