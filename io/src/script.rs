//! Pull-based reading of LAMMPS-style input scripts.
//!
//! Each call to [`ScriptReader::next_command`] reads one logical line
//! (joining `&` continuations and multi-line `"""` quotes), strips its
//! comment, substitutes variables with their *current* values and splits it
//! into words. `include` commands are followed inside the reader.

mod line;

use std::path::{Path, PathBuf};

use crate::command::{Command, Location, ScriptError};
use crate::variables::Variables;

/// How deeply `include` files may nest.
const MAX_INCLUDE_DEPTH: usize = 32;

/// Reads commands from a script and the files it includes.
pub struct ScriptReader {
    /// The open scripts, innermost `include` last.
    sources: Vec<Source>,
    current: Option<Location>,
}

/// One script file held in memory.
struct Source {
    file: PathBuf,
    lines: Vec<String>,
    /// 0-based index of the next unread line.
    next: usize,
}

impl Source {
    fn new(file: PathBuf, text: &str) -> Self {
        Source {
            file,
            lines: text.lines().map(str::to_string).collect(),
            next: 0,
        }
    }

    /// Reads a file; bytes that are not UTF-8 become U+FFFD.
    fn read(path: &Path) -> std::io::Result<Self> {
        let bytes = std::fs::read(path)?;
        Ok(Source::new(
            path.to_path_buf(),
            &String::from_utf8_lossy(&bytes),
        ))
    }
}

impl ScriptReader {
    /// Opens a script file.
    pub fn open(path: &Path) -> Result<Self, ScriptError> {
        let source = Source::read(path).map_err(|e| {
            ScriptError::new(format!(
                "cannot open input script '{}': {e}",
                path.display()
            ))
        })?;
        Ok(Self::with_source(source))
    }

    /// A reader over `text`, reported as file `name`.
    pub fn from_string(name: &str, text: &str) -> Self {
        Self::with_source(Source::new(PathBuf::from(name), text))
    }

    fn with_source(source: Source) -> Self {
        ScriptReader {
            sources: vec![source],
            current: None,
        }
    }

    /// Where the most recently read command starts (`None` before the first).
    pub fn current_location(&self) -> Option<Location> {
        self.current.clone()
    }

    /// Reads the next command, substituting variables from `vars` (with
    /// `resolve` for thermo keywords in expressions). Returns `None` at the
    /// end of the script. After an error, reading resumes with the next line.
    pub fn next_command(
        &mut self,
        vars: &Variables,
        resolve: &dyn Fn(&str) -> Option<f64>,
    ) -> Result<Option<Command>, ScriptError> {
        while let Some((text, loc)) = self.read_logical_line()? {
            self.current = Some(loc.clone());
            let mut words = line::words(&text, vars, resolve)
                .map_err(|e| ScriptError::located(loc.clone(), e))?
                .into_iter();
            let Some(name) = words.next() else { continue };
            let cmd = Command {
                name,
                args: words.collect(),
                loc,
            };
            if cmd.name != "include" {
                return Ok(Some(cmd));
            }
            self.include(&cmd)?;
        }
        Ok(None)
    }

    /// `jump SELF LABEL` (or the current file's name): continues reading the current
    /// file after the line `label LABEL`.
    pub fn jump(&mut self, cmd: &Command) -> Result<(), ScriptError> {
        let [file, label] = cmd.args.as_slice() else {
            return Err(ScriptError::at(cmd, "expected SELF (or this file) and a label"));
        };
        let Some(src) = self.sources.last_mut() else {
            return Err(ScriptError::at(cmd, "no script to jump in"));
        };
        if file != "SELF" && Path::new(file) != src.file {
            return Err(ScriptError::at(cmd, format!("jump to another file ('{file}') is not supported: use SELF")));
        }
        let target = src.lines.iter().position(|l| {
            let mut w = l.split_whitespace();
            w.next() == Some("label") && w.next() == Some(label.as_str())
        });
        match target {
            Some(k) => {
                src.next = k + 1;
                Ok(())
            }
            None => Err(ScriptError::at(cmd, format!("no line 'label {label}' in {}", src.file.display()))),
        }
    }

