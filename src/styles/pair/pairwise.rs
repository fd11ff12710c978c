//! LAMMPS's pairwise DPD styles, with their names, arguments and semantics:
//!
//! - `pair_style dpd T CUTOFF SEED`, `pair_coeff I J A GAMMA [CUTOFF]` with `fix nve`;
//! - `pair_style dpd/fdt T CUTOFF SEED`, `pair_coeff I J A SIGMA [CUTOFF]` with
//!   `fix shardlow` + `fix nve`;
//! - `pair_style dpd/fdt/energy CUTOFF SEED`, `pair_coeff I J A SIGMA KAPPA [CUTOFF]` with
//!   `fix shardlow` + `fix nve` + `fix eos/cv CV`;
//! - `pair_style dpd/ext T CUTOFF SEED`, `pair_coeff I J A GAMMA_PAR GAMMA_PERP S_PAR
//!   S_PERP [CUTOFF]` with `fix nve` (DPD-BASIC);
//! - `pair_style dpd/tstat TSTART TSTOP CUTOFF SEED`, `pair_coeff I J GAMMA [CUTOFF]` and
//!   `pair_style dpd/ext/tstat TSTART TSTOP CUTOFF SEED`, `pair_coeff I J GAMMA_PAR
//!   GAMMA_PERP S_PAR S_PERP [CUTOFF]`: the thermostats alone (no conservative force),
//!   the target temperature ramped from TSTART to TSTOP over each run;
//! - `pair_style hybrid/overlay mdpd/rhosum mdpd T CUTOFF SEED`,
//!   `pair_coeff I J mdpd/rhosum H`, `pair_coeff I J mdpd A B GAMMA CUTOFF CUTOFF_R` with
//!   `fix mvv/dpd [LAMBDA]`.
//!
//! Coefficients are per type pair, as in LAMMPS: `pair_coeff I J` with LAMMPS's type
//! ranges (`*`, `1*2`, `*3`, `2*`) sets every pair i <= j of the ranges; plain numbers
//! with J < I are swapped. None of these styles mixes: a pair left unset stops `run`
//! with LAMMPS's "All pair coeffs are not set".

use super::type_pairs::TypePairs;
use super::{Pair, RunInputs};
use crate::base::args::Args;
use crate::styles::fix::eos::EosModel;
use crate::styles::fix::FixStyle;
use gendpde_integrators::{ClassicDpd, DpdCoeff, DpdEnergyCoeff, DpdExt, DpdExtCoeff, Integration, MdpdCoeff, NoiseForm, PairForce, Physics, ShardlowCoeff, ShardlowDpd, TypeTable};
use gendpde_io::{Command, PairCoeffs, ScriptError};
use gendpde_potentials::Lucy;

#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    Dpd { temperature: f64 },
    DpdExt { temperature: f64 },
    /// The thermostats: no a0, T ramped from `start` to `stop` over each run.
    DpdTstat { start: f64, stop: f64 },
    DpdExtTstat { start: f64, stop: f64 },
    DpdFdt { temperature: f64 },
    DpdFdtEnergy,
    Mdpd { temperature: f64 },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Pairwise {
    pub kind: Kind,
    pub cutoff: f64,
    pub seed: u64,
    /// A (a0), B (mdpd), gamma (dpd, mdpd, the parallel one of dpd/ext) or sigma
    /// (dpd/fdt*), kappa, cutoff, cutoff_r; dpd/ext's gamma_perp, s_par, s_perp.
    pub coeff: TypePairs<Coeff>,
    /// Kernel support h of `mdpd/rhosum`.
    pub rhosum: TypePairs<f64>,
}

#[derive(Clone, Debug, PartialEq, Default)]
pub struct Coeff {
    pub a: f64,
    pub b: f64,
    pub gamma: f64,
    pub sigma: f64,
    pub kappa: f64,
    pub rc: f64,
    pub rd: f64,
    pub gamma_perp: f64,
    pub s_par: f64,
    pub s_perp: f64,
}

