//! Typed reading of command arguments, with errors that say what was expected.

use gendpde_io::{Command, ScriptError};

/// Cursor over the arguments of one command.
pub struct Args<'a> {
    cmd: &'a Command,
    pos: usize,
}

impl<'a> Args<'a> {
    pub fn new(cmd: &'a Command) -> Self {
        Self { cmd, pos: 0 }
    }

    /// The command being read.
    pub fn command(&self) -> &'a Command {
        self.cmd
    }

    pub fn err(&self, msg: impl Into<String>) -> ScriptError {
        ScriptError::at(self.cmd, msg)
    }

    pub fn remaining(&self) -> usize {
        self.cmd.args.len() - self.pos
    }

    pub fn peek(&self) -> Option<&'a str> {
        self.cmd.args.get(self.pos).map(String::as_str)
    }

    /// The next word, named `what` in the error if it is missing.
    pub fn word(&mut self, what: &str) -> Result<&'a str, ScriptError> {
        let w = self.cmd.args.get(self.pos).ok_or_else(|| self.err(format!("missing argument: expected {what}")))?;
        self.pos += 1;
        Ok(w)
    }

    pub fn f64(&mut self, what: &str) -> Result<f64, ScriptError> {
        let w = self.word(what)?;
        match w.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(self.err(format!("expected {what} (a number), got '{w}'"))),
        }
    }

    /// A number that must be > 0.
    pub fn positive(&mut self, what: &str) -> Result<f64, ScriptError> {
        let x = self.f64(what)?;
        if x > 0.0 { Ok(x) } else { Err(self.err(format!("{what} must be positive, got {x:?}"))) }
    }

    /// A number that must be >= 0.
    pub fn non_negative(&mut self, what: &str) -> Result<f64, ScriptError> {
        let x = self.f64(what)?;
        if x >= 0.0 { Ok(x) } else { Err(self.err(format!("{what} must not be negative, got {x:?}"))) }
    }

    pub fn u64(&mut self, what: &str) -> Result<u64, ScriptError> {
        let w = self.word(what)?;
        w.parse::<u64>().map_err(|_| self.err(format!("expected {what} (a non-negative integer), got '{w}'")))
    }

    /// `yes` or `no`.
    pub fn yes_no(&mut self, what: &str) -> Result<bool, ScriptError> {
        match self.word(what)? {
            "yes" => Ok(true),
            "no" => Ok(false),
            w => Err(self.err(format!("expected yes or no for {what}, got '{w}'"))),
        }
    }

    /// Fails if any argument is left over.
    pub fn done(&self) -> Result<(), ScriptError> {
        match self.cmd.args.get(self.pos) {
            None => Ok(()),
            Some(w) => Err(self.err(format!("unexpected argument '{w}'"))),
        }
    }

    /// A LAMMPS range (`*`, `n`, `n*`, `*n`, `m*n`) of integers in 1..=max; `what`
    /// names one element ("a particle type").
    pub fn range(&mut self, what: &str, max: u64) -> Result<std::ops::RangeInclusive<u64>, ScriptError> {
        let w = self.word(&format!("{what} or a range of them"))?;
        let bad = || self.err(format!("expected {what} or range within 1..{max}, got '{w}'"));
        let num = |s: &str, default: u64| if s.is_empty() { Ok(default) } else { s.parse::<u64>().map_err(|_| bad()) };
        let (lo, hi) = match w.split_once('*') {
            Some((a, b)) => (num(a, 1)?, num(b, max)?),
            None => (num(w, 0)?, num(w, 0)?),
        };
        if lo < 1 || hi > max || lo > hi {
            return Err(bad());
        }
        Ok(lo..=hi)
    }

    /// A range of particle types 1..=ntypes.
    pub fn types(&mut self, ntypes: usize) -> Result<std::ops::RangeInclusive<usize>, ScriptError> {
        let r = self.range("a particle type", ntypes as u64)?;
        Ok(*r.start() as usize..=*r.end() as usize)
    }

    /// `* *` (or ranges covering every type) of a pair style with one coefficient set for
    /// all type pairs; anything narrower is refused naming the `style`.
    pub fn all_type_pairs(&mut self, ntypes: usize, style: &str) -> Result<(), ScriptError> {
        let (ti, tj) = (self.types(ntypes)?, self.types(ntypes)?);
        if *ti.start() != 1 || *ti.end() != ntypes || *tj.start() != 1 || *tj.end() != ntypes {
            return Err(self.err(format!("pair {style} takes one coefficient set for all type pairs: use 'pair_coeff * *'")));
        }
        Ok(())
    }
}
