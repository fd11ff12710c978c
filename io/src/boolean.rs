//! The Boolean expressions of LAMMPS's `if` command (Variable::evaluate_boolean): numbers
//! and bare strings, `!`, then `<` `<=` `>` `>=`, then `==` `!=`, then `&&`, then `||`
//! `|^`, left to right, with parentheses. Strings compare only by `==` and `!=`; the
//! variables have been substituted before.

/// An operand: a number, or a string (starting with a letter: `lj/cut`, `a10`).
#[derive(Clone, Debug, PartialEq)]
enum Value {
    Number(f64),
    Text(String),
}

/// Evaluates `text` to true or false; the error says what is wrong with it.
pub fn evaluate_boolean(text: &str) -> Result<bool, String> {
    let tokens = tokens(text)?;
    let mut parser = Parser { tokens: &tokens, pos: 0 };
    let value = parser.or()?;
    if let Some(t) = tokens.get(parser.pos) {
        return Err(format!("unexpected '{t}' in Boolean expression '{text}'"));
    }
    match value {
        Value::Number(x) => Ok(x != 0.0),
        Value::Text(s) => Err(format!("the Boolean expression '{text}' is the string '{s}', not a comparison")),
    }
}

const OPERATORS: [&str; 12] = ["==", "!=", "<=", ">=", "&&", "||", "|^", "<", ">", "!", "(", ")"];

/// Operators, parentheses and operands (a number's sign is part of it).
fn tokens(text: &str) -> Result<Vec<String>, String> {
    let mut out = Vec::new();
    let mut rest = text.trim_start();
    while !rest.is_empty() {
        let len = match OPERATORS.iter().find(|op| rest.starts_with(**op)) {
            Some(op) => op.len(),
            None => rest.find(|c: char| c.is_whitespace() || "=!<>&|()".contains(c)).unwrap_or(rest.len()),
        };
        if len == 0 {
            return Err(format!("unexpected '{}' in Boolean expression '{text}'", &rest[..1]));
        }
        out.push(rest[..len].to_string());
        rest = rest[len..].trim_start();
    }
    Ok(out)
}

struct Parser<'a> {
    tokens: &'a [String],
    pos: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&str> {
        self.tokens.get(self.pos).map(String::as_str)
    }

    /// One level of left-associative binary operators `ops` over operands of `next`.
    fn level(&mut self, ops: &[&str], next: fn(&mut Self) -> Result<Value, String>) -> Result<Value, String> {
        let mut a = next(self)?;
        while let Some(op) = self.peek().filter(|t| ops.contains(t)).map(str::to_string) {
            self.pos += 1;
            let b = next(self)?;
            a = apply(&op, a, b)?;
        }
        Ok(a)
    }

    fn or(&mut self) -> Result<Value, String> {
        self.level(&["||", "|^"], Self::and)
    }

    fn and(&mut self) -> Result<Value, String> {
        self.level(&["&&"], Self::equality)
    }

    fn equality(&mut self) -> Result<Value, String> {
        self.level(&["==", "!="], Self::relation)
    }

    fn relation(&mut self) -> Result<Value, String> {
        self.level(&["<", "<=", ">", ">="], Self::unary)
    }

    fn unary(&mut self) -> Result<Value, String> {
        match self.peek() {
            Some("!") => {
                self.pos += 1;
                Ok(Value::Number(truth(number(&self.unary()?)? == 0.0)))
            }
            Some("(") => {
                self.pos += 1;
                let v = self.or()?;
                if self.peek() != Some(")") {
                    return Err("missing ')' in Boolean expression".into());
                }
                self.pos += 1;
                Ok(v)
            }
            Some(t) if !OPERATORS.contains(&t) => {
                let value = operand(t);
                self.pos += 1;
                value
            }
            Some(t) => Err(format!("expected a number or a string, got '{t}'")),
            None => Err("the Boolean expression ends where an operand is expected".into()),
        }
    }
}

/// A number (starting with a digit, `.`, `-` or `+`) or a string (starting with a letter,
/// then letters, digits, `_` and `/`), as LAMMPS reads them.
fn operand(t: &str) -> Result<Value, String> {
    let first = t.chars().next().unwrap_or(' ');
    if first.is_ascii_digit() || ".-+".contains(first) {
        return t.parse().map(Value::Number).map_err(|_| format!("'{t}' is not a number"));
    }
    if first.is_ascii_alphabetic() && t.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '/') {
        return Ok(Value::Text(t.to_string()));
    }
    Err(format!("'{t}' is neither a number nor a string of letters, digits, _ and /"))
}

fn truth(b: bool) -> f64 {
    if b { 1.0 } else { 0.0 }
}

fn number(v: &Value) -> Result<f64, String> {
    match v {
        Value::Number(x) => Ok(*x),
        Value::Text(s) => Err(format!("the string '{s}' can only be compared with == or !=")),
    }
}

fn apply(op: &str, a: Value, b: Value) -> Result<Value, String> {
    if let (Value::Text(x), Value::Text(y)) = (&a, &b) {
        return match op {
            "==" => Ok(Value::Number(truth(x == y))),
            "!=" => Ok(Value::Number(truth(x != y))),
            _ => Err(format!("the strings '{x}' and '{y}' can only be compared with == or !=")),
        };
    }
    if matches!((&a, &b), (Value::Text(_), Value::Number(_)) | (Value::Number(_), Value::Text(_))) {
        return Err(format!("cannot compare a number with a string ({a:?} {op} {b:?})"));
    }
    let (x, y) = (number(&a)?, number(&b)?);
    Ok(Value::Number(truth(match op {
        "<" => x < y,
        "<=" => x <= y,
        ">" => x > y,
        ">=" => x >= y,
        "==" => x == y,
        "!=" => x != y,
        "&&" => x != 0.0 && y != 0.0,
        "||" => x != 0.0 || y != 0.0,
        _ => (x != 0.0) != (y != 0.0),
    })))
}

#[cfg(test)]
mod tests {
    use super::evaluate_boolean;

    #[test]
    fn lammps_examples_and_precedence() {
        let t = |s: &str| evaluate_boolean(s).unwrap_or_else(|e| panic!("{s}: {e}"));
        assert!(t("2000 > 1000"));
        assert!(!t("a10 == a11"));
        assert!(t("lj/cut == lj/cut"));
        assert!(t("(3.5 > 0.0) || (20 < 1000)"));
        assert!(t("-1.5e1 > -15.3"));
        assert!(t("1 < 2 == 1"), "relations bind tighter than equality");
        assert!(!t("0 && 1 || 0"));
        assert!(t("1 || 0 && 0"), "&& binds tighter than ||");
        assert!(!t("1 |^ 1"));
        assert!(t("!0 && !(1 < 0)"));
        assert!(t("5"));
    }

    #[test]
    fn errors_say_what_is_wrong() {
        let e = |s: &str| evaluate_boolean(s).unwrap_err();
        assert!(e("abc < 3").contains("cannot compare a number with a string"), "{}", e("abc < 3"));
        assert!(e("abc < xyz").contains("only be compared with == or !="));
        assert!(e("(1 < 2").contains("missing ')'"));
        assert!(e("1 <").contains("ends where an operand is expected"));
        assert!(e("1 2").contains("unexpected '2'"));
        assert!(e("abc").contains("not a comparison"));
        assert!(e("$x > 1").contains("neither a number nor a string"));
    }
}
