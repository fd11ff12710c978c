//! The HDF5 file under an H5MD trajectory: errors naming the file, the writer's
//! file-access settings, opening in SWMR-write mode (FFI where the hdf5 crate has no
//! wrapper) and string attributes.

use std::fmt;
use std::path::Path;
use std::str::FromStr;

use hdf5::file::LibraryVersion;
use hdf5::types::VarLenUnicode;
use hdf5::{File, Group};

/// Error of the H5MD reader/writer; the message names the file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct H5mdError(pub String);

impl fmt::Display for H5mdError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for H5mdError {}


/// Maximum bytes of one chunk of a `value` dataset.
pub(super) const CHUNK_BYTES: usize = 1 << 20;
/// Chunk length of the `step` and `time` datasets.
pub(super) const STEP_CHUNK: usize = 256;
/// Raw-data chunk cache of the writer's file.
pub(super) const CHUNK_CACHE_BYTES: usize = 32 << 20;
pub(super) const CHUNK_CACHE_SLOTS: usize = 12_421;

/// HDF5 property of the file-access class that clears the superblock
/// "file is open for writing" flags on open (what `h5clear -s` uses).
pub(super) const CLEAR_STATUS_FLAGS: &[u8] = b"clear_status_flags\0";
/// Property that skips the "file shorter than its EOA" check on open.
pub(super) const SKIP_EOF_CHECK: &[u8] = b"skip_eof_check\0";
/// EOA margin added by [`repair_h5md`] (h5clear's default).
pub(super) const REPAIR_EOA_INCREMENT: u64 = 1 << 20;

pub(super) type Hid = i64; // hid_t of HDF5 >= 1.10

extern "C" {
    pub(super) fn H5Pset(plist_id: Hid, name: *const std::ffi::c_char, value: *const std::ffi::c_void) -> i32;
    pub(super) fn H5Fopen(name: *const std::ffi::c_char, flags: u32, fapl_id: Hid) -> Hid;
    pub(super) fn H5Fclose(file_id: Hid) -> i32;
    pub(super) fn H5Fincrement_filesize(file_id: Hid, increment: u64) -> i32;
}

/// `H5F_ACC_RDWR`.
pub(super) const H5F_ACC_RDWR: u32 = 0x0001;
/// `H5F_ACC_SWMR_WRITE`.
pub(super) const H5F_ACC_SWMR_WRITE: u32 = 0x0020;


pub(super) fn error(path: &Path, what: impl fmt::Display) -> H5mdError {
    H5mdError(format!("{}: {}", path.display(), what))
}

/// Maps an hdf5 error into an [`H5mdError`] naming the file and the action.
pub(super) fn h5<T>(path: &Path, what: &str, r: hdf5::Result<T>) -> Result<T, H5mdError> {
    r.map_err(|e| error(path, format_args!("{what}: {e}")))
}

pub(super) fn vlen(path: &Path, s: &str) -> Result<VarLenUnicode, H5mdError> {
    VarLenUnicode::from_str(s).map_err(|e| error(path, format_args!("invalid string {s:?}: {e}")))
}

pub(super) fn write_str_attr(path: &Path, loc: &Group, name: &str, value: &str) -> Result<(), H5mdError> {
    let v = vlen(path, value)?;
    let attr = h5(
        path,
        &format!("creating attribute {name}"),
        loc.new_attr::<VarLenUnicode>().create(name),
    )?;
    h5(
        path,
        &format!("writing attribute {name}"),
        attr.write_scalar(&v),
    )
}


/// Silences the HDF5 C library's error printing for this thread (the hdf5
/// crate does this on first use; calling it again is cheap and harmless).
pub(super) fn silence() {
    hdf5::silence_errors(true);
}

/// The writer's file-access settings: v110 format (required for SWMR) and
/// a raw-data chunk cache large enough for one frame's block writes.
pub(super) fn writer_options() -> hdf5::FileBuilder {
    let mut b = File::with_options();
    b.with_fapl(|p| {
        p.libver_bounds(LibraryVersion::V110, LibraryVersion::latest())
            .chunk_cache(CHUNK_CACHE_SLOTS, CHUNK_CACHE_BYTES, 1.0)
    });
    b
}

/// Opens `path` read/write in SWMR-write mode with the writer's settings.
pub(super) fn open_swmr_rw(path: &Path) -> Result<File, H5mdError> {
    let cpath = std::ffi::CString::new(path.as_os_str().as_encoded_bytes())
        .map_err(|_| error(path, "file name contains a NUL byte"))?;
    let fapl = h5(
        path,
        "creating file access list",
        hdf5::plist::FileAccessBuilder::new()
            .libver_bounds(LibraryVersion::V110, LibraryVersion::latest())
            .chunk_cache(CHUNK_CACHE_SLOTS, CHUNK_CACHE_BYTES, 1.0)
            .finish(),
    )?;
    hdf5::sync::sync(|| {
        // SAFETY: valid NUL-terminated name and property list; the returned
        // identifier is new (reference count 1) and handed to the hdf5 crate,
        // which closes it when the File is dropped.
        unsafe {
            let id = H5Fopen(cpath.as_ptr(), H5F_ACC_RDWR | H5F_ACC_SWMR_WRITE, fapl.id());
            if id < 0 {
                let why = hdf5::Error::query()
                    .map_or_else(|_| "unknown HDF5 error".to_string(), |e| e.to_string());
                return Err(error(
                    path,
                    format_args!("cannot open in SWMR-write mode: {why}"),
                ));
            }
            hdf5::from_id::<File>(id).map_err(|e| error(path, e))
        }
    })
}

