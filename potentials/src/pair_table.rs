//! LAMMPS's tabulated pair potential (`pair_style table`, src/pair_table.cpp): a section
//! of a potential file (keyword, `N n [R|RSQ rlo rhi] [FPRIME fplo fphi]`, a blank line,
//! then `index r e f` lines) re-tabulated on N points evenly spaced in r^2 between the
//! inner distance and the cutoff, read by lookup (bin middles), linear interpolation or a
//! cubic spline in r^2.
//! The arithmetic follows LAMMPS's `spline_table`, `compute_table`, `spline` and `splint`
//! operation for operation, so forces and energies agree with LAMMPS to round-off.

/// How the re-tabulated values are read (`pair_style table STYLE N`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableStyle {
    /// The value at the middle of the bin.
    Lookup,
    Linear,
    Spline,
}

/// How a section spaces its distances.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Spacing {
    /// r as given in the file.
    File,
    /// `R rlo rhi`: r evenly spaced (the file's r column is replaced).
    R,
    /// `RSQ rlo rhi`: r^2 evenly spaced.
    Rsq,
}

/// One section of a table file as read: r, e and f columns and the parameter line.
#[derive(Clone, Debug, PartialEq)]
pub struct FileTable {
    pub r: Vec<f64>,
    pub e: Vec<f64>,
    pub f: Vec<f64>,
    pub spacing: Spacing,
    /// rlo and rhi of `R`/`RSQ` (unused with [`Spacing::File`]).
    pub rlo: f64,
    pub rhi: f64,
    /// `FPRIME fplo fphi`: dF/dr at the two ends.
    pub fprime: Option<(f64, f64)>,
}

/// An error reading a table file: the 1-based line (0: the file as a whole) and why.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadError {
    pub line: usize,
    pub why: String,
}

impl FileTable {
    /// The section `keyword` of a table file's `text`. Blank lines and `#` comments are
    /// skipped (LAMMPS's TableFileReader), the line after the parameter line is skipped
    /// and must be blank.
    pub fn parse(text: &str, keyword: &str) -> Result<Self, ReadError> {
        Self::parse_section(text, keyword, "FPRIME")
    }

