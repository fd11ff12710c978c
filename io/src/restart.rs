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
//! | name              | type        | meaning                                   |
//! |-------------------|-------------|-------------------------------------------|
//! | `format`          | UTF-8 string| always `gendpde-restart`                  |
//! | `format_version`  | u32         | 1                                         |
//! | `creator_version` | UTF-8 string| version of the program that wrote it      |
//! | `step`            | u64         | current step                              |
//! | `time`            | f64         | simulated time                            |
//! | `dt`              | f64         | timestep                                  |
//! | `natoms`          | u64         | number of particle rows                   |
//! | `max_tag`         | u64         | largest tag ever assigned                 |
//! | `ntypes`          | u64         | number of particle types                  |
//! | `last_build`      | u64         | step of the last neighbour-list build     |
//! | `energy0`         | f64         | only present when `energy0` is `Some`     |
//! | `cell_counts`     | u64 `[3]`   | only present when `cell_counts` is `Some` |
//!
//! Datasets:
//!
//! * `/box/lo`, `/box/hi`: f64 `[3]`;
//! * `/types/mass`: f64 `[ntypes]`, NaN for a type without a mass;
//! * `/script/commands`: variable-length UTF-8 strings `[ncommands]`;
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

use hdf5::types::{FloatSize, IntSize, TypeDescriptor, VarLenUnicode};
use hdf5::{Dataset, File, H5Type, Location};

/// Value of the root `format` attribute.
pub const RESTART_FORMAT: &str = "gendpde-restart";
/// The `format_version` this module writes and the newest it reads.
pub const RESTART_FORMAT_VERSION: u32 = 1;
/// Most particle types a restart may declare (guards allocations driven by
/// a corrupt header).
pub const MAX_RESTART_TYPES: u64 = 1_000_000;
/// Most script commands a restart may hold.
pub const MAX_RESTART_COMMANDS: usize = 10_000_000;

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
        if self.natoms > self.max_tag {
            return Err(format!(
                "natoms = {} exceeds max_tag = {} (tags are unique and at most max_tag)",
                self.natoms, self.max_tag
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
            return Err(format!("particle columns have unequal lengths ({})", list.join(", ")));
        }
        Ok(n)
    }
}

/// Names of the per-particle datasets in `/particles`, with their ranks.
const COLUMNS: [(&str, usize); 10] = [
    ("tag", 1),
    ("type", 1),
    ("mass", 1),
    ("r", 2),
    ("p", 2),
    ("u", 1),
    ("theta", 1),
    ("image", 2),
    ("cell", 2),
    ("r_at_build", 2),
];

/// Open handles of the per-particle datasets, in the order of [`COLUMNS`].
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

fn vlen(path: &Path, what: &str, s: &str) -> Result<VarLenUnicode, RestartError> {
    VarLenUnicode::from_str(s).map_err(|e| error(path, format!("cannot store {what} {s:?}: {e}")))
}

