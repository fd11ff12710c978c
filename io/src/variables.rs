//! The store of LAMMPS-style script variables (`variable` command), one partition:
//! a `world` variable holds its one value, `universe` and `uloop` step as `index` and
//! `loop` do.

use std::collections::HashMap;

use crate::command::{Command, ScriptError};
use crate::expr::{self, VariableLookup};
use crate::format::{format_g, format_printf};

/// Named script variables of every LAMMPS style but python and vector.
#[derive(Clone, Debug, Default)]
pub struct Variables {
    vars: HashMap<String, Var>,
    /// The next index of the universe and uloop variables (LAMMPS's tmp.lammps.variable:
    /// the partition count, 1, at each definition, one more at each `next`).
    universe_next: usize,
}

/// When the program started: timer variables hold the seconds since (LAMMPS's
/// platform::walltime).
static STARTED: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();

#[derive(Clone, Debug)]
enum Var {
    /// A list of strings and the position of the current one (`universe`: stepped by
    /// `next` as the one partition's index).
    Index { values: Vec<String>, pos: usize, universe: bool },
    /// Integers `first..=last`; `pad` zero-pads to the width of `last` (`uloop`: 1..=N).
    Loop { current: i64, last: i64, pad: bool, universe: bool },
    /// The value of the one partition.
    World(String),
    /// An expression evaluated each time the variable is used.
    Equal(String),
    /// A fixed string.
    Str(String),
    /// An expression with one value per particle (per-particle names `x`, `vx`, `mass`,
    /// `type`, `id`, ... are resolved for each particle).
    Atom(String),
    /// A number set by the `variable` command (LAMMPS's internal style), as written.
    Internal(String),
    /// The wall-clock seconds when it was defined, in round-trip form.
    Timer(String),
    /// The name of an environment variable, read each time.
    Getenv(String),
    /// The values of a file, one a line, and the position of the current one.
    File { values: Vec<String>, pos: usize },
    /// Snapshots of per-particle values by tag, and the position of the current one.
    AtomFile { snapshots: Vec<HashMap<u64, f64>>, pos: usize },
    /// An equal-style variable printed with a C format.
    Format { variable: String, format: String },
}

impl Var {
    fn style(&self) -> &'static str {
        match self {
            Var::Index { universe: false, .. } => "index",
            Var::Index { .. } => "universe",
            Var::Loop { universe: false, .. } => "loop",
            Var::Loop { .. } => "uloop",
            Var::World(_) => "world",
            Var::Equal(_) => "equal",
            Var::Str(_) => "string",
            Var::Atom(_) => "atom",
            Var::Internal(_) => "internal",
            Var::Timer(_) => "timer",
            Var::Getenv(_) => "getenv",
            Var::File { .. } => "file",
            Var::AtomFile { .. } => "atomfile",
            Var::Format { .. } => "format",
        }
    }

    /// Whether it evaluates to one number (LAMMPS's equalstyle).
    fn is_equal(&self) -> bool {
        matches!(self, Var::Equal(_) | Var::Internal(_) | Var::Timer(_))
    }
}

/// LAMMPS's check of a format variable's format (validfmt).
fn valid_format(f: &str) -> bool {
    let Some(rest) = f.strip_prefix('%') else { return false };
    let rest = rest.strip_prefix(' ').unwrap_or(rest);
    let rest = rest.strip_prefix('-').unwrap_or(rest);
    let rest = rest.trim_start_matches(|c: char| c.is_ascii_digit());
    let rest = rest.strip_prefix('.').unwrap_or(rest);
    let rest = rest.trim_start_matches(|c: char| c.is_ascii_digit());
    matches!(rest, "e" | "f" | "g" | "E" | "F" | "G")
}

/// The values of a file variable's file (LAMMPS's VarReader): each line up to a `#`,
/// trimmed; blank lines skipped.
fn file_values(path: &str) -> Result<Vec<String>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("Cannot open file variable file {path}: {e}"))?;
    Ok(text.lines().filter_map(|l| Some(l.split('#').next()?.trim()).filter(|v| !v.is_empty()).map(str::to_string)).collect())
}