    /// As [`Self::parse`], with `fprime` the word of the end slopes (pair multi/lucy's
    /// files write `FP`).
    pub fn parse_section(text: &str, keyword: &str, fprime: &str) -> Result<Self, ReadError> {
        let all: Vec<&str> = text.lines().collect();
        let mut pos = 0;
        let content = |l: &str| l.split('#').next().unwrap_or("").trim().to_string();
        // the next line that is not blank after its comment is removed, with its number
        let next = |pos: &mut usize| -> Option<(usize, String)> {
            while *pos < all.len() {
                *pos += 1;
                let c = content(all[*pos - 1]);
                if !c.is_empty() {
                    return Some((*pos, c));
                }
            }
            None
        };
        let err = |line, why: String| ReadError { line, why };
        loop {
            let Some((_, l)) = next(&mut pos) else {
                return Err(err(0, format!("did not find keyword {keyword}")));
            };
            if l.split_whitespace().next() == Some(keyword) {
                break;
            }
        }
        let (pline, params) = next(&mut pos).ok_or_else(|| err(0, format!("no parameter line after keyword {keyword}")))?;
        let mut t = FileTable { r: Vec::new(), e: Vec::new(), f: Vec::new(), spacing: Spacing::File, rlo: 0.0, rhi: 0.0, fprime: None };
        let mut n = 0usize;
        let mut words = params.split_whitespace();
        let number = |words: &mut std::str::SplitWhitespace, what: &str| -> Result<f64, ReadError> {
            let w = words.next().ok_or_else(|| err(pline, format!("{what} is missing")))?;
            w.parse::<f64>().map_err(|_| err(pline, format!("{what}: expected a number, got '{w}'")))
        };
        while let Some(w) = words.next() {
            match w {
                "N" => {
                    let v = words.next().ok_or_else(|| err(pline, "N is missing its value".into()))?;
                    n = v.parse().map_err(|_| err(pline, format!("N: expected a positive integer, got '{v}'")))?;
                }
                "R" | "RSQ" => {
                    t.spacing = if w == "R" { Spacing::R } else { Spacing::Rsq };
                    t.rlo = number(&mut words, "rlo")?;
                    t.rhi = number(&mut words, "rhi")?;
                }
                w if w == fprime => t.fprime = Some((number(&mut words, "fplo")?, number(&mut words, "fphi")?)),
                "BITMAP" => return Err(err(pline, "BITMAP tables are not supported (pair_style table linear or spline)".into())),
                other => return Err(err(pline, format!("invalid keyword {other} in pair table parameters (N, R, RSQ, {fprime})"))),
            }
        }
        if n == 0 {
            return Err(err(pline, "pair table parameters did not set N".into()));
        }
        if n < 2 {
            return Err(err(pline, "invalid pair table length: N must be at least 2".into()));
        }
        // LAMMPS skips the line after the parameter line whatever it holds
        if let Some(l) = all.get(pos).filter(|l| !content(l).is_empty()) {
            return Err(err(pos + 1, format!("expected a blank line after the parameter line, got '{l}'")));
        }
        pos += 1;
        for i in 0..n {
            let (k, l) = next(&mut pos).ok_or_else(|| err(0, format!("data missing: {i} of {n} lines of section {keyword}")))?;
            let w: Vec<&str> = l.split_whitespace().collect();
            let parsed = (w.len() >= 4 && w[0].parse::<i64>().is_ok()).then(|| (w[1].parse::<f64>(), w[2].parse::<f64>(), w[3].parse::<f64>()));
            let Some((Ok(r), Ok(e), Ok(f))) = parsed else {
                return Err(err(k, format!("expected 'index r e f', got '{l}'")));
            };
            // as LAMMPS: (rhi - rlo) * i / (n - 1), in this order
            let r = match t.spacing {
                Spacing::File => r,
                Spacing::R => t.rlo + (t.rhi - t.rlo) * i as f64 / (n - 1) as f64,
                Spacing::Rsq => (t.rlo * t.rlo + (t.rhi * t.rhi - t.rlo * t.rlo) * i as f64 / (n - 1) as f64).sqrt(),
            };
            if t.spacing == Spacing::File && t.r.last().is_some_and(|&last| !(r > last)) {
                return Err(err(k, format!("r = {r} does not increase (the spline needs increasing distances)")));
            }
            t.r.push(r);
            t.e.push(e);
            t.f.push(f);
        }
        Ok(t)
    }

    /// Smallest and largest r of the table (rlo, rhi of `R`/`RSQ`, else the r column).
    pub fn bounds(&self) -> (f64, f64) {
        match self.spacing {
            Spacing::File => (self.r[0], self.r[self.r.len() - 1]),
            _ => (self.rlo, self.rhi),
        }
    }
}

/// A table re-tabulated on N points in r^2 (LAMMPS's `compute_table`); values at the lower
/// edge of each bin, f stored as F/r.
#[derive(Clone, Debug, PartialEq)]
pub struct PairTable {
    pub style: TableStyle,
    pub cut: f64,
    pub innersq: f64,
    delta: f64,
    invdelta: f64,
    deltasq6: f64,
    rsq: Vec<f64>,
    e: Vec<f64>,
    f: Vec<f64>,
    /// de, df (linear) or the spline's second derivatives e2, f2.
    e_aux: Vec<f64>,
    f_aux: Vec<f64>,
}

/// A pair distance outside the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outside {
    Inner,
    Outer,
}