fn write_attr<T: H5Type>(loc: &Location, name: &str, value: &T) -> hdf5::Result<()> {
    loc.new_attr::<T>().shape(()).create(name)?.write_scalar(value)
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
        header.check().map_err(|e| error(path, format!("invalid header: {e}")))?;
        if let Some(t) = header.masses.iter().flatten().find(|m| m.is_nan()) {
            return Err(error(path, format!("invalid header: a per-type mass of {t} cannot be stored")));
        }
        let tmp = temp_path(path);
        let h5 = |e: hdf5::Error| error(&tmp, e);
        let file = File::with_options()
            .with_fapl(|fapl| fapl.libver_v18())
            .create(&tmp)
            .map_err(h5)?;
        // From here on, dropping `writer` on an error removes the temporary file.
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
        let natoms = usize::try_from(header.natoms)
            .map_err(|_| error(path, format!("natoms = {} does not fit in memory indices", header.natoms)))?;

        write_attr(&file, "format", &vlen(path, "format", RESTART_FORMAT)?).map_err(h5)?;
        write_attr(&file, "format_version", &RESTART_FORMAT_VERSION).map_err(h5)?;
        write_attr(&file, "creator_version", &vlen(path, "creator_version", &header.creator_version)?)
            .map_err(h5)?;
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
            file.new_attr_builder().with_data(&c[..]).create("cell_counts").map_err(h5)?;
        }

        let bx = file.create_group("box").map_err(h5)?;
        bx.new_dataset_builder().with_data(&header.lo[..]).create("lo").map_err(h5)?;
        bx.new_dataset_builder().with_data(&header.hi[..]).create("hi").map_err(h5)?;

        let masses: Vec<f64> = header.masses.iter().map(|m| m.unwrap_or(f64::NAN)).collect();
        let types = file.create_group("types").map_err(h5)?;
        types.new_dataset_builder().with_data(&masses[..]).create("mass").map_err(h5)?;

        let commands = header
            .commands
            .iter()
            .map(|c| vlen(path, "script command", c))
            .collect::<Result<Vec<_>, _>>()?;
        let script = file.create_group("script").map_err(h5)?;
        if commands.is_empty() {
            script.new_dataset::<VarLenUnicode>().shape(0).create("commands").map_err(h5)?;
        } else {
            script.new_dataset_builder().with_data(&commands[..]).create("commands").map_err(h5)?;
        }

        let pg = file.create_group("particles").map_err(h5)?;
        let d1 = |name: &str, f: fn(&hdf5::Group) -> hdf5::DatasetBuilderEmpty| {
            f(&pg).shape(natoms).create(name).map_err(h5)
        };
        let d2 = |name: &str, f: fn(&hdf5::Group) -> hdf5::DatasetBuilderEmpty| {
            f(&pg).shape((natoms, 3)).create(name).map_err(h5)
        };
        let cols = Columns {
            tag: d1("tag", |g| g.new_dataset::<u64>())?,
            kind: d1("type", |g| g.new_dataset::<u32>())?,
            mass: d1("mass", |g| g.new_dataset::<f64>())?,
            r: d2("r", |g| g.new_dataset::<f64>())?,
            p: d2("p", |g| g.new_dataset::<f64>())?,
            u: d1("u", |g| g.new_dataset::<f64>())?,
            theta: d1("theta", |g| g.new_dataset::<f64>())?,
            image: d2("image", |g| g.new_dataset::<i32>())?,
            cell: d2("cell", |g| g.new_dataset::<i32>())?,
            r_at_build: d2("r_at_build", |g| g.new_dataset::<f64>())?,
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
            return Err(error(&path, "an earlier write failed; the restart cannot be completed"));
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
                    format!("particle tags must be strictly increasing, got {t} after {}", last.unwrap_or(0)),
                ));
            }
            if t > self.max_tag {
                return Err(error(&path, format!("particle tag {t} exceeds max_tag = {}", self.max_tag)));
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
            cols.r.write_slice::<f64, _, _, _>(&rows.r[..], (a..b, ..))?;
            cols.p.write_slice::<f64, _, _, _>(&rows.p[..], (a..b, ..))?;
            cols.u.write_slice(&rows.u[..], a..b)?;
            cols.theta.write_slice(&rows.theta[..], a..b)?;
            cols.image.write_slice::<i32, _, _, _>(&rows.image[..], (a..b, ..))?;
            cols.cell.write_slice::<i32, _, _, _>(&rows.cell[..], (a..b, ..))?;
            cols.r_at_build.write_slice::<f64, _, _, _>(&rows.r_at_build[..], (a..b, ..))?;
            Ok(())
        })();
        if let Err(e) = result {
            // Part of the block may be on disk; refuse to go on.
            self.inner = None;
            return Err(error(&self.tmp, format!("writing particle rows {a}..{b}: {e}")));
        }
        self.written += n as u64;
        self.last_tag = last;
        Ok(())
    }

    /// Checks that natoms rows were written, flushes, closes and renames to
    /// `path` atomically.
    pub fn finish(mut self) -> Result<(), RestartError> {
        let Some((file, cols)) = self.inner.take() else {
            return Err(error(&self.path, "an earlier write failed; the restart was not written"));
        };
        if self.written != self.natoms {
            return Err(error(
                &self.path,
                format!("only {} of natoms = {} particle rows were written", self.written, self.natoms),
            ));
        }
        drop(cols);
        let tmp = self.tmp.clone();
        file.flush().map_err(|e| error(&tmp, format!("flushing: {e}")))?;
        file.close().map_err(|e| error(&tmp, format!("closing: {e}")))?;
        fs::File::open(&tmp)
            .and_then(|f| f.sync_all())
            .map_err(|e| error(&tmp, format!("syncing to disk: {e}")))?;
        fs::rename(&tmp, &self.path)
            .map_err(|e| error(&self.path, format!("renaming {} into place: {e}", tmp.display())))?;
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
        TypeDescriptor::VarLenUnicode => "variable-length UTF-8 string".into(),
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
    dtype.and_then(|d| d.to_descriptor()).is_ok_and(|t| t == T::type_descriptor())
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
        if !self.file.attr_names().is_ok_and(|n| n.iter().any(|a| a == name)) {
            return Err(self.err(format!("missing root attribute '{name}'")));
        }
        self.file.attr(name).map_err(|e| self.err(format!("cannot open root attribute '{name}': {e}")))
    }

    fn typed_attr<T: H5Type>(&self, name: &str, shape: &[usize]) -> Result<hdf5::Attribute, RestartError> {
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

    fn string(&self, name: &str) -> Result<String, RestartError> {
        Ok(self.scalar::<VarLenUnicode>(name)?.as_str().to_owned())
    }

    fn optional_scalar<T: H5Type>(&self, name: &str) -> Result<Option<T>, RestartError> {
        if self.file.attr_names().is_ok_and(|n| n.iter().any(|a| a == name)) {
            self.scalar(name).map(Some)
        } else {
            Ok(None)
        }
    }

    fn dataset<T: H5Type>(&self, name: &str, shape: &[usize]) -> Result<Dataset, RestartError> {
        // Check each path component, so that a missing group is reported as
        // what it is rather than as an HDF5 error stack.
        let mut prefix = String::new();
        for part in name.split('/') {
            prefix.push('/');
            prefix.push_str(part);
            if !self.file.link_exists(&prefix) {
                return Err(self.err(format!("missing dataset '{name}' ('{prefix}' does not exist)")));
            }
        }
        let d = self.file.dataset(name).map_err(|e| self.err(format!("cannot open dataset '{name}': {e}")))?;
        if !has_type::<T>(d.dtype()) {
            return Err(self.err(format!(
                "dataset '{name}' should be of type {}, found {}",
                type_name(&T::type_descriptor()),
                describe(d.dtype())
            )));
        }
        if d.shape() != shape {
            return Err(self.err(format!("dataset '{name}' should have shape {shape:?}, found {:?}", d.shape())));
        }
        Ok(d)
    }

    fn read_all<T: H5Type>(&self, name: &str, d: &Dataset) -> Result<Vec<T>, RestartError> {
        if d.size() == 0 {
            return Ok(Vec::new());
        }
        d.read_raw::<T>().map_err(|e| self.err(format!("cannot read dataset '{name}': {e}")))
    }

    fn vector3(&self, name: &str) -> Result<[f64; 3], RestartError> {
        let d = self.dataset::<f64>(name, &[3])?;
        let v = self.read_all::<f64>(name, &d)?;
        v.try_into().map_err(|_| self.err(format!("dataset '{name}' should hold 3 values")))
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
            return Err(error(path, "is empty (0 bytes); expected an HDF5 gendpde restart file"));
        }
        let mut sig = [0u8; 8];
        {
            use std::io::Read as _;
            let mut f = fs::File::open(path).map_err(|e| error(path, format!("cannot be read: {e}")))?;
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
            error(path, format!("cannot be opened as HDF5 (truncated or corrupt?): {e}"))
        })?;
        let c = Check { path, file: &file };

        let format = match c.attr("format") {
            Ok(_) => c.string("format")?,
            Err(_) => {
                return Err(c.err(format!(
                    "is an HDF5 file but not a gendpde restart (no root attribute 'format' = \"{RESTART_FORMAT}\")"
                )))
            }
        };
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
            return Err(c.err(format!("unsupported format_version {version} (expected {RESTART_FORMAT_VERSION})")));
        }

        let creator_version = c.string("creator_version")?;
        let step = c.scalar::<u64>("step")?;
        let time = c.scalar::<f64>("time")?;
        let dt = c.scalar::<f64>("dt")?;
        let natoms = c.scalar::<u64>("natoms")?;
        let max_tag = c.scalar::<u64>("max_tag")?;
        let ntypes = c.scalar::<u64>("ntypes")?;
        let last_build = c.scalar::<u64>("last_build")?;
        let energy0 = c.optional_scalar::<f64>("energy0")?;
        let cell_counts = if c.file.attr_names().is_ok_and(|n| n.iter().any(|a| a == "cell_counts")) {
            let a = c.typed_attr::<u64>("cell_counts", &[3])?;
            let v = a.read_raw::<u64>().map_err(|e| c.err(format!("cannot read root attribute 'cell_counts': {e}")))?;
            let mut out = [0usize; 3];
            for (o, &x) in out.iter_mut().zip(&v) {
                *o = usize::try_from(x).map_err(|_| c.err(format!("cell_counts {v:?} out of range")))?;
            }
            if v.len() != 3 {
                return Err(c.err(format!("root attribute 'cell_counts' should hold 3 values, found {}", v.len())));
            }
            Some(out)
        } else {
            None
        };
        if ntypes > MAX_RESTART_TYPES {
            return Err(c.err(format!("ntypes = {ntypes} exceeds the limit of {MAX_RESTART_TYPES}")));
        }
        let ntypes = ntypes as usize;
        let n = usize::try_from(natoms)
            .map_err(|_| c.err(format!("natoms = {natoms} does not fit in memory indices")))?;

        let lo = c.vector3("box/lo")?;
        let hi = c.vector3("box/hi")?;
        let md = c.dataset::<f64>("types/mass", &[ntypes])?;
        let masses = c
            .read_all::<f64>("types/mass", &md)?
            .into_iter()
            .map(|m| if m.is_nan() { None } else { Some(m) })
            .collect();

        let cmd_name = "script/commands";
        let cd = {
            // The length is free; only the type and rank are checked here.
            let d = c.dataset::<VarLenUnicode>(cmd_name, &[]).or_else(|e| {
                let d = c.file.dataset(cmd_name).map_err(|_| e.clone())?;
                if d.ndim() == 1 {
                    c.dataset::<VarLenUnicode>(cmd_name, &d.shape())
                } else {
                    Err(c.err(format!("dataset '{cmd_name}' should be one-dimensional, found shape {:?}", d.shape())))
                }
            })?;
            if d.size() > MAX_RESTART_COMMANDS {
                return Err(c.err(format!("dataset '{cmd_name}' holds {} commands, more than the limit", d.size())));
            }
            d
        };
        let commands = c
            .read_all::<VarLenUnicode>(cmd_name, &cd)?
            .into_iter()
            .map(|s| s.as_str().to_owned())
            .collect();

        let col = |name: &str, rank: usize| {
            let full = format!("particles/{name}");
            match (name, rank) {
                ("tag", _) => c.dataset::<u64>(&full, &[n]),
                ("type", _) => c.dataset::<u32>(&full, &[n]),
                ("image" | "cell", _) => c.dataset::<i32>(&full, &[n, 3]),
                (_, 1) => c.dataset::<f64>(&full, &[n]),
                _ => c.dataset::<f64>(&full, &[n, 3]),
            }
        };
        let mut ds = Vec::with_capacity(COLUMNS.len());
        for (name, rank) in COLUMNS {
            ds.push(col(name, rank)?);
        }
        let mut ds = ds.into_iter();
        let mut next = || ds.next().expect("one dataset per column");
        let cols = Columns {
            tag: next(),
            kind: next(),
            mass: next(),
            r: next(),
            p: next(),
            u: next(),
            theta: next(),
            image: next(),
            cell: next(),
            r_at_build: next(),
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
        header.check().map_err(|e| c.err(format!("inconsistent header: {e}")))?;
        Ok(RestartReader { path: path.to_path_buf(), header, cols, _file: file })
    }

    pub fn header(&self) -> &RestartHeader {
        &self.header
    }

    /// Reads rows [start, start + len) (clipped to natoms) into `rows`
    /// (cleared first).
    pub fn read_rows(&self, start: u64, len: u64, rows: &mut ParticleRows) -> Result<(), RestartError> {
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
            error(&self.path, format!("reading rows {a}..{b} of dataset 'particles/{name}': {e}"))
        };
        fn one<T: H5Type>(d: &Dataset, a: usize, b: usize) -> hdf5::Result<Vec<T>> {
            Ok(d.read_slice_1d::<T, _>(a..b)?.iter().cloned().collect())
        }
        fn three<T: H5Type + Copy + Default>(d: &Dataset, a: usize, b: usize) -> hdf5::Result<Vec<[T; 3]>> {
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
