//! Fix styles: `fix ID GROUP STYLE args...` parsed into declarative [`Fix`]es (the
//! EOS models in [`eos`]); the pair style in force builds the dynamics of a run from
//! them (`styles::pair`).
//! `fix ave/time` is an output (`output::ave_time`).

pub mod eos;
pub mod nph;

use self::eos::{parse_eos, EosModel};
use crate::base::args::Args;
use crate::base::region::Region;
use crate::base::script::echo;
use gendpde_integrators::{HeatModel, NoiseForm, Work};
use gendpde_io::{Command, ScriptError};
use std::collections::HashMap;

/// The fix styles.
#[derive(Clone, Debug, PartialEq)]
pub enum FixStyle {
    Eos(EosModel),
    /// `fix nve/gendpde [work split|isentropic]`: the reversible velocity-Verlet step.
    Verlet { work: Work },
    /// `fix vv/euler [heat original|fourier]`: velocity Verlet with all pair forces, Euler
    /// for u (argon paper, sec 4.1).
    VvEuler { heat: HeatModel },
    /// `fix shardlow [heat original|fourier] [noise arithmetic|harmonic T0] [substeps N]
    /// [reject yes|no]`.
    Shardlow { heat: HeatModel, noise: NoiseForm, substeps: u32, reject: bool },
    /// `fix ID GROUP heat/reservoir T KAPPA SEED [heat original|fourier]`; `mask` is the
    /// group's bit (`u32::MAX` for all).
    Reservoir { temperature: f64, kappa: f64, seed: u64, heat: Option<HeatModel>, mask: u32 },
    /// `fix nve/sdpd`: velocity Verlet at fixed entropy, then the irreversible SDPD step
    /// (pair sdpd/generic).
    NveSdpd,
    /// `fix nve/voronoi`: the step of the Voronoi finite-volume model (pair voronoi/fv).
    NveVoronoi,
    /// `fix nve` (LAMMPS's pairwise styles).
    Nve,
    /// `fix mvv/dpd [LAMBDA]` (pair mdpd).
    Mvv { lambda: f64 },
    /// `fix dpd/energy`: uCond and uMech by half steps from the rates of pair
    /// dpd/fdt/energy (velocity-Verlet DPDE, without fix shardlow).
    DpdEnergy,
    /// `fix mvv/edpd [LAMBDA]` (pair edpd): modified velocity Verlet of x, v and T.
    MvvEdpd { lambda: f64 },
    /// `fix ID all nph ...`: LAMMPS's Nose-Hoover barostat with velocity Verlet; the fixed
    /// point if given (else the box centre at the definition).
    Nph { nph: Box<gendpde_integrators::Nph>, fixedpoint: Option<[f64; 3]> },
    /// `fix sph` (atom_style sph, pair sdpd/taitwater/isothermal): velocity Verlet of x
    /// and v with the velocity estimate v + dt f/m, and of the density.
    Sph,
    /// `fix ID GROUP edpd/source sphere|cuboid|region ... VALUE` (pair edpd).
    EdpdSource { shape: SourceSpec, value: f64, mask: u32 },
}

/// Where `fix edpd/source` heats.
#[derive(Clone, Debug, PartialEq)]
pub enum SourceSpec {
    /// `sphere CX CY CZ RADIUS`.
    Sphere { centre: [f64; 3], radius: f64 },
    /// `cuboid CX CY CZ LX LY LZ`.
    Cuboid { centre: [f64; 3], edges: [f64; 3] },
    /// `region ID`, as defined when the fix was.
    Region(Region),
}

#[derive(Clone, Debug)]
pub struct Fix {
    pub id: String,
    /// The style's name, as the command gives it.
    pub name: String,
    pub style: FixStyle,
    /// The command as written (restart files re-create fixes from it).
    pub text: String,
}

/// Default and largest number of halving levels of a failing Shardlow pair update.
pub const DEFAULT_SUBSTEPS: u32 = 4;
pub const MAX_SUBSTEPS: u32 = 8;

/// What a fix style's parser reads besides its own words.
pub struct FixContext<'a> {
    pub id: &'a str,
    /// Boltzmann's constant of the units.
    pub kb: f64,
    /// The group names by bit, and the bit of the fix's group.
    pub groups: &'a [String],
    pub mask: u32,
    /// The regions defined so far (fix edpd/source region).
    pub regions: &'a HashMap<String, Region>,
}

/// Parses the words after `fix ID GROUP NAME`.
type ParseFix = fn(name: &str, a: &mut Args, c: &FixContext) -> Result<FixStyle, ScriptError>;

