//! Evaluation of LAMMPS equal-style expressions.
//!
//! Precedence, lowest first: `||` `|^` (xor); `&&`; `==` `!=`; `<` `<=` `>` `>=`;
//! `+` `-`; `*` `/` `%`; `^`; unary `-` `!`. As in LAMMPS, unary minus binds tighter
//! than `^` and `^` is left-associative: `-2^2 == 4`, `2^3^2 == 64`. Comparisons and
//! logic yield 1 or 0. Constants: `PI`, `version` (of the reference LAMMPS, 20250722),
//! `on` `yes` `true` (1) and `off` `no` `false` (0). The functions are in functions.rs.

use crate::functions::{self, WORD_FUNCTIONS};
use std::cell::RefCell;
use std::collections::HashMap;

/// LAMMPS's `version` constant: the date of the reference LAMMPS (22 Jul 2025).
const VERSION: f64 = 20250722.0;

/// Deepest chain of `v_name` references followed before giving up.
const MAX_VARIABLE_DEPTH: usize = 64;

/// Deepest nesting of parentheses, operators and functions accepted,
/// counted across variable references.
const MAX_NESTING: usize = 256;

/// The variables an expression reads as `v_name` (the store of the `variable` command).
pub trait VariableLookup {
    /// The expression of equal-style variable `name`; None for other styles and unknown
    /// names.
    fn expression(&self, name: &str) -> Option<&str>;
    /// The value of any other variable as text (an error for unknown names).
    fn text(&self, name: &str, resolve: &dyn Fn(&str) -> Option<f64>) -> Result<String, String>;
}

/// Evaluates an equal-style expression. `v_name` reads another variable;
/// any other unknown identifier (`step`, `c_ID[2]`, ...) is looked up with
/// `resolve`.
pub fn evaluate(
    text: &str,
    vars: &dyn VariableLookup,
    resolve: &dyn Fn(&str) -> Option<f64>,
) -> Result<f64, String> {
    evaluate_nested(text, vars, resolve, 0, 0, &Memo::default())
}

/// Values of the variables already read during one top-level evaluation.
///
/// Nothing changes while an expression is evaluated, so each `v_name` needs
/// evaluating only once: without this, `a1 = v_a0+v_a0`, `a2 = v_a1+v_a1`,
/// ... takes time exponential in the length of the chain.
pub(crate) type Memo = RefCell<HashMap<String, f64>>;

/// The numeric value of a variable as read by `v_name` in an expression
/// `depth` variables and `nesting` levels deep; `memo` holds the values
/// of the variables already read by the same top-level evaluation.
pub(crate) fn variable(
    vars: &dyn VariableLookup,
    name: &str,
    resolve: &dyn Fn(&str) -> Option<f64>,
    depth: usize,
    nesting: usize,
    memo: &Memo,
) -> Result<f64, String> {
    match vars.expression(name) {
        Some(text) => evaluate_nested(text, vars, resolve, depth + 1, nesting, memo),
        None => {
            let text = vars.text(name, resolve)?;
            match text.trim().parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(format!("variable '{name}' is not numeric: '{text}'")),
            }
        }
    }
}

/// [`evaluate`] for an expression reached through `depth` variable
/// references from inside `nesting` levels of enclosing expressions.
fn evaluate_nested(
    text: &str,
    vars: &dyn VariableLookup,
    resolve: &dyn Fn(&str) -> Option<f64>,
    depth: usize,
    nesting: usize,
    memo: &Memo,
) -> Result<f64, String> {
    if depth > MAX_VARIABLE_DEPTH {
        return Err(format!(
            "variables nested deeper than {MAX_VARIABLE_DEPTH} (recursive definition?)"
        ));
    }
    let mut parser = Parser {
        tokens: tokenize(text)?,
        pos: 0,
        nesting,
        vars,
        resolve,
        depth,
        memo,
    };
    if parser.tokens.is_empty() {
        return Err("empty expression".into());
    }
    let value = parser.expression()?;
    if let Some(tok) = parser.tokens.get(parser.pos) {
        return Err(format!("unexpected '{tok}' in expression '{text}'"));
    }
    if !value.is_finite() {
        return Err(format!("expression '{text}' is not a finite number"));
    }
    Ok(value)
}

#[derive(Clone, Debug, PartialEq)]
enum Token {
    Num(f64),
    Ident(String),
    Op(&'static str),
    /// The parenthesised word of a feature function (`is_file(in.x)`), parentheses left out.
    Word(String),
}

impl std::fmt::Display for Token {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            Token::Num(x) => write!(f, "{x}"),
            Token::Ident(s) => f.write_str(s),
            Token::Op(s) => f.write_str(s),
            Token::Word(s) => write!(f, "({s})"),
        }
    }
}

