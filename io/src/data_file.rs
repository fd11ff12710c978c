//! Reading and writing LAMMPS data files (`read_data` / `write_data`).
//!
//! Only what gendpde needs is supported: an orthogonal box, atom types with
//! optional masses, pair coefficients (`Pair Coeffs`, `PairIJ Coeffs`), atoms
//! in `atom_style atomic`, `dpd` or `mdpd` and optional velocities. Anything
//! that would need more (bonds, triclinic boxes, bond coefficients, ...) is
//! reported as an error rather than silently dropped.
//!
//! Layout, as in LAMMPS: the first line is a title and is skipped; header
//! lines (`N atoms`, `N atom types`, `lo hi xlo xhi`, ...) follow in any
//! order until the first section keyword (`Masses`, `Pair Coeffs`,
//! `PairIJ Coeffs`, `Atoms`, `Velocities`).
//! A section keyword is followed by exactly as many data lines as the header
//! says. `#` starts a comment anywhere; blank and comment-only lines are
//! ignored. `Atoms # dpd` names the atom style of the section's lines.
//!
//! Errors are [`ScriptError`]s located in the data file, displayed as
//! `data.dpde:17: Atoms: expected 6 columns (id type dpdTheta x y z), got 5`.

use std::ffi::OsString;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::command::{Location, ScriptError};

mod parse;
mod write;

use self::parse::Parser;
use self::write::render;

/// Most atom types a data file may declare; the masses table is allocated
/// up front, so an absurd count in a corrupt header must not reach it.
pub const MAX_ATOM_TYPES: usize = 1_000_000;

/// The per-atom column layout of the `Atoms` section.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AtomStyle {
    /// `id type x y z [ix iy iz]`.
    Atomic,
    /// `id type dpdTheta x y z [ix iy iz]` (LAMMPS `atom_style dpd`).
    Dpd,
    /// `id type rho x y z [ix iy iz]` (LAMMPS atom_style mdpd; rho is recomputed, so
    /// the column is read and checked but not kept).
    Mdpd,
    /// `id type edpd_temp edpd_cv x y z [ix iy iz]` (LAMMPS atom_style edpd).
    Edpd,
    /// `id type rho esph cv x y z [ix iy iz]` (LAMMPS atom_style sph; esph and cv are
    /// read and checked but not kept: no gendpde style uses them).
    Sph,
}

impl AtomStyle {
    /// The LAMMPS name, as used in `atom_style` and the `Atoms # ...` hint.
    pub fn name(self) -> &'static str {
        match self {
            AtomStyle::Atomic => "atomic",
            AtomStyle::Dpd => "dpd",
            AtomStyle::Mdpd => "mdpd",
            AtomStyle::Edpd => "edpd",
            AtomStyle::Sph => "sph",
        }
    }

    /// The style with LAMMPS name `name`, if supported.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "atomic" => Some(AtomStyle::Atomic),
            "dpd" => Some(AtomStyle::Dpd),
            "mdpd" => Some(AtomStyle::Mdpd),
            "edpd" => Some(AtomStyle::Edpd),
            "sph" => Some(AtomStyle::Sph),
            _ => None,
        }
    }

    /// Column names of an `Atoms` line without image flags.
    fn columns(self) -> &'static [&'static str] {
        match self {
            AtomStyle::Atomic => &["id", "type", "x", "y", "z"],
            AtomStyle::Dpd => &["id", "type", "dpdTheta", "x", "y", "z"],
            AtomStyle::Mdpd => &["id", "type", "rho", "x", "y", "z"],
            AtomStyle::Edpd => &["id", "type", "edpd_temp", "edpd_cv", "x", "y", "z"],
            AtomStyle::Sph => &["id", "type", "rho", "esph", "cv", "x", "y", "z"],
        }
    }
}