/// Every fix style of the dynamics (the EOS fixes are [`eos::EOS_STYLES`], the
/// averaging fixes [`AVERAGING`]), with its parser and whether it takes a group other
/// than all.
pub const FIX_STYLES: &[(&str, ParseFix, bool)] = &[
    ("nve/gendpde", nve_gendpde, false),
    ("vv/euler", |_, a, _| Ok(FixStyle::VvEuler { heat: heat_keyword(a)?.unwrap_or(HeatModel::Original) }), false),
    ("shardlow", shardlow, false),
    ("heat/reservoir", heat_reservoir, true),
    ("nve/sdpd", |_, _, _| Ok(FixStyle::NveSdpd), false),
    ("nve/voronoi", |_, _, _| Ok(FixStyle::NveVoronoi), false),
    ("nve", |_, _, _| Ok(FixStyle::Nve), false),
    ("nph", |_, a, c| nph::parse_nph(c.id, a, c.kb, c.groups).map(|(nph, fixedpoint)| FixStyle::Nph { nph: Box::new(nph), fixedpoint }), false),
    ("mvv/dpd", |_, a, _| Ok(FixStyle::Mvv { lambda: if a.remaining() > 0 { a.positive("lambda")? } else { 0.5 } }), false),
    ("dpd/energy", |_, _, _| Ok(FixStyle::DpdEnergy), false),
    ("mvv/edpd", |_, a, _| Ok(FixStyle::MvvEdpd { lambda: if a.remaining() > 0 { a.f64("lambda")? } else { 0.5 } }), false),
    ("edpd/source", |_, a, c| edpd_source(a, c.mask, c.regions), true),
    ("sph", |_, _, _| Ok(FixStyle::Sph), false),
];

/// The fixes that are outputs (`output::fix`; the names of its `OUTPUT_FIXES`, for the
/// list of known styles).
pub const AVERAGING: [&str; 6] = ["ave/atom", "ave/chunk", "ave/histo", "ave/time", "print", "vector"];

/// Every fix style's name, as error messages list them.
pub fn known_styles() -> String {
    let names = eos::EOS_STYLES.iter().chain(FIX_STYLES.iter().map(|(name, ..)| name)).chain(&AVERAGING);
    names.copied().collect::<Vec<_>>().join(", ")
}

/// `fix ID GROUP STYLE args...`; `kb` is Boltzmann's constant of the units, `groups`
/// the group names by bit (no regions: see [`parse_fix_in`]).
pub fn parse_fix(cmd: &Command, kb: f64, groups: &[String]) -> Result<Fix, ScriptError> {
    parse_fix_in(cmd, kb, groups, &HashMap::new())
}

/// [`parse_fix`] with the regions defined so far (fix edpd/source region).
pub fn parse_fix_in(cmd: &Command, kb: f64, groups: &[String], regions: &HashMap<String, Region>) -> Result<Fix, ScriptError> {
    let mut a = Args::new(cmd);
    let id = a.word("a fix ID")?.to_string();
    let group = a.word("a group")?;
    let name = a.word("a fix style")?;
    // as LAMMPS: the group must exist, then the style; then gendpde's restriction to all
    let mask = crate::base::groups::mask(groups, group, &a)?;
    let c = FixContext { id: &id, kb, groups, mask, regions };
    let (style, grouped) = if eos::EOS_STYLES.contains(&name) {
        (FixStyle::Eos(parse_eos(name, &mut a, kb)?), false)
    } else {
        let Some((_, parse, grouped)) = FIX_STYLES.iter().find(|(n, ..)| *n == name) else {
            return Err(a.err(format!("unknown fix style '{name}'; known: {}", known_styles())));
        };
        (parse(name, &mut a, &c)?, *grouped)
    };
    if group != "all" && !grouped {
        let takers: Vec<&str> = FIX_STYLES.iter().filter(|(.., g)| *g).map(|(n, ..)| *n).collect();
        return Err(a.err(format!("group '{group}': fix {name} acts on group all (only {} take a group)", takers.join(" and "))));
    }
    a.done()?;
    Ok(Fix { id, name: name.to_string(), style, text: echo(cmd) })
}

/// `fix nve/gendpde [work split|isentropic]`.
fn nve_gendpde(_: &str, a: &mut Args, _: &FixContext) -> Result<FixStyle, ScriptError> {
    let mut work = Work::Split;
    while let Some(k) = a.peek() {
        a.word("keyword")?;
        match k {
            "work" => {
                work = match a.word("split or isentropic")? {
                    "split" => Work::Split,
                    "isentropic" => Work::Isentropic,
                    w => return Err(a.err(format!("unknown work rule '{w}'; known: split, isentropic"))),
                }
            }
            _ => return Err(a.err(format!("unknown keyword '{k}'; known: work"))),
        }
    }
    Ok(FixStyle::Verlet { work })
}

