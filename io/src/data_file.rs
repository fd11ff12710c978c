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

use std::collections::HashMap;
use std::ffi::OsString;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::command::{Location, ScriptError};

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

/// The text of a data file, or why `data` cannot be written faithfully.
fn render(data: &DataFile, style: AtomStyle) -> Result<String, String> {
    if data.natoms != data.atoms.len() {
        return Err(format!(
            "natoms is {} but there are {} atoms",
            data.natoms,
            data.atoms.len()
        ));
    }
    if data.ntypes != data.masses.len() {
        return Err(format!(
            "ntypes is {} but there are {} mass entries",
            data.ntypes,
            data.masses.len()
        ));
    }
    let given = data.masses.iter().filter(|m| m.is_some()).count();
    if given != 0 && given != data.masses.len() {
        return Err(format!(
            "masses are set for only {given} of {} atom types",
            data.masses.len()
        ));
    }
    if let Some(v) = &data.velocities {
        if v.len() != data.natoms {
            return Err(format!("{} velocities for {} atoms", v.len(), data.natoms));
        }
    }
    let finite = |what: &str, x: f64| {
        if x.is_finite() {
            Ok(x)
        } else {
            Err(format!("{what} is not finite: {x}"))
        }
    };

    let mut out = String::new();
    let title = data.title.replace(['\n', '\r'], " ");
    // `write!` to a String cannot fail.
    let _ = writeln!(out, "{}\n", title.trim());
    let _ = writeln!(out, "{} atoms", data.natoms);
    let _ = writeln!(out, "{} atom types\n", data.ntypes);
    for (d, (lo_name, hi_name)) in [("xlo", "xhi"), ("ylo", "yhi"), ("zlo", "zhi")]
        .into_iter()
        .enumerate()
    {
        let lo = finite(lo_name, data.lo[d])?;
        let hi = finite(hi_name, data.hi[d])?;
        let _ = writeln!(out, "{lo:?} {hi:?} {lo_name} {hi_name}");
    }
    if given != 0 {
        out.push_str("\nMasses\n\n");
        for (i, m) in data.masses.iter().enumerate() {
            let m = finite("mass", m.unwrap_or(f64::NAN))?;
            let _ = writeln!(out, "{} {m:?}", i + 1);
        }
    }
    if let Some(p) = &data.pair_coeffs {
        let name = if p.ij { "PairIJ Coeffs" } else { "Pair Coeffs" };
        let rows = if p.ij { data.ntypes * (data.ntypes + 1) / 2 } else { data.ntypes };
        if p.rows.len() != rows {
            return Err(format!("{name} has {} lines for {} atom types (expected {rows})", p.rows.len(), data.ntypes));
        }
        match &p.style {
            Some(style) => {
                let _ = writeln!(out, "\n{name} # {style}\n");
            }
            None => {
                let _ = writeln!(out, "\n{name}\n");
            }
        }
        for row in &p.rows {
            let _ = writeln!(out, "{}", row.join(" "));
        }
    }
    let _ = writeln!(out, "\nAtoms # {}\n", style.name());
    for a in &data.atoms {
        let _ = write!(out, "{} {}", a.tag, a.kind);
        if style == AtomStyle::Dpd {
            let Some(theta) = a.theta else {
                return Err(format!("atom {} has no dpdTheta", a.tag));
            };
            let _ = write!(out, " {:?}", finite("dpdTheta", theta)?);
        }
        if style == AtomStyle::Mdpd {
            out.push_str(" 0.0");
        }
        if style == AtomStyle::Edpd {
            let Some([t, cv]) = a.edpd else {
                return Err(format!("atom {} has no edpd_temp and edpd_cv", a.tag));
            };
            let _ = write!(out, " {:?} {:?}", finite("edpd_temp", t)?, finite("edpd_cv", cv)?);
        }
        if style == AtomStyle::Sph {
            let Some(rho) = a.sph_rho else {
                return Err(format!("atom {} has no rho", a.tag));
            };
            let _ = write!(out, " {:?} 0.0 1.0", finite("rho", rho)?);
        }
        for x in a.r {
            let _ = write!(out, " {:?}", finite("position", x)?);
        }
        let [ix, iy, iz] = a.image;
        let _ = writeln!(out, " {ix} {iy} {iz}");
    }
    // Written even when empty, so that `Some(vec![])` reads back as itself.
    if let Some(velocities) = &data.velocities {
        out.push_str("\nVelocities\n\n");
        for (tag, v) in velocities {
            let _ = write!(out, "{tag}");
            for x in v {
                let _ = write!(out, " {:?}", finite("velocity", *x)?);
            }
            out.push('\n');
        }
    }
    Ok(out)
}

