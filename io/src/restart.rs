//! Restart (checkpoint) files in HDF5: everything the dynamics needs to
//! continue bit-identically.
//!
//! Rank 0 of an MPI run writes a restart from blocks of particles that are
//! already sorted by tag ([`RestartWriter`]; it never holds all particles at
//! once), and every rank reads it back in blocks and keeps its own particles
//! ([`RestartReader::read_rows`]).
//!
//! # Layout (`format` = `"gendpde-restart"`, `format_version` = 1)
//!
//! Attributes on the root group (all scalars unless noted):
//!
//! | name              | type                      | meaning                                   |
//! |-------------------|---------------------------|-------------------------------------------|
//! | `format`          | 32-byte ASCII string      | always `gendpde-restart`                  |
//! | `format_version`  | u32                       | 1                                         |
//! | `creator_version` | 256-byte UTF-8 string     | version of the program that wrote it      |
//! | `step`            | u64                       | current step                              |
//! | `time`            | f64                       | simulated time                            |
//! | `dt`              | f64                       | timestep                                  |
//! | `natoms`          | u64                       | number of particle rows                   |
//! | `max_tag`         | u64                       | largest tag ever assigned                 |
//! | `ntypes`          | u64                       | number of particle types                  |
//! | `last_build`      | u64                       | step of the last neighbour-list build     |
//! | `energy0`         | f64                       | only present when `energy0` is `Some`     |
//! | `cell_counts`     | u64 `[3]`                 | only present when `cell_counts` is `Some` |
//!
//! Datasets:
//!
//! * `/box/lo`, `/box/hi`: f64 `[3]`;
//! * `/types/mass`: f64 `[ntypes]`, NaN for a type without a mass;
//! * `/script/commands`: u8 `[nbytes]`, the UTF-8 text of each command
//!   followed by a NUL byte (commands may contain newlines: `"""` quotes);
//! * `/particles/{tag (u64), type (u32), mass (f64), u (f64), theta (f64)}`:
//!   `[natoms]`, and `/particles/{r, p, r_at_build (f64), image, cell (i32)}`:
//!   `[natoms, 3]`, rows in increasing tag order.
//!
//! Floats are stored as native IEEE f64 and never converted, so every value
//! (including NaN payloads, -0 and subnormals) round-trips bit-exactly.
//! Optional header values are stored by presence rather than by a sentinel,
//! so `Some(NaN)` and `None` stay distinct; only a per-type mass of
//! `Some(NaN)` is refused (NaN is the "unset" marker there).
//!
//! No variable-length data is used: HDF5 keeps it in the global heap, which
//! has no checksum, and libhdf5 1.10 crashes (SIGSEGV in `H5HG_read`) on a
//! corrupted one. Strings are fixed-length or plain bytes instead.
//! Files are written with the HDF5 1.8+ object format, whose metadata
//! (superblock, object headers, link and attribute storage) carries
//! checksums, so most corruption is detected by the library on open instead
//! of being parsed as garbage.
//!
//! The writer writes `path.tmp` and renames it to `path` in
//! [`RestartWriter::finish`], after syncing it to disk; a writer that is
//! dropped without finishing removes its temporary file, and an interrupted
//! run never replaces a good restart with a partial one.

use std::ffi::OsString;
use std::fmt;
use std::fs;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use hdf5::types::{FixedAscii, FixedUnicode, FloatSize, IntSize, TypeDescriptor};
use hdf5::{Dataset, File, H5Type, Location};

/// Value of the root `format` attribute.
pub const RESTART_FORMAT: &str = "gendpde-restart";
/// The `format_version` this module writes and the newest it reads.
pub const RESTART_FORMAT_VERSION: u32 = 1;
/// Most particle types a restart may declare (guards allocations driven by
/// a corrupt header).
pub const MAX_RESTART_TYPES: u64 = 1_000_000;
/// Most bytes of script commands a restart may hold.
pub const MAX_COMMAND_BYTES: usize = 1 << 28;

/// An error reading or writing a restart file; the message names the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RestartError(pub String);

impl fmt::Display for RestartError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for RestartError {}

fn error(path: &Path, msg: impl fmt::Display) -> RestartError {
    RestartError(format!("restart file {}: {msg}", path.display()))
}

/// Everything besides the per-particle columns.
#[derive(Clone, Debug, PartialEq)]
pub struct RestartHeader {
    pub step: u64,
    pub time: f64,
    pub dt: f64,
    pub natoms: u64,
    pub max_tag: u64,
    pub ntypes: usize,
    pub lo: [f64; 3],
    pub hi: [f64; 3],
    /// Per type; `None` for a type whose mass was never set.
    pub masses: Vec<Option<f64>>,
    /// Reference energy for the thermo `edrift` column.
    pub energy0: Option<f64>,
    /// Step of the last neighbour-list build.
    pub last_build: u64,
    /// Global cell grid at the last build.
    pub cell_counts: Option<[usize; 3]>,
    /// Script commands that re-create the styles (pair_style, pair_coeff,
    /// fix, timestep, neighbor, neigh_modify ...), in order.
    pub commands: Vec<String>,
    pub creator_version: String,
}

impl RestartHeader {
    /// Checks the header's internal consistency; `Err` holds what is wrong.
    fn check(&self) -> Result<(), String> {
        if self.ntypes as u64 > MAX_RESTART_TYPES {
            return Err(format!(
                "ntypes = {} exceeds the limit of {MAX_RESTART_TYPES}",
                self.ntypes
            ));
        }
        if self.masses.len() != self.ntypes {
            return Err(format!(
                "expected {} per-type masses (ntypes), got {}",
                self.ntypes,
                self.masses.len()
            ));
        }
        for d in 0..3 {
            let (lo, hi) = (self.lo[d], self.hi[d]);
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(format!(
                    "box bounds must be finite with lo < hi, got lo = {:?}, hi = {:?}",
                    self.lo, self.hi
                ));
            }
        }
        if let Some(c) = self.cell_counts {
            if c.contains(&0) {
                return Err(format!("cell_counts must all be at least 1, got {c:?}"));
            }
        }
        Ok(())
    }
}

/// A block of particles (structure of arrays, equal lengths).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ParticleRows {
    pub tag: Vec<u64>,
    pub kind: Vec<u32>,
    pub mass: Vec<f64>,
    pub r: Vec<[f64; 3]>,
    pub p: Vec<[f64; 3]>,
    pub u: Vec<f64>,
    pub theta: Vec<f64>,
    pub image: Vec<[i32; 3]>,
    pub cell: Vec<[i32; 3]>,
    pub r_at_build: Vec<[f64; 3]>,
}

impl ParticleRows {
    /// Number of rows (the length of `tag`; see [`ParticleRows::check`]).
    pub fn len(&self) -> usize {
        self.tag.len()
    }

    pub fn is_empty(&self) -> bool {
        self.tag.is_empty()
    }

    /// Empties every column, keeping the allocations.
    pub fn clear(&mut self) {
        self.tag.clear();
        self.kind.clear();
        self.mass.clear();
        self.r.clear();
        self.p.clear();
        self.u.clear();
        self.theta.clear();
        self.image.clear();
        self.cell.clear();
        self.r_at_build.clear();
    }