/// `fix shardlow [heat original|fourier] [noise arithmetic|harmonic T0] [substeps N]
/// [reject yes|no]`.
fn shardlow(_: &str, a: &mut Args, _: &FixContext) -> Result<FixStyle, ScriptError> {
    let (mut heat, mut substeps, mut reject) = (HeatModel::Original, DEFAULT_SUBSTEPS, false);
    let mut noise = NoiseForm::Arithmetic;
    while let Some(k) = a.peek() {
        match k {
            "heat" => heat = heat_keyword(a)?.unwrap_or(heat),
            "noise" => {
                a.word("noise")?;
                noise = match a.word("a noise form (arithmetic or harmonic T0)")? {
                    "arithmetic" => NoiseForm::Arithmetic,
                    "harmonic" => NoiseForm::Harmonic { temperature: a.positive("the harmonic noise's temperature T0")? },
                    w => return Err(a.err(format!("unknown noise form '{w}'; known: arithmetic, harmonic"))),
                }
            }
            "substeps" => {
                a.word("substeps")?;
                substeps = a.u64("the number of halving levels")?.min(MAX_SUBSTEPS as u64) as u32;
            }
            "reject" => {
                a.word("reject")?;
                reject = a.yes_no("reject")?;
            }
            _ => return Err(a.err(format!("unknown keyword '{k}'; known: heat, noise, substeps, reject"))),
        }
    }
    Ok(FixStyle::Shardlow { heat, noise, substeps, reject })
}

/// `fix ID GROUP heat/reservoir T KAPPA SEED [heat original|fourier]`.
fn heat_reservoir(_: &str, a: &mut Args, c: &FixContext) -> Result<FixStyle, ScriptError> {
    let temperature = a.positive("the reservoir temperature")?;
    let kappa = a.positive("the reservoir coupling kappa")?;
    let seed = a.u64("the random seed")?;
    Ok(FixStyle::Reservoir { temperature, kappa, seed, heat: heat_keyword(a)?, mask: c.mask })
}

/// The EOS of the one `fix eos/...` among `fixes`.
pub fn one_eos(fixes: &[Fix]) -> Result<EosModel, String> {
    let mut models = fixes.iter().filter_map(|f| if let FixStyle::Eos(e) = &f.style { Some(e) } else { None });
    match (models.next(), models.next()) {
        (Some(e), None) => Ok(e.clone()),
        (None, _) => Err("no EOS fix is defined (fix ID all eos/...)".into()),
        (Some(_), Some(_)) => Err("more than one EOS fix is defined".into()),
    }
}

fn heat_keyword(a: &mut Args) -> Result<Option<HeatModel>, ScriptError> {
    match a.peek() {
        None => Ok(None),
        Some("heat") => {
            a.word("heat")?;
            let w = a.word("a heat model (original or fourier)")?;
            HeatModel::parse(w).map(Some).ok_or_else(|| a.err(format!("unknown heat model '{w}'; known: original, fourier")))
        }
        Some(other) => Err(a.err(format!("unknown keyword '{other}'; known: heat"))),
    }
}

/// The words after `fix ID GROUP edpd/source` (LAMMPS DPD-MESO).
fn edpd_source(a: &mut Args, mask: u32, regions: &HashMap<String, Region>) -> Result<FixStyle, ScriptError> {
    let vec3 = |a: &mut Args, what: &str| -> Result<[f64; 3], ScriptError> { Ok([a.f64(what)?, a.f64(what)?, a.f64(what)?]) };
    let shape = match a.word("sphere, cuboid or region")? {
        "sphere" => SourceSpec::Sphere { centre: vec3(a, "the centre (3 numbers)")?, radius: a.f64("the radius")? },
        "cuboid" => SourceSpec::Cuboid { centre: vec3(a, "the centre (3 numbers)")?, edges: vec3(a, "the edge lengths (3 numbers)")? },
        "region" => {
            let id = a.word("a region ID")?;
            SourceSpec::Region(regions.get(id).cloned().ok_or_else(|| a.err(format!("region {id} for fix edpd/source does not exist")))?)
        }
        w => return Err(a.err(format!("expected sphere, cuboid or region, got '{w}'"))),
    };
    Ok(FixStyle::EdpdSource { shape, value: a.f64("the heat source value")?, mask })
}
