//! `write_dump all custom FILE COLUMNS... [modify sort id]`: one snapshot in LAMMPS's
//! text dump format, sorted by particle ID, written by rank 0.
//!
//! Rank 0 collects the particles in blocks of 2^20 consecutive IDs (`gather`), so it
//! never holds more than 2^20 rows (8 MB per column).
//! Values are printed in the shortest form that reads back to the same double.

use crate::base::args::Args;
use crate::base::gather;
use gendpde_integrators::System;
use gendpde_io::ScriptError;
use std::io::Write;

const COLUMNS: &str = "id type mass x y z xu yu zu ix iy iz vx vy vz px py pz u theta n";

fn value(sys: &System, i: usize, col: &str) -> Option<f64> {
    let s = &sys.store;
    let unwrapped = || sys.domain.unwrap(s.r[i], s.image[i]);
    let v = |k: usize| s.p[i][k] / s.mass[i];
    Some(match col {
        "id" => s.tag[i] as f64,
        "type" => s.kind[i] as f64,
        "mass" => s.mass[i],
        "x" => s.r[i][0],
        "y" => s.r[i][1],
        "z" => s.r[i][2],
        "xu" => unwrapped()[0],
        "yu" => unwrapped()[1],
        "zu" => unwrapped()[2],
        "ix" => s.image[i][0] as f64,
        "iy" => s.image[i][1] as f64,
        "iz" => s.image[i][2] as f64,
        "vx" => v(0),
        "vy" => v(1),
        "vz" => v(2),
        "px" => s.p[i][0],
        "py" => s.p[i][1],
        "pz" => s.p[i][2],
        "u" => s.u[i],
        "theta" => s.theta[i],
        "n" => s.n.get(i).copied().unwrap_or(0.0),
        _ => return None,
    })
}

fn is_integer(col: &str) -> bool {
    matches!(col, "id" | "type" | "ix" | "iy" | "iz")
}

/// A `write_dump` snapshot: its file and columns.
pub struct TextDump {
    file: String,
    columns: Vec<String>,
}

impl TextDump {
    /// The words after `write_dump`.
    pub fn parse(a: &mut Args) -> Result<Self, ScriptError> {
        let group = a.word("a group")?;
        if group != "all" {
            return Err(a.err(format!("group '{group}': only group all is defined")));
        }
        match a.word("a dump style (custom)")? {
            "custom" => {}
            s => return Err(a.err(format!("unknown dump style '{s}'; known: custom"))),
        }
        let file = a.word("a file name")?.to_string();
        let mut cols = Vec::new();
        while let Some(w) = a.peek() {
            a.word("a column")?;
            if w == "modify" {
                // dump_modify keywords: dumps are always sorted by ID and print values in
                // shortest round-trip form, so `sort id` and `format ...` change nothing
                while let Some(k) = a.peek() {
                    a.word("a dump_modify keyword")?;
                    match k {
                        "sort" => match a.word("id")? {
                            "id" => {}
                            v => return Err(a.err(format!("write_dump modify sort {v}: dumps are always sorted by id"))),
                        },
                        "format" => {
                            a.word("line, float or int")?;
                            a.word("a format")?;
                        }
                        _ => return Err(a.err(format!("write_dump modify {k}: known are sort id, format"))),
                    }
                }
                continue;
            }
            if !COLUMNS.split(' ').any(|c| c == w) {
                return Err(a.err(format!("unknown column '{w}'; known: {COLUMNS}")));
            }
            cols.push(w.to_string());
        }
        if cols.is_empty() {
            return Err(a.err("missing argument: expected dump columns"));
        }
        Ok(Self { file, columns: cols })
    }

    /// Writes the snapshot of `sys` (rank 0 writes; every rank must call).
    pub fn write(&self, sys: &System, max_tag: u64) -> Result<(), String> {
        let (file, cols) = (&self.file, &self.columns);
        let root = sys.comm.rank() == 0;
        let tmp = format!("{file}.tmp");
        let mut out = if root {
            let f = std::fs::File::create(&tmp).map_err(|e| format!("cannot create '{tmp}': {e}"))?;
            Some(std::io::BufWriter::new(f))
        } else {
            None
        };
        let io_err = |e: std::io::Error| format!("writing '{file}': {e}");
        let natoms = sys.comm.count(sys.store.nlocal);
        if let Some(o) = &mut out {
            let d = &sys.domain;
            write!(o, "ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{natoms}\nITEM: BOX BOUNDS pp pp pp\n", sys.step).map_err(io_err)?;
            for k in 0..3 {
                writeln!(o, "{:?} {:?}", d.lo[k], d.hi[k]).map_err(io_err)?;
            }
            writeln!(o, "ITEM: ATOMS {}", cols.join(" ")).map_err(io_err)?;
        }
        let mut emit = |rows: &[f64]| -> std::io::Result<()> {
            let Some(o) = &mut out else { return Ok(()) };
            for row in rows.chunks_exact(cols.len() + 1) {
                let line: Vec<String> = row[1..]
                    .iter()
                    .zip(cols)
                    .map(|(v, c)| if is_integer(c) { format!("{}", *v as i64) } else { format!("{v:?}") })
                    .collect();
                writeln!(o, "{}", line.join(" "))?;
            }
            Ok(())
        };
        let row = |i: usize, buf: &mut Vec<f64>| {
            buf.push(sys.store.tag[i] as f64);
            buf.extend(cols.iter().map(|c| value(sys, i, c).unwrap_or(f64::NAN)));
        };
        gather::sorted_rows(sys, max_tag, cols.len() + 1, row, &mut emit).map_err(io_err)?;
        if let Some(mut o) = out {
            o.flush().map_err(io_err)?;
            drop(o);
            std::fs::rename(&tmp, file).map_err(|e| format!("renaming '{tmp}' to '{file}': {e}"))?;
        }
        Ok(())
    }
}