    fn column_lengths(&self) -> [(&'static str, usize); 10] {
        [
            ("tag", self.tag.len()),
            ("kind", self.kind.len()),
            ("mass", self.mass.len()),
            ("r", self.r.len()),
            ("p", self.p.len()),
            ("u", self.u.len()),
            ("theta", self.theta.len()),
            ("image", self.image.len()),
            ("cell", self.cell.len()),
            ("r_at_build", self.r_at_build.len()),
        ]
    }

    /// Checks that all columns have the same length.
    fn check(&self) -> Result<usize, String> {
        let lens = self.column_lengths();
        let n = lens[0].1;
        if lens.iter().any(|&(_, l)| l != n) {
            let list: Vec<String> = lens.iter().map(|(c, l)| format!("{c} {l}")).collect();
            return Err(format!(
                "particle columns have unequal lengths ({})",
                list.join(", ")
            ));
        }
        Ok(n)
    }
}

/// Open handles of the per-particle datasets.
struct Columns {
    tag: Dataset,
    kind: Dataset,
    mass: Dataset,
    r: Dataset,
    p: Dataset,
    u: Dataset,
    theta: Dataset,
    image: Dataset,
    cell: Dataset,
    r_at_build: Dataset,
}

fn temp_path(path: &Path) -> PathBuf {
    let mut s = OsString::from(path.as_os_str());
    s.push(".tmp");
    PathBuf::from(s)
}

/// Type of the `format` attribute.
type FormatString = FixedAscii<32>;
/// Type of the `creator_version` attribute.
type VersionString = FixedUnicode<256>;

/// Joins script commands into the bytes of `/script/commands`: each command's
/// UTF-8 text followed by a NUL byte.
fn join_commands(path: &Path, commands: &[String]) -> Result<Vec<u8>, RestartError> {
    let mut bytes = Vec::new();
    for c in commands {
        if c.contains('\0') {
            return Err(error(
                path,
                format!("cannot store script command {c:?}: it contains a NUL character"),
            ));
        }
        bytes.extend_from_slice(c.as_bytes());
        bytes.push(0);
    }
    if bytes.len() > MAX_COMMAND_BYTES {
        return Err(error(
            path,
            format!("the script commands exceed {MAX_COMMAND_BYTES} bytes"),
        ));
    }
    Ok(bytes)
}

fn write_attr<T: H5Type>(loc: &Location, name: &str, value: &T) -> hdf5::Result<()> {
    loc.new_attr::<T>()
        .shape(())
        .create(name)?
        .write_scalar(value)
}

/// Writes a restart file block by block; see the module documentation.
pub struct RestartWriter {
    path: PathBuf,
    tmp: PathBuf,
    /// `None` once finished, or after a failed write left the file unusable.
    inner: Option<(File, Columns)>,
    natoms: u64,
    max_tag: u64,
    written: u64,
    last_tag: Option<u64>,
    /// Set when `path.tmp` has been renamed to `path`.
    done: bool,
}

impl fmt::Debug for RestartWriter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RestartWriter")
            .field("path", &self.path)
            .field("natoms", &self.natoms)
            .field("written", &self.written)
            .finish_non_exhaustive()
    }
}

impl RestartWriter {
    /// Starts writing `path` (really `path` + ".tmp"; `finish` renames it,
    /// so an interrupted write never replaces a good file).
    pub fn create(path: &Path, header: &RestartHeader) -> Result<Self, RestartError> {
        hdf5::silence_errors(true);
        header
            .check()
            .map_err(|e| error(path, format!("invalid header: {e}")))?;
        if let Some(t) = header.masses.iter().flatten().find(|m| m.is_nan()) {
            return Err(error(
                path,
                format!("invalid header: a per-type mass of {t} cannot be stored"),
            ));
        }
        let tmp = temp_path(path);
        let h5 = |e: hdf5::Error| error(&tmp, e);
        // Declared before `file`, so that on an early return the file is closed
        // first and then `writer`'s drop removes it.
        let mut writer = RestartWriter {
            path: path.to_path_buf(),
            tmp: tmp.clone(),
            inner: None,
            natoms: header.natoms,
            max_tag: header.max_tag,
            written: 0,
            last_tag: None,
            done: false,
        };
        let file = File::with_options()
            .with_fapl(|fapl| fapl.libver_v18())
            .create(&tmp)
            .map_err(|e| error(&tmp, format!("cannot be created: {e}")))?;
        let natoms = usize::try_from(header.natoms).map_err(|_| {
            error(
                path,
                format!("natoms = {} does not fit in memory indices", header.natoms),
            )
        })?;

        let format = FormatString::from_ascii(RESTART_FORMAT).map_err(|e| error(path, e))?;
        write_attr(&file, "format", &format).map_err(h5)?;
        write_attr(&file, "format_version", &RESTART_FORMAT_VERSION).map_err(h5)?;
        let version = VersionString::from_str(&header.creator_version).map_err(|e| {
            error(
                path,
                format!(
                    "cannot store creator_version {:?}: {e}",
                    header.creator_version
                ),
            )
        })?;
        write_attr(&file, "creator_version", &version).map_err(h5)?;
        write_attr(&file, "step", &header.step).map_err(h5)?;
        write_attr(&file, "time", &header.time).map_err(h5)?;
        write_attr(&file, "dt", &header.dt).map_err(h5)?;
        write_attr(&file, "natoms", &header.natoms).map_err(h5)?;
        write_attr(&file, "max_tag", &header.max_tag).map_err(h5)?;
        write_attr(&file, "ntypes", &(header.ntypes as u64)).map_err(h5)?;
        write_attr(&file, "last_build", &header.last_build).map_err(h5)?;
        if let Some(e0) = header.energy0 {
            write_attr(&file, "energy0", &e0).map_err(h5)?;
        }
        if let Some(c) = header.cell_counts {
            let c = c.map(|x| x as u64);
            file.new_attr_builder()
                .with_data(&c[..])
                .create("cell_counts")
                .map_err(h5)?;
        }

        let bx = file.create_group("box").map_err(h5)?;
        bx.new_dataset_builder()
            .with_data(&header.lo[..])
            .create("lo")
            .map_err(h5)?;
        bx.new_dataset_builder()
            .with_data(&header.hi[..])
            .create("hi")
            .map_err(h5)?;

        let masses: Vec<f64> = header
            .masses
            .iter()
            .map(|m| m.unwrap_or(f64::NAN))
            .collect();
        let types = file.create_group("types").map_err(h5)?;
        types
            .new_dataset_builder()
            .with_data(&masses[..])
            .create("mass")
            .map_err(h5)?;

        let commands = join_commands(path, &header.commands)?;
        let script = file.create_group("script").map_err(h5)?;
        let cd = script
            .new_dataset::<u8>()
            .shape(commands.len())
            .create("commands")
            .map_err(h5)?;
        if !commands.is_empty() {
            cd.write_raw(&commands[..]).map_err(h5)?;
        }

        let pg = file.create_group("particles").map_err(h5)?;
        let cols = Columns {
            tag: pg
                .new_dataset::<u64>()
                .shape(natoms)
                .create("tag")
                .map_err(h5)?,
            kind: pg
                .new_dataset::<u32>()
                .shape(natoms)
                .create("type")
                .map_err(h5)?,
            mass: pg
                .new_dataset::<f64>()
                .shape(natoms)
                .create("mass")
                .map_err(h5)?,
            r: pg
                .new_dataset::<f64>()
                .shape((natoms, 3))
                .create("r")
                .map_err(h5)?,
            p: pg
                .new_dataset::<f64>()
                .shape((natoms, 3))
                .create("p")
                .map_err(h5)?,
            u: pg
                .new_dataset::<f64>()
                .shape(natoms)
                .create("u")
                .map_err(h5)?,
            theta: pg
                .new_dataset::<f64>()
                .shape(natoms)
                .create("theta")
                .map_err(h5)?,
            image: pg
                .new_dataset::<i32>()
                .shape((natoms, 3))
                .create("image")
                .map_err(h5)?,
            cell: pg
                .new_dataset::<i32>()
                .shape((natoms, 3))
                .create("cell")
                .map_err(h5)?,
            r_at_build: pg
                .new_dataset::<f64>()
                .shape((natoms, 3))
                .create("r_at_build")
                .map_err(h5)?,
        };
        writer.inner = Some((file, cols));
        Ok(writer)
    }