impl PairTable {
    /// Re-tabulates `file` on `n` points up to `cut` (LAMMPS's pair_coeff: the cutoff must
    /// lie in (rlo, rhi] and rlo be positive).
    pub fn new(style: TableStyle, n: usize, file: &FileTable, cut: f64) -> Result<Self, String> {
        let (rlo, rhi) = file.bounds();
        if !(cut > rlo && cut <= rhi) {
            return Err(format!("pair table cutoff {cut} is outside of the table ({rlo}, {rhi}]"));
        }
        if rlo <= 0.0 {
            return Err(format!("invalid pair table lower boundary {rlo}: must be positive"));
        }
        // match: the file's points are the ones needed (linear, RSQ, N equal, rhi = cut)
        let matched = style == TableStyle::Linear && file.r.len() == n && file.spacing == Spacing::Rsq && file.rhi == cut;
        let (e2file, f2file) = file_splines(file, matched);
        let splint_f = |r| splint(&file.r, &file.f, &f2file, r);
        // spline: F here, F/r after the e spline's end slopes are taken
        let mut t = Self::sampled(style, n, file, (rlo, cut), matched, (&e2file, &f2file), style != TableStyle::Spline);
        if style != TableStyle::Spline {
            return Ok(t);
        }
        let (ninput, tlm1, innersq, delta) = (file.r.len(), n - 1, t.innersq, t.delta);
        t.deltasq6 = delta * delta / 6.0;
        // end slopes in g = r^2: dh/dg = -f/2r for h = e
        let ep0 = -t.f[0] / (2.0 * innersq.sqrt());
        let epn = -t.f[tlm1] / (2.0 * cut);
        t.e_aux = vec![0.0; n];
        spline(&t.rsq, &t.e, ep0, epn, &mut t.e_aux);
        // h = f/r: FPRIME, else a secant over a tenth of a bin
        let secant = 0.1;
        let fp0 = match file.fprime {
            Some((fplo, _)) => (fplo / innersq.sqrt() - t.f[0] / innersq) / (2.0 * innersq.sqrt()),
            None => {
                let (rsq1, rsq2) = (innersq, innersq + secant * delta);
                (splint_f(rsq2.sqrt()) / rsq2.sqrt() - t.f[0] / rsq1.sqrt()) / (secant * delta)
            }
        };
        let fpn = match file.fprime {
            Some((_, fphi)) if cut == file.r[ninput - 1] => (fphi / cut - t.f[tlm1] / (cut * cut)) / (2.0 * cut),
            _ => {
                let rsq2 = cut * cut;
                let rsq1 = rsq2 - secant * delta;
                (t.f[tlm1] / rsq2.sqrt() - splint_f(rsq1.sqrt()) / rsq1.sqrt()) / (secant * delta)
            }
        };
        for i in 0..n {
            t.f[i] /= t.rsq[i].sqrt();
        }
        t.f_aux = vec![0.0; n];
        spline(&t.rsq, &t.f, fp0, fpn, &mut t.f_aux);
        Ok(t)
    }

    /// LAMMPS's `pair_style multi/lucy` re-tabulation of a pressure-density section
    /// (pair_multi_lucy.cpp `compute_table`): the file's r column holds densities rho,
    /// re-tabulated on `n` points evenly spaced in rho^2 between the file's bounds (rlo,
    /// rhi of `R`/`RSQ`, else its first and last rho; LAMMPS reads an unset rhi there),
    /// f kept as read (not divided by rho); lookup or linear only. `cut` is the pair
    /// cutoff the table is used within.
    pub fn density(style: TableStyle, n: usize, file: &FileTable, cut: f64) -> Result<Self, String> {
        if style == TableStyle::Spline {
            return Err("only lookup and linear table styles are implemented for pair multi/lucy".into());
        }
        let (lo, hi) = file.bounds();
        if !(lo >= 0.0 && hi > lo) {
            return Err(format!("invalid density range of the table: [{lo}, {hi}]"));
        }
        // match: linear, RSQ and N equal (the upper bound needs no match here)
        let matched = style == TableStyle::Linear && file.r.len() == n && file.spacing == Spacing::Rsq;
        let (e2file, f2file) = file_splines(file, matched);
        let mut t = Self::sampled(style, n, file, (lo, hi), matched, (&e2file, &f2file), false);
        t.cut = cut;
        Ok(t)
    }

