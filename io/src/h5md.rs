//! H5MD 1.1 trajectory snapshots (<https://www.nongnu.org/h5md/h5md.html>).
//!
//! Layout written by [`H5mdWriter`]:
//!
//! ```text
//! /h5md                      attr version = [1, 1] (int32)
//! /h5md/author               attrs name, email (optional)
//! /h5md/creator              attrs name = "gendpde", version
//! /particles/all/box         attrs dimension = 3, boundary = ["periodic"; 3]
//! /particles/all/box/edges/{value [frames, 3], step, time}
//! /particles/all/<element>/value   [frames, N, 3] or [frames, N]
//! /particles/all/<element>/step    int64 [frames]
//! /particles/all/<element>/time    float64 [frames]
//! /observables/<name>/{value [frames], step, time}
//! ```
//!
//! All time-dependent datasets are chunked with an unlimited frame axis.  The
//! `step` and `time` datasets are stored once (in the first element) and are
//! hard links in every other element, the box edges and the observables, as
//! H5MD permits, so a frame becomes visible to all of them with a single
//! extension of `step`.  The edges are time dependent because that is what
//! MDAnalysis reads; the observables have a value at every frame, as
//! MDAnalysis reads `observables/<name>/value[frame]`.  In `metal` units
//! `value` and `time` datasets carry H5MD `unit` attributes (unitless `lj`
//! files have none).  Strings are variable-length UTF-8 (read by h5py as
//! `str`).
//!
//! Durability: the file is created with the v110 format and switched to
//! SWMR-write mode once every object exists, so HDF5 orders its metadata
//! writes and the file stays consistent if the writer is killed.  A frame is
//! committed in [`H5mdWriter::end_frame`] by (1) writing `time` and flushing
//! (values and time reach the OS), then (2) extending `step` and flushing.
//! Readers count frames by the length of `step`, so a value or time entry
//! beyond it is an incomplete frame that [`H5mdWriter::append`] overwrites.
//! A file whose writer was killed keeps HDF5's "open for writing" superblock
//! flag; [`H5mdWriter::append`] and [`check_h5md`] clear/tolerate it (the
//! equivalent of `h5clear -s`).

use std::collections::BTreeSet;
use std::fmt;
use std::path::{Path, PathBuf};

use hdf5::types::{FixedAscii, FixedUnicode, TypeDescriptor, VarLenAscii, VarLenUnicode};
use hdf5::{Attribute, Dataset, Extent, File, Group, SimpleExtents};

mod datasets;
mod field;
mod file;

use datasets::*;
pub use field::{H5mdField, H5mdMeta};
use field::*;
pub use file::H5mdError;
use file::*;

struct Element {
    field: H5mdField,
    value: Dataset,
    step: Dataset,
    time: Dataset,
}

/// Streams frames of per-particle data into an H5MD 1.1 file.
pub struct H5mdWriter {
    path: PathBuf,
    // Datasets are declared before the file so they are closed first.
    elements: Vec<Element>,
    /// `box/edges/value` (None in files of older versions, whose edges are fixed).
    edges_value: Option<Dataset>,
    /// The edges written with the next frames.
    edges: [f64; 3],
    /// `/observables/<name>/value` by name.
    observables: Vec<(String, Dataset)>,
    fields: Vec<H5mdField>,
    file: File,
    n: usize,
    frames: usize,
    /// Step and time of the frame in progress.
    current: Option<(u64, f64)>,
}

impl fmt::Debug for H5mdWriter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("H5mdWriter")
            .field("path", &self.path)
            .field("n", &self.n)
            .field("fields", &self.fields)
            .field("frames", &self.frames)
            .field("current", &self.current)
            .finish()
    }
}

mod repair;
pub use repair::repair_h5md;

