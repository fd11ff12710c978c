//! The fixes that are outputs: at their steps they sample values, write files or the
//! screen, and publish global values read as `f_ID` ([`FixValues`]). They run before
//! thermo and the dumps of the same step (LAMMPS's end_of_step precedes its output), so
//! thermo reads the block just completed.
//!
//! Adding a style: a file with its type implementing [`OutputFix`] and one line in
//! [`OUTPUT_FIXES`].

pub mod ave_atom;
pub mod ave_chunk;
pub mod ave_histo;
pub mod ave_time;
pub mod blocks;
pub mod print;
pub mod vector;

use crate::base::args::Args;
use crate::model::sim::{FixValues, Sim};
use crate::output::schedule::RunOutput;
use gendpde_io::{ScriptError, Variables};

/// An output fix.
pub trait OutputFix: RunOutput {
    fn id(&self) -> &str;
    /// LAMMPS's style name.
    fn style(&self) -> &'static str;
    /// The global values of its last block (None: it has none).
    fn published(&self) -> Option<&FixValues> {
        None
    }
    /// IDs of the compute rdf it reads (the run lays cells that reach their cutoff).
    fn rdfs(&self) -> Vec<&str> {
        Vec::new()
    }
}

/// What an output fix's parser reads besides its words.
pub struct OutputFixContext<'a> {
    pub id: String,
    pub group: &'a str,
    pub sim: &'a Sim,
    pub vars: &'a Variables,
    /// The current step.
    pub step: u64,
}

/// Parses the words after `fix ID GROUP STYLE`.
type ParseOutputFix = fn(a: &mut Args, c: &OutputFixContext) -> Result<Box<dyn OutputFix>, ScriptError>;

/// Every output fix style, with its parser.
pub const OUTPUT_FIXES: &[(&str, ParseOutputFix)] = &[
    ("ave/time", |a, c| Ok(Box::new(ave_time::AveTime::parse(a, c)?))),
    ("ave/atom", |a, c| Ok(Box::new(ave_atom::AveAtom::parse(a, c)?))),
    ("ave/chunk", |a, c| Ok(Box::new(ave_chunk::AveChunk::parse(a, c)?))),
    ("ave/histo", |a, c| Ok(Box::new(ave_histo::AveHisto::parse(a, c)?))),
    ("print", |a, c| Ok(Box::new(print::Print::parse(a, c)?))),
    ("vector", |a, c| Ok(Box::new(vector::Vector::parse(a, c)?))),
];

/// Whether `style` is an output fix.
pub fn is_output_fix(style: &str) -> bool {
    OUTPUT_FIXES.iter().any(|(n, _)| *n == style)
}

/// Parses `fix ID GROUP STYLE args...` of an output fix style (`c`'s ID and group read).
pub fn parse(style: &str, a: &mut Args, c: &OutputFixContext) -> Result<Box<dyn OutputFix>, ScriptError> {
    let (_, parse) = OUTPUT_FIXES.iter().find(|(n, _)| *n == style).expect("an output fix style");
    parse(a, c)
}

#[cfg(test)]
mod tests {
    /// The list of known fix styles names every output fix.
    #[test]
    fn the_known_styles_list_every_output_fix() {
        let mut names: Vec<&str> = super::OUTPUT_FIXES.iter().map(|(n, _)| *n).collect();
        names.sort_unstable();
        assert_eq!(names, crate::styles::fix::AVERAGING);
    }
}
