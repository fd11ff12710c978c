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
//! | `noise_shift`     | u64                       | only present when not 0: the noise key's shift (`reset_timestep`) |
//! | `stale_tallies`   | u8                        | only present (1) when the per-particle energies and virials were not computed at `step` |
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
pub const RESTART_FORMAT_VERSION: u32 = 2;
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
    /// What `reset_timestep` moved the step by (wrapping sum): the noise is keyed by
    /// step + noise_shift.
    pub noise_shift: u64,
    /// The per-particle pair energies and virials are not those of `step` (a step
    /// without output skips them, as LAMMPS's eflag/vflag): a continuation keeps the
    /// ones its set-up computes.
    pub stale_tallies: bool,
    /// Global cell grid at the last build.
    pub cell_counts: Option<[usize; 3]>,
    /// Script commands that re-create the styles (pair_style, pair_coeff,
    /// fix, timestep, neighbor, neigh_modify ...), in order.
    pub commands: Vec<String>,
    pub creator_version: String,
    /// The per-particle columns, in row order; one of them is `id`.
    pub columns: Vec<ColumnSpec>,
    /// The particle store's enabled optional fields (bits of the engine's `Fields`).
    pub enabled: u32,
    /// Group names by bit (an empty name is a free slot).
    pub groups: Vec<String>,
    /// Named state of fixes and computes (energy tallies, open averaging windows).
    pub state: Vec<(String, Vec<f64>)>,
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
        if self.columns.iter().any(|c| c.width == 0 || c.name.is_empty() || c.name.contains(['/', '\0', '.'])) {
            return Err("particle columns need a width and a plain name".into());
        }
        if !self.columns.iter().any(|c| c.name == "id" && c.width == 1 && c.integer) {
            return Err("the particle columns lack the integer column 'id'".into());
        }
        if self.groups.len() > 32 {
            return Err(format!("at most 32 groups, got {}", self.groups.len()));
        }
        Ok(())
    }
}

/// One per-particle column: `width` values per particle, integers or floats.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ColumnSpec {
    pub name: String,
    pub width: usize,
    pub integer: bool,
}

/// Values per particle of `columns`.
pub fn row_width(columns: &[ColumnSpec]) -> usize {
    columns.iter().map(|c| c.width).sum()
}

