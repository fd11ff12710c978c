//! `pair_style sdpd/taitwater/isothermal T MU [SEED]` with `pair_coeff I J RHO0 C0 H`
//! (LAMMPS DPD-SMOOTH; the force law is in `gendpde_integrators::models::sdpd::taitwater`).

use super::type_pairs::TypePairs;
use super::{Pair, RunInputs};
use crate::base::args::Args;
use crate::styles::fix::FixStyle;
use gendpde_integrators::{Physics, SdpdTaitwater, TypeTable};
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::{Lucy, Tait};

/// Tait water of one type: reference density and sound speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TaitCoeff {
    pub rho0: f64,
    pub c0: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct PairTaitwater {
    pub temperature: f64,
    pub viscosity: f64,
    /// The random seed (0 when omitted).
    pub seed: u64,
    /// rho0 and c0 per type (index type - 1), from the last pair_coeff whose I range
    /// held the type.
    pub water: Vec<Option<TaitCoeff>>,
    /// The kernel support h per type pair, None while unset.
    pub cut: TypePairs<f64>,
}

/// The words after `pair_style sdpd/taitwater/isothermal`.
fn parse(a: &mut Args) -> Result<PairTaitwater, ScriptError> {
    let temperature = a.f64("the temperature")?;
    let viscosity = a.f64("the dynamic viscosity")?;
    if temperature <= 0.0 {
        return Err(a.err("Temperature must be positive"));
    }
    if viscosity <= 0.0 {
        return Err(a.err("Viscosity must be positive"));
    }
    let seed = if a.remaining() > 0 { a.u64("the random seed")? } else { 0 };
    a.done()?;
    Ok(PairTaitwater { temperature, viscosity, seed, water: Vec::new(), cut: TypePairs::default() })
}

/// A `pair_coeff I J RHO0 C0 H` line: as LAMMPS, only pairs with J >= I are set, and
/// rho0 and c0 go to every type of the range I.
fn parse_coeff(p: &mut PairTaitwater, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
    let mut a = Args::new(cmd);
    let (ti, tj) = (a.types(ntypes)?, a.types(ntypes)?);
    let water = TaitCoeff { rho0: a.positive("the reference density rho0")?, c0: a.positive("the sound speed")? };
    let h = a.positive("the kernel cutoff h")?;
    a.done()?;
    if p.cut.ntypes() != ntypes {
        (p.water, p.cut) = (vec![None; ntypes], TypePairs::default());
    }
    let mut count = 0;
    for i in ti {
        p.water[i - 1] = Some(water);
        for j in tj.clone().filter(|&j| j >= i) {
            p.cut.put(ntypes, i, j, h);
            count += 1;
        }
    }
    if count == 0 {
        return Err(a.err("Incorrect args for pair coefficients (no type pair with J >= I)"));
    }
    Ok(())
}

impl PairTaitwater {
    /// Tait water per type and the kernel support per type pair; Err names the first
    /// type pair without coefficients.
    pub fn table(&self) -> Result<(Vec<TaitCoeff>, Vec<f64>), String> {
        let n = self.cut.ntypes();
        let unset = |k: usize| format!("Not all pair sdpd/taitwater/isothermal coeffs are set: no pair_coeff for types {} {}", k / n + 1, k % n + 1);
        if n == 0 {
            return Err("pair sdpd/taitwater/isothermal has no coefficients (pair_coeff)".into());
        }
        let cut = self.cut.complete(n).map_err(|(i, j)| unset((i - 1) * n + j - 1))?;
        let water = (0..n).map(|i| self.water[i].ok_or_else(|| unset(i * n + i))).collect::<Result<Vec<_>, _>>()?;
        Ok((water, cut))
    }
}

/// `pair_style sdpd/taitwater/isothermal ...`.
pub fn parse_style(_name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError> {
    parse(a).map(|p| Box::new(p) as Box<dyn Pair>)
}

impl Pair for PairTaitwater {
    fn name(&self) -> &str {
        "sdpd/taitwater/isothermal"
    }

    fn coeff(&mut self, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
        parse_coeff(self, cmd, ntypes)
    }

    fn accepts(&self, fix: &FixStyle) -> bool {
        *fix == FixStyle::Sph
    }

    fn fixes(&self) -> &'static str {
        "sph"
    }

    /// LAMMPS's isothermal Tait-water SDPD, integrated by `fix sph`.
    fn build(&self, run: &RunInputs) -> Result<Box<dyn Physics>, String> {
        let (water, cut) = self.table()?;
        if run.one("sph", |s| (*s == FixStyle::Sph).then_some(()))?.is_none() {
            return Err("pair sdpd/taitwater/isothermal needs fix sph".into());
        }
        Ok(Box::new(SdpdTaitwater {
            eos: water.iter().map(|w| Tait::new(w.rho0, w.c0)).collect(),
            kernel: TypeTable::new(self.cut.ntypes(), cut.iter().map(|&h| Lucy::new(h)).collect()).ok_or("pair sdpd/taitwater/isothermal has no coefficients (pair_coeff)")?,
            kbt: run.kb * self.temperature,
            viscosity: self.viscosity,
            seed: self.seed,
            mvv2e: run.mvv2e,
            settings: run.settings(),
        }))
    }
}
