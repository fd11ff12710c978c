//! Turning one logical script line into words: comment removal, variable
//! substitution and quote-aware splitting, in that order (as LAMMPS does).

use crate::expr::evaluate;
use crate::format::{format_g, format_printf};
use crate::variables::Variables;

pub(super) const TRIPLE: &str = "\"\"\"";

/// Deepest nesting of `$(...)` inside `$(...)`.
const MAX_SUBSTITUTION_NESTING: usize = 32;

/// Splits a logical line into words after removing its comment and
/// substituting variables.
pub(super) fn words(
    text: &str,
    vars: &Variables,
    resolve: &dyn Fn(&str) -> Option<f64>,
) -> Result<Vec<String>, String> {
    let text = substitute(strip_comment(text), vars, resolve, 0)?;
    split_words(&text)
}

/// The quoting context at a point of a line.
#[derive(Clone, Copy, PartialEq)]
enum Quote {
    None,
    Single,
    Double,
    Triple,
}

impl Quote {
    /// Updates the context for a quote at the start of `rest`, returning its
    /// byte length, or 0 if `rest` does not start with a relevant quote.
    fn step(&mut self, rest: &str) -> usize {
        let (next, len) = match *self {
            Quote::None if rest.starts_with(TRIPLE) => (Quote::Triple, 3),
            Quote::Triple if rest.starts_with(TRIPLE) => (Quote::None, 3),
            Quote::None if rest.starts_with('"') => (Quote::Double, 1),
            Quote::Double if rest.starts_with('"') => (Quote::None, 1),
            Quote::None if rest.starts_with('\'') => (Quote::Single, 1),
            Quote::Single if rest.starts_with('\'') => (Quote::None, 1),
            _ => return 0,
        };
        *self = next;
        len
    }
}

/// Byte length of the item at the start of `rest`: a quote or one character.
fn item_len(quote: &mut Quote, rest: &str) -> usize {
    match quote.step(rest) {
        0 => rest.chars().next().map_or(0, char::len_utf8),
        n => n,
    }
}

/// Cuts `text` at the first `#` outside quotes.
fn strip_comment(text: &str) -> &str {
    let mut quote = Quote::None;
    let mut i = 0;
    while i < text.len() {
        if quote == Quote::None && text[i..].starts_with('#') {
            return &text[..i];
        }
        i += item_len(&mut quote, &text[i..]);
    }
    text
}

/// Replaces `$x`, `${name}` and `$(expr[:fmt])` outside quotes (single, double and
/// triple, as LAMMPS's Input::substitute: quoted text waits for the command that reads
/// it, e.g. `print`, to substitute it). Substituted text is not scanned again.
pub(super) fn substitute(
    text: &str,
    vars: &Variables,
    resolve: &dyn Fn(&str) -> Option<f64>,
    nesting: usize,
) -> Result<String, String> {
    if nesting > MAX_SUBSTITUTION_NESTING {
        return Err(format!(
            "$(...) nested deeper than {MAX_SUBSTITUTION_NESTING}"
        ));
    }
    let mut out = String::with_capacity(text.len());
    let mut quote = Quote::None;
    let mut rest = text;
    while !rest.is_empty() {
        if rest.starts_with('$') && quote == Quote::None {
            let (value, len) = expand(&rest[1..], vars, resolve, nesting)?;
            out.push_str(&value);
            rest = &rest[1 + len..];
        } else {
            let len = item_len(&mut quote, rest);
            out.push_str(&rest[..len]);
            rest = &rest[len..];
        }
    }
    Ok(out)
}

