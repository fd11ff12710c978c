//! `write_coeff FILE`: the pair coefficients as `pair_coeff` lines, in the format of
//! LAMMPS's write_coeff.cpp (its pair style's data-file lines, numbers as `%g`).

use crate::base::args::Args;
use crate::model::sim::Sim;
use gendpde_io::ScriptError;

/// The version LAMMPS writes in the first line (that of the reference LAMMPS).
const VERSION: &str = "22 Jul 2025";

/// `write_coeff FILE`: a style with LAMMPS's `PairIJ Coeffs` data lines (pair dpd) writes
/// them; the others, which LAMMPS writes nothing for, leave the header line alone.
pub fn write_coeff(sim: &Sim, a: &mut Args) -> Result<(), ScriptError> {
    let file = a.word("a file name")?;
    a.done()?;
    if sim.system.is_none() {
        return Err(a.err("write_coeff command before simulation box is defined"));
    }
    let mut text = format!("# LAMMPS coeff file via write_coeff, version {VERSION}\n");
    if let Some(pair) = &sim.pair {
        if let Some(section) = pair.data_section(sim.ntypes, true).map_err(|e| a.err(e))? {
            text += &format!("# pair_style {}\n", pair.name());
            for row in &section.rows {
                let words: Vec<String> = row.iter().map(|w| w.parse::<f64>().map_or_else(|_| w.clone(), |x| gendpde_io::format_g(x, 6))).collect();
                text += &format!("pair_coeff {}\n", words.join(" "));
            }
            text += "\n";
        }
    }
    if sim.rank() == 0 {
        std::fs::write(file, text).map_err(|e| a.err(format!("Cannot open coeff file {file}: {e}")))?;
    }
    Ok(())
}
