//! Pair and fix styles: their script syntax, and the assembly of a scene's dynamics.
//!
//! A new EOS is one file in `potentials/src/eos/`, one arm in [`parse_eos`] and, if it
//! is a new Rust type, one arm in [`build_physics`] (see docs/DESIGN.md).

use crate::args::Args;
use gendpde_integrators::{Dissipation, FixedEntropy, GenDpde, HeatModel, Motion, Physics, RebuildPolicy, Reservoir, Settings, Species, Work};
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::eos::Lth;
use gendpde_potentials::volume::PartitionVolume;
use gendpde_potentials::{CubicSpline, Eos, LennardJones, LinearTheta, Linear, Lucy, Quadratic, TableError, TableErrors, TableGrid, Tabulated, WeightKind};

/// `pair_style gendpde CUTOFF SEED [weight W] [volume plain|corrected FCUT]` with
/// `pair_coeff * * GAMMA KAPPA [RC_D [RC_H]]`.
#[derive(Clone, Debug, PartialEq)]
pub struct PairGendpde {
    pub cutoff: f64,
    pub seed: u64,
    pub weight: WeightKind,
    /// f_cut of the corrected particle volume (argon paper eqs 2-3); None: n = n^b.
    pub volume: Option<f64>,
    pub coeff: Option<PairCoeff>,
}

/// The pair style in force.
#[derive(Clone, Debug, PartialEq)]
pub enum PairStyle {
    Gendpde(PairGendpde),
    /// LAMMPS's pairwise DPD styles (src/pairwise.rs).
    Pairwise(crate::pairwise::Pairwise),
}

impl PairStyle {
    /// The largest interaction cutoff (LAMMPS's `cutforce`): for gendpde the largest of
    /// the density, friction and heat cutoffs, for the pairwise styles that of pair_coeff
    /// (and the mdpd/rhosum kernel).
    pub fn cutoff(&self) -> f64 {
        match self {
            Self::Gendpde(p) => p.coeff.as_ref().map_or(p.cutoff, |c| p.cutoff.max(c.rc_friction).max(c.rc_heat)),
            Self::Pairwise(p) => p.coeff.as_ref().map_or(p.cutoff, |c| c.rc).max(p.rhosum.unwrap_or(0.0)),
        }
    }
}

/// Dissipation parameters of `pair_coeff`.
#[derive(Clone, Debug, PartialEq)]
pub struct PairCoeff {
    pub gamma: f64,
    pub kappa: f64,
    pub rc_friction: f64,
    pub rc_heat: f64,
}

/// A particle EOS chosen by a `fix eos/...`, analytic or through a table (`table`
/// keyword).
#[derive(Clone, Debug, PartialEq)]
pub enum EosModel {
    Linear(LinearTheta),
    Lj(LennardJones),
    Lth(Lth),
    LinearTable(Tabulated<LinearTheta>),
    LjTable(Tabulated<LennardJones>),
    LthTable(Tabulated<Lth>),
    /// `eos/cv CV1 CV2 ...`: one linear EOS per particle type (index type - 1).
    PerType(Vec<LinearTheta>),
}

/// Evaluates `$body` with `$e` bound to the concrete EOS of `$model`.
macro_rules! each_eos {
    ($model:expr, $e:ident => $body:expr) => {
        match $model {
            EosModel::Linear($e) => $body,
            EosModel::Lj($e) => $body,
            EosModel::Lth($e) => $body,
            EosModel::LinearTable($e) => $body,
            EosModel::LjTable($e) => $body,
            EosModel::LthTable($e) => $body,
            // describe and bound by type 1 (build_physics takes every type)
            EosModel::PerType(v) => {
                let $e = &v[0];
                $body
            }
        }
    };
}

impl EosModel {
    /// Largest mean number density the model admits, if bounded.
    pub fn max_density(&self) -> Option<f64> {
        each_eos!(self, e => e.max_density())
    }

    /// The state at (theta, n), or at (u, n) when `u` is given: `name value` pairs as
    /// `gendpde eos` prints them (with the table's measured errors for a table).
    pub fn describe(&self, theta: Option<f64>, u: Option<f64>, n: f64) -> Result<Vec<(&'static str, f64)>, String> {
        let mut out = each_eos!(self, e => describe(e, theta, u, n))?;
        if let Some(err) = self.table_errors() {
            out.extend([("table_error_u", err.u.rel), ("table_error_pn2", err.pn2.rel), ("table_error_cv", err.cv.rel), ("table_error_theta", err.theta.rel)]);
        }
        Ok(out)
    }