/// One line of the `Atoms` section.
#[derive(Clone, Debug, PartialEq)]
pub struct DataAtom {
    /// Atom id (LAMMPS tag), at least 1.
    pub tag: u64,
    /// Atom type, 1-based.
    pub kind: u32,
    /// Internal temperature `dpdTheta` (`Some` exactly for [`AtomStyle::Dpd`]).
    pub theta: Option<f64>,
    /// eDPD temperature and heat capacity (`Some` exactly for [`AtomStyle::Edpd`]).
    pub edpd: Option<[f64; 2]>,
    /// SPH density (`Some` exactly for [`AtomStyle::Sph`]).
    pub sph_rho: Option<f64>,
    /// Position.
    pub r: [f64; 3],
    /// Image flags (zero when the line has none).
    pub image: [i32; 3],
}

/// A `Pair Coeffs` (one line `I args` per type, meaning `pair_coeff I I args`) or
/// `PairIJ Coeffs` section (one line `I J args` per pair I <= J, meaning
/// `pair_coeff I J args`). The types are checked here, the values by the pair style.
#[derive(Clone, Debug)]
pub struct PairCoeffs {
    /// `PairIJ Coeffs` rather than `Pair Coeffs`.
    pub ij: bool,
    /// The pair style named after `#` on the section line, if any.
    pub style: Option<String>,
    /// The words of each line, types first.
    pub rows: Vec<Vec<String>>,
    /// The line of each row in the file (0 for rows not read from a file).
    pub lines: Vec<usize>,
}

impl PartialEq for PairCoeffs {
    /// Equal sections hold the same rows, wherever they were read.
    fn eq(&self, other: &Self) -> bool {
        (self.ij, &self.style, &self.rows) == (other.ij, &other.style, &other.rows)
    }
}

/// The contents of a data file.
#[derive(Clone, Debug, PartialEq)]
pub struct DataFile {
    /// The first line, trimmed.
    pub title: String,
    /// Number of atoms; equals `atoms.len()` in a file read by [`read_data`].
    pub natoms: usize,
    /// Number of atom types.
    pub ntypes: usize,
    /// Lower box corner (LAMMPS default -0.5 when the header omits it).
    pub lo: [f64; 3],
    /// Upper box corner (LAMMPS default 0.5 when the header omits it).
    pub hi: [f64; 3],
    /// Mass of each type, index `type - 1`; all `None` without `Masses`.
    pub masses: Vec<Option<f64>>,
    /// The pair coefficients, if the file has a `Pair Coeffs` or `PairIJ Coeffs` section.
    pub pair_coeffs: Option<PairCoeffs>,
    /// The atoms in file order.
    pub atoms: Vec<DataAtom>,
    /// `(id, velocity)` in file order, if the file has a `Velocities` section.
    pub velocities: Option<Vec<(u64, [f64; 3])>>,
}

/// Reads a data file; bytes that are not UTF-8 become U+FFFD.
pub fn read_data(path: &Path, style: AtomStyle) -> Result<DataFile, ScriptError> {
    let bytes = std::fs::read(path).map_err(|e| {
        ScriptError::new(format!("cannot open data file '{}': {e}", path.display()))
    })?;
    parse_data(
        &path.to_string_lossy(),
        &String::from_utf8_lossy(&bytes),
        style,
    )
}

/// Parses the text of a data file, reporting errors as in file `name`.
pub fn parse_data(name: &str, text: &str, style: AtomStyle) -> Result<DataFile, ScriptError> {
    Parser::new(name, text, style).parse()
}

/// Writes `data` as a LAMMPS data file that [`read_data`] with the same
/// `style` reads back identically (up to the title being trimmed). The file
/// is written to `path` with `.tmp` appended and then renamed over `path`,
/// so an interrupted write never leaves a partial file at `path`.
///
/// Fails with [`std::io::ErrorKind::InvalidInput`] if `data` could not be
/// read back: counts disagreeing with the lists, masses given for only some
/// types, missing `dpdTheta` in the dpd style or non-finite numbers.
pub fn write_data(path: &Path, data: &DataFile, style: AtomStyle) -> std::io::Result<()> {
    let text = render(data, style)
        .map_err(|msg| std::io::Error::new(std::io::ErrorKind::InvalidInput, msg))?;
    let mut tmp = OsString::from(path.as_os_str());
    tmp.push(".tmp");
    let tmp = PathBuf::from(tmp);
    let result = (|| {
        let mut file = std::fs::File::create(&tmp)?;
        file.write_all(text.as_bytes())?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests;