/// Operators and punctuation, two-character ones first.
const OPERATORS: [&str; 19] = [
    "<=", ">=", "==", "!=", "&&", "||", "|^", "<", ">", "+", "-", "*", "/", "%", "^", "!", "(", ")", ",",
];

fn tokenize(text: &str) -> Result<Vec<Token>, String> {
    let mut tokens = Vec::new();
    let mut rest = text.trim_start();
    while let Some(c) = rest.chars().next() {
        let len = if c.is_ascii_digit() || c == '.' {
            let len = number_len(rest);
            let word = &rest[..len];
            let x = word
                .parse()
                .map_err(|_| format!("invalid number '{word}'"))?;
            tokens.push(Token::Num(x));
            len
        } else if c.is_ascii_alphabetic() || c == '_' {
            let len = identifier_len(rest)?;
            let name = &rest[..len];
            tokens.push(Token::Ident(name.to_string()));
            match rest[len..].trim_start().strip_prefix('(') {
                Some(inner) if WORD_FUNCTIONS.contains(&name) => {
                    let close = inner.find(')').ok_or_else(|| format!("missing ')' after {name}("))?;
                    tokens.push(Token::Word(inner[..close].to_string()));
                    rest.len() - inner.len() + close + 1
                }
                _ => len,
            }
        } else if let Some(op) = OPERATORS.iter().find(|op| rest.starts_with(**op)) {
            tokens.push(Token::Op(op));
            op.len()
        } else {
            return Err(format!("unexpected character '{c}' in expression"));
        };
        rest = rest[len..].trim_start();
    }
    Ok(tokens)
}

/// Byte length of the number at the start of `s`: digits and dots, then an
/// optional exponent.
fn number_len(s: &str) -> usize {
    let b = s.as_bytes();
    let mut i = b
        .iter()
        .take_while(|c| c.is_ascii_digit() || **c == b'.')
        .count();
    if matches!(b.get(i), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(b.get(i + 1), Some(b'+' | b'-')));
        let digits = b[i + 1 + sign..]
            .iter()
            .take_while(|c| c.is_ascii_digit())
            .count();
        if digits > 0 {
            i += 1 + sign + digits;
        }
    }
    i
}

/// Byte length of the identifier at the start of `s`, including any
/// `[...]` index suffixes as in `c_ID[2]`.
fn identifier_len(s: &str) -> Result<usize, String> {
    let b = s.as_bytes();
    let mut i = b
        .iter()
        .take_while(|c| c.is_ascii_alphanumeric() || **c == b'_')
        .count();
    while b.get(i) == Some(&b'[') {
        match b[i..].iter().position(|&c| c == b']') {
            Some(close) => i += close + 1,
            None => return Err(format!("missing ']' in '{s}'")),
        }
    }
    Ok(i)
}

/// A recursive-descent parser that evaluates as it parses.
struct Parser<'a> {
    tokens: Vec<Token>,
    pos: usize,
    nesting: usize,
    vars: &'a dyn VariableLookup,
    resolve: &'a dyn Fn(&str) -> Option<f64>,
    depth: usize,
    memo: &'a Memo,
}

/// Binary operator levels, lowest precedence first.
const LEVELS: [&[&str]; 7] = [
    &["||", "|^"],
    &["&&"],
    &["==", "!="],
    &["<", "<=", ">", ">="],
    &["+", "-"],
    &["*", "/", "%"],
    &["^"],
];