impl Pairwise {
    /// The `Pair Coeffs` (`i a0 gamma`, LAMMPS's `write_data` default) or `PairIJ Coeffs`
    /// (`i j a0 gamma cutoff`) section of `write_data`: `pair dpd` only, as in LAMMPS
    /// (its other DPD styles write none). Values print in round-trip form, where LAMMPS
    /// prints 6 digits. Err like LAMMPS's set-up when a pair is unset.
    pub fn data_section(&self, ntypes: usize, ij: bool) -> Result<Option<PairCoeffs>, String> {
        if !matches!(self.kind, Kind::Dpd { .. }) {
            return Ok(None);
        }
        let c = self.coeff.complete(ntypes).map_err(|(i, j)| format!("All pair coeffs are not set: no pair_coeff for types {i} {j}"))?;
        let mut rows = Vec::new();
        for i in 1..=ntypes {
            for j in if ij { i..=ntypes } else { i..=i } {
                let p = &c[(i - 1) * ntypes + j - 1];
                let mut row = vec![i.to_string()];
                if ij {
                    row.push(j.to_string());
                }
                row.extend([format!("{:?}", p.a), format!("{:?}", p.gamma)]);
                if ij {
                    row.push(format!("{:?}", p.rc));
                }
                rows.push(row);
            }
        }
        let lines = vec![0; rows.len()];
        Ok(Some(PairCoeffs { ij, style: Some("dpd".into()), rows, lines }))
    }
}

/// A pairwise `pair_style` line (the words after the style name in `a`).
pub fn parse(style: &str, a: &mut Args) -> Result<Pairwise, ScriptError> {
    let kind = match style {
        "dpd" => Kind::Dpd { temperature: a.non_negative("the temperature T")? },
        "dpd/ext" => Kind::DpdExt { temperature: a.non_negative("the temperature T")? },
        "dpd/tstat" | "dpd/ext/tstat" => {
            let start = a.non_negative("the start temperature TSTART")?;
            let stop = a.non_negative("the stop temperature TSTOP")?;
            if style == "dpd/tstat" {
                Kind::DpdTstat { start, stop }
            } else {
                Kind::DpdExtTstat { start, stop }
            }
        }
        "dpd/fdt" => Kind::DpdFdt { temperature: a.positive("the temperature T")? },
        "dpd/fdt/energy" => Kind::DpdFdtEnergy,
        "hybrid/overlay" => {
            for expect in ["mdpd/rhosum", "mdpd"] {
                let w = a.word(expect)?;
                if w != expect {
                    return Err(a.err(format!("pair_style hybrid/overlay supports 'mdpd/rhosum mdpd ...' only, got '{w}'")));
                }
            }
            Kind::Mdpd { temperature: a.positive("the temperature T")? }
        }
        other => return Err(a.err(format!("unknown pair style '{other}'; known: {}", super::known_styles()))),
    };
    let cutoff = a.positive("the cutoff")?;
    let seed = a.u64("the random seed")?;
    if seed == 0 {
        return Err(a.err("the random seed must be positive"));
    }
    a.done()?;
    Ok(Pairwise { kind, cutoff, seed, coeff: TypePairs::default(), rhosum: TypePairs::default() })
}

