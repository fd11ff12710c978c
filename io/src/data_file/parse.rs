//! The data-file parser: header lines, then each section with its per-style columns.

use super::*;
use std::collections::HashMap;

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

pub(super) struct Parser<'a> {
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
    pub(super) fn new(name: &str, text: &'a str, style: AtomStyle) -> Self {
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

    pub(super) fn parse(mut self) -> Result<DataFile, ScriptError> {
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
