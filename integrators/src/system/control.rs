//! What the run loop, a restore and the signal handlers tell the step, and the counters
//! the step reports back.

use std::cell::Cell;
use std::sync::atomic::AtomicUsize;
use std::sync::Arc;

/// Run, restore and signal flags, and the sweep's guard counters.
#[derive(Debug)]
pub struct RunControl {
    /// Whether the force passes of the coming step must sum the per-particle pair
    /// energies and virials (a step after which nothing is written skips them, as
    /// LAMMPS's eflag/vflag; the run sets it before each step).
    pub tally: bool,
    /// Whether the stored per-particle energies and virials belong to the current state
    /// (false after a step that skipped them).
    pub tallied: bool,
    /// The particles, cells and build positions were read from a restart: the next
    /// build keeps them as stored, so the lists come out as when it was written.
    pub restored: bool,
    /// Cell counts of the grid the restored cells belong to.
    pub restored_grid: Option<[usize; 3]>,
    /// The number of a signal this rank received (set by the program's handler; 0: none).
    pub interrupt: Arc<AtomicUsize>,
    /// The largest `interrupt` of all ranks at the last [`crate::System::settle`] (0:
    /// none): the ranks agree on it, so they stop at the same step.
    pub interrupted: Cell<usize>,
    /// Pair updates split into half steps so far (theta -> 0 guard of the sweep).
    pub substeps: u64,
    /// Pair updates left out because no split could keep theta positive (`reject yes`).
    pub rejected: u64,
}

impl Default for RunControl {
    fn default() -> Self {
        Self {
            tally: true,
            tallied: true,
            restored: false,
            restored_grid: None,
            interrupt: Arc::default(),
            interrupted: Cell::new(0),
            substeps: 0,
            rejected: 0,
        }
    }
}
