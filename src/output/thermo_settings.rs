//! The thermo settings of `thermo`, `thermo_style custom` and `thermo_modify` (the
//! output itself is in `thermo.rs`).

/// LAMMPS's `thermo_style one`, its default.
pub const ONE: [&str; 6] = ["step", "temp", "epair", "emol", "etotal", "press"];
/// gendpde's default for its own styles (pair gendpde, sdpd/generic, voronoi/fv).
const GENDPDE: [&str; 7] = ["step", "temp", "tint", "pe", "ke", "etotal", "press"];

/// `thermo`, `thermo_style custom` and `thermo_modify`.
#[derive(Clone, Debug)]
pub struct ThermoConfig {
    pub every: u64,
    pub keywords: Vec<String>,
    /// The columns were set by `thermo_style` (else each run takes the default of its
    /// pair style: [`ThermoConfig::default_columns`]).
    pub styled: bool,
    /// List builds and dangerous builds at the set-up of the current run (LAMMPS counts
    /// `nbuild` and `ndanger` from there).
    pub(crate) builds_at_setup: [u64; 2],
    /// Steps of the current run left after the frame being written (for `cpuremain`).
    pub(crate) steps_left: u64,
    pub norm: bool,
    pub float_format: Option<String>,
    /// `thermo_modify temp ID`: the compute temp of temp, ke, etotal and press.
    pub temp: Option<String>,
    /// `thermo_modify flush yes`: the log is synced to disk after each row.
    pub flush: bool,
    /// The previous thermo line of the current run, for tpcpu and spcpu.
    pub(crate) last: Option<Mark>,
}

/// When a thermo line was written: step, simulated time and CPU seconds into the run.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mark {
    pub step: u64,
    pub time: f64,
    pub cpu: f64,
}

impl Default for ThermoConfig {
    fn default() -> Self {
        let keywords = GENDPDE.map(String::from).to_vec();
        Self { every: 0, keywords, styled: false, builds_at_setup: [0; 2], steps_left: 0, norm: true, float_format: None, temp: None, last: None, flush: false }
    }
}

impl ThermoConfig {
    /// A `thermo_style` of these columns: as LAMMPS's new Thermo, the `thermo_modify`
    /// settings go back to their defaults (`norm` to the units' `default_norm`).
    pub fn restyle(&mut self, keywords: Vec<String>, default_norm: bool) {
        let every = self.every;
        *self = Self { every, keywords, styled: true, norm: default_norm, ..Self::default() };
    }

    /// Without a `thermo_style`, the columns of a run: LAMMPS's `one` for LAMMPS's pair
    /// styles (`lammps_style`), gendpde's own otherwise.
    pub fn default_columns(&mut self, lammps_style: bool) {
        if !self.styled {
            self.keywords = if lammps_style { ONE.map(String::from).to_vec() } else { GENDPDE.map(String::from).to_vec() };
        }
    }
}