    /// The values on `n` points evenly spaced in r^2 over `(inner, outer)` (LAMMPS's
    /// `compute_table`): at the middles of the N-1 bins (lookup), else at the lower edges
    /// with the differences to the next (linear); file values where `matched`, else the
    /// splines `e2f` of [`file_splines`]; f divided by r with `over_r`.
    fn sampled(style: TableStyle, n: usize, file: &FileTable, (inner, outer): (f64, f64), matched: bool, (e2file, f2file): (&[f64], &[f64]), over_r: bool) -> Self {
        let tlm1 = n - 1;
        let innersq = inner * inner;
        let delta = (outer * outer - innersq) / tlm1 as f64;
        let mut t = PairTable {
            style,
            cut: outer,
            innersq,
            delta,
            invdelta: 1.0 / delta,
            deltasq6: 0.0,
            rsq: vec![0.0; n],
            e: vec![0.0; n],
            f: vec![0.0; n],
            e_aux: Vec::new(),
            f_aux: Vec::new(),
        };
        let splint_e = |r| splint(&file.r, &file.e, e2file, r);
        let splint_f = |r| splint(&file.r, &file.f, f2file, r);
        let per = |r: f64| if over_r { r } else { 1.0 };
        if style == TableStyle::Lookup {
            // N-1 bins, values at their middles
            for i in 0..tlm1 {
                let rsq = innersq + (i as f64 + 0.5) * delta;
                let r = rsq.sqrt();
                (t.e[i], t.f[i]) = (splint_e(r), splint_f(r) / per(r));
            }
            return t;
        }
        for i in 0..n {
            let rsq = innersq + i as f64 * delta;
            let r = rsq.sqrt();
            t.rsq[i] = rsq;
            (t.e[i], t.f[i]) = if matched { (file.e[i], file.f[i] / per(r)) } else { (splint_e(r), splint_f(r) / per(r)) };
        }
        if style == TableStyle::Linear {
            t.e_aux = (0..tlm1).map(|i| t.e[i + 1] - t.e[i]).collect();
            t.f_aux = (0..tlm1).map(|i| t.f[i + 1] - t.f[i]).collect();
        }
        t
    }

    /// F/r and the pair energy at `rsq` < cut^2 (LAMMPS's PairTable::compute).
    #[inline]
    pub fn eval(&self, rsq: f64) -> Result<(f64, f64), Outside> {
        if rsq < self.innersq {
            return Err(Outside::Inner);
        }
        let itable = ((rsq - self.innersq) * self.invdelta) as usize;
        if itable >= self.rsq.len() - 1 {
            return Err(Outside::Outer);
        }
        Ok(match self.style {
            TableStyle::Lookup => (self.f[itable], self.e[itable]),
            TableStyle::Linear => {
                let fraction = (rsq - self.rsq[itable]) * self.invdelta;
                (self.f[itable] + fraction * self.f_aux[itable], self.e[itable] + fraction * self.e_aux[itable])
            }
            TableStyle::Spline => {
                let b = (rsq - self.rsq[itable]) * self.invdelta;
                let a = 1.0 - b;
                let (ca, cb) = (a * a * a - a, b * b * b - b);
                let f = a * self.f[itable] + b * self.f[itable + 1] + (ca * self.f_aux[itable] + cb * self.f_aux[itable + 1]) * self.deltasq6;
                let e = a * self.e[itable] + b * self.e[itable + 1] + (ca * self.e_aux[itable] + cb * self.e_aux[itable + 1]) * self.deltasq6;
                (f, e)
            }
        })
    }
}

