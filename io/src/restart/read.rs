//! Reading and validating restart files (`RestartReader`).

use super::*;


/// Reads a restart file; see the module documentation.
pub struct RestartReader {
    path: PathBuf,
    header: RestartHeader,
    cols: Vec<Dataset>,
    /// Tag of the last row read, for the order check across blocks.
    last_tag: std::cell::Cell<u64>,
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
        self.checksummed(name, &d)?;
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

    /// Reads a NUL-terminated list of names (a checksummed byte dataset).
    fn names(&self, name: &str) -> Result<Vec<String>, RestartError> {
        let d = self.dataset::<u8>(name, None)?;
        if d.ndim() != 1 || d.size() > MAX_COMMAND_BYTES {
            return Err(self.err(format!("dataset '{name}' should be a one-dimensional byte list, found shape {:?}", d.shape())));
        }
        let bytes = self.read_all::<u8>(name, &d)?;
        if bytes.last().is_some_and(|&b| b != 0) {
            return Err(self.err(format!("dataset '{name}' does not end with a NUL byte")));
        }
        bytes
            .split(|&b| b == 0)
            .take(bytes.iter().filter(|&&b| b == 0).count())
            .map(|c| String::from_utf8(c.to_vec()))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|_| self.err(format!("dataset '{name}' is not valid UTF-8")))
    }

    /// Requires the Fletcher32 checksum filter on a dataset (HDF5 verifies it on read).
    fn checksummed(&self, name: &str, d: &Dataset) -> Result<(), RestartError> {
        if d.filters().iter().any(|f| matches!(f, hdf5::filters::Filter::Fletcher32)) {
            Ok(())
        } else {
            Err(self.err(format!("dataset '{name}' has no checksum (Fletcher32 filter)")))
        }
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
        if version < RESTART_FORMAT_VERSION {
            return Err(c.err(format!(
                "format_version {version} was written by an older gendpde (this one reads {RESTART_FORMAT_VERSION}); \
                 continue the run with the gendpde that wrote it, or start again from a data file"
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
        let noise_shift = c.optional_scalar::<u64>("noise_shift")?.unwrap_or(0);
        let stale_tallies = c.optional_scalar::<u8>("stale_tallies")?.is_some_and(|v| v != 0);
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

        let enabled = c.scalar::<u32>("enabled")?;
        let groups = c.names("groups")?;
        let state_names = c.names("state/names")?;
        let ld = c.dataset::<u64>("state/lengths", Some(&[state_names.len()]))?;
        let lengths = c.read_all::<u64>("state/lengths", &ld)?;
        let total = lengths.iter().try_fold(0u64, |a, &l| a.checked_add(l)).filter(|&t| t <= MAX_COMMAND_BYTES as u64);
        let total = total.ok_or_else(|| c.err("dataset 'state/lengths' is out of range"))?;
        let vd = c.dataset::<f64>("state/values", Some(&[total as usize]))?;
        let values = c.read_all::<f64>("state/values", &vd)?;
        if values.iter().any(|v| !v.is_finite()) {
            return Err(c.err("dataset 'state/values' holds non-finite values"));
        }
        let mut values = values.into_iter();
        let state = state_names.into_iter().zip(&lengths).map(|(name, &l)| (name, values.by_ref().take(l as usize).collect())).collect();

        let mut columns = Vec::new();
        let mut cols = Vec::new();
        for name in c.names("particles/columns")? {
            let path = format!("particles/{name}");
            if !c.file.link_exists(&format!("/{path}")) || name.is_empty() || name.contains('/') {
                return Err(c.err(format!("missing dataset '{path}' of a listed particle column")));
            }
            let d = c.file.dataset(&path).map_err(|e| c.err(format!("cannot open dataset '{path}': {e}")))?;
            let integer = has_type::<i64>(d.dtype());
            let d = if integer { c.dataset::<i64>(&path, None)? } else { c.dataset::<f64>(&path, None)? };
            let shape = d.shape();
            let width = match shape[..] {
                [rows] if rows == n => 1,
                [rows, w] if rows == n && (1..=16).contains(&w) => w,
                _ => return Err(c.err(format!("dataset '{path}' should have {n} rows of at most 16 values, found shape {shape:?}"))),
            };
            columns.push(ColumnSpec { name, width, integer });
            cols.push(d);
        }

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
            noise_shift,
            stale_tallies,
            cell_counts,
            commands,
            creator_version,
            columns,
            enabled,
            groups,
            state,
        };
        header
            .check()
            .map_err(|e| c.err(format!("inconsistent header: {e}")))?;
        if let Some(bad) = header.masses.iter().flatten().find(|m| !(m.is_finite() && **m > 0.0)) {
            return Err(c.err(format!("inconsistent header: a per-type mass of {bad}; expected a positive finite mass")));
        }
        Ok(RestartReader {
            path: path.to_path_buf(),
            header,
            cols,
            last_tag: std::cell::Cell::new(0),
            _file: file,
        })
    }

    pub fn header(&self) -> &RestartHeader {
        &self.header
    }

    /// Reads rows [start, start + len) (clipped to natoms) into `rows` (cleared first;
    /// row-major, the header's columns). Blocks must be read in increasing order: the
    /// rows are validated as strictly as a data file (tags increasing within
    /// 1..=max_tag, types within 1..=ntypes, positive finite masses, finite floats,
    /// positions near the box, cells on the grid).
    pub fn read_rows(&self, start: u64, len: u64, rows: &mut Vec<f64>) -> Result<(), RestartError> {
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
        let width = row_width(&self.header.columns);
        rows.resize(n * width, 0.0);
        let mut offset = 0;
        for (c, d) in self.header.columns.iter().zip(&self.cols) {
            let err = |e: hdf5::Error| error(&self.path, format!("reading rows {a}..{b} of dataset 'particles/{}': {e}", c.name));
            let values: Vec<f64> = if c.integer {
                read_block::<i64>(d, a, b, c.width).map_err(err)?.into_iter().map(|x| x as f64).collect()
            } else {
                read_block::<f64>(d, a, b, c.width).map_err(err)?
            };
            for (row, v) in rows.chunks_exact_mut(width).zip(values.chunks_exact(c.width)) {
                row[offset..offset + c.width].copy_from_slice(v);
            }
            offset += c.width;
        }
        if a == 0 {
            self.last_tag.set(0);
        }
        for (k, row) in rows.chunks_exact(width).enumerate() {
            if let Err(e) = self.validate(row) {
                rows.clear();
                return Err(error(&self.path, format!("particle row {}: {e}", a + k)));
            }
        }
        Ok(())
    }

    /// Checks one row against the header (see `read_rows`).
    fn validate(&self, row: &[f64]) -> Result<(), String> {
        let h = &self.header;
        let mut offset = 0;
        for c in &h.columns {
            let v = &row[offset..offset + c.width];
            offset += c.width;
            if v.iter().any(|x| !x.is_finite()) {
                return Err(format!("column '{}' holds {v:?}; expected finite values", c.name));
            }
            if c.integer && v.iter().any(|x| x.abs() > (1u64 << 53) as f64) {
                return Err(format!("integer column '{}' holds {v:?}; expected integers below 2^53", c.name));
            }
            match c.name.as_str() {
                "id" => {
                    let t = v[0] as u64;
                    if v[0] < 1.0 || t > h.max_tag || t <= self.last_tag.get() {
                        return Err(format!("id {} after id {}: expected increasing ids within 1..={}", v[0], self.last_tag.get(), h.max_tag));
                    }
                    self.last_tag.set(t);
                }
                "type" if v[0] < 1.0 || v[0] > h.ntypes as f64 => return Err(format!("type {} is outside 1..={}", v[0], h.ntypes)),
                "mass" if v[0] <= 0.0 => return Err(format!("mass {}: expected a positive mass", v[0])),
                "octant" if v[0] < 0.0 || v[0] >= 8.0 => return Err(format!("octant {} is outside 0..8", v[0])),
                "x" => {
                    for d in 0..3 {
                        let l = h.hi[d] - h.lo[d];
                        if v[d] < h.lo[d] - l || v[d] > h.hi[d] + l {
                            return Err(format!("position {v:?} lies far outside the box {:?}..{:?}", h.lo, h.hi));
                        }
                    }
                }
                "cell" => {
                    if let Some(count) = h.cell_counts {
                        if (0..3).any(|d| v[d] < 0.0 || v[d] >= count[d] as f64) {
                            return Err(format!("cell {v:?} is outside the cell grid {count:?}"));
                        }
                    }
                }
                _ => {}
            }
        }
        Ok(())
    }
}

/// Reads rows a..b of a column dataset of `width` values per row, row-major.
fn read_block<T: H5Type + Copy>(d: &Dataset, a: usize, b: usize, width: usize) -> hdf5::Result<Vec<T>> {
    let v: Vec<T> = if width == 1 {
        d.read_slice_1d::<T, _>(a..b)?.iter().copied().collect()
    } else {
        d.read_slice_2d::<T, _>((a..b, ..))?.iter().copied().collect()
    };
    if v.len() != (b - a) * width {
        return Err(format!("got {} values, expected {}", v.len(), (b - a) * width).into());
    }
    Ok(v)
}
