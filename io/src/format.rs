//! C `printf`-compatible formatting of floating-point numbers.

/// Largest width or precision accepted by [`format_printf`].
const MAX_FIELD: usize = 1000;

/// Precision beyond which `%g` output cannot change: a double has at most
/// 767 significant decimal digits and `%g` strips the trailing zeros.
const MAX_G_PRECISION: usize = 800;

/// Formats `x` like C's `printf("%.<precision>g", x)`.
pub fn format_g(x: f64, precision: usize) -> String {
    let spec = Spec {
        precision: Some(precision),
        ..Spec::default()
    };
    spec.render(x)
}

/// Formats `x` as LAMMPS's `fmt::print("{}", x)`: the shortest digits that read back to
/// `x`, in fixed notation for decimal exponents -4 to 15 (no trailing `.0`), else as
/// `1.5e-05` or `1e+16`.
pub fn format_shortest(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return if x == 0.0 { if x.is_sign_negative() { "-0".into() } else { "0".into() } } else { format!("{x}") };
    }
    let e = format!("{x:e}");
    let (mantissa, exp) = e.split_once('e').expect("{:e} has an exponent");
    let exp: i32 = exp.parse().expect("an integer exponent");
    if (-4..16).contains(&exp) {
        format!("{x}")
    } else {
        format!("{mantissa}e{}{:02}", if exp < 0 { '-' } else { '+' }, exp.abs())
    }
}

/// Formats `x` with a printf-style format holding exactly one conversion
/// `%[flags][width][.prec](f|F|e|E|g|G|d|i)`; text around it is copied and
/// `%%` yields `%`. `%d` truncates `x` toward zero.
pub fn format_printf(fmt: &str, x: f64) -> Result<String, String> {
    let mut out = String::new();
    let mut spec = None;
    let mut chars = fmt.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
        } else if chars.peek() == Some(&'%') {
            chars.next();
            out.push('%');
        } else if spec.is_some() {
            return Err(format!("format '{fmt}' has more than one conversion"));
        } else {
            let parsed = Spec::parse(&mut chars).map_err(|e| format!("format '{fmt}': {e}"))?;
            out.push_str(&parsed.try_render(x)?);
            spec = Some(parsed);
        }
    }
    match spec {
        Some(_) => Ok(out),
        None => Err(format!("format '{fmt}' has no % conversion")),
    }
}

/// One parsed `%` conversion.
#[derive(Default)]
struct Spec {
    left: bool,
    plus: bool,
    space: bool,
    zero: bool,
    alt: bool,
    width: usize,
    precision: Option<usize>,
    conv: Conv,
    upper: bool,
}

#[derive(Default, Clone, Copy, PartialEq)]
enum Conv {
    Fixed,
    Exp,
    #[default]
    General,
    Int,
}

impl Spec {
    /// Parses the part of a conversion after its `%`.
    fn parse(chars: &mut std::iter::Peekable<std::str::Chars>) -> Result<Spec, String> {
        let mut spec = Spec::default();
        while let Some(&c) = chars.peek() {
            match c {
                '-' => spec.left = true,
                '+' => spec.plus = true,
                ' ' => spec.space = true,
                '0' => spec.zero = true,
                '#' => spec.alt = true,
                _ => break,
            }
            chars.next();
        }
        spec.width = parse_number(chars)?.unwrap_or(0);
        if chars.peek() == Some(&'.') {
            chars.next();
            spec.precision = Some(parse_number(chars)?.unwrap_or(0));
        }
        let c = chars.next().ok_or("missing conversion character")?;
        spec.conv = match c.to_ascii_lowercase() {
            'f' => Conv::Fixed,
            'e' => Conv::Exp,
            'g' => Conv::General,
            'd' | 'i' => Conv::Int,
            _ => return Err(format!("unsupported conversion '%{c}'")),
        };
        spec.upper = c.is_ascii_uppercase();
        Ok(spec)
    }

    /// Renders `x`, rejecting `%d` of a non-finite value.
    fn try_render(&self, x: f64) -> Result<String, String> {
        if self.conv == Conv::Int && !x.is_finite() {
            return Err(format!("cannot format {x} as an integer"));
        }
        Ok(self.render(x))
    }

