//! Input-script handling for gendpde: a LAMMPS-style script reader with
//! variable substitution, the variable store, an equal-style expression
//! evaluator, C-printf-compatible number formatting and LAMMPS data files.

pub mod boolean;
pub mod command;
pub mod data_file;
pub mod expr;
pub mod format;
pub mod functions;
pub mod h5md;
pub mod restart;
pub mod script;
pub mod variables;

pub use boolean::evaluate_boolean;
pub use data_file::{parse_data, read_data, write_data, AtomStyle, DataAtom, DataFile, PairCoeffs};
pub use expr::evaluate;
pub use format::{format_g, format_printf, format_shortest};
pub use h5md::{check_h5md, repair_h5md, H5mdError, H5mdField, H5mdMeta, H5mdSummary, H5mdWriter};
pub use restart::{row_width, ColumnSpec, RestartError, RestartHeader, RestartReader, RestartWriter};
pub use command::{Command, Location, ScriptError};
pub use script::{substitute, ScriptReader};
pub use variables::Variables;
