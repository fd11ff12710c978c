//! `pair_style edpd CUTOFF SEED` and `pair_coeff I J A0 GAMMA POWER CUTOFF KAPPA POWER_T
//! CUTOFF_T [power c1 c2 c3 c4] [kappa c1 c2 c3 c4]` (LAMMPS DPD-MESO's eDPD; the force
//! law is in `gendpde_integrators::models::edpd`). Coefficients are kept per type pair.

use super::type_pairs::TypePairs;
use super::{Pair, RunInputs};
use crate::base::args::Args;
use crate::styles::fix::{FixStyle, SourceSpec};
use gendpde_integrators::{Edpd, EdpdCoeff, HeatSource, Physics, SourceShape, TypeTable};
use gendpde_io::{Command, ScriptError};

#[derive(Clone, Debug, PartialEq)]
pub struct PairEdpd {
    /// The global cutoff of `pair_style` (each pair_coeff gives its own).
    pub cutoff: f64,
    pub seed: u64,
    /// Coefficients by type pair, None while unset.
    pub coeff: TypePairs<EdpdCoeff>,
}

/// The words after `pair_style edpd`.
fn parse(a: &mut Args) -> Result<PairEdpd, ScriptError> {
    let cutoff = a.positive("the cutoff")?;
    let seed = a.u64("the random seed")?;
    if seed == 0 {
        return Err(a.err("the random seed must be positive"));
    }
    a.done()?;
    Ok(PairEdpd { cutoff, seed, coeff: TypePairs::default() })
}

/// A `pair_coeff` line of pair edpd.
fn parse_coeff(p: &mut PairEdpd, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
    let mut a = Args::new(cmd);
    let (ti, tj) = (a.types(ntypes)?, a.types(ntypes)?);
    let mut c = EdpdCoeff {
        a0: a.f64("A0")?,
        gamma: a.non_negative("gamma")?,
        power: a.f64("the power of the dissipative weight")?,
        rc: a.positive("the cutoff")?,
        kappa: a.non_negative("kappa")?,
        power_t: a.f64("the power of the heat weight")?,
        rc_t: a.positive("the heat cutoff")?,
        power_poly: None,
        kappa_poly: None,
    };
    while let Some(k) = a.peek() {
        a.word("power or kappa")?;
        let mut poly = [0.0; 4];
        for x in &mut poly {
            *x = a.f64(&format!("four coefficients after '{k}'"))?;
        }
        match k {
            "power" => c.power_poly = Some(poly),
            "kappa" => c.kappa_poly = Some(poly),
            _ => return Err(a.err(format!("unknown keyword '{k}'; known: power, kappa"))),
        }
    }
    for i in ti {
        for j in tj.clone() {
            p.coeff.put(ntypes, i.min(j), i.max(j), c.clone());
        }
    }
    Ok(())
}

impl PairEdpd {
    /// The coefficients of every type pair; Err names the first pair without any.
    pub fn table(&self) -> Result<Vec<EdpdCoeff>, String> {
        if self.coeff.ntypes() == 0 {
            return Err("pair edpd has no coefficients (pair_coeff)".into());
        }
        self.coeff.complete(self.coeff.ntypes()).map_err(|(i, j)| format!("pair edpd: no coefficients for types {i} {j} (pair_coeff)"))
    }
}

/// `pair_style edpd ...`.
pub fn parse_style(_name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError> {
    parse(a).map(|p| Box::new(p) as Box<dyn Pair>)
}

impl Pair for PairEdpd {
    fn name(&self) -> &str {
        "edpd"
    }

    fn coeff(&mut self, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
        parse_coeff(self, cmd, ntypes)
    }

    fn accepts(&self, fix: &FixStyle) -> bool {
        matches!(fix, FixStyle::MvvEdpd { .. } | FixStyle::EdpdSource { .. })
    }

    fn fixes(&self) -> &'static str {
        "mvv/edpd, edpd/source"
    }

    fn keep_coefficients(&mut self, old: &dyn Pair) -> bool {
        let Some(old) = old.as_any().downcast_ref::<Self>() else { return false };
        self.coeff = old.coeff.clone();
        let cutoff = self.cutoff;
        self.coeff.for_each_set(|c| c.rc = cutoff);
        true
    }

    /// pair edpd, fix mvv/edpd and any fix edpd/source.
    fn build(&self, run: &RunInputs) -> Result<Box<dyn Physics>, String> {
        let coeff = TypeTable::new(self.coeff.ntypes(), self.table()?).ok_or("pair edpd has no coefficients (pair_coeff)")?;
        let lambda = run.one("mvv/edpd", |s| if let FixStyle::MvvEdpd { lambda } = s { Some(*lambda) } else { None })?;
        let sources = run.fixes.iter().filter_map(|f| match &f.style {
            FixStyle::EdpdSource { shape, value, mask } => {
                let shape = match shape.clone() {
                    SourceSpec::Sphere { centre, radius } => SourceShape::Sphere { centre, radius },
                    SourceSpec::Cuboid { centre, edges } => SourceShape::Cuboid { centre, edges },
                    SourceSpec::Region(r) => SourceShape::Region(std::sync::Arc::new(move |x| r.contains(x))),
                };
                Some(HeatSource { mask: *mask, shape, value: *value })
            }
            _ => None,
        });
        let sources = sources.collect();
        let (_, lambda) = lambda.ok_or("pair edpd integrates with fix mvv/edpd")?;
        Ok(Box::new(Edpd { coeff, seed: self.seed, kb: run.kb, lambda, sources, settings: run.settings() }))
    }
}