    /// Starts reading the file named by an `include` command.
    fn include(&mut self, cmd: &Command) -> Result<(), ScriptError> {
        let [file] = cmd.args.as_slice() else {
            return Err(ScriptError::at(cmd, "expected exactly one file name"));
        };
        if self.sources.len() > MAX_INCLUDE_DEPTH {
            return Err(ScriptError::at(
                cmd,
                format!("include files nested deeper than {MAX_INCLUDE_DEPTH} (include cycle?)"),
            ));
        }
        let source = Source::read(Path::new(file))
            .map_err(|e| ScriptError::at(cmd, format!("cannot open '{file}': {e}")))?;
        self.sources.push(source);
        Ok(())
    }

    /// Reads physical lines up to the end of a command, finishing included
    /// files first. Continuation `&`s become spaces; a line with an open
    /// `"""` quote is joined to the next with a newline.
    fn read_logical_line(&mut self) -> Result<Option<(String, Location)>, ScriptError> {
        loop {
            let Some(src) = self.sources.last_mut() else {
                return Ok(None);
            };
            let Some(first) = src.lines.get(src.next) else {
                self.sources.pop();
                continue;
            };
            let loc = Location {
                file: src.file.clone(),
                line: src.next + 1,
            };
            let mut text = first.clone();
            src.next += 1;
            loop {
                let separator = if let Some(body) = text.trim_end().strip_suffix('&') {
                    text.truncate(body.len());
                    ' '
                } else if text.matches(line::TRIPLE).count() % 2 == 1 {
                    '\n'
                } else {
                    break;
                };
                let Some(next) = src.lines.get(src.next) else {
                    if separator == '\n' {
                        return Err(ScriptError::located(loc, "unterminated \"\"\" quote"));
                    }
                    break;
                };
                text.push(separator);
                text.push_str(next);
                src.next += 1;
            }
            return Ok(Some((text, loc)));
        }
    }
}

