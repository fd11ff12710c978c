//! The store of LAMMPS-style script variables (`variable` command).

use std::collections::HashMap;

use crate::command::{Command, ScriptError};
use crate::expr::{self, VariableLookup};
use crate::format::format_g;

/// Named script variables of styles `index`, `loop`, `equal` and `string`.
#[derive(Clone, Debug, Default)]
pub struct Variables {
    vars: HashMap<String, Var>,
}

#[derive(Clone, Debug)]
enum Var {
    /// A list of strings and the position of the current one.
    Index { values: Vec<String>, pos: usize },
    /// Integers `first..=last`; `pad` zero-pads to the width of `last`.
    Loop { current: i64, last: i64, pad: bool },
    /// An expression evaluated each time the variable is used.
    Equal(String),
    /// A fixed string.
    Str(String),
    /// An expression with one value per particle (per-particle names `x`, `vx`, `mass`,
    /// `type`, `id`, ... are resolved for each particle).
    Atom(String),
    /// A number set by the `variable` command (LAMMPS's internal style), as written.
    Internal(String),
}

impl Var {
    fn style(&self) -> &'static str {
        match self {
            Var::Index { .. } => "index",
            Var::Loop { .. } => "loop",
            Var::Equal(_) => "equal",
            Var::Str(_) => "string",
            Var::Atom(_) => "atom",
            Var::Internal(_) => "internal",
        }
    }
}

impl Variables {
    /// Creates an empty store.
    pub fn new() -> Self {
        Self::default()
    }