/// A line holding data: comment stripped and trimmed, never empty.
#[derive(Clone, Copy)]
struct Line<'a> {
    /// 1-based line number.
    num: usize,
    text: &'a str,
    /// Text after `#`, if any.
    comment: Option<&'a str>,
}

impl Line<'_> {
    /// Whether the line starts a section rather than holding numbers.
    fn is_keyword(&self) -> bool {
        self.text.chars().next().is_some_and(char::is_alphabetic)
    }

    /// The section keyword with whitespace runs collapsed (`Pair  Coeffs`).
    fn keyword(&self) -> String {
        self.text.split_whitespace().collect::<Vec<_>>().join(" ")
    }
}

/// What a header keyword means to gendpde.
#[derive(Clone, Copy, PartialEq)]
enum HeaderKind {
    Atoms,
    AtomTypes,
    /// Box bounds in dimension 0, 1 or 2.
    Bounds(usize),
    /// Triclinic box: unsupported.
    Triclinic,
    /// A count of things gendpde cannot read (bonds, ...): must be 0.
    MustBeZero,
    /// Irrelevant to gendpde (`bond types`, `extra ... per atom`).
    Ignored,
}

/// Header keywords and the number of values before them.
const HEADER_KEYWORDS: &[(&str, usize, HeaderKind)] = &[
    ("atoms", 1, HeaderKind::Atoms),
    ("atom types", 1, HeaderKind::AtomTypes),
    ("xlo xhi", 2, HeaderKind::Bounds(0)),
    ("ylo yhi", 2, HeaderKind::Bounds(1)),
    ("zlo zhi", 2, HeaderKind::Bounds(2)),
    ("xy xz yz", 3, HeaderKind::Triclinic),
    ("avec", 3, HeaderKind::Triclinic),
    ("bvec", 3, HeaderKind::Triclinic),
    ("cvec", 3, HeaderKind::Triclinic),
    ("abc origin", 3, HeaderKind::Triclinic),
    ("bonds", 1, HeaderKind::MustBeZero),
    ("angles", 1, HeaderKind::MustBeZero),
    ("dihedrals", 1, HeaderKind::MustBeZero),
    ("impropers", 1, HeaderKind::MustBeZero),
    ("ellipsoids", 1, HeaderKind::MustBeZero),
    ("lines", 1, HeaderKind::MustBeZero),
    ("triangles", 1, HeaderKind::MustBeZero),
    ("bodies", 1, HeaderKind::MustBeZero),
    ("bond types", 1, HeaderKind::Ignored),
    ("angle types", 1, HeaderKind::Ignored),
    ("dihedral types", 1, HeaderKind::Ignored),
    ("improper types", 1, HeaderKind::Ignored),
    ("extra bond per atom", 1, HeaderKind::Ignored),
    ("extra angle per atom", 1, HeaderKind::Ignored),
    ("extra dihedral per atom", 1, HeaderKind::Ignored),
    ("extra improper per atom", 1, HeaderKind::Ignored),
    ("extra special per atom", 1, HeaderKind::Ignored),
];

struct Parser<'a> {
    file: PathBuf,
    style: AtomStyle,
    title: String,
    /// Lines after the title that hold something besides a comment.
    lines: Vec<Line<'a>>,
    /// Index into `lines` of the next unread line.
    next: usize,
    /// Number of the file's last line, for errors at its end.
    last_line: usize,
}

impl<'a> Parser<'a> {
    fn new(name: &str, text: &'a str, style: AtomStyle) -> Self {
        let mut raw = text.lines();
        let title = raw.next().unwrap_or("").trim().to_string();
        let mut lines = Vec::new();
        let mut last_line = 1;
        for (i, line) in raw.enumerate() {
            let num = i + 2;
            last_line = num;
            let (text, comment) = match line.split_once('#') {
                Some((text, comment)) => (text, Some(comment)),
                None => (line, None),
            };
            let text = text.trim();
            if !text.is_empty() {
                lines.push(Line { num, text, comment });
            }
        }
        Parser {
            file: PathBuf::from(name),
            style,
            title,
            lines,
            next: 0,
            last_line,
        }
    }