    /// The largest relative errors of a table against its analytic model, sampled at 4 x 4
    /// states per cell (None for an analytic model).
    pub fn table_errors(&self) -> Option<TableErrors> {
        match self {
            Self::LinearTable(t) => Some(t.max_error(4)),
            Self::LjTable(t) => Some(t.max_error(4)),
            Self::LthTable(t) => Some(t.max_error(4)),
            _ => None,
        }
    }

    /// Replaces the model by its table on `grid`.
    fn tabulate(self, grid: TableGrid) -> Result<Self, TableError> {
        Ok(match self {
            Self::Linear(e) => Self::LinearTable(Tabulated::new(e, grid)?),
            Self::Lj(e) => Self::LjTable(Tabulated::new(e, grid)?),
            Self::Lth(e) => Self::LthTable(Tabulated::new(e, grid)?),
            Self::PerType(_) => return Err(TableError::Grid("a table of a per-type EOS (give one C_V)".into())),
            table => table,
        })
    }
}

/// u, theta, n, the particle (excess) pressure pi, the total pressure n k_B theta + pi,
/// C_V, the dressed temperature tau (eq 23) and the entropy s.
fn describe<E: Eos>(eos: &E, theta: Option<f64>, u: Option<f64>, n: f64) -> Result<Vec<(&'static str, f64)>, String> {
    let u = match (theta, u) {
        (_, Some(u)) => u,
        (Some(t), None) => eos.u(t, n),
        (None, None) => return Err("give --theta or --u".into()),
    };
    let st = eos.state(u, n, theta.unwrap_or(1.0)).map_err(|e| e.to_string())?;
    let pi = st.pn2 * n * n;
    let mut out = vec![("u", u), ("theta", st.theta), ("n", n), ("pi", pi), ("pressure", n * eos.kb() * st.theta + pi), ("cv", st.cv)];
    out.push(("tau", 1.0 / eos.inv_tau(st.theta, st.cv)));
    out.push(("s", eos.entropy(u, n).unwrap_or(f64::NAN)));
    Ok(out)
}

/// The fix styles.
#[derive(Clone, Debug, PartialEq)]
pub enum FixStyle {
    Eos(EosModel),
    /// `fix nve/gendpde [work split|isentropic]`: the reversible velocity-Verlet step.
    Verlet { work: Work },
    /// `fix vv/euler [heat original|fourier]`: velocity Verlet with all pair forces, Euler
    /// for u (argon paper, sec 4.1).
    VvEuler { heat: HeatModel },
    /// `fix shardlow [heat original|fourier] [substeps N] [reject yes|no]`.
    Shardlow { heat: HeatModel, substeps: u32, reject: bool },
    /// `fix ID GROUP heat/reservoir T KAPPA SEED [heat original|fourier]`; `mask` is the
    /// group's bit (`u32::MAX` for all).
    Reservoir { temperature: f64, kappa: f64, seed: u64, heat: Option<HeatModel>, mask: u32 },
    /// `fix nve` (LAMMPS's pairwise styles).
    Nve,
    /// `fix mvv/dpd [LAMBDA]` (pair mdpd).
    Mvv { lambda: f64 },
}

#[derive(Clone, Debug)]
pub struct Fix {
    pub id: String,
    pub style: FixStyle,
    /// The command as written (restart files re-create fixes from it).
    pub text: String,
}

/// Default and largest number of halving levels of a failing Shardlow pair update.
pub const DEFAULT_SUBSTEPS: u32 = 4;
pub const MAX_SUBSTEPS: u32 = 8;

pub const FIX_STYLES: &str =
    "eos/vdw, eos/lj, eos/lth, eos/ideal, eos/cv, eos/density, eos/linear, nve/gendpde, shardlow, vv/euler, heat/reservoir, nve, mvv/dpd, ave/time";

pub fn parse_pair_style(cmd: &Command) -> Result<PairStyle, ScriptError> {
    let mut a = Args::new(cmd);
    match a.word("a pair style")? {
        "gendpde" => parse_gendpde(&mut a).map(PairStyle::Gendpde),
        other => crate::pairwise::parse_style(other, &mut a).map(PairStyle::Pairwise),
    }
}