    /// Renders `x` with sign, padding and justification.
    fn render(&self, x: f64) -> String {
        let sign = if x.is_sign_negative() && !(self.conv == Conv::Int && x.trunc() == 0.0) {
            "-"
        } else if self.plus {
            "+"
        } else if self.space {
            " "
        } else {
            ""
        };
        let body = self.magnitude(x.abs());
        let len = sign.len() + body.chars().count();
        let pad = self.width.saturating_sub(len);
        let zero_pad = self.zero
            && !self.left
            && x.is_finite()
            && !(self.conv == Conv::Int && self.precision.is_some());
        if pad == 0 {
            format!("{sign}{body}")
        } else if self.left {
            format!("{sign}{body}{}", " ".repeat(pad))
        } else if zero_pad {
            format!("{sign}{}{body}", "0".repeat(pad))
        } else {
            format!("{}{sign}{body}", " ".repeat(pad))
        }
    }

    /// Renders the non-negative magnitude `a` without sign or padding.
    fn magnitude(&self, a: f64) -> String {
        let text = if a.is_nan() {
            "nan".to_string()
        } else if a.is_infinite() {
            "inf".to_string()
        } else {
            match self.conv {
                Conv::Fixed => fixed(a, self.precision.unwrap_or(6), self.alt),
                Conv::Exp => exponential(a, self.precision.unwrap_or(6), self.alt),
                Conv::General => general(a, self.precision.unwrap_or(6), self.alt),
                Conv::Int => integer(a, self.precision),
            }
        };
        if self.upper {
            text.to_ascii_uppercase()
        } else {
            text
        }
    }
}

/// Reads a decimal field (width or precision), if present.
fn parse_number(chars: &mut std::iter::Peekable<std::str::Chars>) -> Result<Option<usize>, String> {
    let mut value: Option<usize> = None;
    while let Some(d) = chars.peek().and_then(|c| c.to_digit(10)) {
        chars.next();
        let next = value.unwrap_or(0) * 10 + d as usize;
        if next > MAX_FIELD {
            return Err(format!("width or precision above {MAX_FIELD}"));
        }
        value = Some(next);
    }
    Ok(value)
}

/// `%f` of a non-negative finite number.
fn fixed(a: f64, precision: usize, alt: bool) -> String {
    let mut s = format!("{a:.precision$}");
    if alt && precision == 0 {
        s.push('.');
    }
    s
}

/// `%e` of a non-negative finite number, with C's two-digit signed exponent.
fn exponential(a: f64, precision: usize, alt: bool) -> String {
    let (mut mantissa, exp) = split_exponential(a, precision);
    if alt && precision == 0 {
        mantissa.push('.');
    }
    format!("{mantissa}e{exp:+03}")
}

/// Rust's `{:.p$e}` output split into mantissa and decimal exponent.
fn split_exponential(a: f64, precision: usize) -> (String, i32) {
    let s = format!("{a:.precision$e}");
    match s.split_once('e') {
        Some((m, e)) => (m.to_string(), e.parse().unwrap_or(0)),
        None => (s, 0),
    }
}

/// `%g` of a non-negative finite number.
fn general(a: f64, precision: usize, alt: bool) -> String {
    let p = precision.clamp(1, MAX_G_PRECISION);
    let (_, x) = split_exponential(a, p - 1);
    // C uses `%f` with P-1-X fraction digits when -4 <= X < P, else `%e`.
    let fraction = i64::try_from(p)
        .ok()
        .filter(|_| x >= -4)
        .and_then(|p| usize::try_from(p - 1 - i64::from(x)).ok());
    match fraction {
        Some(digits) if alt => fixed(a, digits, alt),
        Some(digits) => strip_fraction_zeros(&fixed(a, digits, alt)).to_string(),
        None if alt => exponential(a, p - 1, alt),
        None => {
            let text = exponential(a, p - 1, alt);
            match text.split_once('e') {
                Some((m, e)) => format!("{}e{e}", strip_fraction_zeros(m)),
                None => text,
            }
        }
    }
}