    fn error(&self, line: usize, section: Option<&str>, msg: impl Into<String>) -> ScriptError {
        ScriptError {
            loc: Some(Location {
                file: self.file.clone(),
                line,
            }),
            command: section.map(str::to_string),
            message: msg.into(),
        }
    }

    fn parse(mut self) -> Result<DataFile, ScriptError> {
        let header = self.header()?;
        let mut data = DataFile {
            title: std::mem::take(&mut self.title),
            natoms: header.natoms,
            ntypes: header.ntypes,
            lo: header.lo,
            hi: header.hi,
            masses: vec![None; header.ntypes],
            pair_coeffs: None,
            atoms: Vec::new(),
            velocities: None,
        };
        let mut masses_at = None;
        let mut pair_at = None;
        let mut atoms_at = None;
        let mut velocities_at = None;
        // Atom id -> line number, filled by the Atoms section.
        let mut ids = HashMap::new();
        while let Some(kw) = self.lines.get(self.next).copied() {
            self.next += 1;
            let keyword = kw.keyword();
            let seen = match keyword.as_str() {
                "Masses" => &mut masses_at,
                "Pair Coeffs" | "PairIJ Coeffs" => &mut pair_at,
                "Atoms" => &mut atoms_at,
                "Velocities" => &mut velocities_at,
                _ => {
                    return Err(self.error(
                        kw.num,
                        None,
                        format!(
                            "unsupported section '{keyword}': gendpde reads only \
                             Masses, Pair Coeffs, PairIJ Coeffs, Atoms and Velocities"
                        ),
                    ))
                }
            };
            if let Some(first) = *seen {
                return Err(self.error(
                    kw.num,
                    Some(&keyword),
                    format!("second {keyword} section (the first is at line {first})"),
                ));
            }
            *seen = Some(kw.num);
            match keyword.as_str() {
                "Masses" => {
                    let body = self.body(&kw, "Masses", header.ntypes, "atom types")?;
                    self.masses(&body, &mut data.masses)?;
                }
                "Pair Coeffs" | "PairIJ Coeffs" => {
                    let ij = keyword == "PairIJ Coeffs";
                    let n = header.ntypes;
                    let (rows, what) = if ij { (n * (n + 1) / 2, "type pairs I <= J for the atom types") } else { (n, "atom types") };
                    let body = self.body(&kw, &keyword, rows, what)?;
                    data.pair_coeffs = Some(self.pair_coeffs(&body, &keyword, ij, n, kw.comment)?);
                }
                "Atoms" => {
                    self.check_style_hint(&kw)?;
                    let body = self.body(&kw, "Atoms", header.natoms, "atoms")?;
                    data.atoms = self.atoms(&body, header.ntypes, &mut ids)?;
                }
                _ => {
                    if atoms_at.is_none() {
                        return Err(self.error(
                            kw.num,
                            Some("Velocities"),
                            "the Atoms section must come before Velocities",
                        ));
                    }
                    let body = self.body(&kw, "Velocities", header.natoms, "atoms")?;
                    data.velocities = Some(self.velocities(&body, &ids)?);
                }
            }
        }
        if header.natoms > 0 && atoms_at.is_none() {
            return Err(self.error(
                header.natoms_line,
                None,
                format!(
                    "the header gives {} atoms but the file has no Atoms section",
                    header.natoms
                ),
            ));
        }
        Ok(data)
    }

