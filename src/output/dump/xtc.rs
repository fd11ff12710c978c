//! `dump ID GROUP xtc N FILE`: the GROMACS XTC trajectory (VMD, MDAnalysis, GROMACS),
//! byte for byte LAMMPS's (dump_xtc.cpp): per frame the magic number, the atom count,
//! the step, the time and the box as XDR, then the group's positions in ID order
//! compressed at `dump_modify precision` (`xdr`). Lengths are in nm and times in ps
//! (`sfactor`, `tfactor`), but in lj units, which are written unscaled.

use crate::base::args::Args;
use crate::base::units::Units;
use crate::output::dump::head::{unknown_key, Dump, Head};
use crate::output::dump::xdr;
use crate::output::schedule::{Frame, RunOutput, Span};
use gendpde_io::ScriptError;
use std::fs::File;
use std::io::{BufWriter, Write};

const XTC_MAGIC: i32 = 1995;

pub struct XtcDump {
    head: Head,
    unwrap: bool,
    precision: f32,
    /// Lengths and times in the file per those of the units.
    sfactor: f64,
    tfactor: f64,
    /// The interval of the first frame (LAMMPS refuses a change).
    every: Option<u64>,
    opened: bool,
}

impl XtcDump {
    /// The words after `dump ID GROUP xtc N FILE` (none); `root`: rank 0, which warns.
    pub fn parse(head: Head, units: &Units, root: bool, a: &mut Args) -> Result<Self, ScriptError> {
        head.done(a)?;
        // LAMMPS's force->angstrom: 1 but in micro units (micrometres)
        let angstrom = if units.name == "micro" { 1.0e-4 } else { 1.0 };
        let (sfactor, tfactor) = match units.name {
            "lj" => {
                if root {
                    log::warn!("dump {}: No automatic unit conversion to XTC file format conventions possible for units lj", head.id);
                }
                (1.0, 1.0)
            }
            _ => (0.1 / angstrom, 0.001 / units.femtosecond),
        };
        Ok(Self { head, unwrap: false, precision: 1000.0, sfactor, tfactor, every: None, opened: false })
    }

    fn write_frame(&mut self, f: &Frame) -> Result<(), String> {
        let sys = f.sys;
        let step = sys.clock.step;
        self.head.every.wrote(step);
        if !self.head.once && *self.every.get_or_insert(self.head.every.every) != self.head.every.every {
            return Err("Cannot change dump_modify every for dump xtc".into());
        }
        let step32 = i32::try_from(step).map_err(|_| "Too big a timestep for dump xtc".to_string())?;
        let r = self.head.positions(f, self.unwrap)?;
        if sys.comm.rank() != 0 {
            return Ok(());
        }
        let natoms = i32::try_from(r.len()).map_err(|_| "Too many atoms for dump xtc".to_string())?;
        let mut o = Vec::with_capacity(64 + 4 * r.len());
        for i in [XTC_MAGIC, natoms, step32] {
            xdr::int(&mut o, i);
        }
        xdr::float(&mut o, (step as f64 * self.tfactor * f.sim.dt) as f32);
        let len = sys.domain.len();
        // the box vectors, a row each
        for (k, l) in len.iter().enumerate() {
            for j in 0..3 {
                xdr::float(&mut o, if j == k { (self.sfactor * l) as f32 } else { 0.0 });
            }
        }
        let coords: Vec<f32> = r.iter().flat_map(|p| p.map(|x| (self.sfactor * x) as f32)).collect();
        xdr::coords(&mut o, &coords, self.precision);
        let path = &self.head.file;
        if self.head.out.is_none() {
            // a file closed by a stopped run is added to
            let file = File::options().create(true).write(true).append(self.opened).truncate(!self.opened).open(path);
            self.head.out = Some(BufWriter::new(file.map_err(|e| format!("Cannot open XTC format dump file {path}: {e}"))?));
            self.opened = true;
        }
        self.head.out.as_mut().expect("opened above").write_all(&o).map_err(|e| format!("writing '{path}': {e}"))
    }
}

impl RunOutput for XtcDump {
    fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        self.head.every.next_step(step, run)
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        self.write_frame(f).map_err(|e| format!("dump {}: {e}", self.head.id))
    }
}

impl Dump for XtcDump {
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<(), ScriptError> {
        if self.head.modify(key, a)? {
            return Ok(());
        }
        match key {
            "unwrap" => self.unwrap = a.yes_no("unwrap")?,
            "precision" => {
                let p = a.f64("a precision (10, 100, ..., 1000000)")?;
                if ![10.0, 100.0, 1000.0, 10000.0, 100000.0, 1000000.0].iter().any(|q: &f64| (p - q).abs() <= 1.0e-5) {
                    return Err(a.err(format!("Illegal dump_modify command: precision {p} is none of 10, 100, 1000, 10000, 100000, 1000000")));
                }
                self.precision = p as f32;
            }
            "sfactor" | "tfactor" => {
                let v = a.f64(key)?;
                if v <= 0.0 {
                    return Err(a.err(format!("Illegal dump_modify {key} value (must be > 0.0)")));
                }
                *(if key == "sfactor" { &mut self.sfactor } else { &mut self.tfactor }) = v;
            }
            "flush" => {
                if a.yes_no("flush")? {
                    return Err(a.err("Cannot set dump_modify flush for dump xtc"));
                }
            }
            "sort" => match a.word("id")? {
                "id" => {}
                _ => return Err(a.err("Dump xtc requires sorting by atom ID")),
            },
            _ => return Err(unknown_key(&self.head, key, "unwrap, precision, sfactor, tfactor, flush no, sort id", a)),
        }
        Ok(())
    }

    fn head(&self) -> &Head {
        &self.head
    }

    fn head_mut(&mut self) -> &mut Head {
        &mut self.head
    }
}
