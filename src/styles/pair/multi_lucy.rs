//! LAMMPS DPD-REACT's `pair_style multi/lucy STYLE N` (STYLE lookup or linear) and
//! `pair_coeff I J FILE KEYWORD [CUTOFF]` (src/DPD-REACT/pair_multi_lucy.cpp): the
//! many-body force of a tabulated pressure-density relation. The pair_coeff lines read
//! their sections as `pair_style table` does ([`super::table::parse_coeff`]), the density
//! column indexed in rho^2; the force law is in `gendpde_integrators::models::classic`.

use super::table::TablePair;
use super::Pair;
use crate::base::args::Args;
use gendpde_io::ScriptError;
use gendpde_potentials::pair_table::TableStyle;

/// The words after `pair_style multi/lucy`.
pub fn parse_style(_name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError> {
    let style = match a.word("the table style (lookup or linear)")? {
        "lookup" => TableStyle::Lookup,
        "linear" => TableStyle::Linear,
        other => return Err(a.err(format!("unknown table style '{other}': pair multi/lucy has lookup and linear"))),
    };
    let n = a.u64("the number of table points N")?;
    if !(2..=super::table::MAX_POINTS).contains(&n) {
        return Err(a.err(format!("illegal number of pair table entries: {n} (2 to {})", super::table::MAX_POINTS)));
    }
    a.done()?;
    Ok(Box::new(TablePair { style, n: n as usize, tables: None, multi_lucy: true }))
}