impl H5mdWriter {
    /// Creates (truncating) `path` for `n` particles, the given fields and
    /// what `meta` says; `edges` is the box of the frames until [`Self::set_edges`].
    pub fn create(path: &Path, n: usize, edges: [f64; 3], fields: &[H5mdField], meta: &H5mdMeta) -> Result<Self, H5mdError> {
        silence();
        check_fields(path, fields)?;
        // Build the file under a temporary name and rename it into place
        // once it is complete and in SWMR mode, so a process killed during
        // create leaves no half-built (unreadable) file at `path`.
        let name = path
            .file_name()
            .ok_or_else(|| error(path, "not a file name"))?;
        let mut tmp_name = std::ffi::OsString::from(".");
        tmp_name.push(name);
        tmp_name.push(format!(".tmp{}", std::process::id()));
        let tmp = path.with_file_name(tmp_name);
        let result = Self::create_at(path, &tmp, n, edges, fields, meta)
            .and_then(|w| {
                std::fs::rename(&tmp, path).map_err(|e| {
                    error(path, format_args!("cannot rename {}: {e}", tmp.display()))
                })?;
                Ok(w)
            });
        if result.is_err() {
            let _ = std::fs::remove_file(&tmp);
        }
        result
    }

    fn create_at(path: &Path, tmp: &Path, n: usize, edges: [f64; 3], fields: &[H5mdField], meta: &H5mdMeta) -> Result<Self, H5mdError> {
        let file = h5(path, "cannot create file", writer_options().create(tmp))?;
        let units = meta.units.as_deref();
        write_metadata(path, &file, meta)?;
        let all = h5(path, "opening /particles/all", file.group("particles/all"))?;

        // Time-dependent elements; step/time live in the first one and are
        // hard-linked from the others, the box edges and the observables.
        let first = fields.first().ok_or_else(|| error(path, "no fields to write"))?.h5md_name();
        let link = |g: &Group, what: &str| -> Result<(), H5mdError> {
            for series in ["step", "time"] {
                h5(path, &format!("linking {what}/{series}"), g.link_hard(&format!("/particles/all/{first}/{series}"), series))?;
            }
            Ok(())
        };
        for &field in fields {
            let name = field.h5md_name();
            let g = h5(
                path,
                &format!("creating element {name}"),
                all.create_group(name),
            )?;
            let value = create_value(path, &g, field, n)?;
            set_unit(path, &value, unit(units, name))?;
            if name == first {
                create_series::<i64>(path, &g, "step")?;
                let time = create_series::<f64>(path, &g, "time")?;
                set_unit(path, &time, unit(units, "time"))?;
            } else {
                link(&g, name)?;
            }
        }
        let edges_g = h5(path, "creating box edges", all.create_group("box/edges"))?;
        let value = h5(
            path,
            "creating box/edges/value",
            edges_g.new_dataset::<f64>().chunk([STEP_CHUNK, 3]).shape(SimpleExtents::from_vec(vec![Extent::new(0, None), Extent::fixed(3)])).create("value"),
        )?;
        set_unit(path, &value, unit(units, "length"))?;
        link(&edges_g, "box/edges")?;
        for name in &meta.observables {
            if name.is_empty() || name.contains('/') || name == "." {
                return Err(error(path, format_args!("observable name {name:?} is not an HDF5 name")));
            }
            let g = h5(path, &format!("creating observable {name}"), file.create_group(&format!("observables/{name}")))?;
            h5(path, &format!("creating observables/{name}/value"), g.new_dataset::<f64>().chunk(STEP_CHUNK).shape(0..).create("value"))?;
            link(&g, &format!("observables/{name}"))?;
        }
        drop((all, edges_g, value));
        h5(path, "flushing", file.flush())?;
        h5(path, "starting SWMR write mode", file.start_swmr())?;
        Self::with_elements(path, file, n, fields, 0, edges)
    }

