//! LAMMPS's `pair_style table STYLE N` and `pair_coeff I J FILE KEYWORD [CUTOFF]`
//! (src/pair_table.cpp): each pair_coeff reads one section of a table file and
//! re-tabulates it on N points in r^2 at once, so a bad file or cutoff is refused at
//! its pair_coeff, as in LAMMPS. `pair_style multi/lucy` ([`super::multi_lucy`]) reads
//! its pressure-density tables through the same pair_coeff.

use super::pairwise::Pairwise;
use super::{Pair, RunInputs};
use crate::base::args::Args;
use crate::styles::fix::FixStyle;
use gendpde_integrators::{ClassicDpd, Integration, PairForce, PairTables, Physics};
use gendpde_io::{Command, ScriptError};
use gendpde_potentials::pair_table::{FileTable, PairTable, TableStyle};

type Types = std::ops::RangeInclusive<usize>;

/// The most points a table may have (5 arrays of 8 bytes per point per table).
pub(super) const MAX_POINTS: u64 = 1 << 24;

/// `pair_style table` and the tables its pair_coeff lines read.
#[derive(Clone, Debug, PartialEq)]
pub struct TablePair {
    pub style: TableStyle,
    /// N, the points of the re-tabulation.
    pub n: usize,
    /// The tables of the type pairs (allocated at the first pair_coeff, like LAMMPS).
    pub tables: Option<PairTables>,
    /// `pair_style multi/lucy`: the tables give pressure against density.
    pub multi_lucy: bool,
}


/// The words after `pair_style table` (or after `table` in a hybrid line).
pub fn parse(a: &mut Args) -> Result<TablePair, ScriptError> {
    let style = match a.word("the table style (lookup, linear or spline)")? {
        "lookup" => TableStyle::Lookup,
        "linear" => TableStyle::Linear,
        "spline" => TableStyle::Spline,
        "bitmap" => return Err(a.err("table style bitmap is not supported: use lookup, linear or spline")),
        other => return Err(a.err(format!("unknown table style '{other}': expected lookup, linear or spline"))),
    };
    let n = a.u64("the number of table points N")?;
    if !(2..=MAX_POINTS).contains(&n) {
        return Err(a.err(format!("illegal number of pair table entries: {n} (2 to {MAX_POINTS})")));
    }
    if let Some(w) = a.peek() {
        return match w {
            "ewald" | "pppm" | "msm" | "dispersion" | "tip4p" => Err(a.err(format!("keyword {w}: long-range solvers are not supported"))),
            "rlinear" | "rsquared" => Err(a.err(format!("keyword {w} is not supported (tables are spaced in r^2, LAMMPS's default)"))),
            _ => Err(a.err(format!("unexpected '{w}' after N"))),
        };
    }
    Ok(TablePair { style, n: n as usize, tables: None, multi_lucy: false })
}

