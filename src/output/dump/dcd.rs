//! `dump ID GROUP dcd N FILE`: the CHARMM/NAMD DCD trajectory VMD and MDAnalysis read,
//! byte for byte LAMMPS's (dump_dcd.cpp): a header (the first step, the interval, dt,
//! two 80-character title lines and the atom count), then per frame the unit cell (six
//! doubles) and the x, y and z of the group's particles in ID order as float32 blocks,
//! each block framed by its length as Fortran records are. After every frame the
//! header's frame count and last step are updated in place.

use crate::base::args::Args;
use crate::output::dump::head::{unknown_key, Dump, Head};
use crate::output::schedule::{Frame, RunOutput, Span};
use gendpde_integrators::System;
use gendpde_io::ScriptError;
use std::fs::File;
use std::io::{BufWriter, Seek, SeekFrom, Write};

/// Where the header holds the frame count (NFILE) and the last step (NSTEP).
const NFILE_POS: u64 = 8;
const NSTEP_POS: u64 = 20;

pub struct DcdDump {
    head: Head,
    /// `dump_modify unwrap yes`: unwrapped positions.
    unwrap: bool,
    flush: bool,
    /// The particle count and the interval of the header, fixed by the first frame.
    natoms: Option<u64>,
    skip: u64,
    frames: u32,
}

impl DcdDump {
    /// The words after `dump ID GROUP dcd N FILE` (none).
    pub fn parse(head: Head, a: &mut Args) -> Result<Self, ScriptError> {
        head.done(a)?;
        Ok(Self { head, unwrap: false, flush: true, natoms: None, skip: 0, frames: 0 })
    }

    fn write_frame(&mut self, f: &Frame) -> Result<(), String> {
        let sys = f.sys;
        let step = sys.clock.step;
        self.head.every.wrote(step);
        let n = self.head.count(f.sim, sys)?;
        let natoms = *self.natoms.get_or_insert(n);
        if n != natoms {
            return Err(format!("Dump dcd of non-matching # of atoms: {n} in group, {natoms} in the file"));
        }
        let step32 = i32::try_from(step).map_err(|_| "Too big a timestep for dump dcd".to_string())?;
        let every = if self.head.once { 0 } else { self.head.every.every };
        if self.frames == 0 {
            self.skip = every;
        } else if every != self.skip {
            return Err("Cannot change dump_modify every for dump dcd".into());
        }
        let r = self.head.positions(f, self.unwrap)?;
        let xyz: [Vec<f32>; 3] = std::array::from_fn(|k| r.iter().map(|p| p[k] as f32).collect());
        if sys.comm.rank() != 0 {
            return Ok(());
        }
        let path = self.head.file.clone();
        let io = |e: std::io::Error| format!("writing '{path}': {e}");
        if self.head.out.is_none() {
            let file = match self.frames {
                0 => File::create(&path),
                _ => File::options().read(true).write(true).open(&path),
            };
            let mut o = BufWriter::new(file.map_err(io)?);
            o.seek(SeekFrom::End(0)).map_err(io)?;
            self.head.out = Some(o);
        }
        let o = self.head.out.as_mut().expect("opened above");
        if self.frames == 0 {
            header(o, step32, self.skip as i32, f.sim.dt as f32, natoms as i32).map_err(io)?;
        }
        frame(o, sys, &xyz).map_err(io)?;
        self.frames += 1;
        o.seek(SeekFrom::Start(NFILE_POS)).map_err(io)?;
        o.write_all(&self.frames.to_ne_bytes()).map_err(io)?;
        o.seek(SeekFrom::Start(NSTEP_POS)).map_err(io)?;
        o.write_all(&step32.to_ne_bytes()).map_err(io)?;
        o.seek(SeekFrom::End(0)).map_err(io)?;
        if self.flush {
            o.flush().map_err(io)?;
        }
        Ok(())
    }
}

