//! Pair styles: `pair_style` and `pair_coeff` of GenDPDE ([`gendpde`]) and of LAMMPS's
//! pairwise DPD styles ([`pairwise`]).

pub mod gendpde;
pub mod pairwise;
pub mod sdpd;

use self::gendpde::PairGendpde;
use self::pairwise::Pairwise;
use self::sdpd::PairSdpd;
use crate::base::args::Args;
use gendpde_io::{Command, ScriptError};

/// The pair style in force.
#[derive(Clone, Debug, PartialEq)]
pub enum PairStyle {
    Gendpde(PairGendpde),
    /// LAMMPS's pairwise DPD styles.
    Pairwise(Pairwise),
    /// Thermal SDPD (Serrano-Espanol Sec VII).
    Sdpd(PairSdpd),
}

impl PairStyle {
    /// The largest interaction cutoff (LAMMPS's `cutforce`): for gendpde the largest of
    /// the density, friction and heat cutoffs, for the pairwise styles that of pair_coeff
    /// (and the mdpd/rhosum kernel).
    pub fn cutoff(&self) -> f64 {
        match self {
            Self::Gendpde(p) => p.coeff.as_ref().map_or(p.cutoff, |c| p.cutoff.max(c.rc_friction).max(c.rc_heat)),
            Self::Pairwise(p) => p.coeff.as_ref().map_or(p.cutoff, |c| c.rc).max(p.rhosum.unwrap_or(0.0)),
            Self::Sdpd(p) => p.cutoff,
        }
    }
}

/// `pair_style STYLE args...`.
pub fn parse_pair_style(cmd: &Command) -> Result<PairStyle, ScriptError> {
    let mut a = Args::new(cmd);
    match a.word("a pair style")? {
        "gendpde" => self::gendpde::parse_style(&mut a).map(PairStyle::Gendpde),
        "sdpd/generic" => self::sdpd::parse_style(&mut a).map(PairStyle::Sdpd),
        other => self::pairwise::parse_style(other, &mut a).map(PairStyle::Pairwise),
    }
}

/// `pair_coeff` for the pair style in force.
pub fn parse_pair_coeff(cmd: &Command, pair: &mut PairStyle, ntypes: usize) -> Result<(), ScriptError> {
    match pair {
        PairStyle::Gendpde(p) => {
            p.coeff = Some(self::gendpde::parse_coeff(cmd, p, ntypes)?);
            Ok(())
        }
        PairStyle::Pairwise(p) => self::pairwise::parse_coeff(p, cmd, ntypes),
        PairStyle::Sdpd(p) => {
            p.coeff = Some(self::sdpd::parse_coeff(cmd, ntypes)?);
            Ok(())
        }
    }
}