/// `pair_coeff I J FILE KEYWORD [CUTOFF]` (`a` positioned after I J): reads the section
/// and assigns its table to the type pairs I <= J of the ranges, and J I.
pub fn parse_coeff(t: &mut TablePair, a: &mut Args, types: (Types, Types), ntypes: usize) -> Result<(), ScriptError> {
    let file = a.word("the table file")?;
    let keyword = a.word("the section keyword")?;
    let cut = if a.remaining() > 0 { Some(a.positive("the cutoff")?) } else { None };
    a.done()?;
    let text = std::fs::read_to_string(file).map_err(|e| a.err(format!("cannot open table file {file}: {e}")))?;
    let section = FileTable::parse_section(&text, keyword, if t.multi_lucy { "FP" } else { "FPRIME" }).map_err(|e| match e.line {
        0 => a.err(format!("{file}: {}", e.why)),
        line => a.err(format!("{file}:{line}: {}", e.why)),
    })?;
    // LAMMPS's default cutoff: rhi of R/RSQ, else the last r (multi/lucy: a density)
    let cut = cut.unwrap_or(section.bounds().1);
    let table = if t.multi_lucy { PairTable::density(t.style, t.n, &section, cut) } else { PairTable::new(t.style, t.n, &section, cut) };
    let table = table.map_err(|e| a.err(format!("{file} {keyword}: {e}")))?;
    let tables = t.tables.get_or_insert_with(|| PairTables { tables: Vec::new(), index: vec![None; ntypes * ntypes], ntypes });
    // numeric I > J are swapped (LAMMPS's Input::pair_coeff); else the pairs I <= J count
    let (ti, tj) = match types {
        (i, j) if i.start() == i.end() && j.start() == j.end() && i.start() > j.start() => (j, i),
        other => other,
    };
    let m = tables.tables.len();
    let mut count = 0;
    for i in ti {
        for j in i.max(*tj.start())..=*tj.end() {
            tables.index[(i - 1) * ntypes + j - 1] = Some(m);
            tables.index[(j - 1) * ntypes + i - 1] = Some(m);
            count += 1;
        }
    }
    if count == 0 {
        return Err(a.err("the type ranges hold no pair I <= J"));
    }
    tables.tables.push(table);
    Ok(())
}

/// The tables of a run: every type pair must have one unless `partial` (another
/// sub-style of hybrid/overlay covers the rest).
pub fn tables_for_run(t: &TablePair, partial: bool) -> Result<PairTables, String> {
    let tables = t.tables.clone().ok_or("pair table has no coefficients (pair_coeff I J FILE KEYWORD)")?;
    if !partial {
        if let Some(k) = tables.index.iter().position(Option::is_none) {
            let (i, j) = (k / tables.ntypes + 1, k % tables.ntypes + 1);
            return Err(format!("all pair coeffs are not set: types {i} {j} have no table"));
        }
    }
    Ok(tables)
}

/// `pair_style table STYLE N`.
pub fn parse_style(_name: &str, a: &mut Args) -> Result<Box<dyn Pair>, ScriptError> {
    parse(a).map(|t| Box::new(t) as Box<dyn Pair>)
}

impl Pair for TablePair {
    fn name(&self) -> &str {
        if self.multi_lucy { "multi/lucy" } else { "table" }
    }

    fn coeff(&mut self, cmd: &Command, ntypes: usize) -> Result<(), ScriptError> {
        let mut a = Args::new(cmd);
        let types = (a.types(ntypes)?, a.types(ntypes)?);
        parse_coeff(self, &mut a, types, ntypes)
    }

    fn accepts(&self, fix: &FixStyle) -> bool {
        matches!(fix, FixStyle::Nve | FixStyle::Eos(_))
    }

    fn fixes(&self) -> &'static str {
        if self.multi_lucy { "nve" } else { "nve; overlay dpd/fdt for fix shardlow" }
    }

    /// `pair_style table` or `multi/lucy` alone, integrated by fix nve.
    fn build(&self, run: &RunInputs) -> Result<Box<dyn Physics>, String> {
        let tables = tables_for_run(self, false)?;
        if !run.has(|s| *s == FixStyle::Nve) {
            return Err("no integrator: add fix nve".into());
        }
        let (force, tables) = if self.multi_lucy { (PairForce::MultiLucy(tables), None) } else { (PairForce::Off, Some(tables)) };
        let settings = run.settings();
        Ok(Box::new(ClassicDpd { force, tables, shardlow: None, integration: Integration::Nve, cv: None, energy: false, barostat: None, kb: run.kb, seed: 1, settings }))
    }
}

/// A table overlaid on the pairwise style `p`, which sets the fixes it works with.
pub fn overlaid(t: &TablePair, p: &Pairwise, run: &RunInputs) -> Result<Box<dyn Physics>, String> {
    let tables = tables_for_run(t, true)?;
    Ok(Box::new(ClassicDpd { tables: Some(tables), ..p.dynamics(run)? }))
}