    /// Opens the element datasets of `file` (in SWMR-write mode).  HDF5
    /// 1.10 fails to start SWMR mode while objects are open ("ID already in
    /// use"), hence `create` closes and reopens them.
    fn with_elements(path: &Path, file: File, n: usize, fields: &[H5mdField], frames: usize, edges: [f64; 3]) -> Result<Self, H5mdError> {
        let mut elements = Vec::with_capacity(fields.len());
        for &field in fields {
            let name = field.h5md_name();
            let open = |what: &str| {
                h5(
                    path,
                    &format!("opening {name}/{what}"),
                    file.dataset(&format!("particles/all/{name}/{what}")),
                )
            };
            elements.push(Element {
                field,
                value: open("value")?,
                step: open("step")?,
                time: open("time")?,
            });
        }
        let edges_value = file.dataset("particles/all/box/edges/value").ok();
        let mut observables = Vec::new();
        if let Ok(g) = file.group("observables") {
            for name in h5(path, "listing /observables", g.member_names())? {
                let value = h5(path, &format!("opening observables/{name}/value"), g.dataset(&format!("{name}/value")))?;
                observables.push((name, value));
            }
        }
        Ok(Self {
            path: path.to_path_buf(),
            elements,
            edges_value,
            edges,
            observables,
            fields: fields.to_vec(),
            file,
            n,
            frames,
            current: None,
        })
    }