/// A `pair_coeff` line for a pairwise style.
pub fn parse_coeff(p: &mut Pairwise, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
    let mut a = Args::new(cmd);
    let plain = |k: usize| cmd.args.get(k).is_some_and(|w| w.bytes().all(|b| b.is_ascii_digit()));
    let (mut ti, mut tj) = (a.types(ntypes)?, a.types(ntypes)?);
    if plain(0) && plain(1) && tj.start() < ti.start() {
        std::mem::swap(&mut ti, &mut tj);
    }
    let pairs: Vec<(usize, usize)> = ti.flat_map(|i| (i.max(*tj.start())..=*tj.end()).map(move |j| (i, j))).collect();
    if pairs.is_empty() {
        return Err(a.err(format!("the types '{} {}' hold no pair I <= J", cmd.args[0], cmd.args[1])));
    }
    let optional_cutoff = |a: &mut Args, default: f64| if a.remaining() > 0 { a.positive("the cutoff") } else { Ok(default) };
    let mut c = Coeff::default();
    match p.kind {
        Kind::Dpd { .. } => {
            c.a = a.f64("A (a0)")?;
            c.gamma = a.non_negative("gamma")?;
            c.rc = optional_cutoff(&mut a, p.cutoff)?;
        }
        Kind::DpdExt { .. } | Kind::DpdTstat { .. } | Kind::DpdExtTstat { .. } => {
            // LAMMPS's allocate(): s_par = s_perp = 1, gamma_perp = 0 (dpd/tstat)
            (c.s_par, c.s_perp) = (1.0, 1.0);
            let ext = !matches!(p.kind, Kind::DpdTstat { .. });
            if matches!(p.kind, Kind::DpdExt { .. }) {
                c.a = a.f64("A (a0)")?;
            }
            c.gamma = a.non_negative(if ext { "gamma_par" } else { "gamma" })?;
            if ext {
                c.gamma_perp = a.non_negative("gamma_perp")?;
                c.s_par = a.f64("s_par")?;
                c.s_perp = a.f64("s_perp")?;
            }
            c.rc = optional_cutoff(&mut a, p.cutoff)?;
        }
        Kind::DpdFdt { .. } => {
            c.a = a.f64("A (a0)")?;
            c.sigma = a.non_negative("sigma")?;
            c.rc = optional_cutoff(&mut a, p.cutoff)?;
        }
        Kind::DpdFdtEnergy => {
            c.a = a.f64("A (a0)")?;
            c.sigma = a.non_negative("sigma")?;
            c.kappa = a.non_negative("kappa")?;
            c.rc = optional_cutoff(&mut a, p.cutoff)?;
        }
        Kind::Mdpd { .. } => match a.word("mdpd/rhosum or mdpd")? {
            "mdpd/rhosum" => {
                let h = a.positive("the kernel cutoff h")?;
                a.done()?;
                for (i, j) in pairs {
                    p.rhosum.put(ntypes, i, j, h);
                }
                return Ok(());
            }
            "mdpd" => {
                c.a = a.f64("A")?;
                c.b = a.f64("B")?;
                c.gamma = a.non_negative("gamma")?;
                c.rc = a.positive("the cutoff")?;
                c.rd = a.positive("the cutoff of the repulsive term")?;
                if c.rc < c.rd {
                    return Err(a.err(format!("the cutoff {:?} must not be shorter than that of the repulsive term {:?} (LAMMPS: cutA should be larger than cutB)", c.rc, c.rd)));
                }
            }
            w => return Err(a.err(format!("expected mdpd/rhosum or mdpd, got '{w}'"))),
        },
    }
    a.done()?;
    for (i, j) in pairs {
        p.coeff.put(ntypes, i, j, c.clone());
    }
    Ok(())
}