    /// Reads the header lines up to the first section keyword.
    fn header(&mut self) -> Result<Header, ScriptError> {
        let mut h = Header {
            natoms: 0,
            natoms_line: 1,
            ntypes: 0,
            lo: [-0.5; 3],
            hi: [0.5; 3],
        };
        let mut seen: HashMap<&str, usize> = HashMap::new();
        while let Some(line) = self.lines.get(self.next).copied() {
            if line.is_keyword() {
                break;
            }
            self.next += 1;
            let words: Vec<&str> = line.text.split_whitespace().collect();
            let Some(&(keyword, nvalues, kind)) = HEADER_KEYWORDS
                .iter()
                .filter(|(k, _, _)| {
                    let k: Vec<&str> = k.split(' ').collect();
                    words.ends_with(&k)
                })
                .max_by_key(|(k, _, _)| k.len())
            else {
                return Err(self.error(
                    line.num,
                    None,
                    format!("unknown header line '{}'", line.text),
                ));
            };
            let values = &words[..words.len() - keyword.split(' ').count()];
            if values.len() != nvalues {
                return Err(self.error(
                    line.num,
                    None,
                    format!(
                        "'{keyword}' needs {nvalues} value{} before it, got {}",
                        if nvalues == 1 { "" } else { "s" },
                        values.len()
                    ),
                ));
            }
            if let Some(first) = seen.insert(keyword, line.num) {
                return Err(self.error(
                    line.num,
                    None,
                    format!("'{keyword}' given twice (first at line {first})"),
                ));
            }
            let count = || -> Result<usize, ScriptError> {
                values
                    .first()
                    .and_then(|v| v.parse::<usize>().ok())
                    .ok_or_else(|| {
                        self.error(
                            line.num,
                            None,
                            format!(
                                "'{keyword}' needs a non-negative integer, got '{}'",
                                values.join(" ")
                            ),
                        )
                    })
            };
            match kind {
                HeaderKind::Atoms => {
                    h.natoms = count()?;
                    h.natoms_line = line.num;
                }
                HeaderKind::AtomTypes => {
                    h.ntypes = count()?;
                    if h.ntypes == 0 || h.ntypes > MAX_ATOM_TYPES {
                        return Err(self.error(
                            line.num,
                            None,
                            format!(
                                "the number of atom types must be between 1 and \
                                 {MAX_ATOM_TYPES}, got {}",
                                h.ntypes
                            ),
                        ));
                    }
                }
                HeaderKind::Bounds(d) => {
                    let mut bounds = [0.0; 2];
                    for (b, v) in bounds.iter_mut().zip(values) {
                        *b = number(v)
                            .map_err(|e| self.error(line.num, None, format!("'{keyword}': {e}")))?;
                    }
                    let [lo, hi] = bounds;
                    if lo >= hi {
                        return Err(self.error(
                            line.num,
                            None,
                            format!("'{keyword}': the lower bound {lo} is not below the upper bound {hi}"),
                        ));
                    }
                    h.lo[d] = lo;
                    h.hi[d] = hi;
                }
                HeaderKind::Triclinic => {
                    return Err(self.error(
                        line.num,
                        None,
                        format!("'{keyword}': triclinic boxes are not supported"),
                    ))
                }
                HeaderKind::MustBeZero => {
                    let n = count()?;
                    if n != 0 {
                        return Err(self.error(
                            line.num,
                            None,
                            format!("the header gives {n} {keyword}, but gendpde supports none"),
                        ));
                    }
                }
                HeaderKind::Ignored => {
                    count()?;
                }
            }
        }
        if h.ntypes == 0 {
            let at = self.lines.get(self.next).map_or(self.last_line, |l| l.num);
            return Err(self.error(at, None, "the header has no 'atom types' line"));
        }
        Ok(h)
    }

    /// The `# style` hint after `Atoms`, if any, must name the requested style.
    fn check_style_hint(&self, kw: &Line) -> Result<(), ScriptError> {
        let Some(hint) = kw.comment.and_then(|c| c.split_whitespace().next()) else {
            return Ok(());
        };
        if hint == self.style.name() {
            return Ok(());
        }
        Err(self.error(
            kw.num,
            Some("Atoms"),
            format!(
                "the section is marked '# {hint}' but atom_style {} was requested",
                self.style.name()
            ),
        ))
    }