/// Particle rows per chunk of the particle datasets (each chunk carries a Fletcher32
/// checksum).
const CHUNK_ROWS: usize = 1 << 14;

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
    inner: Option<(File, Vec<Dataset>)>,
    columns: Vec<ColumnSpec>,
    /// Offset of the `id` column in a row.
    id_at: usize,
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
            columns: header.columns.clone(),
            id_at: id_offset(&header.columns),
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
        if header.noise_shift != 0 {
            write_attr(&file, "noise_shift", &header.noise_shift).map_err(h5)?;
        }
        if header.stale_tallies {
            write_attr(&file, "stale_tallies", &1u8).map_err(h5)?;
        }
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
        checked(&bx, "lo", &[3], f64::NAN).and_then(|d| d.write_raw(&header.lo)).map_err(h5)?;
        checked(&bx, "hi", &[3], f64::NAN).and_then(|d| d.write_raw(&header.hi)).map_err(h5)?;

        let masses: Vec<f64> = header
            .masses
            .iter()
            .map(|m| m.unwrap_or(f64::NAN))
            .collect();
        let types = file.create_group("types").map_err(h5)?;
        checked(&types, "mass", &[masses.len()], -1.0).and_then(|d| write_nonempty(&d, &masses)).map_err(h5)?;

        let commands = join_commands(path, &header.commands)?;
        let script = file.create_group("script").map_err(h5)?;
        checked(&script, "commands", &[commands.len()], MISSING_BYTE).and_then(|d| write_nonempty(&d, &commands)).map_err(h5)?;

        write_names(&file, "groups", &header.groups).map_err(h5)?;
        write_attr(&file, "enabled", &header.enabled).map_err(h5)?;
        let state = file.create_group("state").map_err(h5)?;
        let names: Vec<String> = header.state.iter().map(|(n, _)| n.clone()).collect();
        write_names(&state, "names", &names).map_err(h5)?;
        let lengths: Vec<u64> = header.state.iter().map(|(_, v)| v.len() as u64).collect();
        let values: Vec<f64> = header.state.iter().flat_map(|(_, v)| v.iter().copied()).collect();
        checked(&state, "lengths", &[lengths.len()], u64::MAX).and_then(|d| write_nonempty(&d, &lengths)).map_err(h5)?;
        checked(&state, "values", &[values.len()], f64::NAN).and_then(|d| write_nonempty(&d, &values)).map_err(h5)?;

        let pg = file.create_group("particles").map_err(h5)?;
        let names: Vec<String> = header.columns.iter().map(|c| c.name.clone()).collect();
        write_names(&pg, "columns", &names).map_err(h5)?;
        let mut cols = Vec::new();
        for c in &header.columns {
            let shape: Vec<usize> = if c.width == 1 { vec![natoms] } else { vec![natoms, c.width] };
            let d = if c.integer { checked(&pg, &c.name, &shape, MISSING_INTEGER) } else { checked(&pg, &c.name, &shape, f64::NAN) };
            cols.push(d.map_err(h5)?);
        }
        writer.inner = Some((file, cols));
        Ok(writer)
    }

    /// Appends the next rows (row-major, the header's columns; rows arrive in tag
    /// order, in blocks; the total must reach header.natoms).
    pub fn write_rows(&mut self, rows: &[f64]) -> Result<(), RestartError> {
        let path = self.path.clone();
        let width = row_width(&self.columns);
        if rows.len() % width != 0 {
            return Err(error(&path, format!("{} values do not make rows of {width}", rows.len())));
        }
        let n = rows.len() / width;
        let Some((_, cols)) = &self.inner else {
            return Err(error(&path, "an earlier write failed; the restart cannot be completed"));
        };
        if self.written + n as u64 > self.natoms {
            return Err(error(&path, format!("{} rows written plus {n} more exceed natoms = {}", self.written, self.natoms)));
        }
        let mut last = self.last_tag;
        for row in rows.chunks_exact(width) {
            let t = row[self.id_at] as u64;
            if last.is_some_and(|l| t <= l) {
                return Err(error(&path, format!("particle tags must be strictly increasing, got {t} after {}", last.unwrap_or(0))));
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
            let mut offset = 0;
            for (c, d) in self.columns.iter().zip(cols) {
                let column = rows.chunks_exact(width).flat_map(|row| &row[offset..offset + c.width]);
                if c.integer {
                    let v: Vec<i64> = column.map(|&x| x as i64).collect();
                    write_block(d, &v, a, b, c.width)?;
                } else {
                    let v: Vec<f64> = column.copied().collect();
                    write_block(d, &v, a, b, c.width)?;
                }
                offset += c.width;
            }
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

/// Offset of the `id` column in a row of `columns` (0 when absent; `check` refuses that).
fn id_offset(columns: &[ColumnSpec]) -> usize {
    let k = columns.iter().position(|c| c.name == "id").unwrap_or(0);
    row_width(&columns[..k])
}

/// Fill value of byte datasets: not UTF-8, so text read from a chunk whose index was
/// damaged (HDF5 then returns the fill value) is refused.
pub(crate) const MISSING_BYTE: u8 = 0xff;
/// Fill value of integer particle columns: beyond 2^53, which the reader refuses.
pub(crate) const MISSING_INTEGER: i64 = i64::MIN;

/// Creates a dataset of `shape` with a Fletcher32 checksum on every chunk and a fill
/// value the reader refuses (a chunk lost from a damaged index reads as the fill value).
fn checked<T: H5Type + Copy>(loc: &hdf5::Group, name: &str, shape: &[usize], fill: T) -> hdf5::Result<Dataset> {
    let mut chunk = shape.to_vec();
    chunk[0] = chunk[0].clamp(1, CHUNK_ROWS);
    loc.new_dataset::<T>().shape(shape).chunk(chunk).fletcher32().fill_value(fill).create(name)
}

fn write_nonempty<T: H5Type>(d: &Dataset, v: &[T]) -> hdf5::Result<()> {
    if v.is_empty() {
        Ok(())
    } else {
        d.write_raw(v)
    }
}

/// Writes rows a..b of a column dataset of `width` values per row.
fn write_block<T: H5Type>(d: &Dataset, v: &[T], a: usize, b: usize, width: usize) -> hdf5::Result<()> {
    if width == 1 {
        d.write_slice(v, a..b)
    } else {
        let arr = ndarray::ArrayView2::from_shape((b - a, width), v).map_err(|e| e.to_string())?;
        d.write_slice(arr, (a..b, ..))
    }
}

/// Stores names as one checksummed byte dataset, each name followed by a NUL byte.
fn write_names(loc: &hdf5::Group, name: &str, names: &[String]) -> hdf5::Result<()> {
    let mut bytes = Vec::new();
    for n in names {
        bytes.extend_from_slice(n.as_bytes());
        bytes.push(0);
    }
    write_nonempty(&checked(loc, name, &[bytes.len()], MISSING_BYTE)?, &bytes)
}

mod read;
pub use read::RestartReader;

#[cfg(test)]
mod tests;