/// Removes trailing fractional zeros and a then-bare decimal point.
fn strip_fraction_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// `%d` of a non-negative finite number: truncated, zero-extended to
/// `precision` digits (C prints nothing for `%.0d` of zero).
fn integer(a: f64, precision: Option<usize>) -> String {
    let digits = format!("{:.0}", a.trunc());
    match precision {
        Some(0) if digits == "0" => String::new(),
        Some(p) if p > digits.len() => format!("{}{digits}", "0".repeat(p - digits.len())),
        _ => digits,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// As LAMMPS 22 Jul 2025 prints them (fix ave/histo's block lines).
    #[test]
    fn shortest_matches_lammps_fmt() {
        for (x, text) in [
            (1536.0, "1536"),
            (-1.2810265668751807e-17, "-1.2810265668751807e-17"),
            (1.5899805187281213, "1.5899805187281213"),
            (-1.709223458376557, "-1.709223458376557"),
            (0.0, "0"),
            (1e20, "1e+20"),
            (-1e20, "-1e+20"),
            (0.0001, "0.0001"),
            (1e-5, "1e-05"),
            (1e15, "1000000000000000"),
            (1e16, "1e+16"),
        ] {
            assert_eq!(format_shortest(x), text);
        }
    }

    #[test]
    fn g_matches_c_printf() {
        let cases: &[(f64, usize, &str)] = &[
            (0.0001, 15, "0.0001"),
            (1e-05, 15, "1e-05"),
            (123456789.0, 8, "1.2345679e+08"),
            (100.0, 15, "100"),
            (1.5, 15, "1.5"),
            (1e-20, 15, "1e-20"),
            (3.0, 15, "3"),
            (0.0, 15, "0"),
            (-0.0, 6, "-0"),
            (0.1, 15, "0.1"),
            (0.1, 17, "0.10000000000000001"),
            (1e15, 15, "1e+15"),
            (999999.5, 6, "1e+06"),
            (123456.0, 6, "123456"),
            (1e100, 6, "1e+100"),
            (-2.5e-7, 3, "-2.5e-07"),
            (1.0, 0, "1"),
            (f64::INFINITY, 6, "inf"),
            (f64::NEG_INFINITY, 6, "-inf"),
            (f64::NAN, 6, "nan"),
        ];
        for &(x, p, want) in cases {
            assert_eq!(format_g(x, p), want, "%.{p}g of {x:e}");
        }
    }

    #[test]
    fn g_with_huge_precision_is_exact_and_bounded() {
        assert_eq!(format_g(0.5, usize::MAX), "0.5");
        assert_eq!(format_g(1e300, 1 << 40), format_g(1e300, MAX_G_PRECISION));
    }

    #[test]
    fn printf_conversions() {
        let cases: &[(&str, f64, &str)] = &[
            ("%.3f", 1.23456, "1.235"),
            ("%f", 1.0, "1.000000"),
            ("%g", 0.5, "0.5"),
            ("%10.4e", 12345.678, "1.2346e+04"),
            ("%12.4e", -12345.678, " -1.2346e+04"),
            ("%-8.2f|", 1.5, "1.50    |"),
            ("%08.2f", -1.5, "-0001.50"),
            ("%+.1f", 2.0, "+2.0"),
            ("% .1f", 2.0, " 2.0"),
            ("%#.0f", 2.0, "2."),
            ("%#g", 1.0, "1.00000"),
            ("%E", 1.0, "1.000000E+00"),
            ("%G", 1e-10, "1E-10"),
            ("%d", 7.9, "7"),
            ("%d", -7.9, "-7"),
            ("%d", -0.5, "0"),
            ("%5d", 42.0, "   42"),
            ("%.3d", 5.0, "005"),
            ("%.0d", 0.0, ""),
            ("x=%.2f%%", 0.125, "x=0.12%"),
            ("%08f", f64::INFINITY, "     inf"),
        ];
        for &(fmt, x, want) in cases {
            assert_eq!(format_printf(fmt, x).as_deref(), Ok(want), "{fmt} of {x}");
        }
    }

    #[test]
    fn printf_rejects_bad_formats() {
        for fmt in [
            "",
            "abc",
            "%",
            "%q",
            "%f %f",
            "%.5000f",
            "%99999999999999999999f",
        ] {
            assert!(format_printf(fmt, 1.0).is_err(), "{fmt:?} accepted");
        }
        assert!(format_printf("%d", f64::NAN).is_err());
    }
}
