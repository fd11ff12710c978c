//! Making a file whose writer was killed (or ran out of disk) readable again.

use super::*;

/// Repairs a file whose writer was killed, like `h5clear -s -i 1M`:
/// clears the superblock "open for writing" flags (without which HDF5
/// refuses to open the file except in SWMR-read mode) and raises the
/// end-of-allocation address to cover everything written (SWMR writes data
/// and metadata before the superblock's EOA is updated).  Harmless on a
/// cleanly closed file.  Must not be used while a writer has the file open.
pub fn repair_h5md(path: &Path) -> Result<(), H5mdError> {
    silence();
    let cpath = std::ffi::CString::new(path.as_os_str().as_encoded_bytes())
        .map_err(|_| error(path, "file name contains a NUL byte"))?;
    let fapl = h5(
        path,
        "creating file access list",
        hdf5::plist::FileAccess::try_new(),
    )?;
    hdf5::sync::sync(|| {
        let on: u8 = 1; // hbool_t
                        // SAFETY: both properties exist in every file-access list of HDF5
                        // >= 1.10 with the size of hbool_t (1 byte, checked in the tests by
                        // their effect); the pointers are valid for the duration of the
                        // calls, and the hdf5 crate's global lock is held as for its own calls.
        unsafe {
            for prop in [CLEAR_STATUS_FLAGS, SKIP_EOF_CHECK] {
                if H5Pset(fapl.id(), prop.as_ptr().cast(), (&on as *const u8).cast()) < 0 {
                    return Err(error(
                        path,
                        "cannot set the repair properties (HDF5 older than 1.10?)",
                    ));
                }
            }
            let id = H5Fopen(cpath.as_ptr(), H5F_ACC_RDWR, fapl.id());
            if id < 0 {
                return Err(error(
                    path,
                    "cannot open for repair (not an HDF5 file, or still open?)",
                ));
            }
            let grown = H5Fincrement_filesize(id, REPAIR_EOA_INCREMENT);
            if H5Fclose(id) < 0 || grown < 0 {
                return Err(error(path, "repair failed"));
            }
        }
        Ok(())
    })
}