    /// Appends the next rows (rows arrive in tag order, in blocks; the total
    /// must reach header.natoms).
    pub fn write_rows(&mut self, rows: &ParticleRows) -> Result<(), RestartError> {
        let path = self.path.clone();
        let n = rows.check().map_err(|e| error(&path, e))?;
        let Some((_, cols)) = &self.inner else {
            return Err(error(
                &path,
                "an earlier write failed; the restart cannot be completed",
            ));
        };
        if self.written + n as u64 > self.natoms {
            return Err(error(
                &path,
                format!(
                    "{} rows written plus {n} more exceed natoms = {}",
                    self.written, self.natoms
                ),
            ));
        }
        let mut last = self.last_tag;
        for &t in &rows.tag {
            if last.is_some_and(|l| t <= l) {
                return Err(error(
                    &path,
                    format!(
                        "particle tags must be strictly increasing, got {t} after {}",
                        last.unwrap_or(0)
                    ),
                ));
            }
            if t > self.max_tag {
                return Err(error(
                    &path,
                    format!("particle tag {t} exceeds max_tag = {}", self.max_tag),
                ));
            }
            last = Some(t);
        }
        if n == 0 {
            return Ok(());
        }
        let a = self.written as usize;
        let b = a + n;
        let result = (|| -> hdf5::Result<()> {
            cols.tag.write_slice(&rows.tag[..], a..b)?;
            cols.kind.write_slice(&rows.kind[..], a..b)?;
            cols.mass.write_slice(&rows.mass[..], a..b)?;
            cols.r
                .write_slice::<_, f64, _, _>(&rows.r[..], (a..b, ..))?;
            cols.p
                .write_slice::<_, f64, _, _>(&rows.p[..], (a..b, ..))?;
            cols.u.write_slice(&rows.u[..], a..b)?;
            cols.theta.write_slice(&rows.theta[..], a..b)?;
            cols.image
                .write_slice::<_, i32, _, _>(&rows.image[..], (a..b, ..))?;
            cols.cell
                .write_slice::<_, i32, _, _>(&rows.cell[..], (a..b, ..))?;
            cols.r_at_build
                .write_slice::<_, f64, _, _>(&rows.r_at_build[..], (a..b, ..))?;
            Ok(())
        })();
        if let Err(e) = result {
            // Part of the block may be on disk; refuse to go on.
            self.inner = None;
            return Err(error(
                &self.tmp,
                format!("writing particle rows {a}..{b}: {e}"),
            ));
        }
        self.written += n as u64;
        self.last_tag = last;
        Ok(())
    }

    /// Checks that natoms rows were written, flushes, closes and renames to
    /// `path` atomically.
    pub fn finish(mut self) -> Result<(), RestartError> {
        let Some((file, cols)) = self.inner.take() else {
            return Err(error(
                &self.path,
                "an earlier write failed; the restart was not written",
            ));
        };
        if self.written != self.natoms {
            return Err(error(
                &self.path,
                format!(
                    "only {} of natoms = {} particle rows were written",
                    self.written, self.natoms
                ),
            ));
        }
        drop(cols);
        let tmp = self.tmp.clone();
        file.flush()
            .map_err(|e| error(&tmp, format!("flushing: {e}")))?;
        file.close()
            .map_err(|e| error(&tmp, format!("closing: {e}")))?;
        fs::File::open(&tmp)
            .and_then(|f| f.sync_all())
            .map_err(|e| error(&tmp, format!("syncing to disk: {e}")))?;
        fs::rename(&tmp, &self.path).map_err(|e| {
            error(
                &self.path,
                format!("renaming {} into place: {e}", tmp.display()),
            )
        })?;
        self.done = true;
        // Make the rename itself durable (best effort: not every platform
        // lets a directory be opened and synced).
        let dir = match self.path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        if let Ok(d) = fs::File::open(dir) {
            let _ = d.sync_all();
        }
        Ok(())
    }
}

impl Drop for RestartWriter {
    fn drop(&mut self) {
        // Close the HDF5 handles before removing the file.
        self.inner = None;
        if !self.done {
            let _ = fs::remove_file(&self.tmp);
        }
    }
}

/// The HDF5 superblock signature, which gendpde restarts carry at offset 0.
const HDF5_SIGNATURE: [u8; 8] = [0x89, b'H', b'D', b'F', b'\r', b'\n', 0x1a, b'\n'];

/// Reads a restart file; see the module documentation.
pub struct RestartReader {
    path: PathBuf,
    header: RestartHeader,
    cols: Columns,
    _file: File,
}

impl fmt::Debug for RestartReader {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RestartReader")
            .field("path", &self.path)
            .field("header", &self.header)
            .finish_non_exhaustive()
    }
}

fn type_name(t: &TypeDescriptor) -> String {
    match t {
        TypeDescriptor::Unsigned(IntSize::U4) => "u32".into(),
        TypeDescriptor::Unsigned(IntSize::U8) => "u64".into(),
        TypeDescriptor::Integer(IntSize::U4) => "i32".into(),
        TypeDescriptor::Float(FloatSize::U8) => "f64".into(),
        TypeDescriptor::Unsigned(IntSize::U1) => "u8".into(),
        TypeDescriptor::VarLenUnicode => "variable-length UTF-8 string".into(),
        TypeDescriptor::VarLenAscii => "variable-length ASCII string".into(),
        TypeDescriptor::FixedAscii(n) => format!("{n}-byte ASCII string"),
        TypeDescriptor::FixedUnicode(n) => format!("{n}-byte UTF-8 string"),
        other => other.to_string(),
    }
}

/// Describes what an HDF5 object's datatype is, for error messages.
fn describe(dtype: hdf5::Result<hdf5::Datatype>) -> String {
    match dtype.and_then(|d| d.to_descriptor()) {
        Ok(t) => type_name(&t),
        Err(_) => "an unsupported type".into(),
    }
}

fn has_type<T: H5Type>(dtype: hdf5::Result<hdf5::Datatype>) -> bool {
    dtype
        .and_then(|d| d.to_descriptor())
        .is_ok_and(|t| t == T::type_descriptor())
}

/// Validation context for one file being opened.
struct Check<'a> {
    path: &'a Path,
    file: &'a File,
}