/// The snapshots of an atomfile variable's file: a count N, then N lines `ID value`
/// (LAMMPS's VarReader::read_peratom).
fn atomfile_snapshots(path: &str) -> Result<Vec<HashMap<u64, f64>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("Cannot open file variable file {path}: {e}"))?;
    let mut lines = text.lines();
    let mut snapshots = Vec::new();
    while let Some(line) = lines.next() {
        let Some(count) = line.split('#').next().and_then(|l| l.split_whitespace().next()) else { continue };
        let n: usize = count.parse().map_err(|_| format!("Expected integer parameter instead of '{count}' in atomfile {path}"))?;
        let mut values = HashMap::new();
        for _ in 0..n {
            let line = lines.next().ok_or_else(|| format!("atomfile {path} ends inside a snapshot of {n} lines"))?;
            let mut words = line.split_whitespace();
            let parsed = (words.next().and_then(|w| w.parse::<u64>().ok()), words.next().and_then(|w| w.parse::<f64>().ok()));
            let (Some(tag), Some(value)) = parsed else { return Err(format!("Invalid atomfile line '{line}'")) };
            if tag == 0 {
                return Err(format!("Invalid atom ID {tag} in variable file"));
            }
            values.insert(tag, value);
        }
        snapshots.push(values);
    }
    Ok(snapshots)
}

impl Variables {
    /// Creates an empty store (and starts the clock of timer variables).
    pub fn new() -> Self {
        STARTED.get_or_init(std::time::Instant::now);
        Self::default()
    }

