//! Output: the screen and log ([`console`]), and what runs and commands write: thermo,
//! text and H5MD dumps, fix ave/time and ave/chunk, checkpoints and restart files.

pub mod ave_chunk;
pub mod ave_time;
pub mod checkpoint;
pub mod console;
pub mod dump;
pub mod restart;
pub mod schedule;
pub mod thermo;
pub mod thermo_settings;

use self::ave_chunk::AveChunk;
use self::ave_time::AveTime;
use self::checkpoint::Checkpoint;
use self::dump::Dump;
use self::schedule::RunOutput;
use self::thermo::ThermoConfig;

/// The outputs of runs a script defined.
#[derive(Default)]
pub struct Outputs {
    /// `thermo`, `thermo_style`, `thermo_modify`.
    pub thermo: ThermoConfig,
    /// `dump ID GROUP custom|atom|xyz|h5md ...`.
    pub dumps: Vec<Box<dyn Dump>>,
    /// `fix ID all ave/time`.
    pub averages: Vec<AveTime>,
    /// `fix ID GROUP ave/chunk`.
    pub chunk_averages: Vec<AveChunk>,
    /// `checkpoint N FILE`.
    pub checkpoint: Option<Checkpoint>,
}

impl Outputs {
    /// Whether a fix ave/time or ave/chunk has ID `id`.
    pub fn has_fix(&self, id: &str) -> bool {
        self.averages.iter().any(|f| f.id == id) || self.chunk_averages.iter().any(|f| f.id == id)
    }

    /// All of them in the order a run writes them at one step: thermo, the dumps, the
    /// fixes ave/time, the fixes ave/chunk, the checkpoint.
    pub fn all(&mut self) -> impl Iterator<Item = &mut dyn RunOutput> {
        std::iter::once(&mut self.thermo as &mut dyn RunOutput)
            .chain(self.dumps.iter_mut().map(|d| d.as_mut() as &mut dyn RunOutput))
            .chain(self.averages.iter_mut().map(|f| f as &mut dyn RunOutput))
            .chain(self.chunk_averages.iter_mut().map(|f| f as &mut dyn RunOutput))
            .chain(self.checkpoint.iter_mut().map(|c| c as &mut dyn RunOutput))
    }
}