/// `pair_style dpd|dpd/ext|dpd/tstat|dpd/ext/tstat|dpd/fdt|dpd/fdt/energy ...` (and
/// `hybrid/overlay mdpd/rhosum mdpd ...` through [`super::hybrid`]).
pub fn parse_style(name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError> {
    parse(name, a).map(|p| Box::new(p) as Box<dyn Pair>)
}

impl Pair for Pairwise {
    fn name(&self) -> &str {
        match self.kind {
            Kind::Dpd { .. } => "dpd",
            Kind::DpdExt { .. } => "dpd/ext",
            Kind::DpdTstat { .. } => "dpd/tstat",
            Kind::DpdExtTstat { .. } => "dpd/ext/tstat",
            Kind::DpdFdt { .. } => "dpd/fdt",
            Kind::DpdFdtEnergy => "dpd/fdt/energy",
            Kind::Mdpd { .. } => "hybrid/overlay mdpd/rhosum mdpd",
        }
    }

    fn coeff(&mut self, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
        parse_coeff(self, cmd, ntypes)
    }

    fn accepts(&self, fix: &FixStyle) -> bool {
        matches!(fix, FixStyle::Nve | FixStyle::Nph { .. } | FixStyle::Mvv { .. } | FixStyle::DpdEnergy | FixStyle::Shardlow { .. } | FixStyle::Eos(_))
    }

    fn fixes(&self) -> &'static str {
        "nve, nph, shardlow, eos/cv, mvv/dpd, dpd/energy"
    }

    fn keep_coefficients(&mut self, old: &dyn Pair) -> bool {
        let Some(old) = old.as_any().downcast_ref::<Self>() else { return false };
        if std::mem::discriminant(&self.kind) != std::mem::discriminant(&old.kind) || matches!(self.kind, Kind::Mdpd { .. }) {
            return false;
        }
        self.coeff = old.coeff.clone();
        let cutoff = self.cutoff;
        self.coeff.for_each_set(|c| c.rc = cutoff);
        true
    }

    fn data_section(&self, ntypes: usize, ij: bool) -> Result<Option<PairCoeffs>, String> {
        Pairwise::data_section(self, ntypes, ij)
    }

    fn build(&self, run: &RunInputs) -> Result<Box<dyn Physics>, String> {
        self.dynamics(run).map(|d| Box::new(d) as Box<dyn Physics>)
    }
}

