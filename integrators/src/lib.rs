//! GenDPDE integrators, by tier: the framework ([`physics`]: the trait every model
//! implements, [`system`], [`settings`], [`error`], [`rng`], [`simd`], [`type_table`]),
//! the shared [`passes`] (density and forces, the Shardlow sweep, heat and noise laws,
//! velocity Verlet, the barostat) and the [`models`] built from them (GenDPDE, LAMMPS's
//! pairwise styles, eDPD, SDPD, Voronoi). Equation numbers: 2019 PCCP paper unless stated.

pub mod error;
pub mod models;
pub mod passes;
pub mod physics;
pub mod rng;
pub mod settings;
pub mod simd;
pub mod system;
pub mod type_table;

pub use error::StepError;
pub use models::classic::{ClassicDpd, DpdCoeff, DpdEnergyCoeff, DpdExt, DpdExtCoeff, Integration, MdpdCoeff, PairForce, ShardlowCoeff, ShardlowDpd};
pub use models::edpd::{Edpd, EdpdCoeff, HeatSource, SourceShape};
pub use models::gendpde::{GenDpde, Motion, Work};
pub use models::sdpd::generic::{Sdpd, SdpdParams};
pub use models::sdpd::taitwater::SdpdTaitwater;
pub use passes::barostat::{Couple, Nph, NphState};
pub use passes::heat::HeatModel;
pub use passes::isentropic::FixedEntropy;
pub use passes::noise::{isothermal_gamma, isothermal_sigma, NoiseForm};
pub use passes::pair_tables::PairTables;
pub use passes::species::Species;
pub use physics::{Physics, SetupError};
pub use passes::dissipation::{Dissipation, Reservoir};
pub use settings::{RebuildPolicy, Settings};
pub use system::{Clock, FixRecord, FixState, RunControl, Snapshot, System};
pub use type_table::TypeTable;
