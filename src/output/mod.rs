//! Output: the screen and log ([`console`]), and what runs and commands write: thermo,
//! text and H5MD dumps, fix ave/time and ave/chunk, checkpoints and restart files.

pub mod checkpoint;
pub mod console;
pub mod dump;
pub mod fix;
pub mod restart;
pub mod schedule;
pub mod thermo;
pub mod thermo_settings;

use self::checkpoint::Checkpoint;
use self::dump::Dump;
use self::fix::OutputFix;
use self::schedule::RunOutput;
use self::thermo::ThermoConfig;

/// The outputs of runs a script defined.
#[derive(Default)]
pub struct Outputs {
    /// `thermo`, `thermo_style`, `thermo_modify`.
    pub thermo: ThermoConfig,
    /// `dump ID GROUP custom|atom|xyz|h5md ...`.
    pub dumps: Vec<Box<dyn Dump>>,
    /// The output fixes (ave/time, ave/chunk, print, ...).
    pub fixes: Vec<Box<dyn OutputFix>>,
    /// `checkpoint N FILE`.
    pub checkpoint: Option<Checkpoint>,
}

impl Outputs {
    /// The output fix with ID `id`.
    pub fn fix(&self, id: &str) -> Option<&dyn OutputFix> {
        self.fixes.iter().find(|f| f.id() == id).map(|f| f.as_ref())
    }

    /// The IDs of the compute rdf the output fixes read.
    pub fn rdfs(&self) -> Vec<String> {
        self.fixes.iter().flat_map(|f| f.rdfs()).map(String::from).collect()
    }

    /// All of them in the order a run writes them at one step: the output fixes (which
    /// LAMMPS runs before its output), thermo, the dumps, the checkpoint.
    pub fn all(&mut self) -> impl Iterator<Item = &mut dyn RunOutput> {
        self.fixes
            .iter_mut()
            .map(|f| f.as_mut() as &mut dyn RunOutput)
            .chain(std::iter::once(&mut self.thermo as &mut dyn RunOutput))
            .chain(self.dumps.iter_mut().map(|d| d.as_mut() as &mut dyn RunOutput))
            .chain(self.checkpoint.iter_mut().map(|c| c as &mut dyn RunOutput))
    }
}