    /// The `count` data lines after section keyword `kw`. `what` names the
    /// header count, e.g. "atoms".
    fn body(
        &mut self,
        kw: &Line,
        section: &str,
        count: usize,
        what: &str,
    ) -> Result<Vec<Line<'a>>, ScriptError> {
        let mut body = Vec::new();
        while body.len() < count {
            match self.lines.get(self.next) {
                Some(line) if !line.is_keyword() => {
                    body.push(*line);
                    self.next += 1;
                }
                end => {
                    let found = body.len();
                    let end = match end {
                        Some(line) => format!("section '{}' at line {}", line.keyword(), line.num),
                        None => format!("the end of the file at line {}", self.last_line),
                    };
                    return Err(self.error(
                        kw.num,
                        Some(section),
                        format!(
                            "expected {count} lines ({count} {what} in the header), \
                             found {found} before {end}"
                        ),
                    ));
                }
            }
        }
        if let Some(line) = self.lines.get(self.next).filter(|l| !l.is_keyword()) {
            return Err(self.error(
                line.num,
                Some(section),
                format!("more than {count} lines ({count} {what} in the header)"),
            ));
        }
        Ok(body)
    }

    fn masses(&self, body: &[Line], masses: &mut [Option<f64>]) -> Result<(), ScriptError> {
        let mut first_line = vec![0; masses.len()];
        for line in body {
            let err = |msg: String| self.error(line.num, Some("Masses"), msg);
            let words: Vec<&str> = line.text.split_whitespace().collect();
            let [kind, mass] = words[..] else {
                return Err(err(format!(
                    "expected 2 columns (type mass), got {}",
                    words.len()
                )));
            };
            let t = atom_type(kind, masses.len()).map_err(err)?;
            let mass = number(mass).map_err(|e| err(format!("mass: {e}")))?;
            if mass <= 0.0 {
                return Err(err(format!("mass must be positive, got {mass}")));
            }
            let slot = t as usize - 1;
            if let (Some(seen), Some(m)) = (first_line.get_mut(slot), masses.get_mut(slot)) {
                if *seen != 0 {
                    return Err(err(format!(
                        "second mass for type {t} (the first is at line {seen})"
                    )));
                }
                *seen = line.num;
                *m = Some(mass);
            }
        }
        Ok(())
    }

    /// The rows of a pair coefficient section: each type (pair) once, types in range.
    fn pair_coeffs(&self, body: &[Line], section: &str, ij: bool, ntypes: usize, comment: Option<&str>) -> Result<PairCoeffs, ScriptError> {
        let mut first_line: HashMap<(u32, u32), usize> = HashMap::new();
        let (mut rows, mut lines) = (Vec::with_capacity(body.len()), Vec::with_capacity(body.len()));
        for line in body {
            let err = |msg: String| self.error(line.num, Some(section), msg);
            let words: Vec<String> = line.text.split_whitespace().map(str::to_string).collect();
            let ntype_words = if ij { 2 } else { 1 };
            if words.len() <= ntype_words {
                let layout = if ij { "I J coefficients" } else { "I coefficients" };
                return Err(err(format!("expected {layout}, got {} words", words.len())));
            }
            let i = atom_type(&words[0], ntypes).map_err(err)?;
            let j = if ij { atom_type(&words[1], ntypes).map_err(err)? } else { i };
            let key = (i.min(j), i.max(j));
            if let Some(first) = first_line.insert(key, line.num) {
                return Err(err(format!("second line for types {} {} (the first is at line {first})", key.0, key.1)));
            }
            rows.push(words);
            lines.push(line.num);
        }
        let style = comment.and_then(|c| c.split_whitespace().next()).map(str::to_string);
        Ok(PairCoeffs { ij, style, rows, lines })
    }

    fn atoms(
        &self,
        body: &[Line],
        ntypes: usize,
        ids: &mut HashMap<u64, usize>,
    ) -> Result<Vec<DataAtom>, ScriptError> {
        let columns = self.style.columns();
        let base = columns.len();
        let mut atoms = Vec::with_capacity(body.len());
        for line in body {
            let err = |msg: String| self.error(line.num, Some("Atoms"), msg);
            let words: Vec<&str> = line.text.split_whitespace().collect();
            if words.len() != base && words.len() != base + 3 {
                let msg = if words.len() < base {
                    format!(
                        "expected {base} columns ({}), got {}",
                        columns.join(" "),
                        words.len()
                    )
                } else {
                    format!(
                        "expected {base} or {} columns ({} [ix iy iz]), got {}",
                        base + 3,
                        columns.join(" "),
                        words.len()
                    )
                };
                return Err(err(msg));
            }
            let tag = atom_id(words[0]).map_err(err)?;
            let kind = atom_type(words[1], ntypes).map_err(err)?;
            let mut col = 2;
            let mut edpd = None;
            let mut sph_rho = None;
            let theta = match self.style {
                AtomStyle::Atomic => None,
                AtomStyle::Edpd => {
                    let t = number(words[col]).map_err(|e| err(format!("edpd_temp: {e}")))?;
                    let cv = number(words[col + 1]).map_err(|e| err(format!("edpd_cv: {e}")))?;
                    col += 2;
                    edpd = Some([t, cv]);
                    None
                }
                AtomStyle::Dpd => {
                    let theta = number(words[col]).map_err(|e| err(format!("dpdTheta: {e}")))?;
                    col += 1;
                    if theta <= 0.0 {
                        return Err(err(format!("dpdTheta must be positive, got {theta}")));
                    }
                    Some(theta)
                }
                AtomStyle::Mdpd => {
                    number(words[col]).map_err(|e| err(format!("rho: {e}")))?;
                    col += 1;
                    None
                }
                AtomStyle::Sph => {
                    sph_rho = Some(number(words[col]).map_err(|e| err(format!("rho: {e}")))?);
                    number(words[col + 1]).map_err(|e| err(format!("esph: {e}")))?;
                    number(words[col + 2]).map_err(|e| err(format!("cv: {e}")))?;
                    col += 3;
                    None
                }
            };
            let mut r = [0.0; 3];
            for (x, name) in r.iter_mut().zip(["x", "y", "z"]) {
                *x = number(words[col]).map_err(|e| err(format!("{name}: {e}")))?;
                col += 1;
            }
            let mut image = [0; 3];
            if words.len() > col {
                for (i, name) in image.iter_mut().zip(["ix", "iy", "iz"]) {
                    *i = words[col].parse().map_err(|_| {
                        err(format!(
                            "{name}: expected an integer image flag, got '{}'",
                            words[col]
                        ))
                    })?;
                    col += 1;
                }
            }
            if let Some(first) = ids.insert(tag, line.num) {
                return Err(err(format!(
                    "duplicate atom id {tag} (first at line {first})"
                )));
            }
            atoms.push(DataAtom {
                tag,
                kind,
                theta,
                edpd,
                sph_rho,
                r,
                image,
            });
        }
        Ok(atoms)
    }

    fn velocities(
        &self,
        body: &[Line],
        ids: &HashMap<u64, usize>,
    ) -> Result<Vec<(u64, [f64; 3])>, ScriptError> {
        let mut seen: HashMap<u64, usize> = HashMap::with_capacity(body.len());
        let mut velocities = Vec::with_capacity(body.len());
        for line in body {
            let err = |msg: String| self.error(line.num, Some("Velocities"), msg);
            let words: Vec<&str> = line.text.split_whitespace().collect();
            let [id, vx, vy, vz] = words[..] else {
                return Err(err(format!(
                    "expected 4 columns (id vx vy vz), got {}",
                    words.len()
                )));
            };
            let tag = atom_id(id).map_err(err)?;
            if !ids.contains_key(&tag) {
                return Err(err(format!(
                    "velocity for atom id {tag}, which is not in the Atoms section"
                )));
            }
            if let Some(first) = seen.insert(tag, line.num) {
                return Err(err(format!(
                    "second velocity for atom id {tag} (the first is at line {first})"
                )));
            }
            let mut v = [0.0; 3];
            for ((x, word), name) in v.iter_mut().zip([vx, vy, vz]).zip(["vx", "vy", "vz"]) {
                *x = number(word).map_err(|e| err(format!("{name}: {e}")))?;
            }
            velocities.push((tag, v));
        }
        Ok(velocities)
    }
}

/// What the header says.
struct Header {
    natoms: usize,
    /// Line of `N atoms` (1 if absent), for errors about missing atoms.
    natoms_line: usize,
    ntypes: usize,
    lo: [f64; 3],
    hi: [f64; 3],
}

/// A finite floating-point number.
fn number(word: &str) -> Result<f64, String> {
    match word.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!("'{word}' is not a finite number")),
        Err(_) => Err(format!("expected a number, got '{word}'")),
    }
}

/// An atom id: a positive integer.
fn atom_id(word: &str) -> Result<u64, String> {
    match word.parse::<u64>() {
        Ok(id) if id > 0 => Ok(id),
        _ => Err(format!("expected a positive integer atom id, got '{word}'")),
    }
}

/// An atom type in `1..=ntypes`.
fn atom_type(word: &str, ntypes: usize) -> Result<u32, String> {
    let t = word
        .parse::<u32>()
        .map_err(|_| format!("expected an integer atom type, got '{word}'"))?;
    if t == 0 || t as usize > ntypes {
        return Err(format!("atom type {t} is outside 1..{ntypes}"));
    }
    Ok(t)
}

#[cfg(test)]
mod tests;
