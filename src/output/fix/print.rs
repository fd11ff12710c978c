//! `fix ID GROUP print N "text" [file F | append F] [screen yes|no] [title T]`: LAMMPS's
//! fix print, the text with its variables substituted (`$x`, `${name}`, `$(expr)`)
//! every N steps, on the screen and in the log (`screen yes`, the default) and in a file
//! (first line the title, "# Fix print output for fix ID" by default). Rank 0 writes.

use super::{OutputFix, OutputFixContext};
use crate::base::args::Args;
use crate::output::schedule::{write_on_rank0, Frame, RunOutput, Span};
use crate::output::thermo::ThermoContext;
use gendpde_io::ScriptError;
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};

pub struct Print {
    id: String,
    every: u64,
    text: String,
    screen: bool,
    /// The file and whether it is appended to.
    file: Option<(String, bool)>,
    title: Option<String>,
    out: Option<BufWriter<File>>,
}

impl Print {
    pub fn parse(a: &mut Args, c: &OutputFixContext) -> Result<Self, ScriptError> {
        let every = match a.u64("the print interval N")? {
            0 => return Err(a.err("Illegal fix print nevery value 0; must be > 0")),
            n => n,
        };
        let text = a.word("the text to print")?.to_string();
        let (mut screen, mut file, mut title) = (true, None, None);
        while a.remaining() > 0 {
            match a.word("a keyword")? {
                k @ ("file" | "append") => file = Some((a.word("a file name")?.to_string(), k == "append")),
                "screen" => screen = a.yes_no("screen")?,
                "title" => title = Some(a.word("a title")?.to_string()),
                k => return Err(a.err(format!("Unknown fix print keyword: {k}; known: file, append, screen, title"))),
            }
        }
        Ok(Self { id: c.id.clone(), every, text, screen, file, title, out: None })
    }

    /// Appends `line` to the file, opening it (with its title) first.
    fn write_line(&mut self, line: &str) -> std::io::Result<()> {
        let Some((name, append)) = &self.file else { return Ok(()) };
        if self.out.is_none() {
            let mut f = BufWriter::new(if *append { OpenOptions::new().create(true).append(true).open(name)? } else { File::create(name)? });
            // the title heads appended output too, as LAMMPS
            writeln!(f, "{}", self.title.clone().unwrap_or_else(|| format!("# Fix print output for fix {}", self.id)))?;
            self.out = Some(f);
        }
        let out = self.out.as_mut().expect("opened above");
        writeln!(out, "{line}")?;
        out.flush()
    }
}

impl OutputFix for Print {
    fn id(&self) -> &str {
        &self.id
    }
    fn style(&self) -> &'static str {
        "print"
    }
}

impl RunOutput for Print {
    /// The multiples of N, the setup's step too (as LAMMPS).
    fn next_step(&self, step: u64, _run: Span) -> Option<u64> {
        Some(step.next_multiple_of(self.every))
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        let ctx = ThermoContext::new(f.sim, f.sys, f.thermo, f.vars, 0, 0.0);
        let line = gendpde_io::substitute(&self.text, f.vars, &|n| ctx.keyword(n)).map_err(|e| format!("fix {} print: {e}", self.id))?;
        if self.screen {
            f.out.line(&line);
        }
        let what = format!("fix {} print: writing {}", self.id, self.file.as_ref().map_or("", |(n, _)| n.as_str()));
        write_on_rank0(f.sys, &what, || self.write_line(&line))
    }
}