    /// Applies a `variable NAME STYLE args...` command. Existing `index` and
    /// `loop` variables are left unchanged (so command-line values win);
    /// `equal` and `string` variables are redefined. (A `string` value arrives
    /// substituted: the interpreter substitutes it, as LAMMPS's variable.cpp does.)
    pub fn define(&mut self, cmd: &Command) -> Result<(), ScriptError> {
        let err = |msg: String| ScriptError::at(cmd, msg);
        let [name, style, rest @ ..] = cmd.args.as_slice() else {
            return Err(err("expected a name and a style".into()));
        };
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(err(format!(
                "variable name '{name}' must consist of letters, digits and underscores"
            )));
        }
        let existing = self.vars.get(name);
        let var = match style.as_str() {
            "delete" if rest.is_empty() => {
                self.vars.remove(name);
                return Ok(());
            }
            "index" | "loop" if existing.is_some() => return Ok(()),
            "index" if !rest.is_empty() => Var::Index {
                values: rest.to_vec(),
                pos: 0,
            },
            "loop" => parse_loop(rest).map_err(err)?,
            "equal" | "string" | "atom" => {
                let [value] = rest else {
                    return Err(err(format!(
                        "{style}-style variable takes exactly one value (quote it if it has spaces)"
                    )));
                };
                match existing.map(Var::style) {
                    Some(old) if old != style => {
                        return Err(err(format!(
                            "cannot redefine {old}-style variable '{name}' as {style}-style"
                        )))
                    }
                    _ if style == "equal" => Var::Equal(value.clone()),
                    _ if style == "atom" => Var::Atom(value.clone()),
                    _ => Var::Str(value.clone()),
                }
            }
            "internal" => {
                let [value] = rest else {
                    return Err(err(format!("Illegal variable command: expected 3 arguments but found {}", cmd.args.len())));
                };
                if !value.parse::<f64>().is_ok_and(f64::is_finite) {
                    return Err(err(format!("Expected floating point parameter instead of '{value}'")));
                }
                match existing.map(Var::style) {
                    Some(old) if old != "internal" => {
                        return Err(err(format!("cannot redefine {old}-style variable '{name}' as internal-style")))
                    }
                    _ => Var::Internal(value.clone()),
                }
            }
            "delete" | "index" => {
                return Err(err(format!("wrong number of arguments for {style}-style")))
            }
            _ => return Err(err(format!("unsupported variable style '{style}'"))),
        };
        self.vars.insert(name.clone(), var);
        Ok(())
    }

    /// Defines (or replaces) an index-style variable given on the command line.
    pub fn set_command_line(&mut self, name: &str, values: Vec<String>) {
        self.vars
            .insert(name.to_string(), Var::Index { values, pos: 0 });
    }

    /// Advances the named index/loop variables (the `next` command). Returns
    /// true if any of them was exhausted; exhausted variables are deleted.
    pub fn next(&mut self, names: &[String]) -> Result<bool, ScriptError> {
        if names.is_empty() {
            return Err(next_error("expected at least one variable name".into()));
        }
        for name in names {
            match self.vars.get(name) {
                Some(Var::Index { .. } | Var::Loop { .. }) => {}
                Some(var) => {
                    return Err(next_error(format!(
                        "variable '{name}' is {}-style, not index or loop",
                        var.style()
                    )))
                }
                None => return Err(next_error(format!("unknown variable '{name}'"))),
            }
        }
        let mut exhausted = false;
        for name in names {
            let done = match self.vars.get_mut(name) {
                Some(Var::Index { values, pos }) => {
                    *pos += 1;
                    *pos >= values.len()
                }
                Some(Var::Loop { current, last, .. }) if *current < *last => {
                    *current += 1;
                    false
                }
                Some(Var::Loop { .. }) => true,
                _ => false,
            };
            if done {
                self.vars.remove(name);
                exhausted = true;
            }
        }
        Ok(exhausted)
    }

    /// The current value of a variable as text; `equal` variables are
    /// evaluated (with `resolve` for thermo keywords) and printed as `%.15g`.
    pub fn value(
        &self,
        name: &str,
        resolve: &dyn Fn(&str) -> Option<f64>,
    ) -> Result<String, String> {
        match self.vars.get(name) {
            None => Err(format!("unknown variable '{name}'")),
            Some(Var::Index { values, pos }) => values
                .get(*pos)
                .cloned()
                .ok_or_else(|| format!("index variable '{name}' has no values")),
            Some(Var::Loop { current, last, pad }) => Ok(if *pad {
                format!("{current:0width$}", width = last.to_string().len())
            } else {
                current.to_string()
            }),
            Some(Var::Str(s)) => Ok(s.clone()),
            Some(Var::Equal(_) | Var::Internal(_)) => expr::variable(self, name, resolve, 0, 0, &expr::Memo::default())
                .map(|x| format_g(x, 15))
                .map_err(|e| format!("variable '{name}': {e}")),
            Some(Var::Atom(_)) => Err(format!(
                "variable '{name}' is atom-style (a value per particle): read it in dump custom, compute reduce, fix ave/chunk, set or velocity"
            )),
        }
    }

    /// The style of a variable (`index`, `loop`, `equal`, `string`, `atom`, `internal`).
    pub fn style(&self, name: &str) -> Option<&'static str> {
        self.vars.get(name).map(Var::style)
    }

    /// The value of equal- or atom-style variable `name` for one particle, whose
    /// per-particle names (and any global name) `resolve` gives.
    pub fn evaluate_atom(&self, name: &str, resolve: &dyn Fn(&str) -> Option<f64>) -> Result<f64, String> {
        expr::variable(&AtomScope(self), name, resolve, 0, 0, &expr::Memo::default())
            .map_err(|e| format!("variable '{name}': {e}"))
    }

    /// Whether a variable of this name exists.
    pub fn contains(&self, name: &str) -> bool {
        self.vars.contains_key(name)
    }
}

impl VariableLookup for Variables {
    fn expression(&self, name: &str) -> Option<&str> {
        match self.vars.get(name) {
            Some(Var::Equal(text) | Var::Internal(text)) => Some(text),
            _ => None,
        }
    }

    fn text(&self, name: &str, resolve: &dyn Fn(&str) -> Option<f64>) -> Result<String, String> {
        self.value(name, resolve)
    }
}

/// The variables as an atom-style expression reads them: `v_name` of an atom-style
/// variable is evaluated for the same particle.
struct AtomScope<'a>(&'a Variables);