impl PairTable {
    /// The end of the re-tabulated range in r^2 (the last point's).
    pub fn rsq_max(&self) -> f64 {
        self.innersq + (self.rsq.len() - 1) as f64 * self.delta
    }

    /// The energy of pair multi/lucy at rho^2 = `rsq` (pair_multi_lucy.cpp `compute`): as
    /// [`Self::eval`] but, linear, the first bin's value without interpolation (LAMMPS
    /// sets the fraction to 0 when the bin index is 0).
    pub fn density_energy(&self, rsq: f64) -> Result<f64, Outside> {
        let e = self.eval(rsq)?.1;
        let first = self.style == TableStyle::Linear && ((rsq - self.innersq) * self.invdelta) as usize == 0;
        Ok(if first { self.e[0] } else { e })
    }
}

/// The spline second derivatives of the file's e (end slopes -f) and f (end slopes
/// FPRIME, else secants) over r (LAMMPS's `spline_table`); zeros where `matched` (unused).
fn file_splines(file: &FileTable, matched: bool) -> (Vec<f64>, Vec<f64>) {
    let ninput = file.r.len();
    let (mut e2file, mut f2file) = (vec![0.0; ninput], vec![0.0; ninput]);
    if !matched {
        spline(&file.r, &file.e, -file.f[0], -file.f[ninput - 1], &mut e2file);
        let (fplo, fphi) = file.fprime.unwrap_or_else(|| {
            (
                (file.f[1] - file.f[0]) / (file.r[1] - file.r[0]),
                (file.f[ninput - 1] - file.f[ninput - 2]) / (file.r[ninput - 1] - file.r[ninput - 2]),
            )
        });
        spline(&file.r, &file.f, fplo, fphi, &mut f2file);
    }
    (e2file, f2file)
}

/// Second derivatives of the cubic spline through (x, y) with end slopes yp1, ypn
/// (Numerical Recipes' `spline`, as LAMMPS's PairTable::spline).
fn spline(x: &[f64], y: &[f64], yp1: f64, ypn: f64, y2: &mut [f64]) {
    let n = x.len();
    let mut u = vec![0.0; n];
    if yp1 > 0.99e30 {
        y2[0] = 0.0;
        u[0] = 0.0;
    } else {
        y2[0] = -0.5;
        u[0] = (3.0 / (x[1] - x[0])) * ((y[1] - y[0]) / (x[1] - x[0]) - yp1);
    }
    for i in 1..n - 1 {
        let sig = (x[i] - x[i - 1]) / (x[i + 1] - x[i - 1]);
        let p = sig * y2[i - 1] + 2.0;
        y2[i] = (sig - 1.0) / p;
        u[i] = (y[i + 1] - y[i]) / (x[i + 1] - x[i]) - (y[i] - y[i - 1]) / (x[i] - x[i - 1]);
        u[i] = (6.0 * u[i] / (x[i + 1] - x[i - 1]) - sig * u[i - 1]) / p;
    }
    let (qn, un) = if ypn > 0.99e30 { (0.0, 0.0) } else { (0.5, (3.0 / (x[n - 1] - x[n - 2])) * (ypn - (y[n - 1] - y[n - 2]) / (x[n - 1] - x[n - 2]))) };
    y2[n - 1] = (un - qn * u[n - 2]) / (qn * y2[n - 2] + 1.0);
    for k in (0..n - 1).rev() {
        y2[k] = y2[k] * y2[k + 1] + u[k];
    }
}

