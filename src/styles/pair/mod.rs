//! Pair styles: `pair_style` and `pair_coeff` of GenDPDE ([`gendpde`]), of LAMMPS's
//! pairwise DPD styles ([`pairwise`]), tabulated potentials ([`table`]), their
//! overlays ([`hybrid`]), eDPD ([`edpd`]), DPD-REACT's many-body `multi/lucy`
//! ([`multi_lucy`]) and SDPD ([`sdpd`], [`sdpd_taitwater`]).

pub mod edpd;
pub mod gendpde;
pub mod hybrid;
pub mod multi_lucy;
pub mod pairwise;
pub mod table;
pub mod sdpd;
pub mod sdpd_taitwater;
pub mod voronoi;

use self::edpd::PairEdpd;
use self::gendpde::PairGendpde;
use self::hybrid::Overlay;
use self::pairwise::Pairwise;
use self::table::Tabulated;
use self::sdpd::PairSdpd;
use self::sdpd_taitwater::PairTaitwater;
use self::voronoi::PairVoronoi;
use crate::base::args::Args;
use gendpde_io::{Command, ScriptError};

/// The pair style in force.
#[derive(Clone, Debug, PartialEq)]
pub enum PairStyle {
    Gendpde(PairGendpde),
    /// LAMMPS's pairwise DPD styles.
    Pairwise(Pairwise),
    /// DPD-MESO's energy-conserving DPD.
    Edpd(PairEdpd),
    /// `pair_style table`.
    Table(Tabulated),
    /// `pair_style multi/lucy` (its pressure-density tables).
    MultiLucy(Tabulated),
    /// `pair_style hybrid/overlay` of table and a pairwise style.
    Overlay(Overlay),
    /// Thermal SDPD (Serrano-Espanol Sec VII).
    Sdpd(PairSdpd),
    /// DPD-SMOOTH's isothermal SDPD of Tait water.
    Taitwater(PairTaitwater),
    /// The Voronoi finite-volume model (Serrano-Espanol Secs V-VI.A).
    Voronoi(PairVoronoi),
}

impl PairStyle {
    /// The largest interaction cutoff (LAMMPS's `cutforce`): for gendpde the largest of
    /// the density, friction and heat cutoffs, for the pairwise styles the largest over
    /// the type pairs of pair_coeff (and the mdpd/rhosum kernels).
    pub fn cutoff(&self) -> f64 {
        match self {
            Self::Gendpde(p) => p.coeff.as_ref().map_or(p.cutoff, |c| p.cutoff.max(c.rc_friction).max(c.rc_heat)),
            Self::Pairwise(p) => pairwise_cutoff(p),
            Self::Edpd(p) => p.cutoff(),
            Self::Table(t) | Self::MultiLucy(t) => t.cutoff(),
            Self::Overlay(o) => o.table.as_ref().map_or(0.0, Tabulated::cutoff).max(o.pairwise.as_ref().map_or(0.0, |(_, p)| pairwise_cutoff(p))),
            Self::Sdpd(p) => p.cutoff,
            Self::Taitwater(p) => p.cutoff(),
            Self::Voronoi(_) => 0.0,
        }
    }
}

impl PairStyle {
    /// `pair_style` naming the style in force again: as LAMMPS (`Input::pair_style` calls
    /// only the style's `settings()`), the coefficients stay and every cutoff a
    /// `pair_coeff` set is reset to the new global cutoff. False (nothing taken) for
    /// another style and for table and hybrid/overlay, whose `settings()` discard their
    /// coefficients in LAMMPS too.
    pub fn keep_coefficients(&mut self, old: &PairStyle) -> bool {
        match (self, old) {
            (Self::Pairwise(new), Self::Pairwise(old)) if std::mem::discriminant(&new.kind) == std::mem::discriminant(&old.kind) && !matches!(new.kind, pairwise::Kind::Mdpd { .. }) => {
                new.coeff = old.coeff.clone();
                new.coeff.for_each_set(|c| c.rc = new.cutoff);
                true
            }
            (Self::Edpd(new), Self::Edpd(old)) => {
                (new.ntypes, new.coeff) = (old.ntypes, old.coeff.clone());
                new.coeff.iter_mut().flatten().for_each(|c| c.rc = new.cutoff);
                true
            }
            (Self::Gendpde(new), Self::Gendpde(old)) => {
                new.coeff = old.coeff.clone().map(|c| gendpde::PairCoeff { rc_friction: new.cutoff, rc_heat: new.cutoff, ..c });
                true
            }
            _ => false,
        }
    }
}

fn pairwise_cutoff(p: &Pairwise) -> f64 {
    let set = p.coeff.values().map(|c| c.rc).chain(p.rhosum.values().copied());
    set.reduce(f64::max).unwrap_or(p.cutoff)
}

/// `pair_style STYLE args...`.
pub fn parse_pair_style(cmd: &Command) -> Result<PairStyle, ScriptError> {
    let mut a = Args::new(cmd);
    match a.word("a pair style")? {
        "gendpde" => self::gendpde::parse_style(&mut a).map(PairStyle::Gendpde),
        "edpd" => self::edpd::parse_style(&mut a).map(PairStyle::Edpd),
        "table" => self::table::parse_style(&mut a).map(PairStyle::Table),
        "multi/lucy" => self::multi_lucy::parse_style(&mut a).map(PairStyle::MultiLucy),
        name @ ("hybrid" | "hybrid/overlay") if !self::hybrid::is_mdpd(&a) => self::hybrid::parse_style(name, &mut a).map(PairStyle::Overlay),
        "sdpd/generic" => self::sdpd::parse_style(&mut a).map(PairStyle::Sdpd),
        "sdpd/taitwater/isothermal" => self::sdpd_taitwater::parse_style(&mut a).map(PairStyle::Taitwater),
        "voronoi/fv" => self::voronoi::parse_style(&mut a).map(PairStyle::Voronoi),
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
        PairStyle::Edpd(p) => self::edpd::parse_coeff(p, cmd, ntypes),
        PairStyle::Table(t) | PairStyle::MultiLucy(t) => {
            let mut a = Args::new(cmd);
            let types = (a.types(ntypes)?, a.types(ntypes)?);
            self::table::parse_coeff(t, &mut a, types, ntypes)
        }
        PairStyle::Overlay(o) => self::hybrid::parse_coeff(o, cmd, ntypes),
        PairStyle::Sdpd(p) => {
            p.coeff = Some(self::sdpd::parse_coeff(cmd, ntypes)?);
            Ok(())
        }
        PairStyle::Taitwater(p) => self::sdpd_taitwater::parse_coeff(p, cmd, ntypes),
        PairStyle::Voronoi(p) => {
            p.coeff = Some(self::voronoi::parse_coeff(cmd, ntypes)?);
            Ok(())
        }
    }
}