    /// Applies a `variable NAME STYLE args...` command as LAMMPS's Variable::set: an
    /// existing `index`, `loop`, `world`, `universe`, `uloop`, `file`, `atomfile`
    /// variable is left unchanged (so command-line values win); `equal`, `string`, `atom`,
    /// `internal`, `getenv`, `format` and `timer` variables are redefined, as the same
    /// style only. (A `string` value arrives substituted: the interpreter substitutes it,
    /// as LAMMPS's variable.cpp does.)
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
        let one = || match rest {
            [value] => Ok(value),
            _ => Err(err(format!("Illegal variable command: expected 3 arguments but found {}", cmd.args.len()))),
        };
        let redefinable = |style: &str| match existing.map(Var::style) {
            Some(old) if old != style => Err(err(format!("cannot redefine {old}-style variable '{name}' as {style}-style"))),
            _ => Ok(()),
        };
        let var = match style.as_str() {
            "delete" if rest.is_empty() => {
                self.vars.remove(name);
                return Ok(());
            }
            "index" | "loop" | "world" | "universe" | "uloop" | "file" | "atomfile" if existing.is_some() => return Ok(()),
            "index" | "universe" if !rest.is_empty() => {
                let universe = style == "universe";
                if universe {
                    self.same_universe_count(rest.len() as i64).map_err(err)?;
                    self.universe_next = 1;
                }
                Var::Index { values: rest.to_vec(), pos: 0, universe }
            }
            "loop" => parse_loop(rest).map_err(err)?,
            "uloop" => {
                let (n, pad) = match rest {
                    [n] => (n, false),
                    [n, pad] if pad == "pad" => (n, true),
                    [_, other] => return Err(err(format!("Invalid variable uloop argument: {other}"))),
                    _ => return Err(err(format!("Illegal variable command: expected 3 or 4 arguments but found {}", cmd.args.len()))),
                };
                let last = n.parse::<i64>().map_err(|_| err(format!("Expected integer parameter instead of '{n}' in input script or data file")))?;
                if last < 1 {
                    return Err(err("Universe/uloop variable count < # of partitions".into()));
                }
                self.same_universe_count(last).map_err(err)?;
                self.universe_next = 1;
                Var::Loop { current: 1, last, pad, universe: true }
            }
            "world" if !rest.is_empty() => match rest {
                [value] => Var::World(value.clone()),
                _ => return Err(err("World variable count doesn't match # of partitions".into())),
            },
            "equal" | "string" | "atom" => {
                let [value] = rest else {
                    return Err(err(format!(
                        "{style}-style variable takes exactly one value (quote it if it has spaces)"
                    )));
                };
                redefinable(style)?;
                match style.as_str() {
                    "equal" => Var::Equal(value.clone()),
                    "atom" => Var::Atom(value.clone()),
                    _ => Var::Str(value.clone()),
                }
            }
            "internal" => {
                let value = one()?;
                if !value.parse::<f64>().is_ok_and(f64::is_finite) {
                    return Err(err(format!("Expected floating point parameter instead of '{value}'")));
                }
                redefinable(style)?;
                Var::Internal(value.clone())
            }
            "getenv" => {
                let value = one()?;
                redefinable(style)?;
                Var::Getenv(value.clone())
            }
            "timer" => {
                if !rest.is_empty() {
                    return Err(err(format!("Illegal variable command: expected 2 arguments but found {}", cmd.args.len())));
                }
                redefinable(style)?;
                Var::Timer(format!("{:?}", STARTED.get_or_init(std::time::Instant::now).elapsed().as_secs_f64()))
            }
            "file" => {
                let values = file_values(one()?).map_err(err)?;
                if values.is_empty() {
                    return Err(err("File variable could not read value".into()));
                }
                Var::File { values, pos: 0 }
            }
            "atomfile" => {
                let snapshots = atomfile_snapshots(one()?).map_err(err)?;
                if snapshots.is_empty() {
                    return Err(err("Atomfile variable could not read values".into()));
                }
                Var::AtomFile { snapshots, pos: 0 }
            }
            "format" => {
                let [variable, format] = rest else {
                    return Err(err(format!("Illegal variable command: expected 4 arguments but found {}", cmd.args.len())));
                };
                match self.vars.get(variable) {
                    None => return Err(err(format!("Variable {name}: format variable {variable} does not exist"))),
                    Some(v) if !v.is_equal() => return Err(err(format!("Variable {name}: format variable {variable} has incompatible style"))),
                    _ => {}
                }
                redefinable(style)?;
                if !valid_format(format) {
                    return Err(err("Incorrect conversion in format string".into()));
                }
                Var::Format { variable: variable.clone(), format: format.clone() }
            }
            "delete" | "index" | "universe" | "world" => {
                return Err(err(format!("wrong number of arguments for {style}-style")))
            }
            "python" | "vector" => return Err(err(format!("variable style '{style}' is not supported (gendpde embeds no Python and has no vector-valued variables)"))),
            _ => return Err(err(format!("Unknown variable keyword: {style}"))),
        };
        self.vars.insert(name.clone(), var);
        Ok(())
    }

    /// Err unless every universe and uloop variable has `n` values (LAMMPS's rule).
    fn same_universe_count(&self, n: i64) -> Result<(), String> {
        let differs = self.vars.values().any(|v| match v {
            Var::Index { values, universe: true, .. } => values.len() as i64 != n,
            Var::Loop { last, universe: true, .. } => *last != n,
            _ => false,
        });
        if differs { Err("All universe/uloop variables must have same # of values".into()) } else { Ok(()) }
    }

    /// Defines (or replaces) an index-style variable given on the command line.
    pub fn set_command_line(&mut self, name: &str, values: Vec<String>) {
        self.vars
            .insert(name.to_string(), Var::Index { values, pos: 0, universe: false });
    }

    /// Advances the named variables (the `next` command) as LAMMPS's Variable::next:
    /// all of one style (universe and uloop mix), of a style that steps (index, loop,
    /// universe, uloop, file, atomfile), every universe and uloop variable listed. Returns
    /// whether any of them was exhausted (exhausted variables are deleted) and, for
    /// universe and uloop variables, the index LAMMPS reports ("Increment via next: value
    /// N on partition 0").
    pub fn next(&mut self, names: &[String]) -> Result<(bool, Option<usize>), ScriptError> {
        let family = |v: &Var| match v.style() {
            "uloop" => "universe",
            s => s,
        };
        let mut styles = Vec::new();
        for name in names {
            match self.vars.get(name) {
                Some(var) => styles.push(family(var)),
                None => return Err(next_error(format!("Invalid variable '{name}' in next command"))),
            }
        }
        let Some(&first) = styles.first() else {
            return Err(next_error("expected at least one variable name".into()));
        };
        if styles.iter().any(|s| *s != first) {
            return Err(next_error("All variables in next command must have same style".into()));
        }
        if !matches!(first, "index" | "loop" | "universe" | "file" | "atomfile") {
            return Err(next_error(format!("Invalid variable style with next command: '{}' is {first}-style", names[0])));
        }
        if first == "universe" && self.vars.iter().any(|(n, v)| family(v) == "universe" && !names.contains(n)) {
            return Err(next_error("Next command must list all universe and uloop variables".into()));
        }
        let universe = first == "universe";
        let index = self.universe_next;
        if universe {
            self.universe_next += 1;
        }
        let mut exhausted = false;
        for name in names {
            let done = match self.vars.get_mut(name) {
                Some(Var::Index { values, pos, universe: true }) => {
                    *pos = index;
                    *pos >= values.len()
                }
                Some(Var::Loop { current, last, universe: true, .. }) => {
                    *current = index as i64 + 1;
                    *current > *last
                }
                Some(Var::Index { values, pos, .. }) => {
                    *pos += 1;
                    *pos >= values.len()
                }
                Some(Var::File { values, pos }) => {
                    *pos += 1;
                    *pos >= values.len()
                }
                Some(Var::AtomFile { snapshots, pos }) => {
                    *pos += 1;
                    *pos >= snapshots.len()
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
        Ok((exhausted, universe.then_some(self.universe_next)))
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
            Some(Var::Index { values, pos, .. }) => values
                .get(*pos)
                .cloned()
                .ok_or_else(|| format!("index variable '{name}' has no values")),
            Some(Var::World(s)) => Ok(s.clone()),
            Some(Var::File { values, pos }) => Ok(values[*pos].clone()),
            Some(Var::Getenv(env)) => Ok(std::env::var(env).unwrap_or_default()),
            Some(Var::Format { variable, format }) => match self.vars.get(variable) {
                None => Err(format!("Variable {name}: format variable {variable} does not exist")),
                Some(v) if !v.is_equal() => Err(format!("Variable {name}: format variable {variable} has incompatible style")),
                _ => expr::variable(self, variable, resolve, 0, 0, &expr::Memo::default())
                    .and_then(|x| format_printf(format, x))
                    .map_err(|e| format!("variable '{name}': {e}")),
            },
            Some(Var::Loop { current, last, pad, .. }) => Ok(if *pad {
                format!("{current:0width$}", width = last.to_string().len())
            } else {
                current.to_string()
            }),
            Some(Var::Str(s)) => Ok(s.clone()),
            Some(Var::Equal(_) | Var::Internal(_) | Var::Timer(_)) => expr::variable(self, name, resolve, 0, 0, &expr::Memo::default())
                .map(|x| format_g(x, 15))
                .map_err(|e| format!("variable '{name}': {e}")),
            Some(v @ (Var::Atom(_) | Var::AtomFile { .. })) => Err(format!(
                "variable '{name}' is {}-style (a value per particle): read it in dump custom, compute reduce, fix ave/chunk, set or velocity",
                v.style()
            )),
        }
    }

    /// The style of a variable (`index`, `loop`, `equal`, `string`, `atom`, `internal`,
    /// `atomfile`, ...).
    pub fn style(&self, name: &str) -> Option<&'static str> {
        self.vars.get(name).map(Var::style)
    }

    /// The value of equal- or atom-style variable `name` for one particle, whose
    /// per-particle names (and any global name) `resolve` gives.
    pub fn evaluate_atom(&self, name: &str, resolve: &dyn Fn(&str) -> Option<f64>) -> Result<f64, String> {
        expr::variable(&AtomScope(self), name, resolve, 0, 0, &expr::Memo::default())
            .map_err(|e| format!("variable '{name}': {e}"))
    }

    /// The names and styles of the variables, by name.
    pub fn names(&self) -> Vec<(&str, &'static str)> {
        let mut v: Vec<_> = self.vars.iter().map(|(n, var)| (n.as_str(), var.style())).collect();
        v.sort_unstable();
        v
    }

    /// Whether a variable of this name exists.
    pub fn contains(&self, name: &str) -> bool {
        self.vars.contains_key(name)
    }
}

