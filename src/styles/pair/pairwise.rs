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

use crate::base::args::Args;
use crate::styles::PAIR_STYLES;
use gendpde_io::{Command, PairCoeffs, ScriptError};

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

/// One value per unordered pair of types 1..=n (LAMMPS's `setflag` with its
/// coefficient arrays), `None` where no `pair_coeff` set it.
#[derive(Clone, Debug, PartialEq)]
pub struct TypePairs<T> {
    n: usize,
    set: Vec<Option<T>>,
}

impl<T> Default for TypePairs<T> {
    fn default() -> Self {
        Self { n: 0, set: Vec::new() }
    }
}

impl<T: Clone> TypePairs<T> {
    /// The number of types the table holds (0 before the first `pair_coeff`).
    pub fn ntypes(&self) -> usize {
        self.n
    }

    /// The value of types `i`, `j` (1-based, either order).
    pub fn get(&self, i: usize, j: usize) -> Option<&T> {
        let (i, j) = (i.min(j), i.max(j));
        if i == 0 || j > self.n {
            return None;
        }
        self.set[(i - 1) * self.n + j - 1].as_ref()
    }

    /// Every set value.
    pub fn values(&self) -> impl Iterator<Item = &T> {
        self.set.iter().flatten()
    }

    /// The table for `n` types, or the first pair (i <= j) left unset.
    pub fn complete(&self, n: usize) -> Result<Vec<T>, (usize, usize)> {
        let mut flat = Vec::with_capacity(n * n);
        for i in 1..=n {
            for j in 1..=n {
                flat.push(self.get(i, j).cloned().ok_or((i.min(j), i.max(j)))?);
            }
        }
        Ok(flat)
    }

    /// Applies `f` to every set value.
    pub fn for_each_set(&mut self, f: impl FnMut(&mut T)) {
        self.set.iter_mut().flatten().for_each(f);
    }

    fn put(&mut self, n: usize, i: usize, j: usize, v: T) {
        if self.n != n {
            *self = Self { n, set: vec![None; n * n] };
        }
        self.set[(i - 1) * n + j - 1] = Some(v);
    }
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
pub fn parse_style(style: &str, a: &mut Args) -> Result<Pairwise, ScriptError> {
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
        other => return Err(a.err(format!("unknown pair style '{other}'; known: {PAIR_STYLES}"))),
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