/// Writes `i` as LAMMPS's fwrite of an int32 (native byte order).
fn int(o: &mut impl Write, i: i32) -> std::io::Result<()> {
    o.write_all(&i.to_ne_bytes())
}

/// The file header: the first step, the interval, dt, the title lines, the atom count.
fn header(o: &mut impl Write, step: i32, skip: i32, dt: f32, natoms: i32) -> std::io::Result<()> {
    int(o, 84)?;
    o.write_all(b"CORD")?;
    // NFILE (frames, updated), START, SKIP, NSTEP (the last step, updated), five zeros
    for i in [0, step, skip, step, 0, 0, 0, 0, 0] {
        int(o, i)?;
    }
    o.write_all(&dt.to_ne_bytes())?;
    // a unit cell in every frame, then CHARMM version 24
    for i in [1, 0, 0, 0, 0, 0, 0, 0, 0, 24, 84, 164, 2] {
        int(o, i)?;
    }
    let mut title = [0u8; 80];
    let by = b"Written by gendpde";
    title[..by.len()].copy_from_slice(by);
    o.write_all(&title)?;
    let created = format!("REMARKS Created {}", local_time());
    let mut remarks = [b' '; 80];
    remarks[..created.len().min(80)].copy_from_slice(&created.as_bytes()[..created.len().min(80)]);
    o.write_all(&remarks)?;
    for i in [164, 4, natoms, 4] {
        int(o, i)?;
    }
    Ok(())
}

/// One frame: the unit cell (a, cos gamma, b, cos beta, cos alpha, c), then the blocks.
fn frame(o: &mut impl Write, sys: &System, xyz: &[Vec<f32>; 3]) -> std::io::Result<()> {
    let len = sys.domain.len();
    int(o, 48)?;
    for d in [len[0], 0.0, len[1], 0.0, 0.0, len[2]] {
        o.write_all(&d.to_ne_bytes())?;
    }
    int(o, 48)?;
    for c in xyz {
        let bytes = (c.len() * 4) as i32;
        int(o, bytes)?;
        for v in c {
            o.write_all(&v.to_ne_bytes())?;
        }
        int(o, bytes)?;
    }
    Ok(())
}

/// Now in UTC as LAMMPS prints its local time: `04 December,2026 at 21:40`.
fn local_time() -> String {
    const MONTHS: [&str; 12] = ["January", "February", "March", "April", "May", "June", "July", "August", "September", "October", "November", "December"];
    let secs = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs() as i64);
    let (days, minute) = (secs.div_euclid(86400), secs.rem_euclid(86400) / 60);
    // the civil date of a day count (H. Hinnant's days_from_civil inverted)
    let z = days + 719_468;
    let (era, doe) = (z.div_euclid(146_097), z.rem_euclid(146_097));
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let (day, month) = (doy - (153 * mp + 2) / 5 + 1, if mp < 10 { mp + 3 } else { mp - 9 });
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{day:02} {},{year} at {:02}:{:02}", MONTHS[month as usize - 1], minute / 60, minute % 60)
}

impl RunOutput for DcdDump {
    fn next_step(&self, step: u64, run: Span) -> Option<u64> {
        self.head.every.next_step(step, run)
    }

    fn write(&mut self, f: &mut Frame) -> Result<(), String> {
        self.write_frame(f).map_err(|e| format!("dump {}: {e}", self.head.id))
    }
}

impl Dump for DcdDump {
    fn modify(&mut self, key: &str, a: &mut Args) -> Result<(), ScriptError> {
        if self.head.modify(key, a)? {
            return Ok(());
        }
        match key {
            "unwrap" => self.unwrap = a.yes_no("unwrap")?,
            "flush" => self.flush = a.yes_no("flush")?,
            "sort" => match a.word("id")? {
                "id" => {}
                _ => return Err(a.err("Dump dcd requires sorting by atom ID")),
            },
            _ => return Err(unknown_key(&self.head, key, "unwrap, flush, sort id", a)),
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
