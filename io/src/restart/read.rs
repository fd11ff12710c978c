//! Reading and validating restart files (`RestartReader`).

use super::*;


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