impl VariableLookup for Variables {
    fn expression(&self, name: &str) -> Option<&str> {
        match self.vars.get(name) {
            Some(Var::Equal(text) | Var::Internal(text) | Var::Timer(text)) => Some(text),
            _ => None,
        }
    }

    fn text(&self, name: &str, resolve: &dyn Fn(&str) -> Option<f64>) -> Result<String, String> {
        self.value(name, resolve)
    }
}

/// The variables as an atom-style expression reads them: `v_name` of an atom-style
/// variable is evaluated for the same particle, an atomfile variable gives the value of
/// the particle's tag (`id`; 0 for a tag its file does not list, as LAMMPS).
struct AtomScope<'a>(&'a Variables);

impl VariableLookup for AtomScope<'_> {
    fn expression(&self, name: &str) -> Option<&str> {
        match self.0.vars.get(name) {
            Some(Var::Atom(text)) => Some(text),
            _ => self.0.expression(name),
        }
    }

    fn text(&self, name: &str, resolve: &dyn Fn(&str) -> Option<f64>) -> Result<String, String> {
        match self.0.vars.get(name) {
            Some(Var::AtomFile { snapshots, pos }) => {
                let tag = resolve("id").ok_or_else(|| format!("variable '{name}' is atomfile-style: it has a value per particle only"))?;
                Ok(format!("{:?}", snapshots[*pos].get(&(tag as u64)).copied().unwrap_or(0.0)))
            }
            _ => self.0.value(name, resolve),
        }
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
        universe: false,
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

    /// One partition: world holds its one value, universe and uloop step as index and
    /// loop through the shared counter, listed together; file variables step through the
    /// lines; format prints an equal-style variable; getenv reads the environment.
    #[test]
    fn single_partition_styles() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable w world hello")).unwrap();
        assert_eq!(val(&vars, "w"), "hello");
        vars.define(&cmd("variable u universe a b")).unwrap();
        vars.define(&cmd("variable l uloop 2")).unwrap();
        assert_eq!((val(&vars, "u"), val(&vars, "l")), ("a".into(), "1".into()));
        assert!(vars.next(&["u".into()]).is_err(), "uloop l not listed");
        assert_eq!(vars.next(&["u".into(), "l".into()]).unwrap(), (false, Some(2)));
        assert_eq!((val(&vars, "u"), val(&vars, "l")), ("b".into(), "2".into()));
        assert_eq!(vars.next(&["u".into(), "l".into()]).unwrap(), (true, Some(3)));
        assert!(!vars.contains("u") && !vars.contains("l"));
        assert!(vars.define(&cmd("variable v universe a b c")).is_ok());
        assert!(vars.define(&cmd("variable m uloop 2")).is_err(), "counts differ");
        let file = std::env::temp_dir().join(format!("gendpde-var-file-{}", std::process::id()));
        std::fs::write(&file, "# head\n 1.5 \n\ntwo words # c\n").unwrap();
        vars.define(&cmd(&format!("variable f file {}", file.display()))).unwrap();
        assert_eq!(val(&vars, "f"), "1.5");
        assert_eq!(vars.next(&["f".into()]).unwrap(), (false, None));
        assert_eq!(val(&vars, "f"), "two words");
        assert!(vars.next(&["f".into()]).unwrap().0);
        std::fs::remove_file(&file).unwrap();
        vars.define(&cmd("variable x equal 2/3")).unwrap();
        vars.define(&cmd("variable fx format x %.3f")).unwrap();
        assert_eq!(val(&vars, "fx"), "0.667");
        assert!(vars.define(&cmd("variable fy format x %d")).is_err(), "not a float conversion");
        assert!(vars.define(&cmd("variable fz format w %f")).is_err(), "world is not equal-style");
        vars.define(&cmd("variable e getenv GENDPDE_SURELY_UNSET_VARIABLE")).unwrap();
        assert_eq!(val(&vars, "e"), "");
        vars.define(&cmd("variable t timer")).unwrap();
        assert!(val(&vars, "t").parse::<f64>().unwrap() >= 0.0);
        assert!(vars.next(&["fx".into()]).is_err(), "format does not step");
    }

    #[test]
    fn index_values_advance_and_exhaust() {
        let mut vars = Variables::new();
        vars.define(&cmd("variable T index 300 400")).unwrap();
        assert_eq!(val(&vars, "T"), "300");
        assert!(!vars.next(&["T".into()]).unwrap().0);
        assert_eq!(val(&vars, "T"), "400");
        assert!(vars.next(&["T".into()]).unwrap().0);
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
        while !vars.next(&["i".into()]).unwrap().0 {
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
        assert!(vars.next(&["big".into()]).unwrap().0);
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
            "variable x uloop 3 pd",
            "variable x format nope %f",
            "variable x timer 1",
            "variable x file /nonexistent/file",
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
            "next: Invalid variable style with next command: 'e' is equal-style"
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