impl Parser<'_> {
    fn expression(&mut self) -> Result<f64, String> {
        self.binary(0)
    }

    /// Parses a left-associative chain of the operators at `level`.
    fn binary(&mut self, level: usize) -> Result<f64, String> {
        let Some(ops) = LEVELS.get(level) else {
            return self.unary();
        };
        let mut lhs = self.binary(level + 1)?;
        while let Some(op) = self.peek_op().filter(|op| ops.contains(op)) {
            self.pos += 1;
            let rhs = self.binary(level + 1)?;
            lhs = apply(op, lhs, rhs)?;
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> Result<f64, String> {
        match self.peek_op() {
            Some(op @ ("-" | "!")) => {
                self.pos += 1;
                let x = self.nested(Self::unary)?;
                Ok(if op == "-" { -x } else { truth(x == 0.0) })
            }
            _ => self.primary(),
        }
    }

    fn primary(&mut self) -> Result<f64, String> {
        let tok = self.tokens.get(self.pos).cloned();
        self.pos += 1;
        match tok {
            Some(Token::Num(x)) => Ok(x),
            Some(Token::Op("(")) => {
                let x = self.nested(Self::expression)?;
                self.expect(")")?;
                Ok(x)
            }
            Some(Token::Ident(name)) => match self.tokens.get(self.pos).cloned() {
                Some(Token::Op("(")) => {
                    self.pos += 1;
                    let args = self.nested(Self::arguments)?;
                    functions::math(&name, &args, self.resolve)
                }
                Some(Token::Word(arg)) => {
                    self.pos += 1;
                    functions::word(&name, &arg, self.resolve)
                }
                _ => self.identifier(&name),
            },
            Some(tok) => Err(format!("unexpected '{tok}' in expression")),
            None => Err("unexpected end of expression".into()),
        }
    }

    /// Parses comma-separated arguments up to and including the closing `)`.
    fn arguments(&mut self) -> Result<Vec<f64>, String> {
        let mut args = vec![self.expression()?];
        while self.peek_op() == Some(",") {
            self.pos += 1;
            args.push(self.expression()?);
        }
        self.expect(")")?;
        Ok(args)
    }

    fn identifier(&self, name: &str) -> Result<f64, String> {
        match name {
            "PI" => return Ok(std::f64::consts::PI),
            "version" => return Ok(VERSION),
            "on" | "yes" | "true" => return Ok(1.0),
            "off" | "no" | "false" => return Ok(0.0),
            _ => {}
        }
        match name.strip_prefix("v_") {
            Some(var) if !var.is_empty() && !var.contains('[') => {
                if let Some(&x) = self.memo.borrow().get(var) {
                    return Ok(x);
                }
                let x = variable(self.vars, var, self.resolve, self.depth, self.nesting, self.memo)?;
                self.memo.borrow_mut().insert(var.to_string(), x);
                Ok(x)
            }
            _ => (self.resolve)(name)
                .ok_or_else(|| format!("unknown identifier '{name}' in expression")),
        }
    }

    /// Runs `parse` one nesting level deeper, bounding recursion.
    fn nested<T>(&mut self, parse: fn(&mut Self) -> Result<T, String>) -> Result<T, String> {
        if self.nesting >= MAX_NESTING {
            return Err(format!("expression nested deeper than {MAX_NESTING}"));
        }
        self.nesting += 1;
        let result = parse(self);
        self.nesting -= 1;
        result
    }

    fn peek_op(&self) -> Option<&'static str> {
        match self.tokens.get(self.pos) {
            Some(Token::Op(op)) => Some(op),
            _ => None,
        }
    }

    fn expect(&mut self, op: &str) -> Result<(), String> {
        match self.tokens.get(self.pos) {
            Some(Token::Op(found)) if *found == op => {
                self.pos += 1;
                Ok(())
            }
            Some(tok) => Err(format!("expected '{op}' but found '{tok}'")),
            None => Err(format!("expected '{op}' at end of expression")),
        }
    }
}

fn truth(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}