/// The spline through (xa, ya) with second derivatives y2a at x (bisection, as LAMMPS's
/// PairTable::splint).
fn splint(xa: &[f64], ya: &[f64], y2a: &[f64], x: f64) -> f64 {
    let (mut klo, mut khi) = (0, xa.len() - 1);
    while khi - klo > 1 {
        let k = (khi + klo) >> 1;
        if xa[k] > x {
            khi = k;
        } else {
            klo = k;
        }
    }
    let h = xa[khi] - xa[klo];
    let a = (xa[khi] - x) / h;
    let b = (x - xa[klo]) / h;
    a * ya[klo] + b * ya[khi] + ((a * a * a - a) * y2a[klo] + (b * b * b - b) * y2a[khi]) * (h * h) / 6.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lj_file(spacing: &str, n: usize) -> String {
        let (lo, hi) = (0.9_f64, 2.5_f64);
        let mut s = format!("# LJ\n\nLJ\nN {n} {spacing} {lo} {hi}\n\n");
        for i in 0..n {
            let r = match spacing {
                "RSQ" => (lo * lo + (hi * hi - lo * lo) * i as f64 / (n - 1) as f64).sqrt(),
                _ => lo + (hi - lo) * i as f64 / (n - 1) as f64,
            };
            let (e, f) = (4.0 * (r.powi(-12) - r.powi(-6)), 4.0 * (12.0 * r.powi(-13) - 6.0 * r.powi(-7)));
            s += &format!("{} {r:.16e} {e:.16e} {f:.16e}\n", i + 1);
        }
        s
    }

    #[test]
    fn a_fine_spline_reproduces_lennard_jones() {
        let file = FileTable::parse(&lj_file("R", 2000), "LJ").unwrap();
        for style in [TableStyle::Lookup, TableStyle::Linear, TableStyle::Spline] {
            let t = PairTable::new(style, 2000, &file, 2.5).unwrap();
            for r in [0.95, 1.1, 1.5, 2.2] {
                let (fr, e) = t.eval(r * r).unwrap();
                // lookup: the value at the middle of the bin of r^2
                let at = match style {
                    TableStyle::Lookup => (t.innersq + (((r * r - t.innersq) / t.delta).floor() + 0.5) * t.delta).sqrt(),
                    _ => r,
                };
                let (e0, f0) = (4.0 * (at.powi(-12) - at.powi(-6)), 4.0 * (12.0 * at.powi(-13) - 6.0 * at.powi(-7)));
                let f0 = f0 * r / at;
                let tol = if style == TableStyle::Linear { 1e-3 } else { 1e-6 };
                assert!((fr * r - f0).abs() < tol * f0.abs().max(1.0), "{style:?} F({r}) = {} vs {f0}", fr * r);
                assert!((e - e0).abs() < tol * e0.abs().max(1.0), "{style:?} E({r}) = {e} vs {e0}");
            }
            assert_eq!(t.eval(0.8 * 0.8), Err(Outside::Inner));
        }
    }

    #[test]
    fn a_matching_rsq_table_is_used_as_given() {
        let file = FileTable::parse(&lj_file("RSQ", 100), "LJ").unwrap();
        let t = PairTable::new(TableStyle::Linear, 100, &file, 2.5).unwrap();
        assert_eq!(t.e[..], file.e[..]);
    }

    #[test]
    fn bad_files_name_the_line() {
        let e = FileTable::parse("A\nN 3 R 1 2\n\n1 1 0 0\n2 x 0 0\n3 2 0 0\n", "A").unwrap_err();
        assert_eq!(e.line, 5);
        assert!(FileTable::parse("A\nN 3 Q 1 2\n\n", "A").unwrap_err().why.contains("invalid keyword Q"));
        assert!(FileTable::parse("A\nN 3\n\n1 1 0 0\n", "B").unwrap_err().why.contains("did not find keyword B"));
        assert_eq!(FileTable::parse("A\nN 3\n\n1 1 0 0\n2 1.5 0 0\n3 1.5 0 0\n", "A").unwrap_err().line, 6);
        assert!(FileTable::parse("A\nN 2 R 1 2\n1 1 0 0\n2 2 0 0\n", "A").unwrap_err().why.contains("blank line"));
        let file = FileTable::parse(&lj_file("R", 10), "LJ").unwrap();
        assert!(PairTable::new(TableStyle::Spline, 100, &file, 3.0).unwrap_err().contains("outside"));
    }
}