impl Pairwise {
    /// The dynamics of the style with its fixes (fix nve, nph, mvv/dpd, shardlow,
    /// dpd/energy, eos/cv).
    pub fn dynamics(&self, run: &RunInputs) -> Result<ClassicDpd, String> {
        let ntypes = run.ntypes;
        // LAMMPS's Pair::init and init_one: no mixing in these styles
        let unset = |(i, j): (usize, usize), what: &str| format!("All {what}coeffs are not set: no pair_coeff for types {i} {j}");
        let c = self.coeff.complete(ntypes).map_err(|ij| unset(ij, "pair "))?;
        let shardlow = run.has(|s| matches!(s, FixStyle::Shardlow { .. }));
        if run.has(|s| matches!(s, FixStyle::Shardlow { noise: NoiseForm::Harmonic { .. }, .. })) {
            return Err("fix shardlow: 'noise' belongs to pair gendpde (dpd/fdt/energy's noise is already the harmonic form on theta)".into());
        }
        let nve = run.has(|s| *s == FixStyle::Nve);
        let barostat = run.one("nph", |s| if let FixStyle::Nph { nph, .. } = s { Some((**nph).clone()) } else { None })?.map(|(_, b)| b);
        let mvv = run.fixes.iter().find_map(|f| if let FixStyle::Mvv { lambda } = f.style { Some(lambda) } else { None });
        let cv = run.fixes.iter().find_map(|f| match &f.style {
            FixStyle::Eos(EosModel::Linear(e)) if !gendpde_potentials::Eos::density_dependent(e) && e.q == 0.0 => Some(e.cv),
            _ => None,
        });
        if nve && barostat.is_some() {
            return Err("fix nve and fix nph both integrate: keep one".into());
        }
        let integration = match (nve || barostat.is_some(), mvv) {
            (true, None) => Integration::Nve,
            (false, Some(lambda)) => Integration::Mvv { lambda },
            (true, Some(_)) => return Err("fix mvv/dpd and fix nve (or nph) both integrate: keep one".into()),
            (false, None) => return Err("no integrator: add fix nve or nph (or fix mvv/dpd for mdpd)".into()),
        };
        let energy = run.has(|s| *s == FixStyle::DpdEnergy);
        fn table<T>(ntypes: usize, v: Vec<T>) -> Result<TypeTable<T>, String> {
            TypeTable::new(ntypes, v).ok_or_else(|| "the box has no particle types".to_string())
        }
        let kb = run.kb;
        let conservative = || table(ntypes, c.iter().map(|c| DpdCoeff::new(c.a, c.rc, 0.0, 0.0)).collect());
        let sweep_of = |temperature: Option<f64>| {
            let kappa = |k: f64| if temperature.is_some() { 0.0 } else { k };
            let coeff = c.iter().map(|c| ShardlowCoeff::new(c.sigma, kappa(c.kappa), c.rc)).collect();
            table(ntypes, coeff).map(|coeff| ShardlowDpd { coeff, temperature })
        };
        // dpd/ext and the thermostats (a0 = 0, gamma_perp = 0 and s = 1 for dpd/tstat)
        let ext = |start: f64, stop: f64| {
            let coeff = c.iter().map(|c| DpdExtCoeff { a0: c.a, rc: c.rc, gamma_par: c.gamma, gamma_perp: c.gamma_perp, s_par: c.s_par, s_perp: c.s_perp });
            table(ntypes, coeff.collect()).map(|coeff| DpdExt { coeff, start, stop })
        };
        let (force, sweep) = match self.kind {
            Kind::Dpd { temperature } => (PairForce::Dpd(table(ntypes, c.iter().map(|c| DpdCoeff::isothermal(c.a, c.rc, c.gamma, kb, temperature)).collect())?), None),
            Kind::DpdExt { temperature } => (PairForce::DpdExt(ext(temperature, temperature)?), None),
            Kind::DpdTstat { start, stop } | Kind::DpdExtTstat { start, stop } => (PairForce::DpdExt(ext(start, stop)?), None),
            // velocity Verlet (pair_dpd_fdt.cpp without fix shardlow)
            Kind::DpdFdt { temperature } if !shardlow => (PairForce::Dpd(table(ntypes, c.iter().map(|c| DpdCoeff::from_sigma(c.a, c.rc, c.sigma, kb, temperature)).collect())?), None),
            Kind::DpdFdtEnergy if !shardlow => {
                let coeff = c.iter().map(|c| DpdEnergyCoeff { a0: c.a, rc: c.rc, sigma: c.sigma, kappa: c.kappa });
                (PairForce::DpdEnergy(table(ntypes, coeff.collect())?), None)
            }
            Kind::DpdFdt { temperature } => (PairForce::Dpd(conservative()?), Some(sweep_of(Some(temperature))?)),
            Kind::DpdFdtEnergy => (PairForce::Dpd(conservative()?), Some(sweep_of(None)?)),
            Kind::Mdpd { temperature } => {
                if self.rhosum.ntypes() == 0 {
                    return Err("pair mdpd needs 'pair_coeff * * mdpd/rhosum H'".into());
                }
                let h = self.rhosum.complete(ntypes).map_err(|ij| unset(ij, "pair mdpd/rhosum "))?;
                let coeff = c.iter().zip(h).map(|(c, h)| MdpdCoeff::isothermal(c.a, c.b, c.rc, c.rd, c.gamma, kb, temperature, Lucy::new(h)));
                (PairForce::Mdpd(table(ntypes, coeff.collect())?), None)
            }
        };
        if shardlow && matches!(self.kind, Kind::Dpd { .. } | Kind::DpdExt { .. } | Kind::DpdTstat { .. } | Kind::DpdExtTstat { .. } | Kind::Mdpd { .. }) {
            return Err("fix shardlow works with pair dpd/fdt and dpd/fdt/energy".into());
        }
        if energy && (shardlow || !matches!(self.kind, Kind::DpdFdtEnergy)) {
            return Err("fix dpd/energy integrates pair dpd/fdt/energy without fix shardlow (with it the sweep moves u)".into());
        }
        if matches!(self.kind, Kind::DpdFdtEnergy) && cv.is_none() {
            return Err("pair dpd/fdt/energy needs fix eos/cv".into());
        }
        if matches!(integration, Integration::Mvv { .. }) && !matches!(self.kind, Kind::Mdpd { .. }) {
            return Err("fix mvv/dpd integrates pair mdpd".into());
        }
        Ok(ClassicDpd { force, tables: None, shardlow: sweep, integration, cv, energy, barostat, kb, seed: self.seed, settings: run.settings() })
    }
}
