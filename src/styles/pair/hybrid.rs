//! `pair_style hybrid/overlay S1 args S2 args ...` with `pair_coeff I J STYLE args`
//! (LAMMPS's pair_hybrid_overlay): the forces, energies and virials of the sub-styles
//! add up on every type pair each one is given. gendpde overlays `table` and one of
//! LAMMPS's pairwise DPD styles (dpd, dpd/ext, dpd/tstat, dpd/ext/tstat, dpd/fdt, ...); many-body DPD keeps
//! its own `hybrid/overlay mdpd/rhosum mdpd` line ([`super::pairwise`]), and GenDPDE
//! does not combine. `pair_style hybrid` (one sub-style per type pair) is refused.

use super::pairwise::{self, Pairwise};
use super::table::{self, TablePair};
use super::{Pair, RunInputs};
use crate::base::args::Args;
use crate::styles::fix::FixStyle;
use gendpde_integrators::Physics;
use gendpde_io::{Command, ScriptError};

/// The sub-styles of a hybrid/overlay line.
#[derive(Clone, Debug, PartialEq)]
pub struct Overlay {
    pub table: Option<TablePair>,
    /// The pairwise DPD sub-style and its name.
    pub pairwise: Option<(String, Pairwise)>,
}

/// Words of a table sub-style that are not numbers (every other such word starts a
/// sub-style, as LAMMPS splits a hybrid line at the style names).
const TABLE_WORDS: [&str; 11] = ["linear", "spline", "lookup", "bitmap", "ewald", "pppm", "msm", "dispersion", "tip4p", "rlinear", "rsquared"];

/// Whether a `hybrid/overlay` line is many-body DPD's (`mdpd/rhosum mdpd ...`).
fn is_mdpd(a: &Args) -> bool {
    a.peek() == Some("mdpd/rhosum")
}

/// The words after `pair_style hybrid/overlay` (`name` is `hybrid` or `hybrid/overlay`).
fn parse(name: &str, a: &mut Args) -> Result<Overlay, ScriptError> {
    if name == "hybrid" {
        return Err(a.err("pair_style hybrid (one sub-style per type pair) is not supported: use hybrid/overlay"));
    }
    let cmd = a.command();
    let mut groups: Vec<Vec<String>> = Vec::new();
    while a.remaining() > 0 {
        let w = a.word("a sub-style")?;
        match groups.last_mut() {
            Some(g) if w.parse::<f64>().is_ok() || TABLE_WORDS.contains(&w) => g.push(w.to_string()),
            _ => groups.push(vec![w.to_string()]),
        }
    }
    if groups.is_empty() {
        return Err(a.err("expected sub-styles after hybrid/overlay"));
    }
    let mut o = Overlay { table: None, pairwise: None };
    for g in groups {
        let sub = Command { name: cmd.name.clone(), args: g, loc: cmd.loc.clone() };
        let mut s = Args::new(&sub);
        let style = s.word("a sub-style")?;
        match style {
            "table" if o.table.is_none() => o.table = Some(table::parse(&mut s)?),
            "table" => return Err(a.err("hybrid/overlay takes one table sub-style")),
            "gendpde" => return Err(a.err("pair gendpde is many-body (densities and EOS): it cannot be combined in hybrid/overlay")),
            "mdpd" | "mdpd/rhosum" => {
                return Err(a.err("many-body DPD combines only as 'hybrid/overlay mdpd/rhosum mdpd T CUTOFF SEED', without other sub-styles"))
            }
            "hybrid" | "hybrid/overlay" => return Err(a.err("a hybrid style cannot be a sub-style")),
            other if o.pairwise.is_none() => o.pairwise = Some((other.to_string(), pairwise::parse(other, &mut s)?)),
            other => return Err(a.err(format!("'{other}': hybrid/overlay takes one pairwise DPD sub-style (besides table)"))),
        }
    }
    Ok(o)
}

/// `pair_coeff I J STYLE args` for the sub-style named STYLE.
fn parse_coeff(o: &mut Overlay, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
    let mut a = Args::new(cmd);
    let types = (a.types(ntypes)?, a.types(ntypes)?);
    let style = a.word("the sub-style of the pair coefficients")?;
    match (style, &mut o.table, &mut o.pairwise) {
        ("table", Some(_), _) if a.peek().is_some_and(|w| w.parse::<u32>().is_ok()) => Err(a.err("sub-style numbers (pair_coeff I J table K ...) are not supported: one table sub-style")),
        ("table", Some(t), _) => table::parse_coeff(t, &mut a, types, ntypes),
        (name, _, Some((own, p))) if name == own => {
            // the sub-style's own pair_coeff line: I J and the words after the name
            let mut args = cmd.args.clone();
            args.remove(2);
            pairwise::parse_coeff(p, &Command { name: cmd.name.clone(), args, loc: cmd.loc.clone() }, ntypes)
        }
        ("none", ..) => Err(a.err("pair_coeff I J none is not supported")),
        (other, ..) => Err(a.err(format!("'{other}' is not a sub-style of this pair_style hybrid/overlay"))),
    }
}

/// `pair_style hybrid/overlay ...`: many-body DPD's `mdpd/rhosum mdpd` line is a pairwise
/// style of its own; plain `hybrid` is refused.
pub fn parse_style(name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError> {
    if name == "hybrid/overlay" && is_mdpd(a) {
        return pairwise::parse_style(name, a);
    }
    parse(name, a).map(|o| Box::new(o) as Box<dyn Pair>)
}

impl Pair for Overlay {
    fn name(&self) -> &str {
        "hybrid/overlay"
    }

    fn coeff(&mut self, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
        parse_coeff(self, cmd, ntypes)
    }

    /// The pairwise sub-style's fixes, else those of the table alone.
    fn accepts(&self, fix: &FixStyle) -> bool {
        match (&self.pairwise, &self.table) {
            (Some((_, p)), _) => p.accepts(fix),
            (None, Some(t)) => t.accepts(fix),
            (None, None) => false,
        }
    }

    fn fixes(&self) -> &'static str {
        match (&self.pairwise, &self.table) {
            (Some((_, p)), _) => p.fixes(),
            (None, Some(t)) => t.fixes(),
            (None, None) => "none",
        }
    }

    fn build(&self, run: &RunInputs) -> Result<Box<dyn Physics>, String> {
        match (&self.table, &self.pairwise) {
            (Some(t), Some((_, p))) => table::overlaid(t, p, run),
            (Some(t), None) => t.build(run),
            (None, Some((_, p))) => p.build(run),
            (None, None) => Err("pair_style hybrid/overlay has no sub-styles".into()),
        }
    }
}