/// Expands the reference following a `$`; returns its value and the byte
/// length of the reference consumed.
fn expand(
    after: &str,
    vars: &Variables,
    resolve: &dyn Fn(&str) -> Option<f64>,
    nesting: usize,
) -> Result<(String, usize), String> {
    match after.chars().next() {
        None => Err("'$' at end of line".into()),
        Some('{') => {
            let close = after.find('}').ok_or("missing '}' after '${'")?;
            Ok((vars.value(&after[1..close], resolve)?, close + 1))
        }
        Some('(') => {
            let close = matching_paren(after).ok_or("missing ')' after '$('")?;
            let inner = substitute(&after[1..close], vars, resolve, nesting + 1)?;
            let (expr, fmt) = match inner.rsplit_once(':') {
                Some((expr, fmt)) => (expr, Some(fmt)),
                None => (inner.as_str(), None),
            };
            let x = evaluate(expr, vars, resolve).map_err(|e| format!("in $({inner}): {e}"))?;
            let value = match fmt {
                Some(fmt) => format_printf(fmt, x)?,
                // LAMMPS's default for $(...)
                None => format_g(x, 20),
            };
            Ok((value, close + 1))
        }
        Some(c) => Ok((vars.value(&c.to_string(), resolve)?, c.len_utf8())),
    }
}

/// Byte index of the `)` matching the `(` that starts `s`.
fn matching_paren(s: &str) -> Option<usize> {
    let mut depth = 0usize;
    for (i, b) in s.bytes().enumerate() {
        match b {
            b'(' => depth += 1,
            b')' if depth == 1 => return Some(i),
            b')' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    None
}

/// Splits on whitespace; a word starting with `'`, `"` or `"""` runs to the
/// matching quote, which must be followed by whitespace or the line end.
fn split_words(text: &str) -> Result<Vec<String>, String> {
    let mut words = Vec::new();
    let mut rest = text.trim_start_matches(is_space);
    while let Some(c) = rest.chars().next() {
        let (word, len) = if let Some(body) = rest.strip_prefix(TRIPLE) {
            let end = body.find(TRIPLE).ok_or("unbalanced triple quotes")?;
            (&body[..end], end + 6)
        } else if c == '"' || c == '\'' {
            let body = &rest[1..];
            let end = body
                .find(c)
                .ok_or_else(|| format!("unbalanced {c} quotes"))?;
            (&body[..end], end + 2)
        } else {
            let end = rest.find(is_space).unwrap_or(rest.len());
            (&rest[..end], end)
        };
        let after = &rest[len..];
        if after.chars().next().is_some_and(|c| !is_space(c)) {
            return Err(format!(
                "closing quote of '{word}' must be followed by whitespace"
            ));
        }
        words.push(word.to_string());
        rest = after.trim_start_matches(is_space);
    }
    Ok(words)
}

fn is_space(c: char) -> bool {
    c.is_ascii_whitespace() || c == '\x0b'
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_respect_quotes() {
        assert_eq!(strip_comment("run 10 # go"), "run 10 ");
        assert_eq!(strip_comment("print 'a # b' # c"), "print 'a # b' ");
        assert_eq!(strip_comment("print \"a # b\""), "print \"a # b\"");
        assert_eq!(
            strip_comment("print \"\"\"a ' # b\"\"\" #"),
            "print \"\"\"a ' # b\"\"\" "
        );
        assert_eq!(strip_comment("#"), "");
    }

    #[test]
    fn words_and_quotes() {
        let split = |s: &str| split_words(s).unwrap();
        assert_eq!(split("  a\tb  c "), ["a", "b", "c"]);
        assert_eq!(
            split("print \"a b\" 'c d' \"\"\"e \"f\" g\"\"\""),
            ["print", "a b", "c d", "e \"f\" g"]
        );
        assert_eq!(split("x '' y"), ["x", "", "y"]);
        assert_eq!(split("don't"), ["don't"]);
        assert!(split_words("print \"abc").is_err());
        assert!(split_words("print 'a'b").is_err());
        assert!(split_words("print \"\"\"abc").is_err());
        assert!(split("").is_empty());
    }

    #[test]
    fn parens_match() {
        assert_eq!(matching_paren("(a(b)c)d"), Some(6));
        assert_eq!(matching_paren("(()"), None);
    }
}
