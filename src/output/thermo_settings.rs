//! The thermo settings of `thermo`, `thermo_style custom` and `thermo_modify` (the
//! output itself is in `thermo.rs`).

/// `thermo`, `thermo_style custom` and `thermo_modify`.
#[derive(Clone, Debug)]
pub struct ThermoConfig {
    pub every: u64,
    pub keywords: Vec<String>,
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
        let keywords = ["step", "temp", "tint", "pe", "ke", "etotal", "press"].map(String::from).to_vec();
        Self { every: 0, keywords, norm: true, float_format: None, temp: None, last: None, flush: false }
    }
}