/// Substitutes the variables of `text` outside its quotes, as a script line is
/// substituted when it is read: for the commands that substitute their quoted text when
/// they execute (`print`, the commands of `run every`, `variable string`).
pub fn substitute(text: &str, vars: &Variables, resolve: &dyn Fn(&str) -> Option<f64>) -> Result<String, String> {
    line::substitute(text, vars, resolve, 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn none(_: &str) -> Option<f64> {
        None
    }

    /// Runs a script the way an engine would: `variable` and `next` commands
    /// act on `vars`; all other commands are returned.
    fn run(reader: &mut ScriptReader, vars: &mut Variables) -> Result<Vec<Command>, ScriptError> {
        let thermo = |k: &str| (k == "step").then_some(50.0);
        let mut out = Vec::new();
        while let Some(cmd) = reader.next_command(vars, &thermo)? {
            match cmd.name.as_str() {
                "variable" => vars.define(&cmd)?,
                "next" => {
                    vars.next(&cmd.args)?;
                }
                _ => out.push(cmd),
            }
        }
        Ok(out)
    }

    fn commands(text: &str) -> Vec<Command> {
        let mut reader = ScriptReader::from_string("t.in", text);
        run(&mut reader, &mut Variables::new()).unwrap_or_else(|e| panic!("{e}"))
    }

    fn error(text: &str) -> String {
        let mut reader = ScriptReader::from_string("t.in", text);
        match run(&mut reader, &mut Variables::new()) {
            Ok(cmds) => panic!("no error, got {cmds:?}"),
            Err(e) => e.to_string(),
        }
    }

    /// Each command as `line: name arg|arg|...`.
    fn summary(text: &str) -> Vec<String> {
        commands(text)
            .iter()
            .map(|c| {
                format!("{}: {} {}", c.loc.line, c.name, c.args.join("|"))
                    .trim_end()
                    .to_string()
            })
            .collect()
    }

    /// A fresh scratch directory for file-based tests.
    fn scratch(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("gendpde-io-{}-{tag}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn error_display() {
        let cmd = Command {
            name: "pair_coeff".into(),
            args: vec![],
            loc: Location {
                file: "in.vdw".into(),
                line: 12,
            },
        };
        let err = ScriptError::at(&cmd, "expected 3 numbers after the types, got 2");
        assert_eq!(
            err.to_string(),
            "in.vdw:12: pair_coeff: expected 3 numbers after the types, got 2"
        );
        assert_eq!(ScriptError::new("boom").to_string(), "boom");
        assert_eq!(
            ScriptError::located(cmd.loc, "bad").to_string(),
            "in.vdw:12: bad"
        );
    }

    #[test]
    fn continuation_comments_and_blank_lines() {
        let text =
            "# header\n\nunits lj # trailing\npair_style lj/cut &\n   2.5 &  \n  10\n   \nrun 10";
        assert_eq!(
            summary(text),
            ["3: units lj", "4: pair_style lj/cut|2.5|10", "8: run 10"]
        );
        assert_eq!(summary("a b &"), ["1: a b"]);
        assert_eq!(summary("# comment &\nstill comment\nx"), ["3: x"]);
    }

    #[test]
    fn quotes_group_words() {
        let text = "print \"hello  world\" 'a # b' \"\"\"line one\n# not a comment\nline three\"\"\" end\nnext_cmd";
        let cmds = commands(text);
        assert_eq!(
            cmds[0].args,
            [
                "hello  world",
                "a # b",
                "line one\n# not a comment\nline three",
                "end"
            ]
        );
        assert_eq!((cmds[1].name.as_str(), cmds[1].loc.line), ("next_cmd", 4));
        assert_eq!(
            error("print \"\"\"never closed\nmore"),
            "t.in:1: unterminated \"\"\" quote"
        );
        assert_eq!(error("x\nprint 'abc"), "t.in:2: unbalanced ' quotes");
    }

    #[test]
    fn substitution_forms() {
        let text = "variable x index 2.5\n\
                    variable name string hello\n\
                    variable a equal 3\n\
                    print $x ${name} $(1/4) $(PI:%.3f) $(2*$x) $(v_a*2) $(${a}*2) $(step+1:%05.1f) $(0.1)\n\
                    print \"$x ${name}\" '$x ${name}' \"\"\"$x\"\"\" x$x$x";
        let cmds = commands(text);
        // $(0.1) as LAMMPS prints it (%.20g)
        assert_eq!(
            cmds[0].args,
            ["2.5", "hello", "0.25", "3.142", "5", "6", "6", "051.0", "0.10000000000000000555"]
        );
        // quotes keep `$` for the command to substitute (LAMMPS's parsing rule 6)
        assert_eq!(cmds[1].args, ["$x ${name}", "$x ${name}", "$x", "x2.52.5"]);
    }

    #[test]
    fn substitution_uses_values_at_read_time() {
        let text = "variable t equal 1\nprint ${t}\nvariable t equal 2\nprint ${t} $(v_t^3)";
        assert_eq!(summary(text), ["2: print 1", "4: print 2|8"]);
        let text = "variable w string \"a b\"\nprint ${w} '${w}'";
        assert_eq!(summary(text), ["2: print a|b|${w}"]);
    }

    #[test]
    fn loop_with_next() {
        let text = "variable i loop 2\nprint $i\nnext i\nprint $i\nnext i\nprint ${i}";
        assert_eq!(error(text), "t.in:6: unknown variable 'i'");
    }

    #[test]
    fn substitution_errors() {
        assert_eq!(error("run 1\nprint ${zz}"), "t.in:2: unknown variable 'zz'");
        assert_eq!(error("print $q"), "t.in:1: unknown variable 'q'");
        assert_eq!(error("print ${oops"), "t.in:1: missing '}' after '${'");
        assert_eq!(error("print $(1+"), "t.in:1: missing ')' after '$('");
        assert_eq!(error("print $(1/0)"), "t.in:1: in $(1/0): division by zero");
        assert_eq!(
            error("print $(foo)"),
            "t.in:1: in $(foo): unknown identifier 'foo' in expression"
        );
        assert!(error("print $(1:%q)").contains("unsupported conversion"));
        assert_eq!(error("print $"), "t.in:1: '$' at end of line");
        let deep = format!("print {}1{}", "$(".repeat(40), ")".repeat(40));
        assert!(error(&deep).contains("nested deeper than 32"));
    }

    #[test]
    fn command_line_variables_win() {
        let mut vars = Variables::new();
        vars.set_command_line("T", vec!["1.0".into()]);
        let mut reader =
            ScriptReader::from_string("t.in", "variable T index 300\nvelocity all create $T 123");
        let cmds = run(&mut reader, &mut vars).unwrap();
        assert_eq!(cmds[0].args, ["all", "create", "1.0", "123"]);
    }

    #[test]
    fn include_reads_file_in_place() {
        let dir = scratch("include");
        let inc = dir.join("part.in");
        std::fs::write(&inc, "variable b equal 4\nmass 1 $(v_b)\n").unwrap();
        let text = format!("units lj\ninclude {}\nrun 10", inc.display());
        let mut reader = ScriptReader::from_string("main.in", &text);
        let cmds = run(&mut reader, &mut Variables::new()).unwrap();
        let got: Vec<String> = cmds
            .iter()
            .map(|c| format!("{} {}", c.loc, c.name))
            .collect();
        let want = [
            "main.in:1 units".to_string(),
            format!("{}:2 mass", inc.display()),
            "main.in:3 run".into(),
        ];
        assert_eq!(got, want);
        assert_eq!(cmds[1].args, ["1", "4"]);
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn errors_in_included_file_carry_its_lines() {
        let dir = scratch("include-error");
        let inc = dir.join("bad.in");
        std::fs::write(&inc, "units lj\n\nprint &\n  ${missing}\n").unwrap();
        let mut reader =
            ScriptReader::from_string("main.in", &format!("\n\ninclude {}", inc.display()));
        let err = run(&mut reader, &mut Variables::new()).unwrap_err();
        assert_eq!(
            err.loc,
            Some(Location {
                file: inc.clone(),
                line: 3
            })
        );
        assert_eq!(
            err.to_string(),
            format!("{}:3: unknown variable 'missing'", inc.display())
        );
        assert_eq!(reader.current_location(), err.loc);
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn include_cycle_and_missing_file() {
        let dir = scratch("cycle");
        let cyc = dir.join("self.in");
        std::fs::write(&cyc, format!("include {}\n", cyc.display())).unwrap();
        let mut reader = ScriptReader::open(&cyc).unwrap();
        let err = reader.next_command(&Variables::new(), &none).unwrap_err();
        assert_eq!(err.command.as_deref(), Some("include"));
        assert!(err.message.contains("nested deeper than 32"), "{err}");

        let missing = dir.join("missing.in");
        let err = error(&format!("include {}", missing.display()));
        assert!(
            err.starts_with(&format!(
                "t.in:1: include: cannot open '{}': ",
                missing.display()
            )),
            "{err}"
        );
        assert_eq!(
            error("include a b"),
            "t.in:1: include: expected exactly one file name"
        );
        let err = ScriptReader::open(&missing)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.starts_with(&format!(
                "cannot open input script '{}': ",
                missing.display()
            )),
            "{err}"
        );
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn reading_resumes_after_an_error() {
        let mut reader = ScriptReader::from_string("t.in", "print ${x}\nrun 5");
        let vars = Variables::new();
        assert!(reader.next_command(&vars, &none).is_err());
        let cmd = reader.next_command(&vars, &none).unwrap().unwrap();
        assert_eq!((cmd.name.as_str(), cmd.loc.line), ("run", 2));
        assert!(reader.next_command(&vars, &none).unwrap().is_none());
    }

    #[test]
    fn garbage_never_panics() {
        const ALPHABET: &[char] = &[
            'a', 'x', 'v', '_', '1', '0', '.', 'e', ' ', '\t', '\n', '\r', '$', '{', '}', '(', ')',
            '[', ']', '"', '\'', '#', '&', '%', ':', '^', '*', '/', '-', '+', '!', '<', '=', '|',
            ',', 'é', '😀', '\0', '\u{b}',
        ];
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut rand = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) as usize
        };
        let prefixes = [
            "",
            "variable v equal ",
            "variable x index ",
            "print ",
            "print $(",
            "include ",
        ];
        let mut errors = 0;
        for _ in 0..400 {
            let len = rand() % 60;
            let mut text: String = prefixes[rand() % prefixes.len()].into();
            text.extend((0..len).map(|_| ALPHABET[rand() % ALPHABET.len()]));
            let mut reader = ScriptReader::from_string("junk.in", &text);
            let mut vars = Variables::new();
            vars.set_command_line("x", vec!["1".into()]);
            for _ in 0..100 {
                match reader.next_command(&vars, &none) {
                    Ok(None) => break,
                    Ok(Some(cmd)) if cmd.name == "variable" => {
                        let _ = vars.define(&cmd);
                        let _ = vars.value("v", &none);
                    }
                    Err(e) => {
                        // a rejected line names where it is
                        assert!(e.to_string().contains("junk.in:"), "error without its location: {e}");
                        errors += 1;
                    }
                    _ => {}
                }
            }
            let _ = crate::expr::evaluate(&text, &vars, &none);
            let _ = crate::format::format_printf(&text, 1.5);
        }
        assert!(errors > 0, "no garbage line was rejected");
    }
}