/// Applies a binary operator.
fn apply(op: &str, a: f64, b: f64) -> Result<f64, String> {
    Ok(match op {
        "+" => a + b,
        "-" => a - b,
        "*" => a * b,
        "/" if b == 0.0 => return Err("division by zero".into()),
        "/" => a / b,
        "%" if b == 0.0 => return Err("modulo by zero".into()),
        "%" => a % b,
        "^" if a == 0.0 && b < 0.0 => return Err("zero raised to a negative power".into()),
        "^" => a.powf(b),
        "<" => truth(a < b),
        "<=" => truth(a <= b),
        ">" => truth(a > b),
        ">=" => truth(a >= b),
        "==" => truth(a == b),
        "!=" => truth(a != b),
        "&&" => truth(a != 0.0 && b != 0.0),
        "|^" => truth((a != 0.0) != (b != 0.0)),
        _ => truth(a != 0.0 || b != 0.0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::format_g;
    use crate::variables::Variables;

    fn eval(text: &str) -> Result<f64, String> {
        let thermo = |k: &str| match k {
            "step" => Some(100.0),
            "c_thermo_press[2]" => Some(-3.5),
            _ => None,
        };
        evaluate(text, &Variables::new(), &thermo)
    }

    fn ok(text: &str) -> f64 {
        eval(text).unwrap_or_else(|e| panic!("{text}: {e}"))
    }

    #[test]
    fn precedence_and_associativity() {
        // LAMMPS 22 Jul 2025 prints 4 and 64
        assert_eq!(ok("-2^2"), 4.0);
        assert_eq!(ok("2^3^2"), 64.0);
        assert_eq!(ok("2^-1"), 0.5);
        assert_eq!(ok("7%3"), 1.0);
        assert_eq!(ok("-7%3"), -1.0);
        assert_eq!(ok("1+2*3"), 7.0);
        assert_eq!(ok("(1+2)*3"), 9.0);
        assert_eq!(ok("8/2/2"), 2.0);
        assert_eq!(ok("10-2-3"), 5.0);
        assert_eq!(ok("1 + 2 < 4"), 1.0);
        assert_eq!(ok("1 < 2 == 1"), 1.0);
        assert_eq!(ok("1 || 0 && 0"), 1.0);
        assert_eq!(ok("!0 + !5"), 1.0);
        assert_eq!(ok("--3"), 3.0);
    }

    #[test]
    fn comparisons_and_logic() {
        let cases = [
            ("1<2", 1.0),
            ("2<1", 0.0),
            ("2<=2", 1.0),
            ("3>2", 1.0),
            ("2>=3", 0.0),
            ("2==2", 1.0),
            ("2!=2", 0.0),
            ("1&&0", 0.0),
            ("1&&2", 1.0),
            ("0||0", 0.0),
            ("0||3", 1.0),
        ];
        for (text, want) in cases {
            assert_eq!(ok(text), want, "{text}");
        }
    }

    #[test]
    fn numbers() {
        assert_eq!(ok("1e-3"), 0.001);
        assert_eq!(ok(".5"), 0.5);
        assert_eq!(ok("2.5E+2"), 250.0);
        assert_eq!(ok("3."), 3.0);
        assert!(eval("1.2.3").is_err());
        assert!(eval("1e").is_err());
    }

    #[test]
    fn functions_and_constants() {
        let close = |text: &str, want: f64| {
            let got = ok(text);
            assert!((got - want).abs() < 1e-12, "{text} = {got}, want {want}");
        };
        close("sqrt(16)", 4.0);
        close("exp(0)", 1.0);
        close("ln(exp(2))", 2.0);
        close("log(1000)", 3.0);
        close("abs(-2.5)", 2.5);
        close("sin(PI/2)", 1.0);
        close("cos(PI)", -1.0);
        close("tan(PI/4)", 1.0);
        close("asin(1)", std::f64::consts::FRAC_PI_2);
        close("acos(1)", 0.0);
        close("atan(1)", std::f64::consts::FRAC_PI_4);
        close("atan2(1,-1)", 3.0 * std::f64::consts::FRAC_PI_4);
        close("floor(-1.5) + ceil(1.2)", 0.0);
        close("round(2.5) + round(-2.5)", 1.0);
        close("min(3,-1) * max(2, 5)", -5.0);
        close("max(min(1,2), sqrt(2)^2)", 2.0);
    }

    /// LAMMPS 22 Jul 2025 prints these values (its variable.cpp math functions).
    #[test]
    fn lammps_functions_and_constants() {
        let at = |step: f64| move |k: &str| match k {
            "step" => Some(step),
            "dt" => Some(0.005),
            functions::RUN_BEGIN => Some(0.0),
            functions::RUN_END => Some(20.0),
            functions::RUN_ACTIVE => Some(1.0),
            _ => None,
        };
        let v = |text: &str, step: f64| evaluate(text, &Variables::new(), &at(step)).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(v("round(-2.5) + round(0.5)*10 + sign(-3)*100 + sign(0)*1000", 0.0), 908.0);
        assert_eq!(v("ternary(0,2,3) + (1|^1) + (1|^0||0)*10 + version + yes + off + true", 0.0), 20250722.0 + 3.0 + 10.0 + 2.0);
        assert_eq!(v("stagger(100,10) + logfreq(10,2,10) + logfreq2(10,4,10) + logfreq3(10,5,1000)", 0.0), 40.0);
        assert_eq!(v("stride(0,100,10) + stride2(0,1000,100,200,300,10)", 0.0), 110.0);
        // the thermo columns of a LAMMPS run 10 start 0 stop 20, dt 0.005
        let cols = "ramp(1,3) vdisplace(1,2) swiggle(1,2,0.02) cwiggle(1,2,0.02) stride(2,20,3) logfreq(1,2,3) stagger(4,1)";
        let rows = [(3.0, [1.3, 1.03, -1.0, 3.0, 5.0, 6.0, 4.0]), (9.0, [1.9, 1.09, 3.0, 3.0, 11.0, 18.0, 12.0])];
        for (step, want) in rows {
            for (f, w) in cols.split(' ').zip(want) {
                assert!((v(f, step) - w).abs() < 1e-12, "{f} at {step}: {} != {w}", v(f, step));
            }
        }
        assert_eq!(v("is_file(Cargo.toml) + is_file(surely/not/here) + extract_setting(dimension)", 0.0), 4.0);
        assert!(eval("extract_setting(foo)").unwrap_err().contains("Unknown setting foo"));
        assert!(eval("random(1,2,3)").unwrap_err().contains("not supported"));
        assert!(eval("stagger(1,2)").unwrap_err().contains("Invalid math function"));
    }

    #[test]
    fn resolved_identifiers() {
        assert_eq!(ok("step*2"), 200.0);
        assert_eq!(ok("c_thermo_press[2]+1"), -2.5);
        assert_eq!(
            eval("temp").unwrap_err(),
            "unknown identifier 'temp' in expression"
        );
        assert_eq!(eval("v_nope").unwrap_err(), "unknown variable 'nope'");
    }

    #[test]
    fn arithmetic_errors() {
        assert_eq!(eval("1/0").unwrap_err(), "division by zero");
        assert_eq!(eval("1/(2-2)").unwrap_err(), "division by zero");
        assert_eq!(eval("5%0").unwrap_err(), "modulo by zero");
        assert!(eval("0^-1").is_err());
        assert_eq!(eval("sqrt(-1)").unwrap_err(), "sqrt(-1) is undefined");
        assert!(eval("ln(0)").is_err());
        assert!(eval("asin(2)").is_err());
        assert!(eval("exp(1000)").is_err());
        assert!(eval("10^400").is_err());
    }

    #[test]
    fn syntax_errors() {
        for text in [
            "",
            "  ",
            "1+",
            "(1",
            "1)",
            "sqrt(1,2)",
            "min(1)",
            "foo(1)",
            "2 3",
            "1 # 2",
            "c_x[1",
            "()",
        ] {
            assert!(eval(text).is_err(), "{text:?} accepted");
        }
        assert_eq!(eval("foo(1)").unwrap_err(), "unknown function 'foo()'");
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_crash() {
        let deep = format!("{}1{}", "(".repeat(100_000), ")".repeat(100_000));
        assert!(eval(&deep).is_err());
        assert!(eval(&"-".repeat(100_000)).is_err());
        assert_eq!(ok(&format!("{}1{}", "(".repeat(100), ")".repeat(100))), 1.0);
    }

    #[test]
    fn variable_recursion_is_detected() {
        use crate::command::{Command, Location};
        let mut vars = Variables::new();
        let define = |vars: &mut Variables, name: &str, text: &str| {
            let cmd = Command {
                name: "variable".into(),
                args: vec![name.into(), "equal".into(), text.into()],
                loc: Location {
                    file: "t".into(),
                    line: 1,
                },
            };
            vars.define(&cmd).unwrap();
        };
        define(&mut vars, "a", "v_b+1");
        define(&mut vars, "b", "v_a+1");
        define(&mut vars, "c", "2*v_d");
        define(&mut vars, "d", "21");
        let none = |_: &str| None;
        let err = evaluate("v_a", &vars, &none).unwrap_err();
        assert!(err.contains("nested deeper than 64"), "{err}");
        assert_eq!(evaluate("v_c", &vars, &none), Ok(42.0));
    }

    /// Fuzzing regression (target `script`): a chain of variables each
    /// reading the previous one twice took 2^39 evaluations, a hang.
    /// Minimised input: `variable a0 equal 1`, then
    /// `variable aI equal v_aJ+v_aJ` for I = 1..39 (J = I-1), then
    /// `print $(v_a39)`.
    #[test]
    fn fuzz_doubling_variable_chain_is_linear() {
        use crate::script::ScriptReader;
        let mut text = String::from("variable a0 equal 1\n");
        for i in 1..40 {
            text += &format!("variable a{i} equal v_a{}+v_a{}\n", i - 1, i - 1);
        }
        text += "print $(v_a39) ${a39}\n";
        let none = |_: &str| None;
        let start = std::time::Instant::now();
        let mut reader = ScriptReader::from_string("fuzz.in", &text);
        let mut vars = Variables::new();
        let mut printed = None;
        while let Some(cmd) = reader.next_command(&vars, &none).unwrap() {
            if cmd.name == "variable" {
                vars.define(&cmd).unwrap();
            } else {
                printed = Some(cmd.args);
            }
        }
        let want = format_g(2f64.powi(39), 20);
        assert_eq!(printed, Some(vec![want, "549755813888".to_string()]));
        assert_eq!(evaluate("v_a39", &vars, &none), Ok(2f64.powi(39)));
        assert!(start.elapsed().as_secs() < 5, "took {:?}", start.elapsed());
    }
}