impl VariableLookup for AtomScope<'_> {
    fn expression(&self, name: &str) -> Option<&str> {
        match self.0.vars.get(name) {
            Some(Var::Equal(text) | Var::Atom(text) | Var::Internal(text)) => Some(text),
            _ => None,
        }
    }

    fn text(&self, name: &str, resolve: &dyn Fn(&str) -> Option<f64>) -> Result<String, String> {
        self.0.value(name, resolve)
    }
}

/// An error from the `next` command (the caller knows its location).
fn next_error(message: String) -> ScriptError {
    ScriptError {
        loc: None,
        command: Some("next".into()),
        message,
    }
}

/// Parses the arguments of `loop N [pad]` or `loop N1 N2 [pad]`.
fn parse_loop(args: &[String]) -> Result<Var, String> {
    let (numbers, pad) = match args.split_last() {
        Some((last, init)) if last == "pad" => (init, true),
        _ => (args, false),
    };
    let int = |s: &String| {
        s.parse::<i64>()
            .map_err(|_| format!("loop bound '{s}' is not an integer"))
    };
    let (first, last) = match numbers {
        [n] => (1, int(n)?),
        [a, b] => (int(a)?, int(b)?),
        _ => return Err("loop-style expects 'loop N' or 'loop N1 N2' (optionally 'pad')".into()),
    };
    if last < first || last < 1 {
        return Err(format!("empty loop range {first}..{last}"));
    }
    Ok(Var::Loop {
        current: first,
        last,
        pad,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::Location;

    fn cmd(line: &str) -> Command {
        let mut words = line.split_whitespace().map(str::to_string);
        Command {
            name: words.next().unwrap_or_default(),
            args: words.collect(),
            loc: Location {
                file: "test.in".into(),
                line: 1,
            },
        }
    }

    fn none(_: &str) -> Option<f64> {
        None
    }

    fn val(vars: &Variables, name: &str) -> String {
        vars.value(name, &none).unwrap_or_else(|e| panic!("{e}"))
    }

    /// An atom variable reads per-particle names (and other atom variables) from the
    /// resolver of one particle; read as one number it is an error.
    #[test]
    fn atom_variables_evaluate_per_particle() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable k equal 3")).unwrap();
        vars.define(&cmd("variable a atom x*v_k+type")).unwrap();
        vars.define(&cmd("variable b atom v_a^2")).unwrap();
        for (x, t) in [(1.0, 2.0), (-0.5, 1.0)] {
            let particle = |n: &str| match n {
                "x" => Some(x),
                "type" => Some(t),
                _ => None,
            };
            assert_eq!(vars.evaluate_atom("a", &particle), Ok(3.0 * x + t));
            assert_eq!(vars.evaluate_atom("b", &particle), Ok((3.0 * x + t).powi(2)));
        }
        assert_eq!(vars.style("a"), Some("atom"));
        assert!(vars.value("a", &none).unwrap_err().contains("atom-style"));
        vars.define(&cmd("variable e equal v_a+1")).unwrap();
        assert!(vars.value("e", &none).unwrap_err().contains("atom-style"));
        assert!(vars.define(&cmd("variable k atom x")).is_err(), "equal redefined as atom");
    }

    /// LAMMPS's internal style: a number, read as an equal-style variable is, redefined
    /// only as internal; a non-number is refused with LAMMPS's words.
    #[test]
    fn internal_variables_hold_a_number() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable a internal 1.5")).unwrap();
        vars.define(&cmd("variable e equal v_a*2")).unwrap();
        assert_eq!(vars.style("a"), Some("internal"));
        assert_eq!(val(&vars, "a"), "1.5");
        assert_eq!(val(&vars, "e"), "3");
        vars.define(&cmd("variable a internal -2e-3")).unwrap();
        assert_eq!(val(&vars, "e"), "-0.004");
        let e = vars.define(&cmd("variable a internal x")).unwrap_err().to_string();
        assert!(e.contains("Expected floating point parameter instead of 'x'"), "{e}");
        assert!(vars.define(&cmd("variable a internal 1 2")).is_err(), "two values");
        assert!(vars.define(&cmd("variable e internal 1")).is_err(), "equal redefined as internal");
        assert!(vars.define(&cmd("variable a equal 1")).is_err(), "internal redefined as equal");
    }

    #[test]
    fn index_values_advance_and_exhaust() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable T index 300 400")).unwrap();
        assert_eq!(val(&vars, "T"), "300");
        assert!(!vars.next(&["T".into()]).unwrap());
        assert_eq!(val(&vars, "T"), "400");
        assert!(vars.next(&["T".into()]).unwrap());
        assert!(!vars.contains("T"));
    }

    #[test]
    fn command_line_index_takes_precedence() {
        let mut vars = Variables::new();
        vars.set_command_line("T", vec!["1.5".into()]);
        vars.define(&cmd("variable T index 300")).unwrap();
        vars.define(&cmd("variable T loop 5")).unwrap();
        assert_eq!(val(&vars, "T"), "1.5");
    }

    #[test]
    fn loop_counts_then_exhausts() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable i loop 2 4")).unwrap();
        let mut seen = vec![val(&vars, "i")];
        while !vars.next(&["i".into()]).unwrap() {
            seen.push(val(&vars, "i"));
        }
        assert_eq!(seen, ["2", "3", "4"]);
        assert!(!vars.contains("i"));
        assert!(vars.next(&["i".into()]).is_err());
    }

    #[test]
    fn loop_pad_and_bad_ranges() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable n loop 100 pad")).unwrap();
        assert_eq!(val(&vars, "n"), "001");
        let max = i64::MAX;
        vars.define(&cmd(&format!("variable big loop {max} {max}")))
            .unwrap();
        assert!(vars.next(&["big".into()]).unwrap());
        for bad in [
            "variable a loop 0",
            "variable a loop 5 2",
            "variable a loop x",
            "variable a loop",
        ] {
            assert!(vars.define(&cmd(bad)).is_err(), "{bad}");
        }
    }

    #[test]
    fn equal_and_string_are_redefined() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable x equal 1+2")).unwrap();
        vars.define(&cmd("variable x equal 3/2")).unwrap();
        assert_eq!(val(&vars, "x"), "1.5");
        vars.define(&cmd("variable s string abc")).unwrap();
        vars.define(&cmd("variable s string def")).unwrap();
        assert_eq!(val(&vars, "s"), "def");
        let err = vars.define(&cmd("variable s equal 1")).unwrap_err();
        assert!(err.message.contains("cannot redefine"), "{err}");
    }

    #[test]
    fn equal_formats_like_lammps() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable a equal 1e-20")).unwrap();
        vars.define(&cmd("variable b equal 6/2")).unwrap();
        vars.define(&cmd("variable c equal v_b*step")).unwrap();
        assert_eq!(val(&vars, "a"), "1e-20");
        assert_eq!(val(&vars, "b"), "3");
        let step = |k: &str| (k == "step").then_some(1000.0);
        assert_eq!(vars.value("c", &step).unwrap(), "3000");
    }

    #[test]
    fn delete_and_errors() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable s string abc")).unwrap();
        vars.define(&cmd("variable s delete")).unwrap();
        assert!(!vars.contains("s"));
        assert_eq!(vars.value("s", &none).unwrap_err(), "unknown variable 's'");
        for bad in [
            "variable",
            "variable x",
            "variable x equal 1 + 2",
            "variable x index",
            "variable x world a b",
            "variable x-y string a",
        ] {
            let err = vars.define(&cmd(bad)).unwrap_err();
            assert!(
                err.to_string().starts_with("test.in:1: variable: "),
                "{err}"
            );
        }
        vars.define(&cmd("variable e equal 1")).unwrap();
        let err = vars.next(&["e".into()]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "next: variable 'e' is equal-style, not index or loop"
        );
        assert!(vars.next(&[]).is_err());
    }

    #[test]
    fn non_numeric_variable_in_expression() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable s string abc")).unwrap();
        vars.define(&cmd("variable x equal v_s+1")).unwrap();
        let err = vars.value("x", &none).unwrap_err();
        assert!(err.contains("'s' is not numeric"), "{err}");
    }
}
