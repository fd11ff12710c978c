//! The commands about the program's session rather than the model: `shell` (LAMMPS's
//! sub-commands cd, mkdir, mv, rm, rmdir, putenv), `timer`, `info` and `partition`.

use super::Interpreter;
use crate::base::args::Args;
use gendpde_io::ScriptError;
use std::path::Path;

impl Interpreter {
    /// `shell cd|mkdir|mv|rm|rmdir|putenv args...` as LAMMPS's Input::shell: a failure is a
    /// warning; rank 0 changes the files, every rank its directory and environment.
    pub(super) fn shell(&mut self, a: &mut Args) -> Result<(), ScriptError> {
        let sub = a.word("a shell command (cd, mkdir, mv, rm, rmdir or putenv)")?;
        let args = &a.command().args[1..];
        let illegal = || a.err(format!("Illegal shell {sub} command"));
        let root = self.sim.rank() == 0;
        let mut failures = Vec::new();
        let mut check = |what: String, done: std::io::Result<()>| {
            if let Err(e) = done {
                // the system's message, as LAMMPS's getsyserror gives it
                let e = e.to_string();
                let e = e.split(" (os error").next().unwrap_or_default();
                failures.push(format!("WARNING: Shell command '{what}' failed with error '{e}'"));
            }
        };
        match sub {
            "cd" => match args {
                [dir] => check(format!("cd {dir}"), std::env::set_current_dir(dir)),
                _ => return Err(illegal()),
            },
            "mkdir" | "rm" | "rmdir" | "putenv" if args.is_empty() => return Err(illegal()),
            "mkdir" if root => args.iter().for_each(|d| check(format!("mkdir {d}"), std::fs::create_dir_all(d))),
            "rmdir" if root => args.iter().for_each(|d| check(format!("rmdir {d}"), std::fs::remove_dir_all(d))),
            "rm" if root => {
                let (warn, files) = match args {
                    [flag, files @ ..] if flag == "-f" => (false, files),
                    files => (true, files),
                };
                for f in files {
                    if let (Err(e), true) = (std::fs::remove_file(f), warn) {
                        check(format!("rm {f}"), Err(e));
                    }
                }
            }
            "mv" => match args {
                [from, to] if root => {
                    let target = if Path::new(to).is_dir() { Path::new(to).join(Path::new(from).file_name().unwrap_or_default()) } else { to.into() };
                    check(format!("mv {from} {to}"), std::fs::rename(from, target));
                }
                [_, _] => {}
                _ => return Err(illegal()),
            },
            "putenv" => {
                for setting in args {
                    let (name, value) = setting.split_once('=').unwrap_or((setting, ""));
                    if name.is_empty() || name.contains('\0') || value.contains('\0') {
                        check(format!("putenv {setting}"), Err(std::io::Error::from(std::io::ErrorKind::InvalidInput)));
                    } else {
                        std::env::set_var(name, value);
                    }
                }
            }
            "mkdir" | "rm" | "rmdir" => {}
            other => {
                return Err(a.err(format!(
                    "shell {other}: only LAMMPS's built-in sub-commands cd, mkdir, mv, rm, rmdir and putenv are supported (gendpde runs no system shell)"
                )))
            }
        }
        for w in failures {
            self.out.line(&w);
        }
        Ok(())
    }

    /// `timer` keywords (`off`, `loop`, `normal`, `full`, `sync`, `nosync`, `timeout off`,
    /// `every N`), checked and echoed as LAMMPS's "New timer settings" line: gendpde
    /// prints its own timing summary whatever they say. A timeout that would stop the run
    /// is refused.
    pub(super) fn timer(&mut self, a: &mut Args) -> Result<(), ScriptError> {
        if a.remaining() == 0 {
            return Err(a.err("Illegal timer command: missing argument"));
        }
        let (mut style, mut mode) = ("normal", "nosync");
        while a.remaining() > 0 {
            match a.word("a timer keyword")? {
                s @ ("off" | "loop" | "normal" | "full") => style = s,
                m @ ("sync" | "nosync") => mode = m,
                "timeout" => match a.word("a timeout")? {
                    "off" => {}
                    t => return Err(a.err(format!("timer timeout {t} is not supported (gendpde does not stop runs by wall time)"))),
                },
                "every" => {
                    let n = a.u64("the steps between timeout checks")?;
                    if n == 0 {
                        return Err(a.err("Illegal timer every value: 0"));
                    }
                }
                k => return Err(a.err(format!("Illegal timer command: unknown keyword {k}"))),
            }
        }
        self.out.line(&format!("New timer settings: style={style}  mode={mode}  timeout=off"));
        Ok(())
    }

    /// `info [system] [variables] [all]`: LAMMPS's framed report of the system and the
    /// variables (no category: the system); its other categories list LAMMPS's packages,
    /// styles and settings and are refused.
    pub(super) fn info(&mut self, a: &mut Args) -> Result<(), ScriptError> {
        let (mut system, mut variables) = (a.remaining() == 0, false);
        while a.remaining() > 0 {
            match a.word("an info category")? {
                "system" => system = true,
                "variables" => variables = true,
                "all" => (system, variables) = (true, true),
                k => return Err(a.err(format!("info {k} is not supported (gendpde reports: system, variables, all)"))),
            }
        }
        let frame = "Info-Info-Info-Info-Info-Info-Info-Info-Info-Info-Info";
        let mut lines = vec![String::new(), frame.to_string()];
        if system {
            let s = &self.sim;
            lines.push(String::new());
            lines.push("System information:".into());
            lines.push(format!("Units         = {}", s.units.name));
            lines.push(format!("Atom style    = {}", s.atom_style.name()));
            match &s.system {
                Some(sys) => {
                    let pair = s.pair.as_ref().map_or("none".to_string(), |p| p.name().to_string());
                    lines.push(format!("Atoms     = {:>12},  types = {:>8},  style = {pair}", sys.comm.count(sys.store.nlocal), s.ntypes));
                    let (lo, hi, l) = (sys.domain.lo, sys.domain.hi, sys.domain.len());
                    lines.push(String::new());
                    lines.push("Dimensions = 3".into());
                    lines.push(format!("Orthogonal box = {} x {} x {}", fmt(l[0]), fmt(l[1]), fmt(l[2])));
                    lines.push("Boundaries = p,p p,p p,p".into());
                    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                        lines.push(format!("{axis}lo, {axis}hi = {}, {}", fmt(lo[k]), fmt(hi[k])));
                    }
                    lines.push(String::new());
                    lines.push(format!("Current timestep number = {}", sys.clock.step));
                }
                None => lines.push("No simulation box is defined".into()),
            }
            lines.push(format!("Current timestep size = {}", fmt(s.dt)));
        }
        if variables {
            lines.push(String::new());
            lines.push("Variable information:".into());
            for (k, (name, style)) in self.vars.names().into_iter().enumerate() {
                lines.push(format!("Variable[{k:3}]: {name:<16}, style = {style:>8}"));
            }
        }
        lines.push(String::new());
        lines.push(frame.to_string());
        lines.push(String::new());
        for l in lines {
            self.out.line(&l);
        }
        Ok(())
    }
}

/// `partition`: refused, as gendpde runs one partition (LAMMPS's -partition switch).
pub(super) fn partition(a: &mut Args) -> Result<(), ScriptError> {
    Err(a.err("partition is not supported: gendpde runs one partition (LAMMPS's -partition command-line switch does not exist here)"))
}

/// A number as LAMMPS's info prints it (%g with 8 digits).
fn fmt(x: f64) -> String {
    gendpde_io::format_g(x, 8)
}