/// `pair_style gendpde CUTOFF SEED [weight W] [volume plain|corrected FCUT]`.
fn parse_gendpde(a: &mut Args) -> Result<PairGendpde, ScriptError> {
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

/// `pair_coeff` for the pair style in force.
pub fn parse_pair_coeff(cmd: &Command, pair: &mut PairStyle, ntypes: usize) -> Result<(), ScriptError> {
    match pair {
        PairStyle::Gendpde(p) => {
            p.coeff = Some(parse_gendpde_coeff(cmd, p, ntypes)?);
            Ok(())
        }
        PairStyle::Pairwise(p) => crate::pairwise::parse_coeff(p, cmd, ntypes),
    }
}

fn parse_gendpde_coeff(cmd: &Command, pair: &PairGendpde, ntypes: usize) -> Result<PairCoeff, ScriptError> {
    let mut a = Args::new(cmd);
    let ti = a.types(ntypes)?;
    let tj = a.types(ntypes)?;
    if *ti.start() != 1 || *ti.end() != ntypes || *tj.start() != 1 || *tj.end() != ntypes {
        return Err(a.err("pair gendpde takes one coefficient set for all type pairs: use 'pair_coeff * *'"));
    }
    let gamma = a.non_negative("the friction gamma")?;
    let kappa = a.non_negative("the conductivity kappa")?;
    let rc_friction = if a.remaining() > 0 { a.positive("the friction cutoff")? } else { pair.cutoff };
    let rc_heat = if a.remaining() > 0 { a.positive("the heat cutoff")? } else { rc_friction };
    a.done()?;
    Ok(PairCoeff { gamma, kappa, rc_friction, rc_heat })
}

/// `fix ID GROUP STYLE args...`; `kb` is Boltzmann's constant of the units, `groups`
/// the group names by bit.
pub fn parse_fix(cmd: &Command, kb: f64, groups: &[String]) -> Result<Fix, ScriptError> {
    let mut a = Args::new(cmd);
    let id = a.word("a fix ID")?.to_string();
    let group = a.word("a group")?;
    let style_name = a.word("a fix style")?;
    if group != "all" && style_name != "heat/reservoir" {
        return Err(a.err(format!("group '{group}': fix {style_name} acts on group all (only heat/reservoir takes a group)")));
    }
    let style = match style_name {
        s if s.starts_with("eos/") => FixStyle::Eos(parse_eos(s, &mut a, kb)?),
        "nve/gendpde" => {
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
            FixStyle::Verlet { work }
        }
        "vv/euler" => FixStyle::VvEuler { heat: heat_keyword(&mut a)?.unwrap_or(HeatModel::Original) },
        "nve" => FixStyle::Nve,
        "mvv/dpd" => FixStyle::Mvv { lambda: if a.remaining() > 0 { a.positive("lambda")? } else { 0.5 } },
        "shardlow" => {
            let (mut heat, mut substeps, mut reject) = (HeatModel::Original, DEFAULT_SUBSTEPS, false);
            while let Some(k) = a.peek() {
                match k {
                    "heat" => heat = heat_keyword(&mut a)?.unwrap_or(heat),
                    "substeps" => {
                        a.word("substeps")?;
                        substeps = a.u64("the number of halving levels")?.min(MAX_SUBSTEPS as u64) as u32;
                    }
                    "reject" => {
                        a.word("reject")?;
                        reject = a.yes_no("reject")?;
                    }
                    _ => return Err(a.err(format!("unknown keyword '{k}'; known: heat, substeps, reject"))),
                }
            }
            FixStyle::Shardlow { heat, substeps, reject }
        }
        "heat/reservoir" => {
            let temperature = a.positive("the reservoir temperature")?;
            let kappa = a.positive("the reservoir coupling kappa")?;
            let seed = a.u64("the random seed")?;
            let mask = crate::groups::mask_of(groups, group, &a)?;
            FixStyle::Reservoir { temperature, kappa, seed, heat: heat_keyword(&mut a)?, mask }
        }
        other => return Err(a.err(format!("unknown fix style '{other}'; known: {FIX_STYLES}"))),
    };
    a.done()?;
    Ok(Fix { id, style, text: crate::commands::echo(cmd) })
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

/// The EOS fixes: `eos/vdw CV A B [excess|full] [cap F]`, `eos/lj CV`, `eos/ideal CV`, `eos/cv CV`,
/// `eos/density CV c1 [c2 ...]`, `eos/linear CV Q R B [c1 ...]`,
/// `eos/lth CV ALPHA KAPPA_T PI00 THETA0 N00`, each optionally followed by
/// `table THETA_MIN THETA_MAX N_THETA N_MIN N_MAX N_N`.
pub fn parse_eos(style: &str, a: &mut Args, kb: f64) -> Result<EosModel, ScriptError> {
    let model = parse_model(style, a, kb)?;
    if a.peek() != Some("table") {
        return Ok(model);
    }
    a.word("keyword")?;
    let theta = (a.positive("the table's smallest theta")?, a.positive("the table's largest theta")?, a.u64("the number of theta nodes")? as usize);
    let n = (a.non_negative("the table's smallest density")?, a.positive("the table's largest density")?, a.u64("the number of density nodes")? as usize);
    if let Some(w) = a.peek() {
        return Err(a.err(format!("unexpected '{w}' after the table grid")));
    }
    let table = model.tabulate(TableGrid { theta, n }).map_err(|e| a.err(e.to_string()))?;
    if let Some(err) = table.table_errors() {
        log::info!("EOS table: {err}");
    }
    Ok(table)
}

fn parse_model(style: &str, a: &mut Args, kb: f64) -> Result<EosModel, ScriptError> {
    let cv = a.positive("the heat capacity C_V")?;
    if cv <= kb {
        return Err(a.err(format!("C_V = {cv} must exceed k_B = {kb} (the dressed temperature of eq 23 diverges at C_V = k_B)")));
    }
    let mut eos = match style {
        "eos/vdw" => {
            let (va, b) = (a.non_negative("the vdW attraction a")?, a.positive("the vdW excluded volume b")?);
            let mut e = LinearTheta::vdw_excess(cv, va, b);
            while let Some(k) = a.peek().filter(|&k| k != "table") {
                a.word("keyword")?;
                match k {
                    "excess" => e = LinearTheta { cap: e.cap, ..LinearTheta::vdw_excess(cv, va, b) },
                    "full" => e = LinearTheta { cap: e.cap, ..LinearTheta::vdw_full(cv, va, b) },
                    "cap" => {
                        let f = a.positive("the cap fraction of 1/b")?;
                        if f >= 1.0 {
                            return Err(a.err(format!("cap {f} must lie below 1 (a fraction of 1/b)")));
                        }
                        e.cap = f;
                    }
                    _ => return Err(a.err(format!("unknown keyword '{k}'; known: excess, full, cap, table"))),
                }
            }
            e
        }
        "eos/lj" if kb != 1.0 => return Err(a.err("eos/lj is in reduced Lennard-Jones units: use units lj")),
        "eos/lj" => return Ok(EosModel::Lj(LennardJones::new(cv))),
        "eos/lth" => {
            let alpha = a.f64("the particle expansion coefficient alpha")?;
            let kappa_t = a.positive("the particle compressibility kappa_T")?;
            let pi00 = a.f64("the reference particle pressure pi00")?;
            let theta0 = a.positive("the reference temperature theta0")?;
            let n00 = a.positive("the reference density n00")?;
            return Ok(EosModel::Lth(Lth { kb, ..Lth::new(cv, alpha, kappa_t, pi00, theta0, n00) }));
        }
        "eos/ideal" => LinearTheta::ideal(cv),
        "eos/cv" => {
            let mut per_type = vec![LinearTheta { kb, ..LinearTheta::cv_only(cv) }];
            while a.remaining() > 0 && a.peek() != Some("table") {
                let cv = a.positive("the heat capacity C_V of the next type")?;
                if cv <= kb {
                    return Err(a.err(format!("C_V = {cv} must exceed k_B = {kb}")));
                }
                per_type.push(LinearTheta { kb, ..LinearTheta::cv_only(cv) });
            }
            if per_type.len() > 1 {
                return Ok(EosModel::PerType(per_type));
            }
            LinearTheta::cv_only(cv)
        }
        "eos/density" => LinearTheta::density_only(cv, coefficients(a)?),
        "eos/linear" => {
            let q = a.f64("the exponent q of n in psi")?;
            let r = a.f64("the exponent r of 1/(1 - b n) in psi")?;
            let b = a.non_negative("the excluded volume b")?;
            LinearTheta { q, r, b, v_coeffs: coefficients(a)?, ..LinearTheta::cv_only(cv) }
        }
        other => return Err(a.err(format!("unknown EOS fix '{other}'; known: {FIX_STYLES}"))),
    };
    eos.cv = cv;
    eos.kb = kb;
    Ok(EosModel::Linear(eos))
}

fn coefficients(a: &mut Args) -> Result<Vec<f64>, ScriptError> {
    let mut c = Vec::new();
    while a.remaining() > 0 && a.peek() != Some("table") {
        c.push(a.f64("a coefficient c_k of V(n) = sum_k c_k n^k")?);
    }
    Ok(c)
}

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
            return crate::pairwise::build(cmd, p, fixes, settings, kb);
        }
    };
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