    /// Opens an existing file written by [`H5mdWriter::create`] to append
    /// frames (a run continued from a restart); `n` and the set of `fields`
    /// must match the file.  A trailing incomplete frame (writer killed
    /// before `end_frame` finished) is overwritten by the next frame.  A file
    /// left marked "open" by a killed writer is repaired first
    /// ([`repair_h5md`]).  The file is opened directly in SWMR-write mode.
    pub fn append(path: &Path, n: usize, fields: &[H5mdField]) -> Result<Self, H5mdError> {
        silence();
        check_fields(path, fields)?;
        if !path.exists() {
            return Err(error(path, "cannot append: file does not exist"));
        }
        // Open directly in SWMR-write mode (never plain read/write, whose
        // metadata writes are not crash-safe).
        let file = match open_swmr_rw(path) {
            Ok(f) => f,
            Err(first) => {
                // Most likely a writer was killed and left the superblock
                // marked "open for writing"; repair and retry.
                if repair_h5md(path).is_err() {
                    return Err(error(
                        path,
                        format_args!("cannot open for appending: {}", first.0),
                    ));
                }
                open_swmr_rw(path)
                    .map_err(|e| error(path, format_args!("cannot open for appending: {}", e.0)))?
            }
        };
        let all = file.group("particles/all").map_err(|_| {
            error(
                path,
                "not an H5MD file written by gendpde: no /particles/all group",
            )
        })?;

        // Compare the element sets.
        let names = h5(path, "listing /particles/all", all.member_names())?;
        let mut in_file = BTreeSet::new();
        for name in names.iter().filter(|s| *s != "box") {
            match H5mdField::from_h5md_name(name) {
                Some(f) => {
                    in_file.insert(f);
                }
                None => {
                    return Err(error(
                        path,
                        format_args!("unknown element /particles/all/{name}"),
                    ))
                }
            }
        }
        let wanted: BTreeSet<H5mdField> = fields.iter().copied().collect();
        if in_file != wanted {
            let list = |s: &BTreeSet<H5mdField>| {
                s.iter()
                    .map(|f| f.h5md_name())
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            let missing: BTreeSet<_> = wanted.difference(&in_file).copied().collect();
            let extra: BTreeSet<_> = in_file.difference(&wanted).copied().collect();
            return Err(error(
                path,
                format_args!(
                    "cannot append: the file holds fields [{}] but [{}] were requested (missing in file: [{}]; not requested: [{}])",
                    list(&in_file),
                    list(&wanted),
                    list(&missing),
                    list(&extra)
                ),
            ));
        }

        let mut elements = Vec::with_capacity(fields.len());
        let mut frames: Option<usize> = None;
        for &field in fields {
            let name = field.h5md_name();
            let g = h5(path, &format!("opening element {name}"), all.group(name))?;
            let value = h5(path, &format!("opening {name}/value"), g.dataset("value"))?;
            let step = h5(path, &format!("opening {name}/step"), g.dataset("step"))?;
            let time = h5(path, &format!("opening {name}/time"), g.dataset("time"))?;
            let shape = value.shape();
            let expect_ndim = if field.width() == 3 { 3 } else { 2 };
            if shape.len() != expect_ndim || (expect_ndim == 3 && shape[2] != 3) {
                return Err(error(
                    path,
                    format_args!(
                        "{name}/value has shape {shape:?}, not [frames, N{}]",
                        if expect_ndim == 3 { ", 3" } else { "" }
                    ),
                ));
            }
            if shape[1] != n {
                return Err(error(
                    path,
                    format_args!(
                        "cannot append: the file holds {} particles but the run has {n}",
                        shape[1]
                    ),
                ));
            }
            let kind = dtype_kind(path, &value, name)?;
            if kind != Some(field.kind()) {
                return Err(error(
                    path,
                    format_args!("{name}/value is not {}", value_dtype_name(field.kind())),
                ));
            }
            let len = step.size();
            match frames {
                None => frames = Some(len),
                Some(f) if f != len => {
                    return Err(error(
                        path,
                        format_args!("{name}/step has {len} frames but another element has {f}"),
                    ))
                }
                _ => {}
            }
            if shape[0] < len || time.size() < len {
                return Err(error(
                    path,
                    format_args!("{name}: value or time is shorter than step"),
                ));
            }
            elements.push(Element {
                field,
                value,
                step,
                time,
            });
        }
        let frames = frames.unwrap_or(0);
        // the box of the last frame (older files: the fixed edges)
        let edges = match (all.dataset("box/edges/value"), all.dataset("box/edges")) {
            (Ok(v), _) if frames > 0 => h5(path, "reading box edges", v.read_slice_1d::<f64, _>((frames - 1, ..)))?.to_vec(),
            (_, Ok(e)) => h5(path, "reading box edges", e.read_raw::<f64>())?,
            _ => vec![0.0; 3],
        };
        let edges: [f64; 3] = edges.try_into().map_err(|e: Vec<f64>| error(path, format_args!("box edges has {} values, not 3", e.len())))?;
        // A trailing incomplete frame (value/time longer than step) is left
        // in place: begin_frame keeps the length and the frame's data is
        // overwritten.  (Shrinking datasets is avoided in SWMR mode.)
        drop(elements);
        drop(all);
        Self::with_elements(path, file, n, fields, frames, edges)
    }

    /// The fields written, in the order given to `create`/`append`.
    pub fn fields(&self) -> &[H5mdField] {
        &self.fields
    }

    /// Number of particles per frame.
    pub fn particles(&self) -> usize {
        self.n
    }

    /// The file written.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Number of completed frames in the file.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// The box edges of the next frames.
    pub fn set_edges(&mut self, edges: [f64; 3]) {
        self.edges = edges;
    }

    /// Names of the file's observables.
    pub fn observables(&self) -> impl Iterator<Item = &str> {
        self.observables.iter().map(|(n, _)| n.as_str())
    }

    /// Writes observables of the current frame, by name; the file's others
    /// are NaN in this frame, names the file lacks are left out.
    pub fn write_observables(&mut self, values: &[(&str, f64)]) -> Result<(), H5mdError> {
        if self.current.is_none() {
            return Err(self.err("write_observables outside a frame (call begin_frame first)"));
        }
        for (name, ds) in &self.observables {
            if let Some(&(_, v)) = values.iter().find(|(n, _)| n == name) {
                h5(&self.path, &format!("writing observable {name}"), ds.write_slice(&[v][..], self.frames..self.frames + 1))?;
            }
        }
        Ok(())
    }

    /// Starts a frame: grows every value dataset by one frame and writes
    /// the box edges (observables start as NaN).
    pub fn begin_frame(&mut self, step: u64, time: f64) -> Result<(), H5mdError> {
        if let Some((s, _)) = self.current {
            return Err(self.err(format_args!(
                "begin_frame({step}) while frame of step {s} is not ended"
            )));
        }
        i64::try_from(step)
            .map_err(|_| self.err(format_args!("step {step} does not fit in int64")))?;
        let frame = self.frames;
        for el in &self.elements {
            let mut shape = el.value.shape();
            shape[0] = frame + 1;
            h5(
                &self.path,
                &format!("extending {}/value", el.field),
                el.value.resize(shape),
            )?;
        }
        if let Some(v) = &self.edges_value {
            h5(&self.path, "extending box/edges/value", v.resize([frame + 1, 3]))?;
            h5(&self.path, "writing box edges", v.write_slice::<_, f64, _, _>(&[self.edges][..], (frame..frame + 1, ..)))?;
        }
        for (name, ds) in &self.observables {
            h5(&self.path, &format!("extending observables/{name}/value"), ds.resize(frame + 1))?;
            h5(&self.path, &format!("writing observable {name}"), ds.write_slice(&[f64::NAN][..], frame..frame + 1))?;
        }
        self.current = Some((step, time));
        Ok(())
    }

    /// Writes rows `first_row..first_row+len` of `field` in the current
    /// frame; `data` holds `len * field.width()` values (integer fields are
    /// converted and must hold integral values in range).
    pub fn write_rows(
        &mut self,
        field: H5mdField,
        first_row: usize,
        data: &[f64],
    ) -> Result<(), H5mdError> {
        if self.current.is_none() {
            return Err(self.err(format_args!(
                "write_rows({field}) outside a frame (call begin_frame first)"
            )));
        }
        let el = self
            .elements
            .iter()
            .find(|e| e.field == field)
            .ok_or_else(|| self.err(format_args!("field {field} is not written to this file")))?;
        let width = field.width();
        if !data.chunks_exact(width).remainder().is_empty() {
            return Err(self.err(format_args!(
                "write_rows({field}): {} values is not a multiple of the width {width}",
                data.len()
            )));
        }
        let len = data.len() / width;
        if first_row > self.n || len > self.n - first_row {
            return Err(self.err(format_args!(
                "write_rows({field}): rows {first_row}..{} outside 0..{}",
                first_row.saturating_add(len),
                self.n
            )));
        }
        if len == 0 {
            return Ok(());
        }
        let frame = self.frames;
        let rows = first_row..first_row + len;
        let what = format!("writing {field} rows {}..{}", rows.start, rows.end);
        let r = match (field.kind(), width) {
            (Kind::F64, 3) => el.value.write_slice::<_, f64, _, _>(
                as_triples(data, Ok::<f64, H5mdError>)?.as_slice(),
                (frame, rows, ..),
            ),
            (Kind::F64, _) => el.value.write_slice(data, (frame, rows)),
            (Kind::I32, _) => write_ints::<i32>(&el.value, data, width, frame, rows).map_err(|x| self.bad_int(field, x))?,
            (Kind::I64, _) => write_ints::<i64>(&el.value, data, width, frame, rows).map_err(|x| self.bad_int(field, x))?,
        };
        h5(&self.path, &what, r)
    }

    /// Completes the frame: appends step and time to every element and
    /// flushes the file.  `time` is written and flushed before `step` is
    /// extended, so a frame counts (by the length of `step`) only once all
    /// its data is on disk.
    pub fn end_frame(&mut self) -> Result<(), H5mdError> {
        let Some((step, time)) = self.current else {
            return Err(self.err("end_frame without begin_frame"));
        };
        let frame = self.frames;
        let path = self.path.clone();
        // step/time are usually shared by hard links; resizing/writing the
        // same dataset again through another element is idempotent.
        for el in &self.elements {
            h5(&path, "extending time", el.time.resize(frame + 1))?;
            h5(
                &path,
                "writing time",
                el.time.write_slice(&[time][..], frame..frame + 1),
            )?;
        }
        h5(&path, "flushing", self.file.flush())?;
        for el in &self.elements {
            h5(&path, "extending step", el.step.resize(frame + 1))?;
            h5(
                &path,
                "writing step",
                el.step.write_slice(&[step as i64][..], frame..frame + 1),
            )?;
        }
        h5(&path, "flushing", self.file.flush())?;
        self.frames += 1;
        self.current = None;
        Ok(())
    }

    fn err(&self, what: impl fmt::Display) -> H5mdError {
        error(&self.path, what)
    }

    fn bad_int(&self, field: H5mdField, x: f64) -> H5mdError {
        self.err(format_args!(
            "write_rows({field}): value {x} is not a valid {}",
            value_dtype_name(field.kind())
        ))
    }
}


// ---------------------------------------------------------------------------
// Validation.

mod check;
pub use check::{check_h5md, H5mdSummary};

#[cfg(test)]
mod tests;