impl Check<'_> {
    fn err(&self, msg: impl fmt::Display) -> RestartError {
        error(self.path, msg)
    }

    fn attr(&self, name: &str) -> Result<hdf5::Attribute, RestartError> {
        if !self
            .file
            .attr_names()
            .is_ok_and(|n| n.iter().any(|a| a == name))
        {
            return Err(self.err(format!("missing root attribute '{name}'")));
        }
        self.file
            .attr(name)
            .map_err(|e| self.err(format!("cannot open root attribute '{name}': {e}")))
    }

    fn typed_attr<T: H5Type>(
        &self,
        name: &str,
        shape: &[usize],
    ) -> Result<hdf5::Attribute, RestartError> {
        let a = self.attr(name)?;
        let want = type_name(&T::type_descriptor());
        if !has_type::<T>(a.dtype()) {
            return Err(self.err(format!(
                "root attribute '{name}' should be of type {want}, found {}",
                describe(a.dtype())
            )));
        }
        if a.shape() != shape {
            return Err(self.err(format!(
                "root attribute '{name}' should have shape {shape:?}, found {:?}",
                a.shape()
            )));
        }
        Ok(a)
    }

    fn scalar<T: H5Type>(&self, name: &str) -> Result<T, RestartError> {
        self.typed_attr::<T>(name, &[])?
            .read_scalar::<T>()
            .map_err(|e| self.err(format!("cannot read root attribute '{name}': {e}")))
    }

    /// Decodes the bytes of a string attribute.
    fn utf8(&self, name: &str, bytes: &[u8]) -> Result<String, RestartError> {
        String::from_utf8(bytes.to_vec())
            .map_err(|_| self.err(format!("root attribute '{name}' is not valid UTF-8")))
    }

    fn optional_scalar<T: H5Type>(&self, name: &str) -> Result<Option<T>, RestartError> {
        if self
            .file
            .attr_names()
            .is_ok_and(|n| n.iter().any(|a| a == name))
        {
            self.scalar(name).map(Some)
        } else {
            Ok(None)
        }
    }

    /// Opens dataset `name`, checking its element type and, if given, its shape.
    fn dataset<T: H5Type>(
        &self,
        name: &str,
        shape: Option<&[usize]>,
    ) -> Result<Dataset, RestartError> {
        // Check each path component, so that a missing group is reported as
        // what it is rather than as an HDF5 error stack.
        let mut prefix = String::new();
        for part in name.split('/') {
            prefix.push('/');
            prefix.push_str(part);
            if !self.file.link_exists(&prefix) {
                return Err(self.err(format!(
                    "missing dataset '{name}' ('{prefix}' does not exist)"
                )));
            }
        }
        let d = self
            .file
            .dataset(name)
            .map_err(|e| self.err(format!("cannot open dataset '{name}': {e}")))?;
        if !has_type::<T>(d.dtype()) {
            return Err(self.err(format!(
                "dataset '{name}' should be of type {}, found {}",
                type_name(&T::type_descriptor()),
                describe(d.dtype())
            )));
        }
        if let Some(shape) = shape {
            if d.shape() != shape {
                return Err(self.err(format!(
                    "dataset '{name}' should have shape {shape:?}, found {:?}",
                    d.shape()
                )));
            }
        }
        Ok(d)
    }

    fn read_all<T: H5Type>(&self, name: &str, d: &Dataset) -> Result<Vec<T>, RestartError> {
        if d.size() == 0 {
            return Ok(Vec::new());
        }
        d.read_raw::<T>()
            .map_err(|e| self.err(format!("cannot read dataset '{name}': {e}")))
    }

    fn vector3(&self, name: &str) -> Result<[f64; 3], RestartError> {
        let d = self.dataset::<f64>(name, Some(&[3]))?;
        let v = self.read_all::<f64>(name, &d)?;
        v.try_into()
            .map_err(|_| self.err(format!("dataset '{name}' should hold 3 values")))
    }
}

impl RestartReader {
    /// Opens and validates a restart file: format name and version
    /// attributes, header fields present and of the right type, dataset
    /// shapes consistent with natoms, masses length = ntypes. Every problem
    /// is a [`RestartError`] naming the file and what was expected; a
    /// truncated, corrupt or foreign file gives an error, never a panic.
    pub fn open(path: &Path) -> Result<Self, RestartError> {
        hdf5::silence_errors(true);
        let meta = fs::metadata(path).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => error(path, "does not exist"),
            _ => error(path, format!("cannot be read: {e}")),
        })?;
        if !meta.is_file() {
            return Err(error(path, "is not a regular file"));
        }
        if meta.len() == 0 {
            return Err(error(
                path,
                "is empty (0 bytes); expected an HDF5 gendpde restart file",
            ));
        }
        let mut sig = [0u8; 8];
        {
            use std::io::Read as _;
            let mut f =
                fs::File::open(path).map_err(|e| error(path, format!("cannot be read: {e}")))?;
            let mut got = 0;
            while got < sig.len() {
                match f.read(&mut sig[got..]) {
                    Ok(0) => break,
                    Ok(k) => got += k,
                    Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                    Err(e) => return Err(error(path, format!("cannot be read: {e}"))),
                }
            }
            if got < sig.len() || sig != HDF5_SIGNATURE {
                return Err(error(
                    path,
                    "is not an HDF5 file (no HDF5 signature at its start); expected a gendpde restart file",
                ));
            }
        }
        let file = File::open(path).map_err(|e| {
            error(
                path,
                format!("cannot be opened as HDF5 (truncated or corrupt?): {e}"),
            )
        })?;
        let c = Check { path, file: &file };

        let Ok(format) = c.attr("format") else {
            return Err(c.err(format!(
                "is an HDF5 file but not a gendpde restart (no root attribute 'format' = \"{RESTART_FORMAT}\")"
            )));
        };
        if !has_type::<FormatString>(format.dtype()) || !format.shape().is_empty() {
            return Err(c.err(format!(
                "is not a gendpde restart: root attribute 'format' is a {} of shape {:?}, \
                 expected the {} \"{RESTART_FORMAT}\"",
                describe(format.dtype()),
                format.shape(),
                type_name(&FormatString::type_descriptor())
            )));
        }
        let format = c.utf8("format", c.scalar::<FormatString>("format")?.as_bytes())?;
        if format != RESTART_FORMAT {
            return Err(c.err(format!(
                "is not a gendpde restart: root attribute 'format' is {format:?}, expected \"{RESTART_FORMAT}\""
            )));
        }
        let version = c.scalar::<u32>("format_version")?;
        if version > RESTART_FORMAT_VERSION {
            return Err(c.err(format!(
                "format_version {version} is newer than this gendpde supports (up to {RESTART_FORMAT_VERSION}); \
                 use a newer gendpde"
            )));
        }
        if version < 1 {
            return Err(c.err(format!(
                "unsupported format_version {version} (expected {RESTART_FORMAT_VERSION})"
            )));
        }

        let creator_version = c.utf8(
            "creator_version",
            c.scalar::<VersionString>("creator_version")?.as_bytes(),
        )?;
        let step = c.scalar::<u64>("step")?;
        let time = c.scalar::<f64>("time")?;
        let dt = c.scalar::<f64>("dt")?;
        let natoms = c.scalar::<u64>("natoms")?;
        let max_tag = c.scalar::<u64>("max_tag")?;
        let ntypes = c.scalar::<u64>("ntypes")?;
        let last_build = c.scalar::<u64>("last_build")?;
        let energy0 = c.optional_scalar::<f64>("energy0")?;
        let cell_counts = if c
            .file
            .attr_names()
            .is_ok_and(|n| n.iter().any(|a| a == "cell_counts"))
        {
            let a = c.typed_attr::<u64>("cell_counts", &[3])?;
            let v = a
                .read_raw::<u64>()
                .map_err(|e| c.err(format!("cannot read root attribute 'cell_counts': {e}")))?;
            let mut out = [0usize; 3];
            for (o, &x) in out.iter_mut().zip(&v) {
                *o = usize::try_from(x)
                    .map_err(|_| c.err(format!("cell_counts {v:?} out of range")))?;
            }
            if v.len() != 3 {
                return Err(c.err(format!(
                    "root attribute 'cell_counts' should hold 3 values, found {}",
                    v.len()
                )));
            }
            Some(out)
        } else {
            None
        };
        if ntypes > MAX_RESTART_TYPES {
            return Err(c.err(format!(
                "ntypes = {ntypes} exceeds the limit of {MAX_RESTART_TYPES}"
            )));
        }
        let ntypes = ntypes as usize;
        let n = usize::try_from(natoms)
            .map_err(|_| c.err(format!("natoms = {natoms} does not fit in memory indices")))?;

        let lo = c.vector3("box/lo")?;
        let hi = c.vector3("box/hi")?;
        let md = c.dataset::<f64>("types/mass", Some(&[ntypes]))?;
        let masses = c
            .read_all::<f64>("types/mass", &md)?
            .into_iter()
            .map(|m| if m.is_nan() { None } else { Some(m) })
            .collect();

        let cmd_name = "script/commands";
        let cd = c.dataset::<u8>(cmd_name, None)?;
        if cd.ndim() != 1 || cd.size() > MAX_COMMAND_BYTES {
            return Err(c.err(format!(
                "dataset '{cmd_name}' should be one-dimensional with at most {MAX_COMMAND_BYTES} bytes, found shape {:?}",
                cd.shape()
            )));
        }
        let bytes = c.read_all::<u8>(cmd_name, &cd)?;
        if bytes.last().is_some_and(|&b| b != 0) {
            return Err(c.err(format!("dataset '{cmd_name}' does not end with a NUL byte")));
        }
        let commands = bytes
            .split(|&b| b == 0)
            .take(bytes.iter().filter(|&&b| b == 0).count())
            .map(|c| String::from_utf8(c.to_vec()))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|_| c.err(format!("dataset '{cmd_name}' is not valid UTF-8")))?;

        let (v, m) = ([n], [n, 3]);
        let cols = Columns {
            tag: c.dataset::<u64>("particles/tag", Some(&v))?,
            kind: c.dataset::<u32>("particles/type", Some(&v))?,
            mass: c.dataset::<f64>("particles/mass", Some(&v))?,
            r: c.dataset::<f64>("particles/r", Some(&m))?,
            p: c.dataset::<f64>("particles/p", Some(&m))?,
            u: c.dataset::<f64>("particles/u", Some(&v))?,
            theta: c.dataset::<f64>("particles/theta", Some(&v))?,
            image: c.dataset::<i32>("particles/image", Some(&m))?,
            cell: c.dataset::<i32>("particles/cell", Some(&m))?,
            r_at_build: c.dataset::<f64>("particles/r_at_build", Some(&m))?,
        };

        let header = RestartHeader {
            step,
            time,
            dt,
            natoms,
            max_tag,
            ntypes,
            lo,
            hi,
            masses,
            energy0,
            last_build,
            cell_counts,
            commands,
            creator_version,
        };
        header
            .check()
            .map_err(|e| c.err(format!("inconsistent header: {e}")))?;
        Ok(RestartReader {
            path: path.to_path_buf(),
            header,
            cols,
            _file: file,
        })
    }

    pub fn header(&self) -> &RestartHeader {
        &self.header
    }

    /// Reads rows [start, start + len) (clipped to natoms) into `rows`
    /// (cleared first).
    pub fn read_rows(
        &self,
        start: u64,
        len: u64,
        rows: &mut ParticleRows,
    ) -> Result<(), RestartError> {
        rows.clear();
        let natoms = self.header.natoms;
        let a = start.min(natoms);
        let b = start.saturating_add(len).min(natoms);
        if a >= b {
            return Ok(());
        }
        // natoms fits in usize (checked in open).
        let (a, b) = (a as usize, b as usize);
        let n = b - a;
        let err = |name: &str, e: hdf5::Error| {
            error(
                &self.path,
                format!("reading rows {a}..{b} of dataset 'particles/{name}': {e}"),
            )
        };
        fn one<T: H5Type + Clone>(d: &Dataset, a: usize, b: usize) -> hdf5::Result<Vec<T>> {
            Ok(d.read_slice_1d::<T, _>(a..b)?.iter().cloned().collect())
        }
        fn three<T: H5Type + Copy + Default>(
            d: &Dataset,
            a: usize,
            b: usize,
        ) -> hdf5::Result<Vec<[T; 3]>> {
            let arr = d.read_slice_2d::<T, _>((a..b, ..))?;
            if arr.shape() != [b - a, 3] {
                return Err(format!("got shape {:?}, expected [{}, 3]", arr.shape(), b - a).into());
            }
            let flat: Vec<T> = arr.iter().copied().collect();
            Ok(flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
        }
        let c = &self.cols;
        rows.tag = one(&c.tag, a, b).map_err(|e| err("tag", e))?;
        rows.kind = one(&c.kind, a, b).map_err(|e| err("type", e))?;
        rows.mass = one(&c.mass, a, b).map_err(|e| err("mass", e))?;
        rows.r = three(&c.r, a, b).map_err(|e| err("r", e))?;
        rows.p = three(&c.p, a, b).map_err(|e| err("p", e))?;
        rows.u = one(&c.u, a, b).map_err(|e| err("u", e))?;
        rows.theta = one(&c.theta, a, b).map_err(|e| err("theta", e))?;
        rows.image = three(&c.image, a, b).map_err(|e| err("image", e))?;
        rows.cell = three(&c.cell, a, b).map_err(|e| err("cell", e))?;
        rows.r_at_build = three(&c.r_at_build, a, b).map_err(|e| err("r_at_build", e))?;
        if let Err(e) = rows.check() {
            rows.clear();
            return Err(error(&self.path, format!("reading rows {a}..{b}: {e}")));
        }
        debug_assert_eq!(rows.len(), n);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A scratch directory removed when dropped.
    struct TempDir(PathBuf);

    impl TempDir {
        fn new(name: &str) -> Self {
            static COUNTER: AtomicUsize = AtomicUsize::new(0);
            let k = COUNTER.fetch_add(1, Ordering::Relaxed);
            let dir = std::env::temp_dir()
                .join(format!("gendpde-restart-{}-{k}-{name}", std::process::id()));
            let _ = fs::remove_dir_all(&dir);
            fs::create_dir_all(&dir).unwrap();
            TempDir(dir)
        }
        fn join(&self, name: &str) -> PathBuf {
            self.0.join(name)
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = fs::remove_dir_all(&self.0);
        }
    }

    /// Fixed 64-bit LCG (Knuth's MMIX constants).
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            self.0 >> 11
        }
        fn below(&mut self, n: u64) -> u64 {
            self.next() % n
        }
        fn f64(&mut self) -> f64 {
            // Any bit pattern at all, so the round trip sees NaN payloads,
            // infinities, subnormals and -0.
            f64::from_bits(self.next() ^ (self.next() << 53))
        }
        fn f64_3(&mut self) -> [f64; 3] {
            [self.f64(), self.f64(), self.f64()]
        }
        fn i32_3(&mut self) -> [i32; 3] {
            [self.next() as i32, self.next() as i32, self.next() as i32]
        }
    }

    fn header(natoms: u64) -> RestartHeader {
        RestartHeader {
            step: 123_456_789_012,
            time: 0.1 + 0.2,
            dt: 1e-3 / 3.0,
            natoms,
            max_tag: 3 * natoms + 7,
            ntypes: 3,
            lo: [-5.5, -0.0, 1e-300],
            hi: [5.5, 10.0 / 3.0, 2.0],
            masses: vec![Some(1.0 / 3.0), None, Some(f64::from_bits(1))],
            energy0: Some(-1_234.567_890_123_456_7),
            last_build: 123_456_789_000,
            cell_counts: Some([7, 3, 11]),
            commands: vec![
                "pair_style gendpde 1.0 12345".into(),
                "pair_coeff * * 25.0 4.5 1.0".into(),
                "fix 1 all shardlow".into(),
                "timestep 0.001".into(),
                "neighbor 0.3 bin".into(),
                "neigh_modify every 1 delay 0 check yes".into(),
                "".into(),
                "print \"unicode: θ ≈ 1\nsecond line\"".into(),
            ],
            creator_version: "gendpde 0.1.0 (test)".into(),
        }
    }

    /// `natoms` particles with tags 3i + 1, random bits everywhere else.
    fn particles(natoms: u64, seed: u64) -> ParticleRows {
        let mut g = Lcg(seed);
        let mut rows = ParticleRows::default();
        for i in 0..natoms {
            rows.tag.push(3 * i + 1);
            rows.kind.push(g.next() as u32);
            rows.mass.push(g.f64());
            rows.r.push(g.f64_3());
            rows.p.push(g.f64_3());
            rows.u.push(g.f64());
            rows.theta.push(g.f64());
            rows.image.push(g.i32_3());
            rows.cell.push(g.i32_3());
            rows.r_at_build.push(g.f64_3());
        }
        // A few values that must survive exactly.
        if natoms >= 4 {
            rows.mass[0] = f64::from_bits(0x7ff8_0000_dead_beef); // quiet NaN with payload
            rows.mass[1] = f64::from_bits(0x7ff0_0000_0000_0001); // signalling NaN
            rows.u[2] = -0.0;
            rows.theta[3] = f64::from_bits(0x0000_0000_0000_0003); // subnormal
            rows.r[0] = [f64::INFINITY, f64::NEG_INFINITY, f64::MIN_POSITIVE];
            rows.image[0] = [i32::MIN, i32::MAX, 0];
        }
        rows
    }

    fn slice_rows(all: &ParticleRows, a: usize, b: usize) -> ParticleRows {
        ParticleRows {
            tag: all.tag[a..b].to_vec(),
            kind: all.kind[a..b].to_vec(),
            mass: all.mass[a..b].to_vec(),
            r: all.r[a..b].to_vec(),
            p: all.p[a..b].to_vec(),
            u: all.u[a..b].to_vec(),
            theta: all.theta[a..b].to_vec(),
            image: all.image[a..b].to_vec(),
            cell: all.cell[a..b].to_vec(),
            r_at_build: all.r_at_build[a..b].to_vec(),
        }
    }

    fn append_rows(to: &mut ParticleRows, from: &ParticleRows) {
        to.tag.extend_from_slice(&from.tag);
        to.kind.extend_from_slice(&from.kind);
        to.mass.extend_from_slice(&from.mass);
        to.r.extend_from_slice(&from.r);
        to.p.extend_from_slice(&from.p);
        to.u.extend_from_slice(&from.u);
        to.theta.extend_from_slice(&from.theta);
        to.image.extend_from_slice(&from.image);
        to.cell.extend_from_slice(&from.cell);
        to.r_at_build.extend_from_slice(&from.r_at_build);
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    fn bits3(v: &[[f64; 3]]) -> Vec<[u64; 3]> {
        v.iter().map(|x| x.map(f64::to_bits)).collect()
    }

    fn rows_bit_identical(a: &ParticleRows, b: &ParticleRows) -> bool {
        a.tag == b.tag
            && a.kind == b.kind
            && bits(&a.mass) == bits(&b.mass)
            && bits3(&a.r) == bits3(&b.r)
            && bits3(&a.p) == bits3(&b.p)
            && bits(&a.u) == bits(&b.u)
            && bits(&a.theta) == bits(&b.theta)
            && a.image == b.image
            && a.cell == b.cell
            && bits3(&a.r_at_build) == bits3(&b.r_at_build)
    }

    fn assert_rows_bit_exact(a: &ParticleRows, b: &ParticleRows) {
        assert_eq!(a.tag, b.tag);
        assert_eq!(a.kind, b.kind);
        assert_eq!(bits(&a.mass), bits(&b.mass));
        assert_eq!(bits3(&a.r), bits3(&b.r));
        assert_eq!(bits3(&a.p), bits3(&b.p));
        assert_eq!(bits(&a.u), bits(&b.u));
        assert_eq!(bits(&a.theta), bits(&b.theta));
        assert_eq!(a.image, b.image);
        assert_eq!(a.cell, b.cell);
        assert_eq!(bits3(&a.r_at_build), bits3(&b.r_at_build));
    }

    fn assert_header_bit_exact(a: &RestartHeader, b: &RestartHeader) {
        let opt = |v: &[Option<f64>]| v.iter().map(|m| m.map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(a.step, b.step);
        assert_eq!(a.time.to_bits(), b.time.to_bits());
        assert_eq!(a.dt.to_bits(), b.dt.to_bits());
        assert_eq!(
            (a.natoms, a.max_tag, a.ntypes),
            (b.natoms, b.max_tag, b.ntypes)
        );
        assert_eq!(a.lo.map(f64::to_bits), b.lo.map(f64::to_bits));
        assert_eq!(a.hi.map(f64::to_bits), b.hi.map(f64::to_bits));
        assert_eq!(opt(&a.masses), opt(&b.masses));
        assert_eq!(a.energy0.map(f64::to_bits), b.energy0.map(f64::to_bits));
        assert_eq!(a.last_build, b.last_build);
        assert_eq!(a.cell_counts, b.cell_counts);
        assert_eq!(a.commands, b.commands);
        assert_eq!(a.creator_version, b.creator_version);
    }

    /// Writes `rows` to `path` in blocks ending at the given offsets.
    fn write_restart(path: &Path, h: &RestartHeader, rows: &ParticleRows, ends: &[usize]) {
        let mut w = RestartWriter::create(path, h).unwrap();
        let mut a = 0;
        for &b in ends {
            w.write_rows(&slice_rows(rows, a, b)).unwrap();
            a = b;
        }
        w.finish().unwrap();
    }

    fn open_err(path: &Path) -> String {
        match RestartReader::open(path) {
            Ok(_) => panic!("{} opened although it should not", path.display()),
            Err(e) => {
                assert!(
                    e.0.contains(&path.display().to_string()),
                    "error does not name the file: {e}"
                );
                e.0
            }
        }
    }

    fn assert_contains(msg: &str, want: &str) {
        assert!(
            msg.contains(want),
            "expected {want:?} in error message {msg:?}"
        );
    }

    #[test]
    fn round_trip_is_bit_exact() {
        let dir = TempDir::new("round-trip");
        let path = dir.join("restart.h5");
        let h = header(1000);
        let all = particles(1000, 42);
        write_restart(&path, &h, &all, &[333, 334, 1000]);
        assert!(!temp_path(&path).exists(), "temporary file left behind");

        let r = RestartReader::open(&path).unwrap();
        assert_header_bit_exact(r.header(), &h);
        assert_eq!(
            r.header(),
            &RestartHeader {
                masses: r.header().masses.clone(),
                ..h.clone()
            }
        );

        // Read back in blocks unrelated to the written ones, the last one
        // running past natoms (clipped).
        let mut got = ParticleRows::default();
        let mut block = ParticleRows::default();
        let mut start = 0;
        for len in [1, 99, 400, 0, 250, 1000] {
            r.read_rows(start, len, &mut block).unwrap();
            assert_eq!(block.len() as u64, len.min(1000 - start));
            append_rows(&mut got, &block);
            start += block.len() as u64;
        }
        assert_eq!(start, 1000);
        assert_rows_bit_exact(&got, &all);

        // Past the end: empty, and the buffer is cleared.
        r.read_rows(1000, 10, &mut block).unwrap();
        assert!(block.is_empty() && block.r.is_empty() && block.r_at_build.is_empty());
        r.read_rows(u64::MAX, u64::MAX, &mut block).unwrap();
        assert!(block.is_empty());
        r.read_rows(990, u64::MAX, &mut block).unwrap();
        assert_rows_bit_exact(&block, &slice_rows(&all, 990, 1000));
    }

    #[test]
    fn optional_fields_and_empty_system_round_trip() {
        let dir = TempDir::new("optional");
        let path = dir.join("restart.h5");
        let h = RestartHeader {
            natoms: 0,
            max_tag: 0,
            ntypes: 2,
            masses: vec![None, None],
            energy0: None,
            cell_counts: None,
            commands: vec![],
            ..header(0)
        };
        write_restart(&path, &h, &ParticleRows::default(), &[]);
        let r = RestartReader::open(&path).unwrap();
        assert_eq!(r.header(), &h);
        let mut rows = particles(3, 1);
        r.read_rows(0, 10, &mut rows).unwrap();
        assert!(rows.is_empty());

        // Some(NaN) for energy0 stays distinct from None.
        let h2 = RestartHeader {
            energy0: Some(f64::NAN),
            ntypes: 0,
            masses: vec![],
            ..h
        };
        write_restart(&path, &h2, &ParticleRows::default(), &[]);
        let r = RestartReader::open(&path).unwrap();
        assert!(r.header().energy0.is_some_and(f64::is_nan));
        assert_eq!(r.header().masses, vec![]);
    }

    #[test]
    fn unfinished_writer_leaves_no_file_and_keeps_existing_one() {
        let dir = TempDir::new("atomic");
        let path = dir.join("restart.h5");

        // Nothing there yet: a dropped writer leaves nothing behind.
        {
            let mut w = RestartWriter::create(&path, &header(10)).unwrap();
            w.write_rows(&slice_rows(&particles(10, 1), 0, 5)).unwrap();
        }
        assert!(!path.exists());
        assert!(!temp_path(&path).exists());

        // A good file is untouched by a later writer that never finishes.
        let h = header(10);
        let all = particles(10, 2);
        write_restart(&path, &h, &all, &[10]);
        let before = fs::read(&path).unwrap();
        {
            let mut w = RestartWriter::create(&path, &header(20)).unwrap();
            w.write_rows(&slice_rows(&particles(20, 3), 0, 20)).unwrap();
            assert!(temp_path(&path).exists());
            // dropped without finish
        }
        assert_eq!(fs::read(&path).unwrap(), before);
        assert!(!temp_path(&path).exists());
        let r = RestartReader::open(&path).unwrap();
        let mut rows = ParticleRows::default();
        r.read_rows(0, 10, &mut rows).unwrap();
        assert_rows_bit_exact(&rows, &all);
    }

    #[test]
    fn finish_with_too_few_rows_is_an_error() {
        let dir = TempDir::new("too-few");
        let path = dir.join("restart.h5");
        let all = particles(10, 4);
        write_restart(&path, &header(10), &all, &[10]);
        let before = fs::read(&path).unwrap();

        let mut w = RestartWriter::create(&path, &header(10)).unwrap();
        w.write_rows(&slice_rows(&all, 0, 9)).unwrap();
        let e = w.finish().unwrap_err();
        assert_contains(&e.0, "only 9 of natoms = 10 particle rows were written");
        assert_contains(&e.0, &path.display().to_string());
        assert_eq!(fs::read(&path).unwrap(), before);
        assert!(!temp_path(&path).exists());
    }

    #[test]
    fn writer_rejects_bad_rows_and_headers() {
        let dir = TempDir::new("bad-rows");
        let path = dir.join("restart.h5");
        let all = particles(10, 5);

        let mut w = RestartWriter::create(&path, &header(10)).unwrap();
        let mut uneven = slice_rows(&all, 0, 3);
        uneven.theta.pop();
        assert_contains(&w.write_rows(&uneven).unwrap_err().0, "unequal lengths");
        w.write_rows(&slice_rows(&all, 0, 5)).unwrap();
        // Going backwards in tag order.
        assert_contains(
            &w.write_rows(&slice_rows(&all, 4, 6)).unwrap_err().0,
            "strictly increasing",
        );
        // Too many rows.
        let mut more = slice_rows(&all, 5, 10);
        append_rows(
            &mut more,
            &ParticleRows {
                tag: vec![1000],
                ..slice_rows(&all, 0, 1)
            },
        );
        assert_contains(&w.write_rows(&more).unwrap_err().0, "exceed natoms = 10");
        // A tag above max_tag.
        let mut big = slice_rows(&all, 5, 6);
        big.tag[0] = header(10).max_tag + 1;
        assert_contains(&w.write_rows(&big).unwrap_err().0, "exceeds max_tag");
        // Rejected blocks were not counted: the rest still completes the file.
        w.write_rows(&slice_rows(&all, 5, 10)).unwrap();
        w.finish().unwrap();
        let r = RestartReader::open(&path).unwrap();
        let mut rows = ParticleRows::default();
        r.read_rows(0, 10, &mut rows).unwrap();
        assert_rows_bit_exact(&rows, &all);

        let bad = RestartHeader {
            masses: vec![Some(1.0)],
            ..header(10)
        };
        assert_contains(
            &RestartWriter::create(&path, &bad).unwrap_err().0,
            "expected 3 per-type masses",
        );
        let bad = RestartHeader {
            lo: [0.0; 3],
            hi: [1.0, 0.0, 1.0],
            ..header(10)
        };
        assert_contains(
            &RestartWriter::create(&path, &bad).unwrap_err().0,
            "lo < hi",
        );
        let bad = RestartHeader {
            masses: vec![None, Some(f64::NAN), None],
            ..header(10)
        };
        assert_contains(
            &RestartWriter::create(&path, &bad).unwrap_err().0,
            "cannot be stored",
        );
        let bad = RestartHeader {
            commands: vec!["a\0b".into()],
            ..header(10)
        };
        assert_contains(
            &RestartWriter::create(&path, &bad).unwrap_err().0,
            "script command",
        );
        assert!(!temp_path(&path).exists());
        let e =
            RestartWriter::create(&dir.join("no/such/dir/restart.h5"), &header(10)).unwrap_err();
        assert_contains(&e.0, "no/such/dir/restart.h5.tmp: cannot be created");
        // The good file is still there.
        RestartReader::open(&path).unwrap();
    }

    #[test]
    fn open_missing_empty_and_text_files() {
        let dir = TempDir::new("not-hdf5");
        let missing = dir.join("missing.h5");
        assert_contains(&open_err(&missing), "does not exist");

        let empty = dir.join("empty.h5");
        fs::write(&empty, b"").unwrap();
        assert_contains(&open_err(&empty), "is empty");

        let text = dir.join("in.lj");
        fs::write(&text, "units lj\natom_style atomic\nlattice fcc 0.8442\n").unwrap();
        assert_contains(&open_err(&text), "is not an HDF5 file");

        let short = dir.join("short.h5");
        fs::write(&short, &HDF5_SIGNATURE[..5]).unwrap();
        assert_contains(&open_err(&short), "is not an HDF5 file");

        assert_contains(&open_err(&dir.0), "is not a regular file");
    }

    #[test]
    fn open_truncated_restart() {
        let dir = TempDir::new("truncated");
        let path = dir.join("restart.h5");
        write_restart(&path, &header(1000), &particles(1000, 6), &[1000]);
        let bytes = fs::read(&path).unwrap();
        let n = bytes.len();
        let cut = dir.join("cut.h5");
        for len in [1, 8, 100, 512, 2048, n / 10, n / 3, n / 2, n - 100, n - 1] {
            fs::write(&cut, &bytes[..len]).unwrap();
            let msg = open_err(&cut);
            if len < 8 {
                assert_contains(&msg, "is not an HDF5 file");
            } else {
                assert_contains(&msg, "cannot be opened as HDF5 (truncated or corrupt?)");
            }
        }
    }

    #[test]
    fn open_foreign_hdf5_files() {
        let dir = TempDir::new("foreign");
        hdf5::silence_errors(true);

        let plain = dir.join("plain.h5");
        {
            let f = File::create(&plain).unwrap();
            f.new_dataset_builder()
                .with_data(&[1.0f64, 2.0][..])
                .create("x")
                .unwrap();
        }
        assert_contains(
            &open_err(&plain),
            "is an HDF5 file but not a gendpde restart",
        );

        let other = dir.join("other.h5");
        {
            let f = File::create(&other).unwrap();
            write_attr(&f, "format", &FormatString::from_ascii("h5md").unwrap()).unwrap();
        }
        assert_contains(&open_err(&other), "root attribute 'format' is \"h5md\"");

        let wrong_type = dir.join("wrong-type.h5");
        {
            let f = File::create(&wrong_type).unwrap();
            write_attr(&f, "format", &1.5f64).unwrap();
        }
        assert_contains(
            &open_err(&wrong_type),
            "is not a gendpde restart: root attribute 'format' is a f64",
        );
    }

    /// Writes a valid 100-particle restart, then lets `edit` alter it.
    fn crafted(dir: &TempDir, name: &str, edit: impl FnOnce(&File)) -> PathBuf {
        let path = dir.join(name);
        write_restart(&path, &header(100), &particles(100, 7), &[100]);
        hdf5::silence_errors(true);
        let f = File::open_rw(&path).unwrap();
        edit(&f);
        f.close().unwrap();
        path
    }

    #[test]
    fn open_inconsistent_restarts() {
        let dir = TempDir::new("inconsistent");

        let p = crafted(&dir, "short-u.h5", |f| {
            let g = f.group("particles").unwrap();
            g.unlink("u").unwrap();
            g.new_dataset::<f64>().shape(99).create("u").unwrap();
        });
        assert_contains(
            &open_err(&p),
            "dataset 'particles/u' should have shape [100], found [99]",
        );

        let p = crafted(&dir, "short-r.h5", |f| {
            let g = f.group("particles").unwrap();
            g.unlink("r").unwrap();
            g.new_dataset::<f64>().shape((50, 3)).create("r").unwrap();
        });
        assert_contains(
            &open_err(&p),
            "dataset 'particles/r' should have shape [100, 3], found [50, 3]",
        );

        let p = crafted(&dir, "no-tag.h5", |f| {
            f.group("particles").unwrap().unlink("tag").unwrap()
        });
        assert_contains(&open_err(&p), "missing dataset 'particles/tag'");

        let p = crafted(&dir, "no-particles.h5", |f| f.unlink("particles").unwrap());
        assert_contains(
            &open_err(&p),
            "missing dataset 'particles/tag' ('/particles' does not exist)",
        );

        let p = crafted(&dir, "float-tags.h5", |f| {
            let g = f.group("particles").unwrap();
            g.unlink("tag").unwrap();
            g.new_dataset::<f64>().shape(100).create("tag").unwrap();
        });
        assert_contains(
            &open_err(&p),
            "dataset 'particles/tag' should be of type u64, found f64",
        );

        let p = crafted(&dir, "masses.h5", |f| {
            let g = f.group("types").unwrap();
            g.unlink("mass").unwrap();
            g.new_dataset_builder()
                .with_data(&[1.0f64, 2.0][..])
                .create("mass")
                .unwrap();
        });
        assert_contains(
            &open_err(&p),
            "dataset 'types/mass' should have shape [3], found [2]",
        );

        let p = crafted(&dir, "newer.h5", |f| {
            f.attr("format_version")
                .unwrap()
                .write_scalar(&2u32)
                .unwrap();
        });
        assert_contains(
            &open_err(&p),
            "format_version 2 is newer than this gendpde supports",
        );

        let p = crafted(&dir, "no-step.h5", |f| f.delete_attr("step").unwrap());
        assert_contains(&open_err(&p), "missing root attribute 'step'");

        let p = crafted(&dir, "float-step.h5", |f| {
            f.delete_attr("step").unwrap();
            write_attr(f, "step", &5.0f64).unwrap();
        });
        assert_contains(
            &open_err(&p),
            "root attribute 'step' should be of type u64, found f64",
        );

        let p = crafted(&dir, "cells.h5", |f| {
            f.delete_attr("cell_counts").unwrap();
            f.new_attr_builder()
                .with_data(&[1u64, 2][..])
                .create("cell_counts")
                .unwrap();
        });
        assert_contains(
            &open_err(&p),
            "root attribute 'cell_counts' should have shape [3], found [2]",
        );

        let p = crafted(&dir, "box.h5", |f| {
            f.dataset("box/hi")
                .unwrap()
                .write_raw(&[1.0f64, -1.0, 1.0][..])
                .unwrap();
        });
        assert_contains(&open_err(&p), "inconsistent header: box bounds");
    }

    #[test]
    fn flipped_bytes_never_panic() {
        let dir = TempDir::new("fuzz");
        let path = dir.join("restart.h5");
        // Few particles, so that metadata makes up much of the file.
        let all = particles(40, 8);
        write_restart(&path, &header(40), &all, &[17, 40]);
        let good = fs::read(&path).unwrap();
        let bad = dir.join("bad.h5");
        let mut g = Lcg(0x5eed);
        let (mut opened, mut identical) = (0, 0);
        let nvar = 200;
        for variant in 0..nvar {
            let mut bytes = good.clone();
            let flips = 1 + g.below(4);
            for _ in 0..flips {
                // Half the flips land in the first 4 KiB (superblock, root
                // group, attributes), the rest anywhere.
                let span = if variant % 2 == 0 {
                    bytes.len().min(4096)
                } else {
                    bytes.len()
                };
                let at = g.below(span as u64) as usize;
                bytes[at] ^= 1 << g.below(8);
            }
            fs::write(&bad, &bytes).unwrap();
            if let Ok(r) = RestartReader::open(&bad) {
                opened += 1;
                let mut rows = ParticleRows::default();
                let mut got = ParticleRows::default();
                let mut ok = true;
                let mut start = 0;
                while start < r.header().natoms.min(1000) {
                    match r.read_rows(start, 16, &mut rows) {
                        Ok(()) => append_rows(&mut got, &rows),
                        Err(_) => {
                            ok = false;
                            break;
                        }
                    }
                    start += 16;
                }
                if ok && rows_bit_identical(&got, &all) && r.header() == &header(40) {
                    identical += 1;
                }
            }
        }
        eprintln!(
            "flipped-byte variants: {opened} of {nvar} opened, {identical} read back unchanged"
        );
    }
}
